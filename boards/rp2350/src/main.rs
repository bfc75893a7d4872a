//! Raspberry Pi Pico 2 (RP2350, Cortex-M33 with FPU, 150 MHz) driving a 240×240 ST7789
//! over SPI1 through `mipidsi`: the `f32` kernel draws the lit `shadows` scene (two
//! lights, hard shadows, a checkered floor), the camera orbiting 5° a frame
//! (`orbit.rs`). On the FPU the arithmetic is IEEE-754 `f32`, as on the Cortex-M4F and
//! the host: the same source draws the same frames there. The top line shows the
//! frame rate, or why the frame was not drawn.
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

mod orbit;
mod scenes;

use core::fmt::{Debug, Write as _};

use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyleBuilder};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::text::{Baseline, Text};
use embedded_hal_bus::spi::ExclusiveDevice;
use embedded_raytracer::{Camera, CameraError, FrameError, Render};
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

/// Why a frame was not drawn.
enum Failed<E> {
    Camera(CameraError),
    Frame(FrameError),
    Display(E),
}

/// One frame, in one call. `check` first: `draw` leaves a frame it cannot draw exactly
/// untouched, which would look like a frozen picture.
fn frame<D: DrawTarget<Color = Rgb565>>(
    display: &mut D,
    camera: Result<Camera, CameraError>,
) -> Result<(), Failed<D::Error>> {
    let camera = camera.map_err(Failed::Camera)?;
    let render = Render::new(&scenes::SHADOWS, &camera);
    render.check().map_err(Failed::Frame)?;
    render.draw(display).map_err(Failed::Display)
}

/// `text` in white on black from the top-left corner, cut into lines of the panel's
/// width (ASCII: the library's messages are).
fn show<D: DrawTarget<Color = Rgb565>>(display: &mut D, text: &str) -> Result<(), D::Error> {
    let style = MonoTextStyleBuilder::new()
        .font(&FONT_6X10)
        .text_color(Rgb565::WHITE)
        .background_color(Rgb565::BLACK)
        .build();
    let per_line = (display.bounding_box().size.width as usize / 6)
        .saturating_sub(1)
        .max(1);
    for (row, line) in text.as_bytes().chunks(per_line).enumerate() {
        let line = core::str::from_utf8(line).unwrap_or("?");
        Text::with_baseline(line, Point::new(2, 2 + 10 * row as i32), style, Baseline::Top).draw(display)?;
    }
    Ok(())
}

/// The status line: the frame rate, or the error.
fn status<E: Debug>(drawn: &Result<(), Failed<E>>, us: u64, display_errors: u32) -> heapless::String<256> {
    let mut s = heapless::String::new();
    let tenths = 10_000_000 / us.max(1);
    // A `String` only fails when full; 256 bytes hold every message here.
    let written = match drawn {
        Ok(()) => write!(s, "f32 {}.{} fps", tenths / 10, tenths % 10),
        Err(Failed::Camera(e)) => write!(s, "camera: {e}"),
        Err(Failed::Frame(e)) => write!(s, "{e}"),
        Err(Failed::Display(e)) => write!(s, "display error: {e:?}"),
    }
    .and_then(|()| match display_errors {
        0 => Ok(()),
        n => write!(s, " ({n} label writes failed)"),
    });
    if written.is_err() {
        s.clear();
        s.push_str("(message too long)").ok();
    }
    s
}

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
    let mut angle = 0.0f32;
    let mut display_errors = 0u32;
    loop {
        let start = timer.get_counter().ticks();
        let drawn = frame(&mut display, orbit::orbit(&scenes::SHADOWS_CAMERA, angle, size));
        let us = timer.get_counter().ticks().wrapping_sub(start);
        // Drawn over the picture; if the display cannot take it, nothing else can
        // show it: counted, and shown once it can.
        if show(&mut display, &status(&drawn, us, display_errors)).is_err() {
            display_errors = display_errors.saturating_add(1);
        }
        angle = orbit::next_angle(angle);
    }
}
