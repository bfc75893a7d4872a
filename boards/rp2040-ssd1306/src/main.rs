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

mod frame;
mod orbit;
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
    let mut angle = 0.0f32;
    let mut flush_errors = 0u32;
    let mut last_us = 0u64;
    loop {
        let start = timer.get_counter().ticks();
        // The frame into the driver's buffer, the last frame's figures over it, then
        // the buffer to the panel (1 KiB over I²C).
        let drawn = frame::frame(
            &mut display,
            &scenes::LAB,
            orbit::orbit(&scenes::LAB_CAMERA, angle, size),
        );
        let shown = frame::show(&mut display, &frame::status(&drawn, last_us, flush_errors));
        // Drawing into the buffer cannot fail (its error type is the flush's); the
        // flush's errors are counted and shown once the panel takes a frame again.
        if shown.is_err() || display.flush().is_err() {
            flush_errors = flush_errors.saturating_add(1);
        }
        last_us = timer.get_counter().ticks().wrapping_sub(start);
        angle = orbit::next_angle(angle);
    }
}
