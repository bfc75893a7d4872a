//! Raspberry Pi Pico 2 (RP2350, Cortex-M33 with FPU, 150 MHz) driving a 240×240 ST7789
//! over SPI1 through `mipidsi`: the `f32` kernel draws `scenes/bounce.toml` (a lit ball
//! bouncing on a checkered floor, its shadow, two still spheres), the motion the
//! library's (`embedded_raytracer::motion`). Frames are incremental: only the pixels
//! the ball and its shadow can have changed are traced and sent. On the FPU the arithmetic is IEEE-754 `f32`, as on the Cortex-M4F
//! and the host: the same source draws the same frames there. The top line shows the
//! frame rate and the share of the panel traced and sent, or why the frame was not
//! drawn.
//!
//! ```sh
//! cargo build --release
//! picotool load -u -v -x -t elf target/thumbv8m.main-none-eabihf/release/rp2350-st7789
//! ```
//!
//! Wiring (README.md): SCK GP10, MOSI GP11, CS GP9, DC GP8, RST GP12, BL GP13.
//! Builds in CI; not run on hardware.
#![no_std]
#![no_main]

mod frame;
mod scenes;

use embedded_graphics::prelude::*;
use embedded_hal_bus::spi::ExclusiveDevice;
use mipidsi::{interface::SpiInterface, models::ST7789, options::ColorInversion, Builder};
use panic_halt as _;
use rp235x_hal::{
    self as hal, clocks::Clock, fugit::RateExtU32, gpio::FunctionSpi, pac, Sio, Timer, Watchdog,
};

/// The boot ROM's image definition: a secure-mode Arm executable (`memory.x` puts it in
/// the first 4 KiB of flash).
#[link_section = ".start_block"]
#[used]
pub static IMAGE_DEF: hal::block::ImageDef = hal::block::ImageDef::secure_exe();

#[hal::entry]
fn main() -> ! {
    let Some(mut pac) = pac::Peripherals::take() else {
        panic!("peripherals taken twice");
    };
    let mut watchdog = Watchdog::new(pac.WATCHDOG);
    // 150 MHz from the Pico 2's 12 MHz crystal.
    let Ok(clocks) = hal::clocks::init_clocks_and_plls(
        12_000_000,
        pac.XOSC,
        pac.CLOCKS,
        pac.PLL_SYS,
        pac.PLL_USB,
        &mut pac.RESETS,
        &mut watchdog,
    ) else {
        panic!("clock setup failed");
    };
    let mut timer = Timer::new_timer0(pac.TIMER0, &mut pac.RESETS, &clocks);
    let sio = Sio::new(pac.SIO);
    let pins = hal::gpio::Pins::new(pac.IO_BANK0, pac.PADS_BANK0, sio.gpio_bank0, &mut pac.RESETS);

    // SPI1 at 62.5 MHz asked (the ST7789's fastest write clock), 37.5 MHz given
    // (150 MHz / 4), mode 3.
    let sck = pins.gpio10.into_function::<FunctionSpi>();
    let mosi = pins.gpio11.into_function::<FunctionSpi>();
    let spi = hal::spi::Spi::<_, _, _, 8>::new(pac.SPI1, (mosi, sck)).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        62_500_000u32.Hz(),
        embedded_hal::spi::MODE_3,
    );
    let cs = pins
        .gpio9
        .into_push_pull_output_in_state(hal::gpio::PinState::High);
    let dc = pins.gpio8.into_push_pull_output();
    let rst = pins.gpio12.into_push_pull_output();
    let _backlight = pins
        .gpio13
        .into_push_pull_output_in_state(hal::gpio::PinState::High);

    let Ok(spi_device) = ExclusiveDevice::new_no_delay(spi, cs);
    let mut buffer = [0u8; 512];
    let interface = SpiInterface::new(spi_device, dc, &mut buffer);
    let Ok(mut display) = Builder::new(ST7789, interface)
        .display_size(240, 240)
        .invert_colors(ColorInversion::Inverted) // IPS ST7789 panels are inverted
        .reset_pin(rst)
        .init(&mut timer)
    else {
        panic!("display init failed");
    };

    let size = display.bounding_box().size;
    let film = frame::Film {
        scene: &scenes::BOUNCE,
        camera: scenes::BOUNCE_CAMERA.with_size(size),
        animation: &scenes::BOUNCE_ANIMATION,
    };
    let mut scene = scenes::BOUNCE.clone();
    let mut shown = embedded_raytracer::Incremental::new();
    let mut display_errors = 0u32;
    let mut k = 0u32;
    loop {
        let start = timer.get_counter().ticks();
        let drawn = frame::frame(&mut display, &mut shown, &film, k, &mut scene);
        let us = timer.get_counter().ticks().wrapping_sub(start);
        // Drawn over the picture; if the display cannot take it, nothing else can
        // show it: counted, and shown once it can.
        let line = frame::status(&drawn, us, size.width * size.height, display_errors);
        if frame::show(&mut display, &mut shown, &line).is_err() {
            display_errors = display_errors.saturating_add(1);
        }
        // The motion repeats after `frames()` frames exactly: counting within one
        // loop keeps every frame's time as exact as the first loop's.
        k = (k + 1) % film.animation.frames();
    }
}
