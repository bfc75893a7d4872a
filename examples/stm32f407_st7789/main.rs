//! A real board: an STM32F407 (STM32F4DISCOVERY, or any F405/F407 board with an 8 MHz
//! crystal) driving a 240×240 ST7789 SPI LCD through `mipidsi`. Renders `scenes/lab.toml`
//! at 240×240 (its camera, size replaced), then bounces its small yellow sphere (the
//! library's motion, `embedded_raytracer::motion`), frame after frame through
//! `Incremental`: only the pixels the sphere can have changed are
//! traced and sent. The top-left corner shows each frame's rate, time (render + SPI
//! transfer, measured with the DWT cycle counter) and the share of the panel sent, or
//! why the frame was not drawn.
//!
//! ```sh
//! cargo build --release --example stm32f407_st7789 --target thumbv7em-none-eabihf
//! probe-rs run --chip STM32F407VGTx target/thumbv7em-none-eabihf/release/examples/stm32f407_st7789
//! ```
//!
//! Builds in CI; not tested on hardware. `cargo run` with the same arguments flashes it
//! through a debug probe (`.cargo/config.toml`'s runner). The memory map is the
//! repository root's `memory.x`. Wiring:
//!
//! | LCD pin | STM32F407 | note |
//! |---|---|---|
//! | SCL / SCK | PA5 | SPI1 SCK (AF5), 21 MHz, mode 3 |
//! | SDA / MOSI | PA7 | SPI1 MOSI (AF5) |
//! | DC | PB0 | data/command |
//! | RES / RST | PB1 | reset |
//! | CS | PB12 | chip select (modules without CS work too: SPI mode 3) |
//! | BLK | 3V3 | backlight on |
//! | VCC, GND | 3V3, GND | |
//!
//! On the STM32F4DISCOVERY, SPI1 (PA5–PA7) also reaches the on-board accelerometer:
//! PE3, its chip select, is driven high so it stays off the bus.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(all(target_os = "none", target_abi = "eabihf"))]
mod scenes;

#[cfg(all(target_os = "none", target_abi = "eabihf"))]
mod fw {
    use core::fmt::Write as _;

    use cortex_m::peripheral::DWT;
    use cortex_m_rt::entry;
    use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyleBuilder};
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_graphics::prelude::*;
    use embedded_graphics::text::{Baseline, Text};
    use embedded_hal_bus::spi::ExclusiveDevice;
    use embedded_raytracer::motion::{Animation, Bounce, Motion, MotionError};
    use embedded_raytracer::{CameraError, FrameError, FrameStats, Incremental, Render};
    use mipidsi::{interface::SpiInterface, models::ST7789, options::ColorInversion, Builder};
    use panic_halt as _;
    use stm32f4xx_hal::{
        gpio::PinState,
        pac,
        prelude::*,
        rcc::Config,
        spi::{Mode, Phase, Polarity, Spi},
    };

    use crate::scenes;

    /// Why a frame was not drawn.
    enum Refused {
        Camera(CameraError),
        Motion(MotionError),
        Frame(FrameError),
        Display,
    }

    /// The small yellow sphere (sphere 3) bounces 1.2 units high every 0.96 s: 24
    /// frames at the motion's 25 frames a second, after which it repeats exactly.
    const ANIMATION: Animation<1> = Animation::from_array([Motion::Bounce(Bounce::new(3, 1.2, 0.96))]);

    #[entry]
    fn main() -> ! {
        let (Some(dp), Some(mut cp)) = (pac::Peripherals::take(), cortex_m::Peripherals::take()) else {
            panic!("peripherals taken twice");
        };

        // 8 MHz HSE crystal → 168 MHz SYSCLK; SPI1 sits on APB2 (84 MHz).
        let mut rcc = dp.RCC.freeze(Config::hse(8.MHz()).sysclk(168.MHz()));
        let sysclk_hz = rcc.clocks.sysclk().raw();

        let gpioa = dp.GPIOA.split(&mut rcc);
        let gpiob = dp.GPIOB.split(&mut rcc);
        let gpioe = dp.GPIOE.split(&mut rcc);
        // STM32F4DISCOVERY: deselect the accelerometer that shares SPI1.
        let _accel_cs = gpioe.pe3.into_push_pull_output_in_state(PinState::High);

        // Mode 3 works with and without a CS pin on ST7789 modules; 21 MHz = 84 MHz / 4.
        let spi = Spi::new(
            dp.SPI1,
            (Some(gpioa.pa5), pac::SPI1::NoMiso, Some(gpioa.pa7)),
            Mode {
                polarity: Polarity::IdleHigh,
                phase: Phase::CaptureOnSecondTransition,
            },
            21.MHz(),
            &mut rcc,
        );
        let cs = gpiob.pb12.into_push_pull_output_in_state(PinState::High);
        let dc = gpiob.pb0.into_push_pull_output();
        let rst = gpiob.pb1.into_push_pull_output();

        cp.DCB.enable_trace();
        cp.DWT.enable_cycle_counter();
        let mut delay = cp.SYST.delay(&rcc.clocks);
        let Ok(spi_device) = ExclusiveDevice::new_no_delay(spi, cs);
        let mut buffer = [0u8; 512];
        let interface = SpiInterface::new(spi_device, dc, &mut buffer);
        let Ok(mut display) = Builder::new(ST7789, interface)
            .display_size(240, 240)
            .invert_colors(ColorInversion::Inverted) // IPS ST7789 panels are inverted
            .reset_pin(rst)
            .init(&mut delay)
        else {
            panic!("display init failed");
        };

        let size = display.bounding_box().size;
        let base_camera = scenes::LAB_CAMERA.with_size(size);
        let mut scene = scenes::LAB.clone();
        // What the display shows: the next frame traces and sends only what changed.
        let mut shown = Incremental::new();
        let text_style = MonoTextStyleBuilder::new()
            .font(&FONT_6X10)
            .text_color(Rgb565::WHITE)
            .background_color(Rgb565::BLACK)
            .build();
        let mut n = 0u32;
        // Labels the display did not take.
        let mut label_errors = 0u32;
        loop {
            let start = DWT::cycle_count();
            // Rgb888 → Rgb565 inferred from the display. An error is shown, not
            // discarded: a camera the kernel refuses, a frame it cannot draw exactly
            // (`check`: the frame would be left undrawn), or a display that failed a
            // write (its content is then unknown: the next frame is drawn whole).
            let mut label = heapless::String::<200>::new();
            let mut params = base_camera;
            let moved = ANIMATION.apply_frame(&scenes::LAB, &base_camera, n, &mut scene, &mut params);
            let drawn = match (moved, params.build()) {
                (Err(e), _) => Err(Refused::Motion(e)),
                (Ok(()), Err(e)) => Err(Refused::Camera(e)),
                (Ok(()), Ok(camera)) => {
                    let render = Render::new(&scene, &camera);
                    match render.check() {
                        Ok(()) => match shown.draw(&render, &mut display) {
                            Ok(FrameStats { refused: Some(e), .. }) => Err(Refused::Frame(e)),
                            Ok(stats) => Ok(stats),
                            Err(_) => {
                                shown.invalidate();
                                Err(Refused::Display)
                            }
                        },
                        Err(e) => Err(Refused::Frame(e)),
                    }
                }
            };
            let cycles = DWT::cycle_count().wrapping_sub(start);
            let tenths = u64::from(sysclk_hz) * 10 / u64::from(cycles.max(1));
            let written = match drawn {
                Ok(stats) => write!(
                    label,
                    "{}.{} fps {} ms sent {}%",
                    tenths / 10,
                    tenths % 10,
                    u64::from(cycles) * 1000 / u64::from(sysclk_hz),
                    u64::from(stats.sent) * 100 / u64::from(size.width * size.height)
                ),
                Err(Refused::Camera(e)) => write!(label, "camera: {e}"),
                Err(Refused::Motion(e)) => write!(label, "motion: {e}"),
                Err(Refused::Frame(e)) => write!(label, "{e}"),
                Err(Refused::Display) => write!(label, "display write failed"),
            };
            let written = written.and_then(|()| match label_errors {
                0 => Ok(()),
                n => write!(label, " ({n} labels failed)"),
            });
            // 200 bytes hold every message; a longer one would be cut.
            if written.is_err() {
                label.truncate(199);
            }
            // Lines of 39 characters (FONT_6X10 on 240 pixels; the messages are ASCII),
            // drawn on the display that just failed, if it did: nothing else can show
            // it, so a failure here is counted and shown once the display takes it.
            // Each line covers part of the picture: `shown` is told, so that the next
            // frame restores it.
            let mut label_shown = Ok(Point::zero());
            for (row, line) in label.as_bytes().chunks(39).enumerate() {
                let line = core::str::from_utf8(line).unwrap_or("?");
                let text = Text::with_baseline(
                    line,
                    Point::new(2, 2 + 10 * row as i32),
                    text_style,
                    Baseline::Top,
                );
                shown.invalidate_area(text.bounding_box());
                label_shown = label_shown.and(text.draw(&mut display));
            }
            if label_shown.is_err() {
                label_errors = label_errors.saturating_add(1);
            }
            // The motion repeats after `frames()` frames exactly: counting within one
            // loop keeps every frame's time as exact as the first loop's.
            n = (n + 1) % ANIMATION.frames();
        }
    }
}

#[cfg(all(target_os = "none", not(target_abi = "eabihf")))]
compile_error!("stm32f407_st7789 is Cortex-M4F firmware: build it with --target thumbv7em-none-eabihf");

// On the host (`cargo test` builds every example) there is nothing to run.
#[cfg(not(target_os = "none"))]
fn main() {
    println!(
        "stm32f407_st7789 is firmware: cargo build --release --example stm32f407_st7789 --target thumbv7em-none-eabihf"
    );
}
