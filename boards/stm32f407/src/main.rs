//! The STM32F407 + ST7789 board of the root example `examples/stm32f407_st7789` (same
//! wiring), with incremental frames and tracing overlapped with the SPI transfer. The
//! lit ball of `scenes/bounce.toml` bounces on its checkered floor (the library's
//! motion); `Incremental::update` says, frame by frame, what changed since the frame
//! the display shows:
//! - a whole frame (the first, or one after an error) is traced in bands of 16 rows into
//!   two band buffers, and while DMA2 (stream 3, channel 3: SPI1_TX) sends one band to
//!   the display, the core traces the next into the other;
//! - any other frame traces only the changed pixels of the bands that hold a changed
//!   run (`Changes::draw_band`), and each run goes out in its own address window,
//!   written by the core (between two runs it sets the next window anyway, and a run
//!   is short).
//!
//! SPI1 runs at 42 MHz (APB2 84 MHz / 2, the fastest SPI1 clock). The top-left corner
//! shows the last frame's rate, time, how much of it the core spent waiting for the
//! wire (DWT cycle counter) and the share of the panel sent — or, if a band could not
//! be traced (it goes out dark red), why; the label is drawn over band 0 and redrawn
//! every frame (`Incremental::invalidate_area`).
//!
//! ```sh
//! cargo build --release     # in boards/stm32f407: .cargo/config.toml sets the target
//! cargo run --release       # flashes it with probe-rs (STM32F407VGTx) and runs it
//! ```
//!
//! Builds in CI; not tested on hardware. Wiring: as the root example (README.md here),
//! SCK PA5, MOSI PA7, DC PB0, RST PB1, CS PB12; PE3 high on the STM32F4DISCOVERY.
//!
//! A whole frame:
//! 1. band 0, with the label over it; the address window (CASET, RASET: the whole
//!    240×240 panel) and RAMWR, written byte by byte on SPI1 with DC low for each
//!    command byte; then DC high for the data;
//! 2. band 0 goes out by DMA;
//! 3. for k = 1 … 14: trace band k into the free buffer, wait for the transfer in
//!    flight, start band k and take back the buffer it freed;
//! 4. wait for band 14 and for SPI1 to finish shifting it out.
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

mod frame;
mod scenes;
// `trace_band` there traces the lab scene as the file has it, for the lab's
// `band_cycles` firmware; this one traces the moving scene (`trace` below).
#[allow(dead_code)]
mod st7789_band;

mod fw {
    use core::fmt::Write as _;
    use core::ops::Range;

    use cortex_m::peripheral::DWT;
    use cortex_m_rt::entry;
    use embedded_graphics::prelude::*;
    use embedded_graphics::primitives::Rectangle;
    use embedded_hal_bus::spi::ExclusiveDevice;
    use embedded_raytracer::{BandError, Camera, Incremental, Render, Scene};
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

    use crate::frame::{self, Wire};
    use crate::scenes;
    use crate::st7789_band::{draw_label, WireRgb565, BANDS, BAND_PIXELS, BAND_ROWS, HEIGHT, WIDTH};

    /// ST7789 commands (datasheet, "System function command table 1").
    const CASET: u8 = 0x2A;
    const RASET: u8 = 0x2B;
    const RAMWR: u8 = 0x2C;

    /// A band buffer: `'static`, so DMA may own it while a transfer runs.
    type Band = &'static mut [WireRgb565; BAND_PIXELS];

    /// SPI1 fed by DMA2 stream 3 on channel 3 (RM0090, "DMA2 request mapping").
    type BandTransfer = Transfer<Stream3<pac::DMA2>, 3, pac::SPI1, MemoryToPeripheral, Band>;

    /// The scene's frame on this panel.
    type Frame<'a> = Render<'a, 3, WireRgb565, 1, 1, 0>;

    /// Waits until SPI1 has shifted out everything written to it (TXE, then BSY: the
    /// reference manual's order), so that DC or CS may change.
    fn wait_idle(spi: &pac::SPI1) {
        while spi.sr().read().txe().bit_is_clear() {}
        while spi.sr().read().bsy().bit_is_set() {}
    }

    /// Writes `bytes` on SPI1 without DMA (not waiting for the last to go out).
    fn write(spi: &pac::SPI1, bytes: &[u8]) {
        for &byte in bytes {
            while spi.sr().read().txe().bit_is_clear() {}
            spi.dr().write(|w| w.dr().set(u16::from(byte)));
        }
    }

    /// SPI1 and the DC pin as the controller's wire, written by the core.
    struct Core<'a, DC> {
        spi: &'a pac::SPI1,
        dc: &'a mut DC,
    }

    impl<DC: embedded_hal::digital::OutputPin<Error = core::convert::Infallible>> Wire<WireRgb565>
        for Core<'_, DC>
    {
        /// The address window `x` × `y` and RAMWR; leaves DC high, ready for the pixels.
        fn window(&mut self, x: Range<u32>, y: Range<u32>) {
            let bounds = |r: Range<u32>| {
                let [a_hi, a_lo] = (r.start as u16).to_be_bytes();
                let [b_hi, b_lo] = (r.end.saturating_sub(1) as u16).to_be_bytes();
                [a_hi, a_lo, b_hi, b_lo]
            };
            // DC may change only once the bytes before it are out.
            for (command, params) in [(CASET, bounds(x)), (RASET, bounds(y))] {
                wait_idle(self.spi);
                let Ok(()) = self.dc.set_low();
                write(self.spi, &[command]);
                wait_idle(self.spi);
                let Ok(()) = self.dc.set_high();
                write(self.spi, &params);
            }
            wait_idle(self.spi);
            let Ok(()) = self.dc.set_low();
            write(self.spi, &[RAMWR]);
            wait_idle(self.spi);
            let Ok(()) = self.dc.set_high();
        }

        fn pixels(&mut self, pixels: &[WireRgb565]) {
            for pixel in pixels {
                write(self.spi, &pixel.bytes());
            }
        }
    }

    /// Traces band `k` of `scene` seen by `camera` into `buf`. Without a frame (the
    /// camera or the moved sphere refused) or if the band is refused, the band is dark
    /// red (not the black background) and the reason is returned; the frame still goes
    /// out whole, so the display's write pointer stays in step. Not inlined: one copy
    /// of the render loop for every call site. The render is built here, with the
    /// default method: a `Render` handed in would be a run-time value in this function,
    /// and its `draw_band` would link every method's code.
    #[inline(never)]
    fn trace(
        frame: Option<(&Scene<3, 1, 1, 0>, &Camera)>,
        k: u32,
        buf: &mut [WireRgb565],
    ) -> Option<&'static str> {
        let rows = k * BAND_ROWS..(k + 1) * BAND_ROWS;
        let why = match frame.map(|(scene, camera)| Frame::new(scene, camera).draw_band(rows, buf)) {
            Some(Ok(())) => return None,
            None => "motion or camera refused",
            Some(Err(BandError::Frame(_))) => "frame refused (FrameError)",
            Some(Err(_)) => "band rows or buffer wrong",
        };
        buf.fill(WireRgb565::REFUSED);
        Some(why)
    }

    /// Cycles as milliseconds with one decimal, for the label.
    fn tenths_of_ms(cycles: u32, sysclk_hz: u32) -> (u64, u64) {
        let tenths = u64::from(cycles) * 10_000 / u64::from(sysclk_hz);
        (tenths / 10, tenths % 10)
    }

    /// The top line: why a band of the last frame could not be traced, or the last
    /// frame's rate, time, wait (cycles) and share of the panel sent.
    fn label(refused: Option<&str>, shown: Option<(u32, u32, u32)>, sysclk_hz: u32) -> heapless::String<40> {
        let mut label = heapless::String::<40>::new();
        let written = match (refused, shown) {
            (Some(why), _) => write!(label, "error: {why}"),
            (None, Some((frame, wait, sent))) => {
                let (frame_ms, frame_tenth) = tenths_of_ms(frame, sysclk_hz);
                let (wait_ms, wait_tenth) = tenths_of_ms(wait, sysclk_hz);
                let fps_tenths = u64::from(sysclk_hz) * 10 / u64::from(frame.max(1));
                let share = u64::from(sent) * 100 / u64::from(WIDTH * HEIGHT);
                write!(
                    label,
                    "{}.{} fps {frame_ms}.{frame_tenth} ms wait {wait_ms}.{wait_tenth} {share}%",
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
        label
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

        let base_camera = scenes::BOUNCE_CAMERA.with_size(Size::new(WIDTH, HEIGHT));
        let animation = &scenes::BOUNCE_ANIMATION;
        let mut scene = scenes::BOUNCE.clone();
        // What the display shows: the next frame traces and sends only what changed.
        let mut display_has = Incremental::<3, 1, 1, 0>::new();
        let label_area = Rectangle::new(Point::zero(), Size::new(WIDTH, frame::LABEL_ROWS));
        // The cycle count at the last frame's start, and the cycles spent waiting for
        // the wire since then.
        let mut last_start: Option<u32> = None;
        let mut waited = 0u32;
        // The last frame's pixels sent, and why a band of it could not be traced.
        let mut sent = 0u32;
        let mut refused: Option<&'static str> = None;
        let mut n = 0u32;
        loop {
            let start = DWT::cycle_count();
            let shown = last_start.map(|last| (start.wrapping_sub(last), waited, sent));
            last_start = Some(start);
            waited = 0;
            let label = label(refused.take(), shown, sysclk_hz);
            let mut params = base_camera;
            let camera = animation
                .apply_frame(&scenes::BOUNCE, &base_camera, n, &mut scene, &mut params)
                .ok()
                .and_then(|()| params.build().ok());
            // The scene and camera of the frame, if both exist. Each use below builds its
            // own `Frame` (`Render::new`: the default method, a constant): once a
            // render's address has gone to a call that may not be inlined (`update`
            // hands it to some), the optimiser no longer takes its method for that
            // constant, and drawing it would link every method's code.
            let frame = camera.as_ref().map(|camera| (&scene, camera));
            let changes = frame.map(|(scene, camera)| display_has.update(&Frame::new(scene, camera)));
            cs.set_low();
            match (&changes, frame) {
                (Some(changes), Some((scene, camera)))
                    if !changes.is_full() && changes.refused().is_none() =>
                {
                    // Only the changed runs, by the core.
                    let mut wire = Core {
                        spi: &spi1,
                        dc: &mut dc,
                    };
                    let draw = |band: &mut [WireRgb565]| draw_label(band, &label);
                    let frame = Frame::new(scene, camera);
                    sent = match frame::send_runs(changes, &frame, BAND_ROWS, &mut front[..], draw, &mut wire)
                    {
                        Ok(sent) => sent,
                        Err(_) => {
                            refused = Some("band rows or buffer wrong");
                            0
                        }
                    };
                    wait_idle(&spi1);
                }
                _ => {
                    // Step 1: band 0 with the label, chip select, address window, RAMWR.
                    refused = refused.or(trace(frame, 0, &mut front[..]));
                    draw_label(&mut front[..], &label);
                    let mut wire = Core {
                        spi: &spi1,
                        dc: &mut dc,
                    };
                    wire.window(0..WIDTH, 0..HEIGHT);
                    wait_idle(&spi1);

                    // Step 2: band 0 on the wire.
                    let mut transfer: BandTransfer =
                        Transfer::init_memory_to_peripheral(stream, spi1, front, None, dma_config);
                    transfer.start(|_| {});

                    // Step 3: trace band k while band k − 1 is on the wire.
                    for k in 1..BANDS {
                        refused = refused.or(trace(frame, k, &mut back[..]));
                        let wait_start = DWT::cycle_count();
                        transfer.wait();
                        waited = waited.wrapping_add(DWT::cycle_count().wrapping_sub(wait_start));
                        // Not double-buffered: this restarts the stream on `back` and
                        // never fails; an error would hand `back` back unsent.
                        back = match transfer.next_transfer(back) {
                            Ok((sent, _)) => sent,
                            Err(
                                DMAError::NotReady(unsent)
                                | DMAError::SmallBuffer(unsent)
                                | DMAError::Overrun(unsent),
                            ) => unsent,
                        };
                    }

                    // Step 4: the last band off the wire.
                    let wait_start = DWT::cycle_count();
                    transfer.wait();
                    (stream, spi1, front, _) = transfer.release();
                    wait_idle(&spi1);
                    waited = waited.wrapping_add(DWT::cycle_count().wrapping_sub(wait_start));
                    sent = WIDTH * HEIGHT;
                }
            }
            cs.set_high();
            // The label is over the picture; a band traced dark red leaves a picture
            // that is no frame: the next one is drawn whole.
            display_has.invalidate_area(label_area);
            if refused.is_some() {
                display_has.invalidate();
            }
            // The motion repeats after `frames()` frames exactly: counting within one
            // loop keeps every frame's time as exact as the first loop's.
            n = (n + 1) % animation.frames();
        }
    }
}
