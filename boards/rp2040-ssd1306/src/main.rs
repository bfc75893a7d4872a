//! Raspberry Pi Pico (RP2040, Cortex-M0+, no FPU) driving a 128×64 SSD1306 OLED over
//! I²C: the integer kernel draws `scenes/circling.toml` (three spheres circling, the
//! library's motion) through the library's ordered dither (`embedded_raytracer::dither`:
//! shading as a dot density on a 1-bit panel) into the driver's frame buffer, frame
//! after frame through `Incremental` (only what the moving spheres can have changed),
//! and the driver sends the buffer's changed area; where the integer kernel's rule refuses a frame, the `f32` kernel draws it.
//! The top line says which kernel drew the last frame, its frame rate and the share of
//! the panel drawn, or why the frame was not drawn.
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

mod frame;
mod scenes;

use embedded_graphics::prelude::*;
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
    let film = frame::Film {
        scene: &scenes::CIRCLING,
        camera: scenes::CIRCLING_CAMERA.with_size(size),
        animation: &scenes::CIRCLING_ANIMATION,
    };
    let mut scene = scenes::CIRCLING.clone();
    let mut shown = embedded_raytracer::Incremental::new();
    let mut flush_errors = 0u32;
    // The time of the last frame, from its start to the end of its flush; none before
    // the first has been timed.
    let mut last_us = None;
    let mut k = 0u32;
    loop {
        let start = timer.get_counter().ticks();
        // The frame's changes into the driver's buffer, the last frame's figures over
        // it, then the buffer's changed area to the panel (at most 1 KiB over I²C).
        let drawn = frame::frame(&mut display, &mut shown, &film, k, &mut scene);
        let line = frame::status(&drawn, last_us, size.width * size.height, flush_errors);
        let shown_line = frame::show(&mut display, &mut shown, &line);
        // Drawing into the buffer cannot fail (its error type is the flush's); a
        // failed flush leaves the panel unknown, so the next frame is drawn whole.
        if shown_line.is_err() || display.flush().is_err() {
            flush_errors = flush_errors.saturating_add(1);
            shown.invalidate();
        }
        last_us = Some(timer.get_counter().ticks().wrapping_sub(start));
        // The motion repeats after `frames()` frames exactly: counting within one
        // loop keeps every frame's time as exact as the first loop's.
        k = (k + 1) % film.animation.frames();
    }
}
