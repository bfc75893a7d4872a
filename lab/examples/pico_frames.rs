//! The Pico board examples' frames drawn on the host through each one's own `frame.rs`
//! and `scenes.rs` (as `lab/tests/lab/board_examples.rs` draws them), for the emulator
//! check (`.ci/pico-emu`), which compares them with what the firmware sent in rp2040js.
//!
//! ```text
//! cargo run --release -p embedded-raytracer-lab --features tools --example pico_frames -- DIR simple US,US,…
//! cargo run --release -p embedded-raytracer-lab --features tools --example pico_frames -- DIR ssd1306 -,US,…
//! ```
//!
//! Frames 0, 1, … (one per value) are drawn one after another through one
//! `Incremental`, each with the status line the firmware draws over it, its frame time
//! the value given: the microseconds the firmware read from its timer (`simple`: the
//! frame's own; the SSD1306: the frame before's, `-` for none).
//!
//! - `simple`: `DIR/host-simple-K-frame.raw`, the panel after frame K (RGB565, 240×240,
//!   2 bytes a pixel, little-endian), and `DIR/host-simple-K-status.raw`, the panel
//!   with frame K's status line over it.
//! - `ssd1306`: `DIR/host-ssd1306-K-frame.raw`, the 128×64 panel after frame K and its
//!   status line (a byte a pixel: 1 lit, 0 dark).
//! - `DIR/host-BOARD.txt`: per frame `K sent traced` and the status line after a tab.
//! - `DIR/font-6x10.txt`: the status lines' font (embedded-graphics' `FONT_6X10`), a
//!   glyph per printable ASCII character: its code, then ten rows of six `#`/`.`.

use std::convert::Infallible;
use std::fmt::Write as _;
use std::fs;
use std::path::Path;
use std::process::ExitCode;

use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
use embedded_graphics::pixelcolor::{BinaryColor, Rgb565};
use embedded_graphics::prelude::*;
use embedded_graphics::text::{Baseline, Text};
use embedded_raytracer::{Arithmetic, FrameStats, Incremental};

#[path = "../../boards/rp2040/src/bin/simple/frame.rs"]
mod simple;
#[path = "../../boards/rp2040/src/scenes.rs"]
mod simple_scenes;

#[path = "../../boards/rp2040-ssd1306/src/frame.rs"]
mod ssd1306;
#[path = "../../boards/rp2040-ssd1306/src/scenes.rs"]
mod ssd1306_scenes;

/// A display on the host: every pixel, starting dark.
struct Panel<C> {
    size: Size,
    px: Vec<C>,
}

impl<C: PixelColor> Panel<C> {
    fn new(size: Size, dark: C) -> Self {
        Self {
            size,
            px: vec![dark; (size.width * size.height) as usize],
        }
    }
}

impl<C: PixelColor> OriginDimensions for Panel<C> {
    fn size(&self) -> Size {
        self.size
    }
}

impl<C: PixelColor> DrawTarget for Panel<C> {
    type Color = C;
    type Error = Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(&mut self, pixels: I) -> Result<(), Infallible> {
        for Pixel(p, c) in pixels {
            if self.bounding_box().contains(p) {
                self.px[(p.y as u32 * self.size.width + p.x as u32) as usize] = c;
            }
        }
        Ok(())
    }
}

fn rgb565_bytes(panel: &Panel<Rgb565>) -> Vec<u8> {
    panel
        .px
        .iter()
        .flat_map(|c| c.into_storage().to_le_bytes())
        .collect()
}

fn binary_bytes(panel: &Panel<BinaryColor>) -> Vec<u8> {
    panel.px.iter().map(|c| u8::from(c.is_on())).collect()
}

/// One line of the frames' text file.
fn line(k: usize, stats: &FrameStats, status: &str) -> String {
    format!("{k} {} {}\t{status}\n", stats.sent, stats.traced)
}

fn simple_frames(dir: &Path, us: &[Option<u64>]) -> Result<(), String> {
    let size = Size::new(240, 240);
    let film = simple::Film {
        scene: &simple_scenes::CIRCLING,
        camera: simple_scenes::CIRCLING_CAMERA.with_size(size),
        animation: &simple_scenes::CIRCLING_ANIMATION,
    };
    let mut scene = simple_scenes::CIRCLING.clone();
    let mut shown = Incremental::new();
    let mut panel = Panel::new(size, Rgb565::BLACK);
    let mut text = String::new();
    let frames = film.animation.frames();
    for (k, us) in us.iter().enumerate() {
        let us = us.ok_or("simple: every frame has its own time")?;
        let frame = k as u32 % frames;
        let drawn: Result<(Arithmetic, FrameStats), simple::Failed<Infallible>> =
            simple::frame(&mut panel, &mut shown, &film, frame, &mut scene);
        let Ok((_, stats)) = &drawn else {
            return Err(format!("simple: frame {k} not drawn"));
        };
        let stats = *stats;
        write_file(dir, &format!("host-simple-{k}-frame.raw"), &rgb565_bytes(&panel))?;
        let status = simple::status(&drawn, us, size.width * size.height, 0);
        let Ok(()) = simple::show(&mut panel, &mut shown, &status);
        write_file(dir, &format!("host-simple-{k}-status.raw"), &rgb565_bytes(&panel))?;
        text.push_str(&line(k, &stats, &status));
    }
    write_file(dir, "host-simple.txt", text.as_bytes())
}

fn ssd1306_frames(dir: &Path, us: &[Option<u64>]) -> Result<(), String> {
    let size = Size::new(128, 64);
    let film = ssd1306::Film {
        scene: &ssd1306_scenes::CIRCLING,
        camera: ssd1306_scenes::CIRCLING_CAMERA.with_size(size),
        animation: &ssd1306_scenes::CIRCLING_ANIMATION,
    };
    let mut scene = ssd1306_scenes::CIRCLING.clone();
    let mut shown = Incremental::new();
    let mut panel = Panel::new(size, BinaryColor::Off);
    let mut text = String::new();
    let frames = film.animation.frames();
    for (k, &us) in us.iter().enumerate() {
        let frame = k as u32 % frames;
        let drawn: Result<(Arithmetic, FrameStats), ssd1306::Failed<Infallible>> =
            ssd1306::frame(&mut panel, &mut shown, &film, frame, &mut scene);
        let Ok((_, stats)) = &drawn else {
            return Err(format!("ssd1306: frame {k} not drawn"));
        };
        let stats = *stats;
        let status = ssd1306::status(&drawn, us, size.width * size.height, 0);
        let Ok(()) = ssd1306::show(&mut panel, &mut shown, &status);
        write_file(dir, &format!("host-ssd1306-{k}-frame.raw"), &binary_bytes(&panel))?;
        text.push_str(&line(k, &stats, &status));
    }
    write_file(dir, "host-ssd1306.txt", text.as_bytes())
}

/// Every printable ASCII character of `FONT_6X10` as rows of `#` (on) and `.` (off).
fn font() -> String {
    let style = MonoTextStyle::new(&FONT_6X10, BinaryColor::On);
    let mut out = String::new();
    for code in 0x20u8..0x7f {
        let mut cell = Panel::new(Size::new(6, 10), BinaryColor::Off);
        let glyph = [code];
        let Ok(glyph) = std::str::from_utf8(&glyph) else {
            continue;
        };
        let Ok(_) = Text::with_baseline(glyph, Point::zero(), style, Baseline::Top).draw(&mut cell);
        let _ = writeln!(out, "{code}");
        for row in cell.px.chunks(6) {
            let row: String = row.iter().map(|c| if c.is_on() { '#' } else { '.' }).collect();
            let _ = writeln!(out, "{row}");
        }
    }
    out
}

fn write_file(dir: &Path, name: &str, bytes: &[u8]) -> Result<(), String> {
    let path = dir.join(name);
    fs::write(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))
}

fn run(args: &[String]) -> Result<(), String> {
    let [dir, board, us] = args else {
        return Err("usage: pico_frames DIR simple|ssd1306 US,US,… (- for no time)".into());
    };
    let us = us
        .split(',')
        .map(|v| match v {
            "-" => Ok(None),
            v => v.parse().map(Some).map_err(|e| format!("{v}: {e}")),
        })
        .collect::<Result<Vec<Option<u64>>, String>>()?;
    let dir = Path::new(dir);
    fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    write_file(dir, "font-6x10.txt", font().as_bytes())?;
    match board.as_str() {
        "simple" => simple_frames(dir, &us),
        "ssd1306" => ssd1306_frames(dir, &us),
        other => Err(format!("unknown board {other}")),
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("pico_frames: {e}");
            ExitCode::from(2)
        }
    }
}
