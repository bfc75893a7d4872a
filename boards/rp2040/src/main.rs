//! Raspberry Pi Pico (RP2040, two Cortex-M0+ cores at 133 MHz) driving a 240×240 ST7789
//! over SPI1: `scenes/circling.toml`'s spheres circle (the library's motion), and
//! `Incremental::update` says frame by frame what changed since the frame the display
//! shows. A whole frame is traced by both cores, in alternate bands of 20 rows
//! (`split.rs`: core 0 bands 0, 2, …, 10, core 1 bands 1, 3, …, 11), each core into its
//! own band buffer, and DMA sends the bands to the display in order; any other frame
//! (only runs changed) core 0 traces and sends alone, each run in its own address
//! window (`runs.rs`). The top-left corner shows the last frame's rate, time and how
//! long core 0 waited in it (the RP2040's 1 MHz timer) — or, if a band could not be
//! traced (it goes out dark red), which band and why.
//!
//! ```sh
//! cd boards/rp2040 && cargo build --release
//! elf2uf2-rs -d target/thumbv6m-none-eabi/release/rp2040-st7789    # Pico in BOOTSEL mode
//! probe-rs run --chip RP2040 target/thumbv6m-none-eabi/release/rp2040-st7789   # or over SWD
//! ```
//!
//! Builds in CI; not tested on hardware. Wiring (README, "Raspberry Pi Pico (RP2040), two
//! cores"): SCK GP10, MOSI GP11, CS GP9, DC GP8, RST GP12, BL GP13.
//!
//! At the start of each frame core 0 writes `WHOLE` or `RUNS` on the SIO FIFO; for
//! `RUNS` core 1 only steps the motion. The hand-off of a whole frame (core 0 owns SPI1
//! and the DMA channel):
//! 1. core 0 traces band 0 (with the last frame's figures over it), sets the address
//!    window (CASET, RASET: the whole panel) and sends RAMWR, byte by byte with DC low
//!    for the command bytes; then DC high, and band 0 goes out by DMA (channel 0 into
//!    SPI1's TX FIFO, paced by its DREQ);
//! 2. for k = 1 … 11:
//!    - core 1's band k: core 0 waits for core 1's word `k` on the SIO FIFO, takes core
//!      1's buffer from the mailbox, waits for band k − 1 (its own) to finish and starts
//!      band k;
//!    - core 0's band k: core 0 waits for band k − 1 (core 1's) to finish and hands
//!      that buffer straight back (into the mailbox, then the word `k − 1` on the FIFO),
//!      so that core 1 traces its next band while core 0 traces band k into its own
//!      buffer (back since band k − 2 finished); then it starts band k;
//! 3. core 0 waits for band 11 and for SPI1 to shift it out, raises CS, and hands
//!    core 1's buffer back.
//!
//! Core 1, for each of its bands k: traces band k into its buffer, puts the buffer in the
//! mailbox, writes `k` to the FIFO, and waits for the word `k` back (band k has gone out)
//! before it takes the buffer back for its next band. So a band goes out only after the
//! one before it, and a core reuses its buffer only once its transfer has finished.
//! Both cores apply the motion the same way (the same soft-float code on the same
//! numbers), so they trace the same frame without exchanging scenes.
//!
//! The bands are traced straight into the ST7789's wire format
//! (`boards/stm32f407/src/st7789_band.rs`: Rgb565, high byte first), as in
//! `boards/stm32f407/src/main.rs`.
#![no_std]
#![no_main]

mod scenes;

mod runs;
mod split;

// `BANDS` and `BAND_PIXELS` there are the STM32 example's 16-row bands;
// here the bands come from `split.rs`.
#[allow(dead_code)]
mod st7789_band;

use core::cell::Cell;
use core::convert::Infallible;
use core::fmt::Write as _;
use core::ops::Range;

use critical_section::Mutex;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::SpiBus;
use embedded_hal_bus::spi::ExclusiveDevice;
use embedded_raytracer::{Camera, Incremental, IntegerError, Method, Render, Scene};
use mipidsi::{interface::SpiInterface, models::ST7789, options::ColorInversion, Builder};
use panic_halt as _;
use rp2040_hal::{
    self as hal,
    clocks::{Clock, ClocksManager},
    dma::{single_buffer, DMAExt},
    fugit::{HertzU32, RateExtU32},
    gpio::FunctionSpi,
    multicore::{Multicore, Stack},
    pac,
    pll::{common_configs::PLL_USB_48MHZ, setup_pll_blocking, PLLConfig},
    sio::{Sio, SioFifo},
    xosc::setup_xosc_blocking,
    Timer, Watchdog,
};

use crate::split::BAND_ROWS;
use crate::st7789_band::{draw_label, WireRgb565, HEIGHT, WIDTH};

/// The second-stage bootloader for the Pico's W25Q080 flash, at the start of flash
/// (`memory.x`).
#[link_section = ".boot2"]
#[used]
pub static BOOT2: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// The Pico's crystal.
const XTAL_HZ: u32 = 12_000_000;

/// The system clock, 133 MHz: 12 MHz × 133 = 1596 MHz in the VCO (its limit is 1600),
/// divided by 6 and by 2. The peripheral clock (SPI) is the system clock.
const PLL_SYS_133MHZ: PLLConfig = PLLConfig {
    vco_freq: HertzU32::MHz(1596),
    refdiv: 1,
    post_div1: 6,
    post_div2: 2,
};

/// The SPI clock asked for: the ST7789's fastest serial write clock (16 ns cycle). The
/// PL022 divides the 133 MHz peripheral clock by an even prescaler times (1 + SCR), so
/// the fastest clock at or below it, which the HAL picks, is 133 / 4 = 33.25 MHz.
const SPI_HZ: u32 = 62_500_000;

/// Bands per frame; every band is `BAND_ROWS` rows, one buffer's worth.
const BANDS: u32 = split::band_count(HEIGHT, BAND_ROWS);
const BAND_PIXELS: usize = (WIDTH * BAND_ROWS) as usize;
const _: () = assert!(HEIGHT.is_multiple_of(BAND_ROWS), "every band fills a buffer");
// Step 2 hands band k − 1 to the other core of two that alternate.
const _: () = assert!(split::CORES == 2, "two cores, alternate bands");
// `draw_label` draws into the first `st7789_band::BAND_ROWS` rows of band 0.
const _: () = assert!(BAND_ROWS >= st7789_band::BAND_ROWS, "the label fits in band 0");

/// Core 0's word to core 1 at the start of a frame: both cores trace it (`WHOLE`), or
/// core 0 sends its changed runs alone (`RUNS`). Above any band index.
const WHOLE: u32 = 0x5748_4F4C;
const RUNS: u32 = 0x5255_4E53;

/// The label's rows over the picture (`draw_label`: 6×10 text at (2, 2)).
const LABEL: Rectangle = Rectangle::new(Point::zero(), Size::new(WIDTH, 12));

/// ST7789 commands (datasheet, "System function command table 1").
const CASET: u8 = 0x2A;
const RASET: u8 = 0x2B;
const RAMWR: u8 = 0x2C;

/// A band buffer: `'static`, so DMA may own it while a transfer runs, and so it can
/// move between the cores.
type Band = &'static mut [WireRgb565; BAND_PIXELS];

/// Core 1's band buffer while core 0 (or DMA) has it: put in by the core handing it
/// over, before it signals on the SIO FIFO; taken by the other core after the signal.
/// The critical section is the HAL's two-core one (hardware spin-lock 31).
static MAILBOX: Mutex<Cell<Option<Band>>> = Mutex::new(Cell::new(None));

/// Core 1's stack (16 KiB; a lab render needs under 2 KiB on the Cortex-M0).
static CORE1_STACK: Stack<4096> = Stack::new();

/// The band rows of band `k` of this firmware's frame.
fn rows(k: u32) -> Range<u32> {
    split::band_rows(k, HEIGHT, BAND_ROWS)
}

/// The lab camera at the panel's size; `None` if the kernel rejects it.
fn camera() -> Option<Camera> {
    scenes::CIRCLING_CAMERA
        .with_size(Size::new(WIDTH, HEIGHT))
        .build()
        .ok()
}

/// The scene of frame `k` of the motion (`scenes::CIRCLING_ANIMATION`) into `scene`;
/// both cores compute their own copy alike, so they trace the same frame without
/// exchanging scenes. The motion moves no camera. `None` if the motion is refused.
fn scene_at(scene: &mut Scene<3>, k: u32) -> Option<&Scene<3>> {
    let mut params = scenes::CIRCLING_CAMERA;
    scenes::CIRCLING_ANIMATION
        .apply_frame(&scenes::CIRCLING, &scenes::CIRCLING_CAMERA, k, scene, &mut params)
        .ok()
        .map(|()| &*scene)
}

/// The next frame's number: the motion repeats after `frames()` frames exactly, so
/// counting within one loop keeps every frame's time as exact as the first loop's.
fn next(k: u32) -> u32 {
    (k + 1) % scenes::CIRCLING_ANIMATION.frames()
}

/// The first band of the frame that could not be traced, and why, from either core:
/// core 0 shows it in the next frame's top line instead of the frame time.
static REFUSED: Mutex<Cell<Option<(u32, &'static str)>>> = Mutex::new(Cell::new(None));

/// The scene's frame on this panel, as both cores trace it: the integer kernel's
/// method, so that `Incremental`'s plan follows the integer kernel's rule.
type Frame<'a> = Render<'a, 3, WireRgb565>;

/// The frame of `scene` seen by `camera`, if both exist.
fn frame<'a>(scene: Option<&'a Scene<3>>, camera: Option<&'a Camera>) -> Option<Frame<'a>> {
    Some(Render::new(scene?, camera?).with_method(Method::INTEGER))
}

/// Traces band `k` (`rows`) of `frame` into `buf` with the integer kernel alone
/// (`Render::draw_band_integer`: no `f32` render is linked; its rule takes every frame
/// of the animation, `lab/tests/lab/rp2040_split.rs`). Without a frame (the camera or
/// the moved sphere refused) or if the band is refused, the band is dark red and
/// `REFUSED` says why.
fn trace(frame: Option<&Frame<'_>>, k: u32, rows: Range<u32>, buf: &mut [WireRgb565]) {
    let why = match frame.map(|frame| frame.draw_band_integer(rows, buf)) {
        Some(Ok(())) => return,
        None => "camera or scene refused",
        Some(Err(IntegerError::Refused)) => "integer kernel refused",
        Some(Err(_)) => "band rows or buffer wrong",
    };
    buf.fill(WireRgb565::REFUSED);
    critical_section::with(|cs| {
        let first = REFUSED.borrow(cs);
        if first.get().is_none() {
            first.set(Some((k, why)));
        }
    });
}

/// Waits for the FIFO word `want` from the other core: the hand-off protocol keeps
/// both cores at the same band, so any other word means it broke.
fn expect_word(fifo: &mut SioFifo, want: u32) {
    if fifo.read_blocking() != want {
        panic!("the cores disagree on the band");
    }
}

/// Core 1's buffer from the mailbox (the other core has just signalled it is there).
fn take_mailbox() -> Band {
    match critical_section::with(|cs| MAILBOX.borrow(cs).take()) {
        Some(band) => band,
        None => panic!("signalled without a buffer in the mailbox"),
    }
}

/// Core 1's buffer into the mailbox, before the signal on the FIFO.
fn put_mailbox(band: Band) {
    critical_section::with(|cs| MAILBOX.borrow(cs).set(Some(band)));
}

/// Core 1: frame after frame, waits for core 0's word for the frame; for a whole frame
/// (`WHOLE`) traces its bands (`split::core_bands(1, …)`) into its one buffer, handing
/// each to core 0 and taking it back once it has gone out; for a frame of changed runs
/// (`RUNS`, which core 0 sends alone) only steps the animation.
fn core1(mut buf: Band) -> ! {
    // SAFETY: core 1 uses only the SIO block, and of it only its FIFO ends: every core
    // reads and writes its own ends at the same addresses; core 0's `Sio` never
    // reaches core 1's.
    let pac = unsafe { pac::Peripherals::steal() };
    let mut fifo = Sio::new(pac.SIO).fifo;
    let camera = camera();
    let mut scene = scenes::CIRCLING.clone();
    let mut n = 0u32;
    loop {
        let frame = frame(scene_at(&mut scene, n), camera.as_ref());
        match fifo.read_blocking() {
            WHOLE => {
                for (k, band_rows) in split::core_bands(1, HEIGHT, BAND_ROWS) {
                    trace(frame.as_ref(), k, band_rows, &mut buf[..]);
                    put_mailbox(buf);
                    fifo.write_blocking(k);
                    // Band k has gone out: the buffer is back.
                    expect_word(&mut fifo, k);
                    buf = take_mailbox();
                }
            }
            RUNS => {}
            _ => panic!("the cores disagree on the frame"),
        }
        n = next(n);
    }
}

/// Clocks: the crystal, PLL_SYS at 133 MHz (system and peripheral clocks), PLL_USB at
/// 48 MHz, and the watchdog's 1 µs tick, which the timer counts.
fn init_clocks(
    xosc: pac::XOSC,
    clocks: pac::CLOCKS,
    pll_sys: pac::PLL_SYS,
    pll_usb: pac::PLL_USB,
    resets: &mut pac::RESETS,
    watchdog: &mut Watchdog,
) -> Option<ClocksManager> {
    let xosc = setup_xosc_blocking(xosc, XTAL_HZ.Hz()).ok()?;
    watchdog.enable_tick_generation((XTAL_HZ / 1_000_000) as u8);
    let mut clocks = ClocksManager::new(clocks);
    let pll_sys = setup_pll_blocking(
        pll_sys,
        xosc.operating_frequency(),
        PLL_SYS_133MHZ,
        &mut clocks,
        resets,
    )
    .ok()?;
    let pll_usb = setup_pll_blocking(
        pll_usb,
        xosc.operating_frequency(),
        PLL_USB_48MHZ,
        &mut clocks,
        resets,
    )
    .ok()?;
    clocks.init_default(&xosc, &pll_sys, &pll_usb).ok()?;
    Some(clocks)
}

/// Writes `bytes` without DMA and waits until SPI1 has shifted them out, so that DC or
/// CS may change. The RP2040's SPI and GPIO cannot fail (`Infallible`).
fn write_blocking(spi: &mut impl SpiBus<u8, Error = Infallible>, bytes: &[u8]) {
    let Ok(()) = spi.write(bytes);
    let Ok(()) = spi.flush();
}

/// The address window `x` × `y` (CASET, RASET) and RAMWR; leaves DC high, ready for
/// the pixels. Step 1's is the whole panel.
fn start_window(
    spi: &mut impl SpiBus<u8, Error = Infallible>,
    dc: &mut impl OutputPin<Error = Infallible>,
    x: Range<u32>,
    y: Range<u32>,
) {
    let bounds = |r: Range<u32>| {
        let [a_hi, a_lo] = (r.start as u16).to_be_bytes();
        let [b_hi, b_lo] = (r.end.saturating_sub(1) as u16).to_be_bytes();
        [a_hi, a_lo, b_hi, b_lo]
    };
    for (command, params) in [(CASET, bounds(x)), (RASET, bounds(y))] {
        let Ok(()) = dc.set_low();
        write_blocking(spi, &[command]);
        let Ok(()) = dc.set_high();
        write_blocking(spi, &params);
    }
    let Ok(()) = dc.set_low();
    write_blocking(spi, &[RAMWR]);
    let Ok(()) = dc.set_high();
}

/// SPI1 and the DC pin as the controller's wire for a frame of changed runs
/// (`runs.rs`), written by core 0 (CS low): between two runs it must set the next
/// window anyway, and a run is short.
struct Core<'a, S, D> {
    spi: &'a mut S,
    dc: &'a mut D,
}

impl<S: SpiBus<u8, Error = Infallible>, D: OutputPin<Error = Infallible>> runs::Wire<WireRgb565>
    for Core<'_, S, D>
{
    fn window(&mut self, x: Range<u32>, y: Range<u32>) {
        start_window(self.spi, self.dc, x, y);
    }

    fn pixels(&mut self, pixels: &[WireRgb565]) {
        for pixel in pixels {
            let Ok(()) = self.spi.write(&pixel.bytes());
        }
        let Ok(()) = self.spi.flush();
    }
}

/// The top line: the first band the last frame could not trace and why, or the last
/// frame's rate, time and core 0's wait (µs).
fn label(refused: Option<(u32, &str)>, shown: Option<(u64, u64)>) -> heapless::String<40> {
    let mut label = heapless::String::<40>::new();
    let written = match (refused, shown) {
        (Some((k, why)), _) => write!(label, "band {k}: {why}"),
        (None, Some((frame, wait))) => {
            let (frame_ms, frame_tenth) = tenths_of_ms(frame);
            let (wait_ms, wait_tenth) = tenths_of_ms(wait);
            let fps_tenths = 10_000_000 / frame.max(1);
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
    label
}

/// Microseconds as milliseconds with one decimal, for the label.
fn tenths_of_ms(us: u64) -> (u64, u64) {
    (us / 1000, us / 100 % 10)
}

#[hal::entry]
fn main() -> ! {
    let Some(mut pac) = pac::Peripherals::take() else {
        panic!("peripherals taken twice");
    };
    let mut watchdog = Watchdog::new(pac.WATCHDOG);
    let Some(clocks) = init_clocks(
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

    let mut sio = Sio::new(pac.SIO);
    let pins = hal::gpio::Pins::new(pac.IO_BANK0, pac.PADS_BANK0, sio.gpio_bank0, &mut pac.RESETS);
    // SPI1 on GP10 (SCK) and GP11 (TX = MOSI), mode 3 as in the STM32 examples (modules
    // without CS work in mode 3).
    let sck = pins.gpio10.into_function::<FunctionSpi>();
    let mosi = pins.gpio11.into_function::<FunctionSpi>();
    let mut spi = hal::spi::Spi::<_, _, _, 8>::new(pac.SPI1, (mosi, sck)).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        SPI_HZ.Hz(),
        embedded_hal::spi::MODE_3,
    );
    let mut cs = pins
        .gpio9
        .into_push_pull_output_in_state(hal::gpio::PinState::High);
    let mut dc = pins.gpio8.into_push_pull_output();
    let mut rst = pins.gpio12.into_push_pull_output();
    let _backlight = pins
        .gpio13
        .into_push_pull_output_in_state(hal::gpio::PinState::High);

    // The controller's reset and init sequence through mipidsi, as in the STM32
    // examples; the driver only borrows the bus and the pins and is dropped afterwards,
    // so the frames below can drive SPI1 themselves.
    {
        let Ok(spi_device) = ExclusiveDevice::new_no_delay(&mut spi, &mut cs);
        let mut buffer = [0u8; 16];
        let interface = SpiInterface::new(spi_device, &mut dc, &mut buffer);
        if Builder::new(ST7789, interface)
            .display_size(WIDTH as u16, HEIGHT as u16)
            .invert_colors(ColorInversion::Inverted) // IPS ST7789 panels are inverted
            .reset_pin(&mut rst)
            .init(&mut timer)
            .is_err()
        {
            panic!("display init failed");
        }
    }

    let (Some(mut own), Some(core1_buf)) = (
        cortex_m::singleton!(: [WireRgb565; BAND_PIXELS] = [WireRgb565::BLACK; BAND_PIXELS]),
        cortex_m::singleton!(: [WireRgb565; BAND_PIXELS] = [WireRgb565::BLACK; BAND_PIXELS]),
    ) else {
        panic!("band buffers taken twice");
    };

    // Core 1 starts tracing its first band now, while core 0 traces band 0.
    {
        let mut mc = Multicore::new(&mut pac.PSM, &mut pac.PPB, &mut sio.fifo);
        let core1_stack = CORE1_STACK.take();
        let spawned = core1_stack.map(|stack| mc.cores()[1].spawn(stack, move || core1(core1_buf)));
        if !matches!(spawned, Some(Ok(()))) {
            panic!("core 1 did not start");
        }
    }
    let mut fifo = sio.fifo;

    let mut ch = pac.DMA.split(&mut pac.RESETS).ch0;
    let camera = camera();
    let mut scene = scenes::CIRCLING.clone();
    // What the display shows, for the next frame's changes.
    let mut display_has = Incremental::<3>::new();
    let mut n = 0u32;
    // The timer at the last frame's start, and how long core 0 has waited since then
    // (for core 1's bands and for the wire), in µs.
    let mut last_start: Option<u64> = None;
    let mut waited = 0u64;
    loop {
        let start = timer.get_counter().ticks();
        let shown = last_start.map(|last| (start.wrapping_sub(last), waited));
        last_start = Some(start);
        waited = 0;
        let frame = frame(scene_at(&mut scene, n), camera.as_ref());
        let changes = frame.as_ref().map(|frame| display_has.update(frame));
        let refused = critical_section::with(|cs| REFUSED.borrow(cs).take());
        let label = label(refused, shown);
        if let (Some(changes), Some(frame)) = (&changes, &frame) {
            if !(changes.is_full() || changes.refused().is_some()) {
                // Only runs changed: core 0
                // sends them alone, core 1 skips the frame.
                fifo.write_blocking(RUNS);
                let Ok(()) = cs.set_low();
                let mut wire = Core {
                    spi: &mut spi,
                    dc: &mut dc,
                };
                let label = |band: &mut [WireRgb565]| draw_label(band, &label);
                if let Err(e) = runs::send_runs(changes, frame, BAND_ROWS, &mut own[..], label, &mut wire) {
                    let why = match e {
                        IntegerError::Refused => "integer kernel refused",
                        _ => "display error",
                    };
                    critical_section::with(|cs| REFUSED.borrow(cs).set(Some((0, why))));
                    display_has.invalidate();
                }
                let Ok(()) = cs.set_high();
                display_has.invalidate_area(LABEL);
                n = next(n);
                continue;
            }
        }
        fifo.write_blocking(WHOLE);

        // Step 1: band 0 with the last frame's figures, the address window, band 0 out.
        trace(frame.as_ref(), 0, rows(0), &mut own[..]);
        draw_label(&mut own[..], &label);
        let Ok(()) = cs.set_low();
        start_window(&mut spi, &mut dc, 0..WIDTH, 0..HEIGHT);
        let mut transfer = single_buffer::Config::new(ch, own, spi).start();
        // Core 0's buffer while it is not on the wire.
        let mut free: Option<Band> = None;

        // Step 2: bands 1 … BANDS − 1, each started once the one before it is out.
        for k in 1..BANDS {
            let wait_start = timer.get_counter().ticks();
            transfer = if split::core_of(k) == 0 {
                // Band k − 1 is core 1's: back to core 1 as soon as it is out, so that
                // core 1 traces on while core 0 traces band k.
                let (c, sent, s) = transfer.wait();
                waited += timer.get_counter().ticks().wrapping_sub(wait_start);
                put_mailbox(sent);
                fifo.write_blocking(k - 1);
                let Some(buf) = free.take() else {
                    panic!("core 0's buffer is still on the wire");
                };
                trace(frame.as_ref(), k, rows(k), &mut buf[..]);
                single_buffer::Config::new(c, buf, s).start()
            } else {
                // Band k is core 1's; band k − 1, core 0's, comes back to core 0.
                expect_word(&mut fifo, k);
                let buf = take_mailbox();
                let (c, sent, s) = transfer.wait();
                waited += timer.get_counter().ticks().wrapping_sub(wait_start);
                free = Some(sent);
                single_buffer::Config::new(c, buf, s).start()
            };
        }

        // Step 3: the last band out of the FIFO and off the wire, CS up, its buffer
        // back to its core.
        let wait_start = timer.get_counter().ticks();
        let sent;
        (ch, sent, spi) = transfer.wait();
        let Ok(()) = spi.flush();
        let Ok(()) = cs.set_high();
        waited += timer.get_counter().ticks().wrapping_sub(wait_start);
        own = if split::core_of(BANDS - 1) == 0 {
            sent
        } else {
            put_mailbox(sent);
            fifo.write_blocking(BANDS - 1);
            match free.take() {
                Some(buf) => buf,
                None => panic!("core 0's buffer is still on the wire"),
            }
        };
        // The label is over the picture; a band traced dark red, or no frame at all,
        // leaves a picture that is no frame: the next one is drawn whole.
        display_has.invalidate_area(LABEL);
        if frame.is_none() || critical_section::with(|cs| REFUSED.borrow(cs).get().is_some()) {
            display_has.invalidate();
        }
        n = next(n);
    }
}
