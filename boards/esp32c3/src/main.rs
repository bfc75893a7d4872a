//! ESP32-C3 (one RV32IMC core at 160 MHz, no FPU) driving a 240×240 ST7789 over SPI2
//! through `mipidsi`: the integer kernel draws the lab scene, the camera orbiting 5° a
//! frame (`orbit.rs`); where the integer kernel's rule refuses a frame, the `f32`
//! kernel (soft float) draws it. The top line says which kernel drew the last frame and
//! its frame rate, or why the frame was not drawn.
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

mod orbit;
mod scenes;

use core::fmt::{Debug, Write as _};

use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyleBuilder};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::text::{Baseline, Text};
use embedded_hal_bus::spi::ExclusiveDevice;
use embedded_raytracer::{Camera, CameraError, FrameError, IntegerError, Render};
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

/// Which kernel drew a frame.
enum Kernel {
    Integer,
    F32,
}

/// Why a frame was not drawn.
enum Failed<E> {
    Camera(CameraError),
    Frame(FrameError),
    Display(E),
}

/// One frame, in one call: the integer kernel, or the `f32` kernel where the integer
/// kernel's rule refuses the frame (after `check`, since `draw` leaves a frame it
/// cannot draw exactly untouched).
fn frame<D: DrawTarget<Color = Rgb565>>(
    display: &mut D,
    camera: Result<Camera, CameraError>,
) -> Result<Kernel, Failed<D::Error>> {
    let camera = camera.map_err(Failed::Camera)?;
    let render = Render::new(&scenes::LAB, &camera);
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
    let mut angle = 0.0f32;
    let mut display_errors = 0u32;
    loop {
        let start = Instant::now();
        let drawn = frame(&mut display, orbit::orbit(&scenes::LAB_CAMERA, angle, size));
        let us = start.elapsed().as_micros();
        // Drawn over the picture; if the display cannot take it, nothing else can
        // show it: counted, and shown once it can.
        if show(&mut display, &status(&drawn, us, display_errors)).is_err() {
            display_errors = display_errors.saturating_add(1);
        }
        angle = orbit::next_angle(angle);
    }
}
