//! The simple Pico example: one core, the integer kernel drawing `scenes/circling.toml`
//! (three spheres circling, the library's motion; `../../scenes.rs`, the same as the
//! two-core example's) straight into a 240×240 ST7789 through `mipidsi` (its bytes
//! sent by DMA while the core traces on: `dma_spi.rs`), frame after frame through
//! `Incremental`: only what the moving spheres can have changed is traced
//! and sent. Where the integer kernel's per-frame rule refuses a frame,
//! the `f32` kernel draws it; the top line says which kernel drew the last frame, its
//! frame rate and the share of the panel sent, or what went wrong.
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

mod dma_spi;
mod frame;
#[path = "../../scenes.rs"]
mod scenes;

use core::cell::RefCell;
use embedded_graphics::prelude::*;
use mipidsi::{interface::SpiInterface, models::ST7789, options::ColorInversion, Builder};
use panic_halt as _;
use rp2040_hal::{
    self as hal, clocks::Clock, dma::DMAExt, fugit::RateExtU32, gpio::FunctionSpi, pac, Sio, Timer, Watchdog,
};

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
    let mut timer = Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);
    let sio = Sio::new(pac.SIO);
    let pins = hal::gpio::Pins::new(pac.IO_BANK0, pac.PADS_BANK0, sio.gpio_bank0, &mut pac.RESETS);

    // SPI1 at 62.5 MHz, mode 3: 125 MHz / 2 (prescale 2, SCR 0) is the rate asked.
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

    // The bytes go out by DMA while the core traces on (dma_spi.rs): two chunk
    // buffers, DMA channel 0.
    let (Some(a), Some(b)) = (
        cortex_m::singleton!(: [u8; dma_spi::CHUNK] = [0; dma_spi::CHUNK]),
        cortex_m::singleton!(: [u8; dma_spi::CHUNK] = [0; dma_spi::CHUNK]),
    ) else {
        panic!("chunk buffers taken twice");
    };
    let ch = pac.DMA.split(&mut pac.RESETS).ch0;
    let bus = RefCell::new(dma_spi::Bus::new(
        ch,
        spi,
        [dma_spi::Chunk::new(a), dma_spi::Chunk::new(b)],
        cs,
        dc,
    ));
    let mut buffer = [0u8; dma_spi::CHUNK];
    let interface = SpiInterface::new(dma_spi::Device(&bus), dma_spi::Dc(&bus), &mut buffer);
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
        scene: &scenes::CIRCLING,
        camera: scenes::CIRCLING_CAMERA.with_size(size),
        animation: &scenes::CIRCLING_ANIMATION,
    };
    let mut scene = scenes::CIRCLING.clone();
    let mut shown = embedded_raytracer::Incremental::new();
    let mut display_errors = 0u32;
    let mut k = 0u32;
    loop {
        let start = timer.get_counter().ticks();
        let drawn = frame::frame(&mut display, &mut shown, &film, k, &mut scene);
        // The frame ends on the panel: its last bytes off the wire.
        if let Ok(mut bus) = bus.try_borrow_mut() {
            bus.finish();
        }
        let us = timer.get_counter().ticks().wrapping_sub(start);
        // Drawn over the picture; if the display cannot take it, nothing else can
        // show it: counted, and shown once it can.
        let line = frame::status(&drawn, us, size.width * size.height, display_errors);
        if frame::show(&mut display, &mut shown, &line).is_err() {
            display_errors = display_errors.saturating_add(1);
        }
        // The status line on the panel before the next frame starts.
        if let Ok(mut bus) = bus.try_borrow_mut() {
            bus.finish();
        }
        // The motion repeats after `frames()` frames exactly: counting within one
        // loop keeps every frame's time as exact as the first loop's.
        k = (k + 1) % film.animation.frames();
    }
}
