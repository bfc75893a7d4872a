//! Raspberry Pi Pico (RP2040, Cortex-M0+, no FPU) driving a 128×64 SSD1306 OLED over
//! I²C: the integer kernel draws the lab scene through the library's ordered dither
//! (`embedded_raytracer::dither`: shading as a dot density on a 1-bit panel) into the
//! driver's frame buffer, the camera orbiting 5° a frame (`orbit.rs`); where the
//! integer kernel's rule refuses a frame, the `f32` kernel draws it. The top line says
//! which kernel drew the last frame and its frame rate, or why the frame was not drawn.
//!
//! ```sh
//! cargo build --release
//! elf2uf2-rs -d target/thumbv6m-none-eabi/release/rp2040-ssd1306   # Pico in BOOTSEL mode
//! ```
//!
//! Wiring (README.md): SDA GP4, SCL GP5 (I2C0, 400 kHz), address 0x3C.
//! Builds in CI; not run on hardware.
#![no_std]
#![no_main]

mod orbit;
mod scenes;

use core::fmt::{Debug, Write as _};

use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyleBuilder};
use embedded_graphics::pixelcolor::BinaryColor;
use embedded_graphics::prelude::*;
use embedded_graphics::text::{Baseline, Text};
use embedded_raytracer::dither::DitherExt as _;
use embedded_raytracer::{Camera, CameraError, FrameError, IntegerError, Render};
use panic_halt as _;
use rp2040_hal::{
    self as hal,
    fugit::RateExtU32,
    gpio::{FunctionI2c, PullUp},
    pac, Sio, Timer, Watchdog,
};
use ssd1306::{prelude::*, I2CDisplayInterface, Ssd1306};

/// The second-stage bootloader for the Pico's W25Q080 flash (`memory.x`).
#[link_section = ".boot2"]
#[used]
pub static BOOT2: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// Which kernel drew a frame.
enum Kernel {
    Integer,
    F32,
}

/// Why a frame was not drawn or not shown.
enum Failed<E> {
    Camera(CameraError),
    Frame(FrameError),
    Display(E),
}

/// One frame, in one call: the integer kernel, or the `f32` kernel where the integer
/// kernel's rule refuses the frame (after `check`, since `draw` leaves a frame it
/// cannot draw exactly untouched), both through the 8×8 ordered dither.
fn frame<D>(display: &mut D, camera: Result<Camera, CameraError>) -> Result<Kernel, Failed<D::Error>>
where
    D: DrawTarget<Color = BinaryColor>,
{
    let camera = camera.map_err(Failed::Camera)?;
    let render = Render::new(&scenes::LAB, &camera);
    match render.draw_integer(&mut display.dithered()) {
        Ok(()) => Ok(Kernel::Integer),
        Err(IntegerError::Target(e)) => Err(Failed::Display(e)),
        Err(_refused) => {
            render.check().map_err(Failed::Frame)?;
            render.draw(&mut display.dithered()).map_err(Failed::Display)?;
            Ok(Kernel::F32)
        }
    }
}

/// `text` lit on dark from the top-left corner, cut into lines of the panel's width
/// (ASCII: the library's messages are).
fn show<D: DrawTarget<Color = BinaryColor>>(display: &mut D, text: &str) -> Result<(), D::Error> {
    let style = MonoTextStyleBuilder::new()
        .font(&FONT_6X10)
        .text_color(BinaryColor::On)
        .background_color(BinaryColor::Off)
        .build();
    let per_line = (display.bounding_box().size.width as usize / 6).max(1);
    for (row, line) in text.as_bytes().chunks(per_line).enumerate() {
        let line = core::str::from_utf8(line).unwrap_or("?");
        Text::with_baseline(line, Point::new(0, 10 * row as i32), style, Baseline::Top).draw(display)?;
    }
    Ok(())
}

/// The status line: the kernel and its frame rate, or the error.
fn status<E: Debug>(drawn: &Result<Kernel, Failed<E>>, us: u64, flush_errors: u32) -> heapless::String<256> {
    let mut s = heapless::String::new();
    let tenths = 10_000_000 / us.max(1);
    // A `String` only fails when full; 256 bytes hold every message here.
    let written = match drawn {
        Ok(Kernel::Integer) => write!(s, "int {}.{} fps", tenths / 10, tenths % 10),
        Ok(Kernel::F32) => write!(s, "f32 {}.{} fps", tenths / 10, tenths % 10),
        Err(Failed::Camera(e)) => write!(s, "camera: {e}"),
        Err(Failed::Frame(e)) => write!(s, "{e}"),
        Err(Failed::Display(e)) => write!(s, "display: {e:?}"),
    }
    .and_then(|()| match flush_errors {
        0 => Ok(()),
        n => write!(s, " {n} I2C err"),
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
    let timer = Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);
    let sio = Sio::new(pac.SIO);
    let pins = hal::gpio::Pins::new(pac.IO_BANK0, pac.PADS_BANK0, sio.gpio_bank0, &mut pac.RESETS);

    // I2C0 on GP4 (SDA) and GP5 (SCL) at 400 kHz, the SSD1306's fast mode; the
    // modules carry their own pull-ups, the pins' internal ones help short wires.
    let sda = pins.gpio4.reconfigure::<FunctionI2c, PullUp>();
    let scl = pins.gpio5.reconfigure::<FunctionI2c, PullUp>();
    let i2c = hal::I2C::i2c0(
        pac.I2C0,
        sda,
        scl,
        400.kHz(),
        &mut pac.RESETS,
        &clocks.system_clock,
    );
    let mut display = Ssd1306::new(
        I2CDisplayInterface::new(i2c),
        DisplaySize128x64,
        DisplayRotation::Rotate0,
    )
    .into_buffered_graphics_mode();
    if display.init().is_err() {
        panic!("display init failed (no SSD1306 at 0x3C?)");
    }

    let size = display.bounding_box().size;
    let mut angle = 0.0f32;
    let mut flush_errors = 0u32;
    let mut last_us = 0u64;
    loop {
        let start = timer.get_counter().ticks();
        // The frame into the driver's buffer, the last frame's figures over it, then
        // the buffer to the panel (1 KiB over I²C).
        let drawn = frame(&mut display, orbit::orbit(&scenes::LAB_CAMERA, angle, size));
        let shown = show(&mut display, &status(&drawn, last_us, flush_errors));
        // Drawing into the buffer cannot fail (its error type is the flush's); the
        // flush's errors are counted and shown once the panel takes a frame again.
        if shown.is_err() || display.flush().is_err() {
            flush_errors = flush_errors.saturating_add(1);
        }
        last_us = timer.get_counter().ticks().wrapping_sub(start);
        angle = orbit::next_angle(angle);
    }
}
