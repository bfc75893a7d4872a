//! ESP32-C3 (one RV32IMC core at 160 MHz, no FPU) driving a 240×240 ST7789 over SPI2
//! through `mipidsi`: the integer kernel draws `scenes/circling.toml` (three spheres
//! circling, the library's motion), frame after frame through `Incremental`, which
//! traces and sends only what the moving spheres can have changed; where the
//! integer kernel's rule refuses a frame, the `f32` kernel (soft float) draws it. The
//! top line says which kernel drew the last frame, its frame rate and the share of the
//! panel sent, or why the frame was not drawn.
//!
//! ```sh
//! cargo build --release
//! espflash flash --monitor --chip esp32c3 target/riscv32imc-unknown-none-elf/release/esp32c3-st7789
//! ```
//!
//! Wiring (README.md): SCK GPIO6, MOSI GPIO7, CS GPIO10, DC GPIO3, RST GPIO4, BL GPIO5.
//! Builds in CI on stable Rust; not run on hardware.
#![no_std]
#![no_main]

mod frame;
mod scenes;

use embedded_graphics::prelude::*;
use embedded_hal_bus::spi::ExclusiveDevice;
use esp_hal::clock::CpuClock;
use esp_hal::delay::Delay;
use esp_hal::gpio::{Level, Output, OutputConfig};
use esp_hal::spi::{master::Spi, Mode};
use esp_hal::time::{Instant, Rate};
use mipidsi::options::{ColorInversion, Orientation, Rotation};
use mipidsi::{interface::SpiInterface, models::ST7789, Builder};
use panic_halt as _;

// The application descriptor the ESP-IDF second-stage bootloader looks for in the
// image; without it the bootloader refuses to start the firmware.
esp_bootloader_esp_idf::esp_app_desc!();

#[esp_hal::main]
fn main() -> ! {
    // `init` also turns off the watchdogs the boot ROM and bootloader leave running (the
    // RTC and timer-group watchdogs), so a frame that takes seconds resets nothing. If
    // you enable one, feed it once a frame.
    let peripherals = esp_hal::init(esp_hal::Config::default().with_cpu_clock(CpuClock::max()));
    let mut delay = Delay::new();

    // SPI2 at 40 MHz (80 MHz / 2; the ST7789 is specified to 62.5 MHz), mode 3.
    let Ok(spi) = Spi::new(
        peripherals.SPI2,
        esp_hal::spi::master::Config::default()
            .with_frequency(Rate::from_mhz(40))
            .with_mode(Mode::_3),
    ) else {
        panic!("SPI configuration refused");
    };
    let spi = spi.with_sck(peripherals.GPIO6).with_mosi(peripherals.GPIO7);
    let cs = Output::new(peripherals.GPIO10, Level::High, OutputConfig::default());
    let dc = Output::new(peripherals.GPIO3, Level::Low, OutputConfig::default());
    let rst = Output::new(peripherals.GPIO4, Level::High, OutputConfig::default());
    let _backlight = Output::new(peripherals.GPIO5, Level::High, OutputConfig::default());

    let Ok(spi_device) = ExclusiveDevice::new_no_delay(spi, cs);
    let mut buffer = [0u8; 512];
    let interface = SpiInterface::new(spi_device, dc, &mut buffer);
    // A 240×240 panel on the ST7789's 240×320 memory: the offset is (0, 0) upright, and
    // mipidsi moves it to (0, 80) itself when the picture is turned by 180°. A module
    // whose glass sits at rows 80–319 needs `.display_offset(0, 80)` (README.md).
    let Ok(mut display) = Builder::new(ST7789, interface)
        .display_size(240, 240)
        .orientation(Orientation::new().rotate(Rotation::Deg0))
        .invert_colors(ColorInversion::Inverted) // IPS ST7789 panels are inverted
        .reset_pin(rst)
        .init(&mut delay)
    else {
        panic!("display init failed");
    };

    let size = display.bounding_box().size;
    let film = frame::Film {
        scene: &scenes::CIRCLING,
        camera: scenes::CIRCLING_CAMERA.with_size(size),
        animation: &scenes::CIRCLING_ANIMATION,
    };
    let mut scene = scenes::CIRCLING.clone();
    let mut shown = embedded_raytracer::Incremental::new();
    let mut display_errors = 0u32;
    let mut k = 0u32;
    loop {
        let start = Instant::now();
        let drawn = frame::frame(&mut display, &mut shown, &film, k, &mut scene);
        let us = start.elapsed().as_micros();
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
