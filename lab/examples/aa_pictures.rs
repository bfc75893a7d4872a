//! The README's anti-aliasing pictures: `Sampling::Center` beside `Sampling::Adaptive(4)`
//! on the displays anti-aliasing is for, enlarged (nearest neighbour) so the pixels show,
//! and the edge pixels `Adaptive(4)` traced with the grid.
//!
//! ```text
//! cargo run --release --features tools --example aa_pictures [-- --out DIR]   # default: docs/
//! ```
//!
//! Writes:
//! - `aa-lab-128x64-binary-dither.png`: `scenes/lab.toml` at 128×64 on a 1-bit display
//!   (`BinaryColor` through `dithered()`, Bayer 8×8) in the simulator's blue OLED
//!   colours, ×4;
//! - `aa-lab-240x240-rgb565.png`: `scenes/lab.toml` at 240×240 `Rgb565`, the crop
//!   [`CROP`] of it, ×4;
//! - `aa-shadows-edge-pixels.png`: `scenes/shadows.toml` (240×240): the pixels whose
//!   `Sample::rays` from `Render::trace` with `Adaptive(4)` is more than 1 in white, over
//!   the `Center` render dimmed to a quarter, ×2.
//!
//! Each image is rendered whole through the public API (`Render::draw` into the
//! simulator's frame buffer, `Render::trace` for the mask), with the scene file's camera
//! at the picture's size (same vertical field of view, the simulator's `--size`). The
//! PNGs carry no time or text chunk: the same build writes the same bytes. Prints how
//! many pixels differ between the two renders of each pair and how many edge pixels
//! the mask has (the README quotes them).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use embedded_graphics::pixelcolor::{BinaryColor, Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics_simulator::{BinaryColorTheme, OutputSettingsBuilder, SimulatorDisplay};
use embedded_raytracer::dither::DitherExt;
use embedded_raytracer::{Camera, Render, Sampling, Scene};

use embedded_raytracer_scenes as standard;

/// The part of the 240×240 render shown enlarged: the red sphere's rim against the
/// cyan sphere and the background, and the blue sphere's edge.
const CROP: Rectangle = Rectangle::new(Point::new(36, 50), Size::new(90, 90));

/// Output pixels between the two halves of a pair.
const GAP: u32 = 12;

/// The gap's colour.
const GAP_COLOR: Rgb888 = Rgb888::new(255, 255, 255);

/// An RGB image, row-major.
struct Picture {
    size: Size,
    pixels: Vec<Rgb888>,
}

impl Picture {
    fn new(size: Size, fill: Rgb888) -> Self {
        Self {
            size,
            pixels: vec![fill; (size.width * size.height) as usize],
        }
    }

    /// The display's pixels as the simulator shows them (`BinaryColor` in `theme`).
    fn of<C: PixelColor + Into<Rgb888>>(display: &SimulatorDisplay<C>, theme: BinaryColorTheme) -> Self {
        // One output pixel per display pixel (the builder's defaults are the window's
        // enlarged, spaced pixels).
        let settings = OutputSettingsBuilder::new()
            .scale(1)
            .pixel_spacing(0)
            .theme(theme)
            .build();
        let image = display.to_rgb_output_image(&settings);
        let bytes = image.as_image_buffer();
        Self {
            size: display.size(),
            pixels: bytes
                .as_raw()
                .chunks_exact(3)
                .map(|c| Rgb888::new(c[0], c[1], c[2]))
                .collect(),
        }
    }

    fn index(&self, p: Point) -> usize {
        (p.y as u32 * self.size.width + p.x as u32) as usize
    }

    fn get(&self, p: Point) -> Rgb888 {
        self.pixels[self.index(p)]
    }

    fn set(&mut self, p: Point, color: Rgb888) {
        let k = self.index(p);
        self.pixels[k] = color;
    }

    /// Draws `area` of `src` with its top-left at `at`, each pixel as a `scale × scale`
    /// square (nearest neighbour).
    fn blit(&mut self, src: &Picture, area: Rectangle, at: Point, scale: u32) {
        for p in area.points() {
            let color = src.get(p);
            let q = at + (p - area.top_left) * scale as i32;
            for d in Rectangle::new(Point::zero(), Size::new(scale, scale)).points() {
                self.set(q + d, color);
            }
        }
    }

    /// `area` of `left` and of `right`, ×`scale`, side by side with [`GAP`] between;
    /// prints how many of the whole images' pixels differ.
    fn pair(left: &Picture, right: &Picture, area: Rectangle, scale: u32) -> Self {
        let differ = left
            .pixels
            .iter()
            .zip(&right.pixels)
            .filter(|(a, b)| a != b)
            .count();
        println!(
            "{differ} of {} pixels differ between Center and Adaptive(4)",
            left.pixels.len()
        );
        let half = area.size * scale;
        let mut out = Self::new(Size::new(2 * half.width + GAP, half.height), GAP_COLOR);
        out.blit(left, area, Point::zero(), scale);
        out.blit(right, area, Point::new((half.width + GAP) as i32, 0), scale);
        out
    }

    fn whole(&self) -> Rectangle {
        Rectangle::new(Point::zero(), self.size)
    }

    /// Writes an 8-bit RGB PNG (no ancillary chunks).
    fn save(&self, path: &Path) -> Result<(), String> {
        let fail = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
        let file = std::fs::File::create(path).map_err(|e| fail(&e))?;
        let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), self.size.width, self.size.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(|e| fail(&e))?;
        let bytes: Vec<u8> = self.pixels.iter().flat_map(|c| [c.r(), c.g(), c.b()]).collect();
        writer.write_image_data(&bytes).map_err(|e| fail(&e))?;
        writer.finish().map_err(|e| fail(&e))?;
        println!("{} ({}×{})", path.display(), self.size.width, self.size.height);
        Ok(())
    }
}

/// The scene file's camera at `size` (same vertical field of view).
fn resized(camera: &Camera, size: Size) -> Camera {
    camera
        .params()
        .with_size(size)
        .build()
        .expect("the standard scenes' cameras are valid at the pictures' sizes")
}

/// `scene` drawn with `sampling` on an `Rgb565` display.
fn rgb565<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    sampling: Sampling,
) -> SimulatorDisplay<Rgb565> {
    let mut display = SimulatorDisplay::<Rgb565>::new(camera.size());
    let Ok(()) = Render::<N, Rgb565, L, P, D>::new(scene, camera)
        .with_sampling(sampling)
        .draw(&mut display);
    display
}

/// `scene` drawn with `sampling` on a 1-bit display through `dithered()` (the averaged
/// colours are dithered).
fn dithered<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    sampling: Sampling,
) -> SimulatorDisplay<BinaryColor> {
    let mut display = SimulatorDisplay::<BinaryColor>::new(camera.size());
    let Ok(()) = Render::<N, Rgb888, L, P, D>::new(scene, camera)
        .with_sampling(sampling)
        .draw(&mut display.dithered());
    display
}

fn run() -> Result<(), String> {
    let mut out = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../docs"));
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--out" => out = PathBuf::from(args.next().ok_or("--out needs a directory")?),
            _ => return Err(format!("unknown argument `{a}`; usage: aa_pictures [--out DIR]")),
        }
    }
    std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    let adaptive = Sampling::adaptive(4).map_err(|e| e.to_string())?;
    let lab = standard::load("lab");

    // The 1-bit OLED, dithered after averaging.
    let camera = resized(&lab.camera, Size::new(128, 64));
    let [center, smooth] = [Sampling::Center, adaptive]
        .map(|s| Picture::of(&dithered(&lab.scene, &camera, s), BinaryColorTheme::OledBlue));
    Picture::pair(&center, &smooth, center.whole(), 4).save(&out.join("aa-lab-128x64-binary-dither.png"))?;

    // The 240×240 colour LCD.
    let camera = resized(&lab.camera, Size::new(240, 240));
    let [center, smooth] = [Sampling::Center, adaptive]
        .map(|s| Picture::of(&rgb565(&lab.scene, &camera, s), BinaryColorTheme::Default));
    Picture::pair(&center, &smooth, CROP, 4).save(&out.join("aa-lab-240x240-rgb565.png"))?;

    // The edge pixels of the shadows scene over its dimmed centre-ray render.
    let shadows = standard::load_full("shadows");
    let mut mask = Picture::new(shadows.camera.size(), Rgb888::BLACK);
    let render: Render<
        '_,
        { standard::MAX_SPHERES },
        Rgb888,
        { standard::MAX_LIGHTS },
        { standard::MAX_PLANES },
        { standard::MAX_DEPTH },
    > = Render::new(&shadows.scene, &shadows.camera);
    render.trace(|s| {
        let c = s.color;
        mask.set(s.pixel, Rgb888::new(c.r() / 4, c.g() / 4, c.b() / 4));
    });
    let mut edges = 0usize;
    render.with_sampling(adaptive).trace(|s| {
        if s.rays > 1 {
            mask.set(s.pixel, Rgb888::WHITE);
            edges += 1;
        }
    });
    println!(
        "shadows: {edges} edge pixels of {} ({:.2} %)",
        mask.pixels.len(),
        100.0 * edges as f64 / mask.pixels.len() as f64
    );
    let mut big = Picture::new(mask.size * 2, Rgb888::BLACK);
    big.blit(&mask, mask.whole(), Point::zero(), 2);
    big.save(&out.join("aa-shadows-edge-pixels.png"))
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::FAILURE
        }
    }
}
