//! The sampling axis: every `Sampling` choice on every standard scene with the default
//! method, its cost (host ns/pixel, rays per pixel) against its mean error from the
//! supersampled reference; measured, drawn in two panels with their legend, and
//! written as a section of the md and a block of the csv.

use std::fmt::Write as _;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_raytracer::{scene_file::SceneFile, Camera, Method, Options, Sampling, Scene};
use embedded_raytracer_lab::aa;
use embedded_raytracer_scenes::{self as standard, FEATURE_SCENES, MAX_SPHERES, SCENES};
use plotters::prelude::*;

use crate::measure::time_sampled;
use crate::panels::{fmt_tick, log_ticks};
use crate::plot::{DrawResult, Label};

/// One sampling choice on one scene (default method).
pub struct SamplingPoint {
    pub scene: &'static str,
    /// The reference's rays per pixel side.
    pub reference_rays: u32,
    /// The image measured (the scene's, capped at the adaptive row buffer's width).
    pub size: Size,
    pub quality: aa::Quality,
    /// Median ns/pixel.
    pub ns: f64,
}

/// Measures every sampling choice of `scene` against the reference (its colours are
/// not kept) and adds one timing case per choice, at the same image size.
fn sampling_cases<'a, const N: usize, const L: usize, const P: usize, const D: usize>(
    name: &'static str,
    scene: &'a Scene<N, L, P, D>,
    camera: &Camera,
    reference_rays: u32,
    points: &mut Vec<SamplingPoint>,
    cases: &mut Vec<Box<dyn Fn() -> f64 + 'a>>,
) {
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let measured = aa::measure(scene, camera, reference_rays, threads);
    let camera = aa::capped(camera);
    for mut quality in measured.samplings {
        quality.colors = Vec::new();
        let sampling = quality.sampling;
        points.push(SamplingPoint {
            scene: name,
            reference_rays,
            size: measured.size,
            quality,
            ns: f64::NAN,
        });
        cases.push(Box::new(move || {
            time_sampled(
                scene,
                &camera,
                Method::TARGET_DEFAULT,
                Options::DEFAULT,
                sampling,
                1,
            )
        }));
    }
}

/// The sampling axis of the spheres-only scenes `files` ([`SCENES`] order) and the
/// feature scenes: errors against the reference first, then `runs` interleaved timing
/// rounds of every scene and sampling choice (`quick`: against a 4 × 4-ray reference).
pub fn measure(files: &[SceneFile<MAX_SPHERES>], quick: bool, runs: usize) -> Vec<SamplingPoint> {
    let reference_rays = if quick { 4 } else { aa::REFERENCE_RAYS };
    let feature_files: Vec<standard::FullSceneFile> = FEATURE_SCENES
        .iter()
        .map(|scene| standard::load_full(scene))
        .collect();
    let mut sampled = Vec::new();
    let mut sampled_cases: Vec<Box<dyn Fn() -> f64 + '_>> = Vec::new();
    for (scene, file) in SCENES.iter().zip(files) {
        sampling_cases(
            scene,
            &file.scene,
            &file.camera,
            reference_rays,
            &mut sampled,
            &mut sampled_cases,
        );
    }
    for (scene, file) in FEATURE_SCENES.iter().zip(&feature_files) {
        sampling_cases(
            scene,
            &file.scene,
            &file.camera,
            reference_rays,
            &mut sampled,
            &mut sampled_cases,
        );
    }
    let mut samples = vec![Vec::new(); sampled_cases.len()];
    for _ in 0..runs {
        for (k, case) in sampled_cases.iter().enumerate() {
            samples[k].push(case());
        }
    }
    for (p, mut times) in sampled.iter_mut().zip(samples) {
        times.sort_by(f64::total_cmp);
        p.ns = times[times.len() / 2];
        eprintln!(
            "{:8} {:12} {:8.2} ns/pixel  {:5.2} rays/pixel  mean error {:5.2}",
            p.scene, p.quality.sampling, p.ns, p.quality.rays_per_pixel, p.quality.mean
        );
    }
    sampled
}

/// The colour of a scene's points in the sampling panels, in [`SCENES`] then
/// [`FEATURE_SCENES`] order.
fn scene_color(scene: &str) -> RGBColor {
    const COLORS: [RGBColor; 7] = [
        RGBColor(220, 30, 60),
        RGBColor(30, 120, 220),
        RGBColor(20, 160, 60),
        RGBColor(230, 120, 20),
        RGBColor(150, 80, 200),
        RGBColor(0, 0, 0),
        RGBColor(0, 160, 160),
    ];
    let k = SCENES
        .iter()
        .chain(&FEATURE_SCENES)
        .position(|s| *s == scene)
        .unwrap_or(0);
    COLORS[k % COLORS.len()]
}

/// One sampling panel: log `x` (cost) against log mean error; per scene a line from
/// `Center` through `Grid(2…4)` (thin, hollow circles) and one through `Adaptive(2…4)`
/// (thick, filled circles).
pub fn draw_sampling<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    x_name: &str,
    x: &dyn Fn(&SamplingPoint) -> f64,
    pts: &[SamplingPoint],
    labels: &mut Vec<Label>,
) -> DrawResult<()>
where
    DB::ErrorType: 'static,
{
    let xmin = pts.iter().map(x).fold(f64::INFINITY, f64::min) / 1.3;
    let xmax = pts.iter().map(x).fold(0.0, f64::max) * 1.3;
    let ymin = pts.iter().map(|p| p.quality.mean).fold(f64::INFINITY, f64::min) / 1.3;
    let ymax = pts.iter().map(|p| p.quality.mean).fold(0.0, f64::max) * 1.3;
    let mut chart = ChartBuilder::on(area)
        .margin_top(24)
        .margin_left(48)
        .margin_bottom(26)
        .margin_right(14)
        .build_cartesian_2d((xmin..xmax).log_scale(), (ymin..ymax).log_scale())?;
    let grey = RGBColor(225, 225, 225);
    for t in log_ticks(xmin, xmax) {
        chart.draw_series(std::iter::once(PathElement::new(
            vec![(t, ymin), (t, ymax)],
            grey,
        )))?;
        let (px, py) = chart.backend_coord(&(t, ymin));
        labels.push(Label {
            x: px - 6,
            y: py + 12,
            text: fmt_tick(t),
            color: Rgb888::BLACK,
        });
    }
    for t in log_ticks(ymin, ymax) {
        chart.draw_series(std::iter::once(PathElement::new(
            vec![(xmin, t), (xmax, t)],
            grey,
        )))?;
        let (px, py) = chart.backend_coord(&(xmin, t));
        labels.push(Label {
            x: px - 44,
            y: py + 3,
            text: format!("{:>6}", fmt_tick(t)),
            color: Rgb888::BLACK,
        });
    }
    let (tx, ty) = chart.backend_coord(&(xmin, ymax));
    labels.push(Label {
        x: tx,
        y: ty - 8,
        text: title.to_string(),
        color: Rgb888::BLACK,
    });
    let (bx, by) = chart.backend_coord(&(xmax, ymin));
    labels.push(Label {
        x: bx - 6 * x_name.len() as i32 - 12,
        y: by + 22,
        text: x_name.into(),
        color: Rgb888::new(90, 90, 90),
    });
    chart.draw_series(std::iter::once(PathElement::new(
        vec![
            (xmin, ymin),
            (xmax, ymin),
            (xmax, ymax),
            (xmin, ymax),
            (xmin, ymin),
        ],
        BLACK,
    )))?;
    let mut scenes: Vec<&str> = pts.iter().map(|p| p.scene).collect();
    scenes.dedup();
    for scene in scenes {
        let color = scene_color(scene);
        let of = |keep: &dyn Fn(Sampling) -> bool| -> Vec<(f64, f64)> {
            pts.iter()
                .filter(|p| p.scene == scene && keep(p.quality.sampling))
                .map(|p| (x(p), p.quality.mean))
                .collect()
        };
        let grid = of(&|s| matches!(s, Sampling::Center | Sampling::Grid(_)));
        let adaptive = of(&|s| matches!(s, Sampling::Center | Sampling::Adaptive(_)));
        chart.draw_series(std::iter::once(PathElement::new(
            grid.clone(),
            color.stroke_width(1),
        )))?;
        chart.draw_series(std::iter::once(PathElement::new(
            adaptive.clone(),
            color.stroke_width(2),
        )))?;
        chart.draw_series(
            grid.iter()
                .skip(1)
                .map(|p| Circle::new(*p, 4, color.stroke_width(1))),
        )?;
        chart.draw_series(
            adaptive
                .iter()
                .skip(1)
                .map(|p| Circle::new(*p, 4, color.filled())),
        )?;
        if let Some(&c) = grid.first() {
            let (px, py) = chart.backend_coord(&c);
            let plot = chart.plotting_area().strip_coord_spec();
            let (ox, oy) = plot.get_base_pixel();
            plot.draw(&plotters::element::Rectangle::new(
                [(px - ox - 4, py - oy - 4), (px - ox + 4, py - oy + 4)],
                color.filled(),
            ))?;
        }
    }
    Ok(())
}

/// The sampling panels' legend (marker positions relative to its panel, labels
/// absolute), below the methods' legend that runs into this panel's top; `n` is the
/// reference's rays per pixel side.
pub fn sampling_legend<DB: DrawingBackend>(
    legend: &DrawingArea<DB, plotters::coord::Shift>,
    n: u32,
    labels: &mut Vec<Label>,
) -> DrawResult<()>
where
    DB::ErrorType: 'static,
{
    let (lx, ly) = legend.get_base_pixel();
    let mut y = 70;
    let item = |labels: &mut Vec<Label>, y: i32, text: String, color: Rgb888| {
        labels.push(Label {
            x: lx + 60,
            y: ly + y + 4,
            text,
            color,
        });
    };
    item(
        labels,
        y,
        "sampling panels (left and right of here):".into(),
        Rgb888::BLACK,
    );
    y += 24;
    for scene in SCENES.iter().chain(&FEATURE_SCENES) {
        let c = scene_color(scene);
        legend.draw(&Circle::new((40, y), 5, c.filled()))?;
        item(labels, y, (*scene).into(), Rgb888::new(c.0, c.1, c.2));
        y += 20;
    }
    y += 10;
    legend.draw(&plotters::element::Rectangle::new(
        [(36, y - 4), (44, y + 4)],
        BLACK.filled(),
    ))?;
    item(labels, y, "center (1 ray)".into(), Rgb888::BLACK);
    y += 20;
    legend.draw(&PathElement::new(vec![(26, y), (54, y)], BLACK.stroke_width(1)))?;
    legend.draw(&Circle::new((40, y), 4, BLACK.stroke_width(1)))?;
    item(labels, y, "grid:2, grid:3, grid:4".into(), Rgb888::BLACK);
    y += 20;
    legend.draw(&PathElement::new(vec![(26, y), (54, y)], BLACK.stroke_width(2)))?;
    legend.draw(&Circle::new((40, y), 4, BLACK.filled()))?;
    item(
        labels,
        y,
        "adaptive:2, adaptive:3, adaptive:4".into(),
        Rgb888::BLACK,
    );
    y += 24;
    item(
        labels,
        y,
        "y: mean error (levels, log) vs the".into(),
        Rgb888::BLACK,
    );
    y += 12;
    item(
        labels,
        y,
        format!("  {n}x{n}-ray reference, linear light"),
        Rgb888::BLACK,
    );
    y += 20;
    item(
        labels,
        y,
        "default method; scenes wider than".into(),
        Rgb888::BLACK,
    );
    y += 12;
    item(labels, y, "  256 px at 256 wide".into(), Rgb888::BLACK);
    Ok(())
}

/// The sampling axis's md section and csv block.
pub fn write_sampling(md: &mut String, csv: &mut String, sampled: &[SamplingPoint]) -> std::fmt::Result {
    let n = sampled.first().map_or(aa::REFERENCE_RAYS, |p| p.reference_rays);
    writeln!(md, "\n## Sampling: cost against error\n")?;
    writeln!(md, "Every `Sampling` choice with the default method: host ns/pixel (timed like the methods above) and its ratio to `center` on the same scene, rays averaged per pixel, and the error against the {n} × {n}-ray box-filtered reference in linear light (`reference::aa`) in 8-bit levels, the largest channel difference per pixel, over all pixels and over the pixels `adaptive:4` traced with the grid (the measurement of `cargo run --release --features tools --example aa_table`; scenes wider than 256 pixels, adaptive sampling's row buffer, at 256 wide). The chart's two panels at the bottom right plot the mean error against ns/pixel and against rays/pixel.\n")?;
    writeln!(md, "| scene | size | sampling | ns/pixel | × center | rays/pixel | mean error | max error | mean error, edge pixels |")?;
    writeln!(md, "|---|---|---|---:|---:|---:|---:|---:|---:|")?;
    writeln!(csv, "\nsampling_scene,width,height,sampling,ns_per_pixel,ratio_to_center,rays_per_pixel,mean_error,max_error,edge_mean_error,edge_max_error")?;
    for p in sampled {
        let center = sampled
            .iter()
            .find(|c| c.scene == p.scene && c.quality.sampling == Sampling::Center)
            .map_or(f64::NAN, |c| c.ns);
        let q = &p.quality;
        writeln!(
            md,
            "| {} | {}×{} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.1} | {:.2} |",
            p.scene,
            p.size.width,
            p.size.height,
            q.sampling,
            p.ns,
            p.ns / center,
            q.rays_per_pixel,
            q.mean,
            q.max,
            q.edge_mean
        )?;
        writeln!(
            csv,
            "{},{},{},{},{:.3},{:.3},{:.4},{:.4},{:.2},{:.4},{:.2}",
            p.scene,
            p.size.width,
            p.size.height,
            q.sampling,
            p.ns,
            p.ns / center,
            q.rays_per_pixel,
            q.mean,
            q.max,
            q.edge_mean,
            q.edge_max
        )?;
    }
    Ok(())
}
