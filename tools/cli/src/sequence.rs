//! Sequences: several scene files as the consecutive frames of one display, or one
//! scene's motion drawn at the moments of its frames (`t = (k − 1)/fps` for frame `k`,
//! the library's `frame_time`, as the simulator and the boards compute it).
//!
//! Each frame is drawn by one `Incremental` into one in-memory frame ([`Canvas`]), as a
//! display would be: only the pixels that can differ from the frame before are traced
//! and sent. The canvas then holds the frame's full render, bit for bit, so each
//! `DIR/000k.png` is the same bytes as the single-frame PNG of that file or moment
//! (encoded alike: [`png_out::write_frame`]), and the APNG's frames the same pixels.
//!
//! Everything that can be refused is refused before anything is written: every file is
//! loaded, every frame's motion applied, camera built and frame checked
//! (`Render::check`), every output checked by the single-frame rules.

use std::convert::Infallible;
use std::fs;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raytracer::motion::frame_time;
use embedded_raytracer::{
    scene_file, Arithmetic, FrameStats, Incremental, Method, Options, Render, Sampling, Scene,
    SecondaryOrigin,
};

use crate::args::Args;
use crate::{destination, frame_message, png_out, signals, write_with, Destination};
use embedded_raytracer_scenes::{FullSceneFile, MAX_DEPTH, MAX_LIGHTS, MAX_PLANES, MAX_SPHERES};

/// Whether the flags ask for a sequence rather than one frame.
pub fn wanted(args: &Args) -> bool {
    args.scenes.len() > 1 || args.frames.is_some() || args.output_frames.is_some()
}

/// `file` (loaded from `path`) at frame `frame` of its motion (0: its start), at `fps`
/// frames a second (default the file's own), at `size` if given: the scene and camera
/// every tool draws for that moment. A still file is itself.
pub fn at_frame(
    path: &Path,
    file: &FullSceneFile,
    size: Option<Size>,
    frame: u32,
    fps: Option<f32>,
) -> Result<Box<FullSceneFile>, String> {
    let mut base = *file.camera.params();
    if let Some(size) = size {
        base = base.with_size(size);
        base.build()
            .map_err(|e| format!("{}: --size {}x{}: {e}", path.display(), size.width, size.height))?;
    }
    let mut moved = Box::new(file.clone());
    let rate = fps.unwrap_or(file.animation.fps());
    let t = frame_time(frame, rate);
    if !t.is_finite() {
        // The moment itself is out of range: the rate is to blame, not the motions.
        let source = if fps.is_some() { "--fps" } else { "animation.fps" };
        return Err(format!(
            "{}: {source}: {rate:?} frames a second is too few: frame {}'s moment, \
             {frame}/{rate:?} s, is beyond what f32 holds",
            path.display(),
            u64::from(frame) + 1
        ));
    }
    let mut params = base;
    file.animation
        .apply(&file.scene, &base, t, &mut moved.scene, &mut params)
        .map_err(|e| {
            let field = e
                .motion()
                .map_or(String::new(), |m| format!("motion[{m}].{}: ", e.file_key()));
            format!("{}: {field}{e} (frame {})", path.display(), u64::from(frame) + 1)
        })?;
    moved.camera = params.build().map_err(|e| {
        format!(
            "{}: camera at frame {}: {e}",
            path.display(),
            u64::from(frame) + 1
        )
    })?;
    Ok(moved)
}

/// One frame in memory, 3 bytes a pixel, row-major: the display a sequence is drawn on.
pub struct Canvas {
    size: Size,
    rgb: Vec<u8>,
}

impl Canvas {
    fn new(size: Size) -> Self {
        Self {
            size,
            rgb: vec![0; size.width as usize * size.height as usize * 3],
        }
    }

    fn set(&mut self, p: Point, c: Rgb888) {
        let (w, h) = (self.size.width as i64, self.size.height as i64);
        let (x, y) = (i64::from(p.x), i64::from(p.y));
        if (0..w).contains(&x) && (0..h).contains(&y) {
            let i = ((y * w + x) * 3) as usize;
            if let Some(px) = self.rgb.get_mut(i..i + 3) {
                px.copy_from_slice(&[c.r(), c.g(), c.b()]);
            }
        }
    }
}

impl OriginDimensions for Canvas {
    fn size(&self) -> Size {
        self.size
    }
}

impl DrawTarget for Canvas {
    type Color = Rgb888;
    type Error = Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb888>>>(&mut self, pixels: I) -> Result<(), Infallible> {
        for Pixel(p, c) in pixels {
            self.set(p, c);
        }
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb888>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Infallible> {
        for (p, c) in area.points().zip(colors) {
            self.set(p, c);
        }
        Ok(())
    }
}

/// The flags every frame is drawn with.
struct Look {
    method: Method,
    secondary: SecondaryOrigin,
    sampling: Sampling,
}

/// What the display shows, per scene type: a spheres-only file is drawn through the
/// spheres-only type (the Lab #1 loop, as the single-frame path draws it), one with
/// lights, planes or mirrors through a type of the host's capacities. A frame of
/// another type than the last one is drawn whole.
///
/// A file with at most one plane goes through a type whose plane capacity is 1: the
/// incremental rule draws every frame whole in a type that can hold a second plane
/// (whose shadow rays are not culled) when a sphere moves under a light, whatever the
/// number of planes the scene has. The pixels are the scene's, not the type's.
struct Shown {
    spheres: Box<Incremental<MAX_SPHERES>>,
    one_plane: Box<Incremental<MAX_SPHERES, MAX_LIGHTS, 1, MAX_DEPTH>>,
    full: Box<Incremental<MAX_SPHERES, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>>,
}

impl Shown {
    fn new() -> Self {
        Self {
            spheres: Box::new(Incremental::new()),
            one_plane: Box::new(Incremental::new()),
            full: Box::new(Incremental::new()),
        }
    }
}

/// The scene of at most one plane in the type of plane capacity 1 ([`Shown`]).
fn with_one_plane(
    scene: &Scene<MAX_SPHERES, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>,
) -> Option<Box<Scene<MAX_SPHERES, MAX_LIGHTS, 1, MAX_DEPTH>>> {
    if scene.planes().len() > 1 {
        return None;
    }
    let mut one = Box::new(Scene::new(scene.background()));
    // Cannot fail: the same objects, already checked, within the same capacities.
    one.set_settings(scene.settings()).ok()?;
    for s in scene.spheres() {
        one.push(*s).ok()?;
    }
    for l in scene.lights() {
        one.push_light(*l).ok()?;
    }
    for p in scene.planes() {
        one.push_plane(*p).ok()?;
    }
    Some(one)
}

/// Draws `file` onto `canvas` through `shown` (`check`: only checks it can be drawn);
/// returns the frame's statistics and the arithmetic it was drawn in.
fn draw(
    file: &FullSceneFile,
    look: &Look,
    shown: &mut Shown,
    canvas: &mut Canvas,
    check: bool,
) -> Result<(FrameStats, Arithmetic), embedded_raytracer::FrameError> {
    match file.spheres_only() {
        Some(spheres) => {
            let render = Render::new(&spheres.scene, &file.camera)
                .with_method(look.method)
                .with_sampling(look.sampling);
            render.check()?;
            if check {
                return Ok((FrameStats::default(), render.arithmetic()));
            }
            shown.full.invalidate();
            shown.one_plane.invalidate();
            let Ok(stats) = shown.spheres.draw(&render, canvas);
            Ok((stats, render.arithmetic()))
        }
        None => {
            if let Some(scene) = with_one_plane(&file.scene) {
                let render = Render::new(&*scene, &file.camera)
                    .with_method(look.method)
                    .with_options(Options::DEFAULT.with_secondary(look.secondary))
                    .with_sampling(look.sampling);
                render.check()?;
                if check {
                    return Ok((FrameStats::default(), render.arithmetic()));
                }
                shown.spheres.invalidate();
                shown.full.invalidate();
                let Ok(stats) = shown.one_plane.draw(&render, canvas);
                return Ok((stats, render.arithmetic()));
            }
            let render = Render::new(&file.scene, &file.camera)
                .with_method(look.method)
                .with_options(Options::DEFAULT.with_secondary(look.secondary))
                .with_sampling(look.sampling);
            render.check()?;
            if check {
                return Ok((FrameStats::default(), render.arithmetic()));
            }
            shown.spheres.invalidate();
            shown.one_plane.invalidate();
            let Ok(stats) = shown.full.draw(&render, canvas);
            Ok((stats, render.arithmetic()))
        }
    }
}

/// The sequence the flags ask for: loads, checks, draws and writes it.
pub fn run(args: &Args) -> Result<(), String> {
    let first = args.scenes.first().ok_or("no scene file given")?.clone();
    if args.scenes.len() > 1 && args.frames.is_some() {
        return Err(format!(
            "--frames draws the motion of one scene file, and {} were given (each of several files is one frame)",
            args.scenes.len()
        ));
    }
    // Every file, loaded before anything is written.
    let mut files = Vec::with_capacity(args.scenes.len());
    for path in &args.scenes {
        let file: Box<FullSceneFile> = Box::new(scene_file::load(path).map_err(|e| e.to_string())?);
        files.push((path.clone(), file));
    }
    let moving = files.len() == 1;
    let first_file = &files.first().ok_or("no scene file given")?.1;
    let count = match (moving, args.frames) {
        (true, Some(n)) => n,
        (true, None) => first_file.animation.frames(),
        (false, _) => u32::try_from(files.len()).map_err(|_| "too many scene files")?,
    };
    let fps = args.fps.unwrap_or(first_file.animation.fps());
    let still = args.frame.map_or(0, |k| k - 1);
    let frame_of = |k: u32| -> Result<(&Path, Box<FullSceneFile>), String> {
        let (path, file, frame) = if moving {
            (&first, first_file, k)
        } else {
            let (path, file) = files.get(k as usize).ok_or("no such frame")?;
            (path, file, still)
        };
        Ok((path.as_path(), at_frame(path, file, args.size, frame, args.fps)?))
    };
    let look = Look {
        method: args.method(),
        secondary: args.secondary.unwrap_or(Options::DEFAULT.secondary),
        sampling: args.sampling.unwrap_or(Sampling::Center),
    };

    // Every frame checked before anything is written: its motion, camera, size and frame.
    let mut shown = Shown::new();
    let size = frame_of(0)?.1.camera.size();
    let mut nowhere = Canvas::new(Size::zero());
    for k in 0..count {
        let (path, file) = frame_of(k)?;
        let s = file.camera.size();
        if s != size {
            return Err(format!(
                "{}: camera.width/height: {}x{} is not the sequence's {}x{} (every frame is one display)",
                path.display(),
                s.width,
                s.height,
                size.width,
                size.height
            ));
        }
        draw(&file, &look, &mut shown, &mut nowhere, true).map_err(|e| frame_message(path, e))?;
    }

    // Every output checked by the single-frame rules before anything is traced.
    let apng = match (&args.output, &args.output_frames) {
        (Some(output), _) => Some(output.clone()),
        (None, Some(_)) => None,
        (None, None) => {
            let stem = first
                .file_stem()
                .ok_or_else(|| format!("{}: not a file name", first.display()))?;
            Some(PathBuf::from(stem).with_extension("png"))
        }
    };
    let check_output = |output: &Path| -> Result<Destination, String> {
        let mut last = None;
        for path in &args.scenes {
            last = Some(destination(output, path, args.force)?);
        }
        last.ok_or_else(|| "no scene file given".to_string())
    };
    let digits = count.to_string().len().max(4);
    if let (Some(output), Some(dir)) = (&apng, &args.output_frames) {
        // The animation is written last: over a frame of its own, it would replace it.
        let frame = |k: u32| place(&dir.join(format!("{k:0digits$}.png")));
        if let Some(k) = place(output).and_then(|at| (1..=count).find(|&k| frame(k).as_ref() == Some(&at))) {
            return Err(format!(
                "{}: --output: it is also frame {k} of --output-frames {}; give it another name",
                output.display(),
                dir.display()
            ));
        }
    }
    let apng = match apng {
        Some(output) => Some((check_output(&output)?, output)),
        None => None,
    };
    let mut frame_outputs = Vec::new();
    if let Some(dir) = &args.output_frames {
        make_directory(dir)?;
        for k in 1..=count {
            let name = dir.join(format!("{k:0digits$}.png"));
            frame_outputs.push((check_output(&name)?, name));
        }
    }
    let to_stderr = apng
        .iter()
        .chain(&frame_outputs)
        .any(|(d, _)| matches!(d, Destination::Stream { .. }));
    signals::install(
        apng.as_ref()
            .map(|(_, name)| name.as_path())
            .or(args.output_frames.as_deref())
            .unwrap_or(Path::new("")),
    );

    // The frames, drawn incrementally on one canvas.
    let mut canvas = Canvas::new(size);
    let mut animated = match &apng {
        Some((_, name)) => Some(
            png_out::Animated::new(size, count, fps)
                .map_err(|e| format!("{}: cannot write the PNG: {e}", name.display()))?,
        ),
        None => None,
    };
    let mut frame_outputs = frame_outputs.into_iter();
    let (mut traced, mut sent, mut tracing) = (0u64, 0u64, Duration::ZERO);
    let mut arithmetics: Vec<Arithmetic> = Vec::new();
    for k in 0..count {
        let (path, file) = frame_of(k)?;
        let start = Instant::now();
        let (stats, arithmetic) =
            draw(&file, &look, &mut shown, &mut canvas, false).map_err(|e| frame_message(path, e))?;
        let took = start.elapsed();
        if let Some(e) = stats.refused {
            return Err(frame_message(path, e));
        }
        tracing += took;
        traced += u64::from(stats.traced);
        sent += u64::from(stats.sent);
        if !arithmetics.contains(&arithmetic) {
            arithmetics.push(arithmetic);
        }
        if let Some((destination, name)) = frame_outputs.next() {
            write_with(destination, &name, |out| {
                png_out::write_frame(size, &canvas.rgb, out)
            })?;
        }
        if let (Some(animated), Some((_, name))) = (&mut animated, &apng) {
            animated
                .push(&canvas.rgb)
                .map_err(|e| format!("{}: cannot write the PNG: {e}", name.display()))?;
        }
        if !args.quiet {
            let _ = writeln!(
                io::stderr(),
                "frame {}/{count}: traced {} px, sent {} px in {} windows{}, {:.3} ms",
                k + 1,
                stats.traced,
                stats.sent,
                stats.windows,
                if stats.full { " (whole frame)" } else { "" },
                took.as_secs_f64() * 1e3
            );
        }
    }
    if let (Some(animated), Some((destination, name))) = (animated, apng.as_ref()) {
        let fail = |e: io::Error| format!("{}: cannot write the PNG: {e}", name.display());
        let bytes = animated.finish().map_err(fail)?;
        let destination = match destination {
            Destination::File { path, existing } => Destination::File {
                path: path.clone(),
                existing: existing.clone(),
            },
            Destination::Stream { path } => Destination::Stream { path: path.clone() },
        };
        write_with(destination, name, |mut out| out.write_all(&bytes))?;
    }

    let pixels = u64::from(count) * u64::from(size.width) * u64::from(size.height);
    let arithmetic = arithmetics
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join("+");
    let sampling = match look.sampling {
        Sampling::Center => String::new(),
        other => format!(", sampling {other}"),
    };
    let outputs = apng
        .iter()
        .map(|(_, name)| name.display().to_string())
        .chain(args.output_frames.iter().map(|dir| {
            format!(
                "{}",
                dir.join(format!("{:0digits$}..{count:0digits$}.png", 1))
                    .display()
            )
        }))
        .collect::<Vec<_>>()
        .join(", ");
    let summary = format!(
        "{}: {count} frame{} of {}x{} pixels{}, method {}, arithmetic {arithmetic}{sampling}, traced {traced} pixels ({:.1} % of {pixels}), sent {sent}, {:.3} ms -> {outputs}",
        first.display(),
        if count == 1 { "" } else { "s" },
        size.width,
        size.height,
        crate::features(first_file, look.secondary),
        look.method,
        100.0 * traced as f64 / pixels.max(1) as f64,
        tracing.as_secs_f64() * 1e3,
    );
    let _ = if to_stderr {
        writeln!(io::stderr(), "{summary}")
    } else {
        writeln!(io::stdout(), "{summary}")
    };
    Ok(())
}

/// The file a write to `p` reaches: where it exists, the file its links lead to (a
/// write goes there); else the name `p` gives it in its directory, the directory
/// resolved through links where it exists and made absolute where it does not yet.
/// `None` for standard output (`-`) or a path without a file name.
fn place(p: &Path) -> Option<PathBuf> {
    if p == Path::new("-") {
        return None;
    }
    if let Ok(file) = fs::canonicalize(p) {
        return Some(file);
    }
    let parent = p
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let parent = fs::canonicalize(parent)
        .or_else(|_| std::path::absolute(parent))
        .ok()?;
    Some(parent.join(p.file_name()?))
}

/// `dir`, made if missing (its parent must exist), refused if it is not a directory.
fn make_directory(dir: &Path) -> Result<(), String> {
    match fs::metadata(dir) {
        Ok(meta) if meta.is_dir() => Ok(()),
        Ok(_) => Err(format!("{}: --output-frames: not a directory", dir.display())),
        Err(e) if e.kind() == io::ErrorKind::NotFound => fs::create_dir(dir).map_err(|e| {
            format!(
                "{}: --output-frames: cannot make the directory: {e}",
                dir.display()
            )
        }),
        Err(e) => Err(format!("{}: --output-frames: {e}", dir.display())),
    }
}
