//! The STM32F407 + ST7789 board of the root example `examples/stm32f407_st7789` (same
//! wiring), with tracing
//! overlapped with the SPI transfer: the frame is traced in bands of 16 rows into two
//! band buffers, and while DMA2 (stream 3, channel 3: SPI1_TX) sends one band to the
//! display, the core traces the next into the other. SPI1 runs at 42 MHz (APB2 84 MHz
//! / 2, the fastest SPI1 clock). The camera orbits the lab scene's look-at point, 5° per
//! frame, and the top-left corner shows the last frame's rate, time and how much of it
//! the core spent waiting for the wire (DWT cycle counter) — or, if a band could not be
//! traced (it goes out dark red), why.
//!
//! ```sh
//! cargo build --release     # in boards/stm32f407: .cargo/config.toml sets the target
//! cargo run --release       # flashes it with probe-rs (STM32F407VGTx) and runs it
//! ```
//!
//! Builds in CI; not tested on hardware. Wiring: as the root example (README.md here), SCK PA5, MOSI PA7, DC PB0, RST PB1, CS PB12; PE3 high on the
//! STM32F4DISCOVERY.
//!
//! Per frame:
//! 1. the address window (CASET, RASET: the whole 240×240 panel) and RAMWR, written
//!    byte by byte on SPI1 with DC low for each command byte; then DC high for the data;
//! 2. band 0 (already traced, see 4) goes out by DMA;
//! 3. for k = 1 … 14: trace band k into the free buffer, wait for the transfer in
//!    flight, start band k and take back the buffer it freed;
//! 4. while band 14 is on the wire: band 0 of the next frame, with the frame-time label
//!    drawn over it; then wait for band 14 and for SPI1 to finish shifting it out.
//!
//! The bands are traced straight into the wire format: `WireRgb565`
//! (`st7789_band.rs`) is a colour whose two bytes are the Rgb565 value
//! high byte first, the order the ST7789 reads a 16-bit pixel in, so `draw_band` writes
//! what DMA sends and there is no second pass over the band (it would read and write
//! every pixel once more, and need a third buffer to trace into).
//! The lab's `band_cycles` firmware estimates the cycles of this band path
//! (`docs/firmware.md`).
#![no_std]
#![no_main]

mod scenes;
mod st7789_band;

mod fw {
    use core::fmt::Write as _;

    use cortex_m::peripheral::DWT;
    use cortex_m_rt::entry;
    use embedded_graphics::prelude::*;
    use embedded_hal_bus::spi::ExclusiveDevice;
    use embedded_raytracer::{Camera, Vec3};
    use mipidsi::{interface::SpiInterface, models::ST7789, options::ColorInversion, Builder};
    use panic_halt as _;
    use stm32f4xx_hal::{
        dma::{config::DmaConfig, DMAError, MemoryToPeripheral, Stream3, StreamsTuple, Transfer},
        gpio::{PinState, Speed},
        pac,
        prelude::*,
        rcc::Config,
        spi::{Mode, Phase, Polarity, Spi},
    };

    use crate::scenes;
    use crate::st7789_band::{
        draw_label, take_refused, trace_band, WireRgb565, BANDS, BAND_PIXELS, HEIGHT, WIDTH,
    };

    /// The orbit's step per frame (5°).
    const STEP: f32 = 5.0 * (core::f32::consts::PI / 180.0);

    /// ST7789 commands (datasheet, "System function command table 1").
    const CASET: u8 = 0x2A;
    const RASET: u8 = 0x2B;
    const RAMWR: u8 = 0x2C;

    /// A band buffer: `'static`, so DMA may own it while a transfer runs.
    type Band = &'static mut [WireRgb565; BAND_PIXELS];

    /// SPI1 fed by DMA2 stream 3 on channel 3 (RM0090, "DMA2 request mapping").
    type BandTransfer = Transfer<Stream3<pac::DMA2>, 3, pac::SPI1, MemoryToPeripheral, Band>;

    /// Waits until SPI1 has shifted out everything written to it (TXE, then BSY: the
    /// reference manual's order), so that DC or CS may change.
    fn wait_idle(spi: &pac::SPI1) {
        while spi.sr().read().txe().bit_is_clear() {}
        while spi.sr().read().bsy().bit_is_set() {}
    }

    /// Writes `bytes` on SPI1 without DMA, then waits until they are out.
    fn write_blocking(spi: &pac::SPI1, bytes: &[u8]) {
        for &byte in bytes {
            while spi.sr().read().txe().bit_is_clear() {}
            spi.dr().write(|w| w.dr().set(u16::from(byte)));
        }
        wait_idle(spi);
    }

    /// Step 1 of a frame: the address window (the whole panel) and RAMWR; leaves DC
    /// high, ready for the pixels.
    fn start_frame(
        spi: &pac::SPI1,
        dc: &mut impl embedded_hal::digital::OutputPin<Error = core::convert::Infallible>,
    ) {
        let [x1_hi, x1_lo] = ((WIDTH - 1) as u16).to_be_bytes();
        let [y1_hi, y1_lo] = ((HEIGHT - 1) as u16).to_be_bytes();
        for (command, params) in [(CASET, [0, 0, x1_hi, x1_lo]), (RASET, [0, 0, y1_hi, y1_lo])] {
            let Ok(()) = dc.set_low();
            write_blocking(spi, &[command]);
            let Ok(()) = dc.set_high();
            write_blocking(spi, &params);
        }
        let Ok(()) = dc.set_low();
        write_blocking(spi, &[RAMWR]);
        let Ok(()) = dc.set_high();
    }

    /// Cycles as milliseconds with one decimal, for the label.
    fn tenths_of_ms(cycles: u32, sysclk_hz: u32) -> (u64, u64) {
        let tenths = u64::from(cycles) * 10_000 / u64::from(sysclk_hz);
        (tenths / 10, tenths % 10)
    }

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

        // 42 MHz = 84 MHz / 2; the pins at their fastest edges, which a 42 MHz clock
        // needs (the HAL's note on `Spi::new`). Mode 3, as in the blocking example. If
        // a module with long wires garbles the picture, 21 MHz halves the wire rate
        // (the frame then costs at least the 43.9 ms the wire takes).
        let sck = gpioa.pa5.into_alternate().speed(Speed::VeryHigh);
        let mosi = gpioa.pa7.into_alternate().speed(Speed::VeryHigh);
        let mut spi = Spi::new(
            dp.SPI1,
            (Some(sck), pac::SPI1::NoMiso, Some(mosi)),
            Mode {
                polarity: Polarity::IdleHigh,
                phase: Phase::CaptureOnSecondTransition,
            },
            42.MHz(),
            &mut rcc,
        );
        let mut cs = gpiob.pb12.into_push_pull_output_in_state(PinState::High);
        let mut dc = gpiob.pb0.into_push_pull_output();
        let mut rst = gpiob.pb1.into_push_pull_output();

        cp.DCB.enable_trace();
        cp.DWT.enable_cycle_counter();
        let mut delay = cp.SYST.delay(&rcc.clocks);

        // The controller's reset and init sequence through mipidsi, exactly as in the
        // blocking example; the driver only borrows the bus and the pins and is dropped
        // afterwards, so the frames below can drive SPI1 themselves.
        {
            let Ok(spi_device) = ExclusiveDevice::new_no_delay(&mut spi, &mut cs);
            let mut buffer = [0u8; 16];
            let interface = SpiInterface::new(spi_device, &mut dc, &mut buffer);
            if Builder::new(ST7789, interface)
                .display_size(WIDTH as u16, HEIGHT as u16)
                .invert_colors(ColorInversion::Inverted) // IPS ST7789 panels are inverted
                .reset_pin(&mut rst)
                .init(&mut delay)
                .is_err()
            {
                panic!("display init failed");
            }
        }

        // SPI1 as a DMA peripheral: the register block (the pins keep their alternate
        // function), with TX DMA requests on. The HAL's `use_dma().tx()` would do the
        // same but hide the status register, which step 1 and the end of a frame read
        // before DC or CS may change.
        let (mut spi1, _pins) = spi.release();
        spi1.cr2().modify(|_, w| w.txdmaen().enabled());
        let mut stream = StreamsTuple::new(dp.DMA2, &mut rcc).3;
        // Byte to byte, memory address incrementing, FIFO off (direct mode).
        let dma_config = DmaConfig::default().memory_increment(true);

        let (Some(mut front), Some(mut back)) = (
            cortex_m::singleton!(: [WireRgb565; BAND_PIXELS] = [WireRgb565::BLACK; BAND_PIXELS]),
            cortex_m::singleton!(: [WireRgb565; BAND_PIXELS] = [WireRgb565::BLACK; BAND_PIXELS]),
        ) else {
            panic!("band buffers taken twice");
        };

        let size = Size::new(WIDTH, HEIGHT);
        let lab = scenes::LAB_CAMERA;
        let offset = lab.eye - lab.look_at;
        // Orbit the lab camera's eye around the look-at point (about +y).
        let camera_at = |angle: f32| {
            let (s, c) = (libm::sinf(angle), libm::cosf(angle));
            let eye =
                lab.look_at + Vec3::new(c * offset.x + s * offset.z, offset.y, c * offset.z - s * offset.x);
            Camera::new(eye, lab.look_at, lab.up, lab.fov_y, size).ok()
        };

        let mut angle = 0.0f32;
        let mut camera = camera_at(angle);
        trace_band(camera.as_ref(), 0, &mut front[..]);
        // The cycle count at the last frame's step 1, and the cycles spent waiting for
        // the wire since then.
        let mut last_start: Option<u32> = None;
        let mut waited = 0u32;
        // The last complete frame's time and waiting time, for the label.
        let mut shown: Option<(u32, u32)> = None;
        loop {
            let start = DWT::cycle_count();
            if let Some(last) = last_start {
                shown = Some((start.wrapping_sub(last), waited));
            }
            last_start = Some(start);

            // Step 1: chip select, address window, RAMWR.
            cs.set_low();
            start_frame(&spi1, &mut dc);
            waited = DWT::cycle_count().wrapping_sub(start);

            // Step 2: band 0 on the wire.
            let mut transfer: BandTransfer =
                Transfer::init_memory_to_peripheral(stream, spi1, front, None, dma_config);
            transfer.start(|_| {});

            // Step 3: trace band k while band k − 1 is on the wire.
            for k in 1..BANDS {
                trace_band(camera.as_ref(), k, &mut back[..]);
                let wait_start = DWT::cycle_count();
                transfer.wait();
                waited = waited.wrapping_add(DWT::cycle_count().wrapping_sub(wait_start));
                // Not double-buffered: this restarts the stream on `back` and never
                // fails; an error would hand `back` back unsent.
                back = match transfer.next_transfer(back) {
                    Ok((sent, _)) => sent,
                    Err(
                        DMAError::NotReady(unsent)
                        | DMAError::SmallBuffer(unsent)
                        | DMAError::Overrun(unsent),
                    ) => unsent,
                };
            }

            // Step 4: the next frame's band 0, with the last complete frame's figures
            // over it, while this frame's last band is on the wire.
            angle = (angle + STEP) % (2.0 * core::f32::consts::PI);
            camera = camera_at(angle);
            trace_band(camera.as_ref(), 0, &mut back[..]);
            // The top line: why a band of the last frame could not be traced, or the
            // last complete frame's rate, time and wait.
            let mut label = heapless::String::<40>::new();
            let written = match (take_refused(), shown) {
                (Some(why), _) => write!(label, "error: {why}"),
                (None, Some((frame, wait))) => {
                    let (frame_ms, frame_tenth) = tenths_of_ms(frame, sysclk_hz);
                    let (wait_ms, wait_tenth) = tenths_of_ms(wait, sysclk_hz);
                    let fps_tenths = u64::from(sysclk_hz) * 10 / u64::from(frame.max(1));
                    write!(
                        label,
                        "{}.{} fps {frame_ms}.{frame_tenth} ms wait {wait_ms}.{wait_tenth}",
                        fps_tenths / 10,
                        fps_tenths % 10
                    )
                }
                (None, None) => Ok(()),
            };
            // 40 characters fill the line; a longer label is cut.
            if written.is_err() {
                label.truncate(39);
            }
            draw_label(&mut back[..], &label);
            let wait_start = DWT::cycle_count();
            transfer.wait();
            let sent;
            (stream, spi1, sent, _) = transfer.release();
            wait_idle(&spi1);
            cs.set_high();
            waited = waited.wrapping_add(DWT::cycle_count().wrapping_sub(wait_start));
            front = back;
            back = sent;
        }
    }
}
