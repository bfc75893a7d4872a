//! The PNG, streamed in bands of rows: `Render::draw_band` traces bands on a pool of
//! `threads` threads (it gives the same pixels for any split), the calling thread
//! encodes them in order into one PNG stream while the pool traces the next ones. At
//! most `2 × threads` bands are in flight, so memory is O(width × threads × BAND), not
//! O(width × height); the bytes do not depend on the number of threads, since the
//! encoder sees the same rows in the same order and the same chunks.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use embedded_graphics::{pixelcolor::Rgb888, prelude::*};
use embedded_raytracer::Render;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Rows in a band: enough that a band's fixed cost (its first row's set-up, an adaptive
/// sampling's shared row) is small, few enough that 8192-wide bands stay at 400 KB.
pub const BAND: u32 = 16;

/// How long a render runs before its progress bar appears.
const QUIET_START: Duration = Duration::from_millis(500);

/// What to write.
pub struct Job {
    pub size: Size,
    /// Tracing threads; 1: every band on the calling thread, no pool.
    pub threads: usize,
    /// A progress bar on stderr (a terminal, not `--quiet`) once the render has run
    /// for [`QUIET_START`].
    pub progress: bool,
}

/// Where a render's time went.
#[derive(Clone, Copy, Debug, Default)]
pub struct Timing {
    /// Wall time of the render less the encoder's share (with threads: the pool's start
    /// and the time the encoder waited for bands).
    pub rendering: Duration,
    /// The time spent inside `draw_band`, summed over the bands (and so over the
    /// threads): the tracing alone, whatever the pool costs to start.
    pub tracing: Duration,
    /// The time spent encoding and writing the PNG.
    pub encoding: Duration,
}

/// Renders into a PNG stream on `out`; returns where the time went.
pub fn write<const N: usize, const L: usize, const P: usize, const D: usize>(
    render: &Render<'_, N, Rgb888, L, P, D>,
    job: &Job,
    out: &File,
) -> io::Result<Timing> {
    let start = Instant::now();
    let size = job.size;
    let mut out = BufWriter::new(out);
    let mut writer = rgb_encoder(&mut out, size).write_header()?;
    let mut encoding = Duration::ZERO;
    let mut tracing = Duration::ZERO;
    {
        let mut stream = writer.stream_writer()?;
        let mut progress = Progress::new(job, start);
        let mut emit = |rows: u32, band: Band| -> io::Result<()> {
            tracing += band.tracing;
            let bytes = &band.bytes;
            let t = Instant::now();
            stream.write_all(bytes)?;
            encoding += t.elapsed();
            progress.advance(rows);
            Ok(())
        };
        if job.threads <= 1 {
            let mut pixels = Vec::new();
            for k in 0..size.height.div_ceil(BAND) {
                let rows = band_rows(k, size.height);
                let band = trace_band(render, size.width, rows.clone(), &mut pixels)?;
                emit(rows.len() as u32, band)?;
            }
        } else {
            in_parallel(render, size, job.threads, &mut emit)?;
        }
        progress.finish();
        let t = Instant::now();
        stream.finish()?;
        encoding += t.elapsed();
    }
    let t = Instant::now();
    writer.finish()?;
    out.flush()?;
    encoding += t.elapsed();
    Ok(Timing {
        rendering: start.elapsed().saturating_sub(encoding),
        tracing,
        encoding,
    })
}

/// The encoder of every PNG the CLI writes: 8-bit RGB, the crate's default
/// compression and filter (a still frame of a sequence is the same bytes as the
/// single-frame render's PNG only if both are encoded alike).
fn rgb_encoder<W: Write>(out: W, size: Size) -> png::Encoder<'static, W> {
    let mut encoder = png::Encoder::new(out, size.width, size.height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder
}

/// Writes a frame already drawn (`rgb`: 3 bytes a pixel, row-major) as a PNG on `out`,
/// fed to the encoder in the bands [`write`] feeds it, so the bytes are the ones
/// [`write`] gives for the same pixels. Returns the time spent encoding and writing.
pub fn write_frame(size: Size, rgb: &[u8], out: &File) -> io::Result<Duration> {
    let start = Instant::now();
    let mut out = BufWriter::new(out);
    let mut writer = rgb_encoder(&mut out, size).write_header()?;
    {
        let mut stream = writer.stream_writer()?;
        let row = size.width as usize * 3;
        for k in 0..size.height.div_ceil(BAND) {
            let rows = band_rows(k, size.height);
            let band = rgb
                .get(rows.start as usize * row..rows.end as usize * row)
                .ok_or_else(|| io::Error::other("the frame is smaller than its size"))?;
            stream.write_all(band)?;
        }
        stream.finish()?;
    }
    writer.finish()?;
    out.flush()?;
    Ok(start.elapsed())
}

/// An animated PNG (APNG) assembled in memory frame by frame: every frame the whole
/// image, shown for `1/fps` s, looping forever.
pub struct Animated {
    writer: png::Writer<Shared>,
    bytes: Shared,
}

/// The APNG's bytes, shared between the encoder (which owns its writer until it
/// finishes) and [`Animated::finish`].
#[derive(Clone, Default)]
struct Shared(std::rc::Rc<std::cell::RefCell<Vec<u8>>>);

impl Write for Shared {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.0.borrow_mut().extend_from_slice(buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

impl Animated {
    /// An APNG of `frames` frames of `size` at `fps` frames a second.
    pub fn new(size: Size, frames: u32, fps: f32) -> io::Result<Self> {
        let bytes = Shared::default();
        let mut encoder = rgb_encoder(bytes.clone(), size);
        encoder.set_animated(frames, 0)?;
        let (num, den) = frame_delay(fps);
        encoder.set_frame_delay(num, den)?;
        Ok(Self {
            writer: encoder.write_header()?,
            bytes,
        })
    }

    /// Appends the next frame (`rgb`: 3 bytes a pixel, row-major).
    pub fn push(&mut self, rgb: &[u8]) -> io::Result<()> {
        self.writer.write_image_data(rgb).map_err(io::Error::other)
    }

    /// The finished file's bytes (the encoder checks that every frame was given).
    pub fn finish(self) -> io::Result<Vec<u8>> {
        self.writer.finish().map_err(io::Error::other)?;
        Ok(self.bytes.0.take())
    }
}

/// The APNG frame delay `num/den` seconds closest to `1/fps`: `1/fps` exactly for a
/// whole frame rate up to 65,535, otherwise in milliseconds (at least 1).
fn frame_delay(fps: f32) -> (u16, u16) {
    if fps.fract() == 0.0 && (1.0..=65535.0).contains(&fps) {
        return (1, fps as u16);
    }
    let ms = (1000.0 / f64::from(fps)).round().clamp(1.0, 65535.0);
    (ms as u16, 1000)
}

/// Band `k`'s rows.
fn band_rows(k: u32, height: u32) -> std::ops::Range<u32> {
    k * BAND..((k + 1) * BAND).min(height)
}

/// A traced band: its RGB bytes and the time `draw_band` took.
struct Band {
    bytes: Vec<u8>,
    tracing: Duration,
}

/// Traces `rows` into `pixels` (reused) and returns their RGB bytes.
fn trace_band<const N: usize, const L: usize, const P: usize, const D: usize>(
    render: &Render<'_, N, Rgb888, L, P, D>,
    width: u32,
    rows: std::ops::Range<u32>,
    pixels: &mut Vec<Rgb888>,
) -> io::Result<Band> {
    pixels.clear();
    pixels.resize(width as usize * rows.len(), Rgb888::BLACK);
    let start = Instant::now();
    render
        .draw_band(rows, pixels)
        .map_err(|e| io::Error::other(format!("the render refused a band: {e:?}")))?;
    let tracing = start.elapsed();
    Ok(Band {
        bytes: pixels.iter().flat_map(|c| [c.r(), c.g(), c.b()]).collect(),
        tracing,
    })
}

/// The bands traced on a pool of `threads` threads and handed to `emit` in order, on
/// the calling thread (which the pool does not count: it encodes while they trace).
fn in_parallel<const N: usize, const L: usize, const P: usize, const D: usize>(
    render: &Render<'_, N, Rgb888, L, P, D>,
    size: Size,
    threads: usize,
    emit: &mut impl FnMut(u32, Band) -> io::Result<()>,
) -> io::Result<()> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(|i| format!("ertrace-trace-{i}"))
        .build()
        .map_err(io::Error::other)?;
    let bands = size.height.div_ceil(BAND);
    let window = (2 * threads).min(bands as usize) as u32;
    let (done, finished) = mpsc::channel::<(u32, io::Result<Band>)>();
    pool.in_place_scope(|scope| {
        let spawn = |k: u32| {
            let done = done.clone();
            scope.spawn(move |_| {
                let rows = band_rows(k, size.height);
                let bytes = trace_band(render, size.width, rows, &mut Vec::new());
                // The receiver is gone only when the encoder stopped on an error.
                let _ = done.send((k, bytes));
            });
        };
        (0..window).for_each(spawn);
        let mut next = window;
        let mut waiting = BTreeMap::new();
        for k in 0..bands {
            let bytes = loop {
                if let Some(bytes) = waiting.remove(&k) {
                    break bytes;
                }
                let (i, bytes) = finished.recv().map_err(io::Error::other)?;
                waiting.insert(i, bytes);
            };
            emit(band_rows(k, size.height).len() as u32, bytes?)?;
            if next < bands {
                spawn(next);
                next += 1;
            }
        }
        Ok(())
    })
}

/// The progress bar: rows done, elapsed and remaining time, drawn on stderr once the
/// render has run for [`QUIET_START`] (never when `Job::progress` is off).
struct Progress {
    bar: Option<ProgressBar>,
    shown: bool,
    start: Instant,
}

impl Progress {
    fn new(job: &Job, start: Instant) -> Self {
        let bar = job.progress.then(|| {
            let bar =
                ProgressBar::with_draw_target(Some(u64::from(job.size.height)), ProgressDrawTarget::hidden());
            if let Ok(style) = ProgressStyle::with_template(
                "{elapsed_precise} [{wide_bar}] {pos}/{len} rows, {eta_precise} left",
            ) {
                bar.set_style(style);
            }
            bar
        });
        Self {
            bar,
            shown: false,
            start,
        }
    }

    fn advance(&mut self, rows: u32) {
        let Some(bar) = &self.bar else { return };
        bar.inc(u64::from(rows));
        if !self.shown && self.start.elapsed() >= QUIET_START {
            bar.set_draw_target(ProgressDrawTarget::stderr());
            bar.enable_steady_tick(Duration::from_secs(1));
            self.shown = true;
        }
    }

    fn finish(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}
