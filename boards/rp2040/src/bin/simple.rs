//! The simple Pico example: one core, the integer kernel drawing the lab scene straight
//! into a 240×240 ST7789 through `mipidsi`, the camera orbiting 5° a frame
//! (`../orbit.rs`, the same orbit as the two-core example). Where the integer kernel's
//! per-frame rule refuses a frame, the `f32` kernel draws it; the top line says which
//! kernel drew the last frame and its frame rate, or what went wrong.
//!
//! ```sh
//! cargo build --release --bin simple
//! elf2uf2-rs -d target/thumbv6m-none-eabi/release/simple        # Pico in BOOTSEL mode
//! ```
//!
//! Wiring as the two-core example (README.md): SCK GP10, MOSI GP11, CS GP9, DC GP8,
//! RST GP12, BL GP13. Builds in CI; not run on hardware.
#![no_std]
#![no_main]

#[path = "../orbit.rs"]
mod orbit;
#[path = "../scenes.rs"]
mod scenes;

use core::fmt::{Debug, Write as _};

use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyleBuilder};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::text::{Baseline, Text};
use embedded_hal_bus::spi::ExclusiveDevice;
use embedded_raytracer::{Camera, FrameError, IntegerError, Render};
use mipidsi::{interface::SpiInterface, models::ST7789, options::ColorInversion, Builder};
use panic_halt as _;
use rp2040_hal::{
    self as hal, clocks::Clock, fugit::RateExtU32, gpio::FunctionSpi, pac, Sio, Timer, Watchdog,
};

/// The second-stage bootloader for the Pico's W25Q080 flash (`memory.x`).
#[link_section = ".boot2"]
#[used]
pub static BOOT2: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// Which kernel drew a frame.
enum Kernel {
    Integer,
    F32,
}

/// Why a frame was not drawn.
enum Failed<E> {
    Camera,
    Frame(FrameError),
    Display(E),
}

/// One frame, in one call: the integer kernel, or the `f32` kernel where the integer
/// kernel's rule refuses the frame (after `check`, since `draw` leaves a frame it
/// cannot draw exactly untouched).
fn frame<D: DrawTarget<Color = Rgb565>>(
    display: &mut D,
    camera: Option<&Camera>,
) -> Result<Kernel, Failed<D::Error>> {
    let camera = camera.ok_or(Failed::Camera)?;
    let render = Render::new(&scenes::LAB, camera);
    match render.draw_integer(display) {
        Ok(()) => Ok(Kernel::Integer),
        Err(IntegerError::Target(e)) => Err(Failed::Display(e)),
        Err(_refused) => {
            render.check().map_err(Failed::Frame)?;
            render.draw(display).map_err(Failed::Display)?;
            Ok(Kernel::F32)
        }
    }
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

/// The status line: the kernel and its frame rate, or the error.
fn status<E: Debug>(
    drawn: &Result<Kernel, Failed<E>>,
    us: u64,
    display_errors: u32,
) -> heapless::String<256> {
    let mut s = heapless::String::new();
    let tenths = 10_000_000 / us.max(1);
    // A `String` only fails when full; 256 bytes hold every message here.
    let written = match drawn {
        Ok(Kernel::Integer) => write!(s, "integer {}.{} fps", tenths / 10, tenths % 10),
        Ok(Kernel::F32) => write!(s, "f32 (integer refused) {}.{} fps", tenths / 10, tenths % 10),
        Err(Failed::Camera) => write!(s, "error: camera refused"),
        Err(Failed::Frame(e)) => write!(s, "error: {e}"),
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
    // 125 MHz from the Pico's 12 MHz crystal.
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
    let mut timer = Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);
    let sio = Sio::new(pac.SIO);
    let pins = hal::gpio::Pins::new(pac.IO_BANK0, pac.PADS_BANK0, sio.gpio_bank0, &mut pac.RESETS);

    // SPI1 at 62.5 MHz asked, 31.25 MHz given (125 MHz / 4), mode 3.
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
        let drawn = frame(&mut display, orbit::camera_at(angle, size).as_ref());
        let us = timer.get_counter().ticks().wrapping_sub(start);
        // Drawn over the picture; if the display cannot take it, nothing else can
        // show it: counted, and shown once it can.
        if show(&mut display, &status(&drawn, us, display_errors)).is_err() {
            display_errors = display_errors.saturating_add(1);
        }
        angle = orbit::next_angle(angle);
    }
}
