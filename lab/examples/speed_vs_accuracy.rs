//! The chart of speed against accuracy: every method on every standard scene.
//!
//! ```text
//! cargo run --release --example speed_vs_accuracy            # writes docs/speed_vs_accuracy.{csv,png,md}
//! cargo run --release --example speed_vs_accuracy -- --quick --out target/chart   # CI: 1 run each
//! ```
//!
//! For each scene and method: the time per pixel (median of several renders in this
//! process, into an in-memory Rgb565 frame buffer) and the error against an `f64`
//! reference render: **coverage errors** (pixels whose hit sphere differs from the
//! reference's, hit/miss included) and the **max shade error** (largest 8-bit channel
//! difference among the pixels that hit the same sphere as the reference, or both miss).
//! Also the growth curve: ns/pixel against the number of spheres (the first 1 … 64 of
//! the `crowd` scene), and the same errors on `lab` against the **estimated Cortex-M4
//! cycles per pixel** of `lab/data/cycles_cortex_m4.txt` (240×240, from `.ci/cycles
//! --update`; a model, see the README) instead of the host's time.
//!
//! And the **sampling axis** (two panels at the bottom right, a section of the md and
//! csv): every `Sampling` choice on every standard scene with the default method, its
//! cost — host ns/pixel timed in the same interleaved way, and rays averaged per pixel —
//! against its mean error over all pixels, in 8-bit levels, from the 16 × 16-ray
//! box-filtered reference in linear light (`reference::aa`; the measurement of
//! `aa_table`, `common/aa.rs`, so the errors are the README's anti-aliasing table's:
//! scenes wider than 256 pixels at 256 wide). `--quick` measures against a 4 × 4-ray
//! reference instead (16 times cheaper; a smoke test, not the README's figures).
//!
//! The reference is the accuracy lab's independent `f64` renderer
//! ([`embedded_raytracer_lab::reference`]: the seed's camera and Lab #1 shading, the robust
//! sphere test, all in `f64`, sharing no code with the kernel), and the metrics are its
//! [`compare`](embedded_raytracer_lab::reference::compare) (pixels the reference cannot
//! decide are not counted).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::text::Text;
use embedded_graphics_simulator::{OutputSettings, SimulatorDisplay};
use embedded_raytracer::{
    scene_file, Camera, Method, Options, Render, Sampling, Scene, SecondaryOrigin, SphereTest, Sqrt, Stepping,
};
use embedded_raytracer_lab::reference::{self, compare, ReferenceImage};
use plotters::prelude::*;

use embedded_raytracer_lab::aa;
use embedded_raytracer_lab::cycle_model;
use embedded_raytracer_scenes as standard;
use standard::{FEATURE_SCENES, MAX_SPHERES, SCENES};

// ---------------------------------------------------------------------------------
// Timing and errors.

use embedded_raytracer_lab::slice_target;
use slice_target::SliceTarget;

/// Median ns/pixel over `runs` renders.
fn time_render<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    method: Method,
    options: Options,
    runs: usize,
) -> f64 {
    time_sampled(scene, camera, method, options, Sampling::Center, runs)
}

/// Median ns/pixel over `runs` renders with `sampling`.
fn time_sampled<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    method: Method,
    options: Options,
    sampling: Sampling,
    runs: usize,
) -> f64 {
    let size = camera.size();
    let pixels = f64::from(size.width) * f64::from(size.height);
    let mut buf = vec![Rgb565::BLACK; (size.width * size.height) as usize];
    let render = Render::new(scene, camera)
        .with_method(method)
        .with_options(options)
        .with_sampling(sampling);
    let mut times: Vec<f64> = (0..runs)
        .map(|_| {
            let mut target = SliceTarget { buf: &mut buf, size };
            let start = Instant::now();
            let Ok(()) = render.draw(&mut target);
            let ns = start.elapsed().as_nanos() as f64;
            std::hint::black_box(&buf);
            ns / pixels
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

/// Coverage errors and the max shade error against the reference.
fn errors<const N: usize>(
    scene: &Scene<N>,
    camera: &Camera,
    method: Method,
    culling: bool,
    reference: &ReferenceImage,
) -> (usize, u8) {
    let render = Render::<N, Rgb888>::new(scene, camera)
        .with_method(method)
        .with_options(Options::DEFAULT.with_span_culling(culling));
    let m = compare(&render, reference);
    (m.coverage_errors, m.shade_max)
}

/// Pixels more than 2 levels off the reference (outside its undecidable band), max and
/// mean error, for a scene with lights, planes or mirrors.
fn lit_errors<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    method: Method,
    options: Options,
    reference: &ReferenceImage,
) -> (usize, u8, f64) {
    let render = Render::<N, Rgb888, L, P, D>::new(scene, camera)
        .with_method(method)
        .with_options(options);
    let m = compare(&render, reference);
    (m.over_2, m.color_max, m.color_mean)
}

/// The secondary-origin axis of the lit scenes: every method with each.
const ORIGINS: [(&str, SecondaryOrigin); 2] = [
    ("convex", SecondaryOrigin::Convex),
    ("epsilon 1e-3", SecondaryOrigin::TEXTBOOK),
];

/// One point of a lit scene: method × secondary origin (or the literal baseline).
struct LitPoint {
    scene: &'static str,
    origin: &'static str,
    label: String,
    method: Option<Method>,
    ns: f64,
    over_2: usize,
    color_max: u8,
    color_mean: f64,
}

/// The scene of the estimated-cycles panels.
const CYCLES_SCENE: &str = "lab";

/// `(scene, method, estimated Cortex-M4 cycles per pixel)` from the cycle model's data
/// file.
fn estimated_cycles(path: &Path) -> Result<Vec<(String, String, f64)>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(cycle_model::estimates(&text)
        .iter()
        .map(|e| {
            (
                e.scene().to_string(),
                e.method().to_string(),
                e.per_pixel("cycles"),
            )
        })
        .collect())
}

/// One point of the chart.
struct Point3 {
    scene: &'static str,
    label: String,
    method: Option<Method>,
    ns: f64,
    coverage: usize,
    shade: u8,
    pixels: u64,
}

const BASELINE: &str = "baseline (literal, no culling)";

// ---------------------------------------------------------------------------------
// Plotting: plotters draws the shapes into an RGB buffer (no font features); the
// labels are drawn afterwards with embedded-graphics' built-in 6x10 mono font.

const W: u32 = 2800;
const H: u32 = 1230;

fn test_color(t: Option<SphereTest>) -> RGBColor {
    match t {
        Some(SphereTest::Algebraic) => RGBColor(230, 120, 20),
        Some(SphereTest::Geometric) => RGBColor(150, 80, 200),
        Some(SphereTest::Robust) => RGBColor(30, 120, 220),
        Some(SphereTest::ForwardDiff) => RGBColor(20, 160, 60),
        Some(SphereTest::Auto) => RGBColor(220, 30, 60),
        // A test the chart does not know yet: black, like the integer kernel.
        _ => RGBColor(0, 0, 0),
    }
}

/// `log10(1 + e)`: errors of 0 sit on the axis.
fn symlog(e: f64) -> f64 {
    (1.0 + e).log10()
}

/// Pareto front (min ns, min error) as points sorted by ns.
fn pareto(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut sorted: Vec<_> = points.to_vec();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for p in sorted {
        if p.1 < best {
            best = p.1;
            front.push(p);
        }
    }
    front
}

/// Timing noise margin of the Pareto marks in the tables: on a shared machine medians
/// of the same work differ by a few percent from run to run.
const NOISE: f64 = 0.05;

/// On the front unless another point is at least as accurate and more than `NOISE`
/// faster, or more accurate and not slower.
fn on_noisy_front(p: (f64, f64), all: &[(f64, f64)]) -> bool {
    !all.iter()
        .any(|q| (q.1 <= p.1 && q.0 < p.0 * (1.0 - NOISE)) || (q.1 < p.1 && q.0 <= p.0))
}

struct Label {
    x: i32,
    y: i32,
    text: String,
    color: Rgb888,
}

type DrawResult<T> = Result<T, Box<dyn std::error::Error>>;

fn plot(
    points: &[Point3],
    lit: &[LitPoint],
    growth: &[(usize, String, f64)],
    cycles: &[(String, String, f64)],
    sampled: &[SamplingPoint],
    path: &Path,
) -> DrawResult<()> {
    let mut buf = vec![255u8; (W * H * 3) as usize];
    let mut labels: Vec<Label> = Vec::new();
    let black = Rgb888::BLACK;
    {
        let root = BitMapBackend::with_buffer(&mut buf, (W, H)).into_drawing_area();
        root.fill(&WHITE)?;
        // Two rows of seven panels: coverage (top) and shade (bottom) per scene; the
        // growth curve and the legend; the estimated-cycles panels. A third row: the
        // lit scenes' pixels more than 2 levels off, per secondary origin.
        let panels = root.split_evenly((3, 7));
        let mut k = 14;
        for scene in FEATURE_SCENES {
            for (origin, _) in ORIGINS {
                let sel: Vec<&LitPoint> = lit
                    .iter()
                    .filter(|p| p.scene == scene && (p.origin == origin || p.method.is_none()))
                    .collect();
                let xy: Vec<(f64, f64)> = sel.iter().map(|p| (p.ns, symlog(p.over_2 as f64))).collect();
                let pts: Vec<Point3> = sel
                    .iter()
                    .map(|p| Point3 {
                        scene: p.scene,
                        label: p.label.clone(),
                        method: p.method,
                        ns: p.ns,
                        coverage: p.over_2,
                        shade: p.color_max,
                        pixels: 0,
                    })
                    .collect();
                let pts: Vec<&Point3> = pts.iter().collect();
                if let (Some(area), false) = (panels.get(k), pts.is_empty()) {
                    let title = format!("{scene}, {origin}: pixels > 2 levels off");
                    draw_panel(area, &title, "ns/pixel", &xy, &pts, &mut labels)?;
                }
                k += 1;
            }
        }
        for (metric, name) in [(0, "coverage errors (pixels)"), (1, "max shade error (levels)")] {
            let error = |p: &Point3| {
                symlog(if metric == 0 {
                    p.coverage as f64
                } else {
                    f64::from(p.shade)
                })
            };
            for (k, scene) in SCENES.iter().enumerate() {
                let Some(area) = panels.get(metric * 7 + k) else {
                    break;
                };
                let pts: Vec<&Point3> = points.iter().filter(|p| p.scene == *scene).collect();
                let xy: Vec<(f64, f64)> = pts.iter().map(|p| (p.ns, error(p))).collect();
                draw_panel(
                    area,
                    &format!("{scene}: {name}"),
                    "ns/pixel",
                    &xy,
                    &pts,
                    &mut labels,
                )?;
            }
            // Estimated Cortex-M4 cycles per pixel (the methods the firmware renders).
            let (pts, xy): (Vec<&Point3>, Vec<(f64, f64)>) = points
                .iter()
                .filter(|p| p.scene == CYCLES_SCENE)
                .filter_map(|p| {
                    let method = p.method?.to_string();
                    let c = cycles.iter().find(|c| c.0 == p.scene && c.1 == method)?;
                    Some((p, (c.2, error(p))))
                })
                .unzip();
            if let (Some(area), false) = (panels.get(metric * 7 + 6), pts.is_empty()) {
                let title = format!("{CYCLES_SCENE}, est. M4 cycles: {name}");
                draw_panel(area, &title, "est. M4 cycles/px", &xy, &pts, &mut labels)?;
            }
        }
        if let Some(area) = panels.get(5) {
            draw_growth(area, growth, &mut labels)?;
        }
        // The sampling axis: cost against the error from the n x n reference, by time
        // and by rays; their legend under the methods' one.
        if let (Some(time), Some(legend), Some(rays), false) =
            (panels.get(18), panels.get(19), panels.get(20), sampled.is_empty())
        {
            let title = "sampling: mean error vs ns/pixel";
            draw_sampling(time, title, "ns/pixel", &|p| p.ns, sampled, &mut labels)?;
            let title = "sampling: mean error vs rays/pixel";
            draw_sampling(
                rays,
                title,
                "rays/pixel",
                &|p| p.quality.rays_per_pixel,
                sampled,
                &mut labels,
            )?;
            sampling_legend(legend, sampled[0].reference_rays, &mut labels)?;
        }
        // Legend (marker positions relative to its panel, labels absolute).
        if let Some(legend) = panels.get(12) {
            let (lx, ly) = legend.get_base_pixel();
            let tests = [
                SphereTest::Algebraic,
                SphereTest::Geometric,
                SphereTest::Robust,
                SphereTest::ForwardDiff,
                SphereTest::Auto,
            ];
            let mut y = 40;
            let item = |labels: &mut Vec<Label>, y: i32, text: String| {
                labels.push(Label {
                    x: lx + 60,
                    y: ly + y + 4,
                    text,
                    color: black,
                });
            };
            for t in tests {
                legend.draw(&Circle::new((40, y), 6, test_color(Some(t)).filled()))?;
                item(&mut labels, y, format!("sphere test {}", t.name()));
                y += 24;
            }
            legend.draw(&Cross::new((40, y), 6, BLACK.stroke_width(2)))?;
            item(&mut labels, y, "literal baseline (no culling)".into());
            y += 34;
            legend.draw(&Circle::new((40, y), 5, BLACK.stroke_width(1)))?;
            item(&mut labels, y, "stepping direct".into());
            y += 24;
            legend.draw(&TriangleMarker::new((40, y), 6, BLACK.stroke_width(1)))?;
            item(&mut labels, y, "stepping incremental".into());
            y += 24;
            legend.draw(&plotters::element::Rectangle::new(
                [(36, y - 4), (44, y + 4)],
                BLACK.stroke_width(1),
            ))?;
            item(&mut labels, y, "stepping world-space".into());
            y += 34;
            item(&mut labels, y, "filled = exact sqrt, hollow = fast".into());
            y += 20;
            legend.draw(&PathElement::new(
                vec![(30, y), (50, y)],
                RGBColor(160, 160, 160).stroke_width(2),
            ))?;
            item(&mut labels, y, "Pareto front".into());
            y += 20;
            item(&mut labels, y, "x: ns/pixel (log scale)".into());
            y += 20;
            item(&mut labels, y, "right: estimated Cortex-M4".into());
            y += 12;
            item(&mut labels, y, "  cycles/pixel at 240x240".into());
            y += 20;
            item(&mut labels, y, "y: log10(1 + error)".into());
            y += 20;
            item(&mut labels, y, "errors vs the f64 reference".into());
            y += 20;
            item(&mut labels, y, "bottom row: lit scenes, secondary".into());
            y += 12;
            item(&mut labels, y, "  rays from the hit point (convex)".into());
            y += 12;
            item(&mut labels, y, "  or the textbook epsilon 1e-3".into());
        }
        root.present()?;
    }
    // Labels with embedded-graphics' mono font, then PNG through the simulator.
    let mut display = SimulatorDisplay::<Rgb888>::new(Size::new(W, H));
    let pixels = buf.chunks_exact(3).enumerate().map(|(k, c)| {
        embedded_graphics::Pixel(
            Point::new((k as u32 % W) as i32, (k as u32 / W) as i32),
            Rgb888::new(c[0], c[1], c[2]),
        )
    });
    display.draw_iter(pixels)?;
    for l in &labels {
        Text::new(
            &l.text,
            Point::new(l.x, l.y),
            MonoTextStyle::new(&FONT_6X10, l.color),
        )
        .draw(&mut display)?;
    }
    display
        .to_rgb_output_image(&OutputSettings::default())
        .save_png(path)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(())
}

/// Tick values for a log axis between `lo` and `hi`: 1-2-5 per decade.
fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let mut ticks = Vec::new();
    let mut decade = 10f64.powf(lo.log10().floor());
    while decade <= hi {
        for m in [1.0, 2.0, 5.0] {
            let t = decade * m;
            if t >= lo && t <= hi {
                ticks.push(t);
            }
        }
        decade *= 10.0;
    }
    ticks
}

fn fmt_tick(t: f64) -> String {
    if t >= 1.0 {
        format!("{t:.0}")
    } else {
        format!("{t}")
    }
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    x_name: &str,
    xy: &[(f64, f64)],
    pts: &[&Point3],
    labels: &mut Vec<Label>,
) -> DrawResult<()>
where
    DB::ErrorType: 'static,
{
    let xmin = xy.iter().map(|p| p.0).fold(f64::INFINITY, f64::min) / 1.3;
    let xmax = xy.iter().map(|p| p.0).fold(0.0, f64::max) * 1.3;
    let ymax = xy.iter().map(|p| p.1).fold(0.0, f64::max).max(1.0) * 1.1;
    let mut chart = ChartBuilder::on(area)
        .margin_top(24)
        .margin_left(48)
        .margin_bottom(26)
        .margin_right(14)
        .build_cartesian_2d((xmin..xmax).log_scale(), -0.05 * ymax..ymax)?;
    let grey = RGBColor(225, 225, 225);
    // Grid and tick labels.
    for t in log_ticks(xmin, xmax) {
        chart.draw_series(std::iter::once(PathElement::new(
            vec![(t, -0.05 * ymax), (t, ymax)],
            grey,
        )))?;
        let (px, py) = chart.backend_coord(&(t, -0.05 * ymax));
        labels.push(Label {
            x: px - 6,
            y: py + 12,
            text: fmt_tick(t),
            color: Rgb888::BLACK,
        });
    }
    for e in [0.0, 1.0, 10.0, 100.0, 1e3, 1e4, 1e5, 1e6] {
        let y = symlog(e);
        if y <= ymax {
            chart.draw_series(std::iter::once(PathElement::new(
                vec![(xmin, y), (xmax, y)],
                grey,
            )))?;
            let (px, py) = chart.backend_coord(&(xmin, y));
            labels.push(Label {
                x: px - 44,
                y: py + 3,
                text: format!("{e:>6}"),
                color: Rgb888::BLACK,
            });
        }
    }
    let (tx, ty) = chart.backend_coord(&(xmin, ymax));
    labels.push(Label {
        x: tx,
        y: ty - 8,
        text: title.to_string(),
        color: Rgb888::BLACK,
    });
    let (bx, by) = chart.backend_coord(&(xmax, -0.05 * ymax));
    labels.push(Label {
        x: bx - 6 * x_name.len() as i32 - 12,
        y: by + 22,
        text: x_name.into(),
        color: Rgb888::new(90, 90, 90),
    });
    // Frame.
    chart.draw_series(std::iter::once(PathElement::new(
        vec![
            (xmin, -0.05 * ymax),
            (xmax, -0.05 * ymax),
            (xmax, ymax),
            (xmin, ymax),
            (xmin, -0.05 * ymax),
        ],
        BLACK,
    )))?;
    // Pareto front.
    let front = pareto(xy);
    let mut steps = Vec::new();
    for (k, p) in front.iter().enumerate() {
        if k > 0 {
            steps.push((p.0, front[k - 1].1));
        }
        steps.push(*p);
    }
    steps.push((xmax, front.last().map_or(0.0, |p| p.1)));
    chart.draw_series(std::iter::once(PathElement::new(
        steps,
        RGBColor(160, 160, 160).stroke_width(2),
    )))?;
    // One marker per method.
    for (p, &(x, y)) in pts.iter().zip(xy) {
        let Some(m) = p.method else {
            chart.draw_series(std::iter::once(Cross::new((x, y), 6, BLACK.stroke_width(2))))?;
            continue;
        };
        let color = test_color(Some(m.sphere_test));
        let style = if m.sqrt == Sqrt::Exact {
            color.filled()
        } else {
            color.stroke_width(2)
        };
        match m.stepping {
            Stepping::Direct => {
                chart.draw_series(std::iter::once(Circle::new((x, y), 5, style)))?;
            }
            Stepping::Incremental => {
                chart.draw_series(std::iter::once(TriangleMarker::new((x, y), 6, style)))?;
            }
            Stepping::WorldSpace => {
                let (px, py) = chart.backend_coord(&(x, y));
                let plot = chart.plotting_area().strip_coord_spec();
                let (ox, oy) = plot.get_base_pixel();
                plot.draw(&plotters::element::Rectangle::new(
                    [(px - ox - 4, py - oy - 4), (px - ox + 4, py - oy + 4)],
                    style,
                ))?;
            }
            // A stepping the chart does not know yet: a circle, like direct stepping.
            _ => {
                chart.draw_series(std::iter::once(Circle::new((x, y), 5, style)))?;
            }
        }
    }
    Ok(())
}

fn draw_growth<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    growth: &[(usize, String, f64)],
    labels: &mut Vec<Label>,
) -> DrawResult<()>
where
    DB::ErrorType: 'static,
{
    let ymax = growth.iter().map(|g| g.2).fold(1.0, f64::max) * 1.5;
    let ymin = growth.iter().map(|g| g.2).fold(f64::INFINITY, f64::min) / 1.5;
    let mut chart = ChartBuilder::on(area)
        .margin_top(24)
        .margin_left(48)
        .margin_bottom(26)
        .margin_right(14)
        .build_cartesian_2d((1f64..64f64).log_scale(), (ymin..ymax).log_scale())?;
    let grey = RGBColor(225, 225, 225);
    for n in [1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0] {
        chart.draw_series(std::iter::once(PathElement::new(
            vec![(n, ymin), (n, ymax)],
            grey,
        )))?;
        let (px, py) = chart.backend_coord(&(n, ymin));
        labels.push(Label {
            x: px - 4,
            y: py + 12,
            text: format!("{n}"),
            color: Rgb888::BLACK,
        });
    }
    for t in log_ticks(ymin, ymax) {
        chart.draw_series(std::iter::once(PathElement::new(vec![(1.0, t), (64.0, t)], grey)))?;
        let (px, py) = chart.backend_coord(&(1.0, t));
        labels.push(Label {
            x: px - 44,
            y: py + 3,
            text: format!("{:>6}", fmt_tick(t)),
            color: Rgb888::BLACK,
        });
    }
    let (tx, ty) = chart.backend_coord(&(1.0, ymax));
    labels.push(Label {
        x: tx,
        y: ty - 8,
        text: "growth: ns/pixel vs spheres (crowd, first n)".into(),
        color: Rgb888::BLACK,
    });
    let mut series: Vec<String> = growth.iter().map(|g| g.1.clone()).collect();
    series.dedup();
    for (k, name) in series.iter().enumerate() {
        let color = match k {
            0 => RGBColor(220, 30, 60),
            1 => RGBColor(0, 0, 0),
            _ => RGBColor(20, 160, 60),
        };
        let line: Vec<(f64, f64)> = growth
            .iter()
            .filter(|g| &g.1 == name)
            .map(|g| (g.0 as f64, g.2))
            .collect();
        chart.draw_series(std::iter::once(PathElement::new(
            line.clone(),
            color.stroke_width(2),
        )))?;
        chart.draw_series(line.iter().map(|p| Circle::new(*p, 3, color.filled())))?;
        let (px, py) = chart.backend_coord(&(1.0, ymax));
        labels.push(Label {
            x: px + 8,
            y: py + 14 + 12 * k as i32,
            text: name.clone(),
            color: Rgb888::new(color.0, color.1, color.2),
        });
    }
    Ok(())
}

// ---------------------------------------------------------------------------------
// The sampling axis.

/// One sampling choice on one scene (default method).
struct SamplingPoint {
    scene: &'static str,
    /// The reference's rays per pixel side.
    reference_rays: u32,
    /// The image measured (the scene's, capped at the adaptive row buffer's width).
    size: Size,
    quality: aa::Quality,
    /// Median ns/pixel.
    ns: f64,
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
fn draw_sampling<DB: DrawingBackend>(
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
fn sampling_legend<DB: DrawingBackend>(
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
fn write_sampling(md: &mut String, csv: &mut String, sampled: &[SamplingPoint]) -> std::fmt::Result {
    let n = sampled.first().map_or(aa::REFERENCE_RAYS, |p| p.reference_rays);
    writeln!(md, "\n## Sampling: cost against error\n")?;
    writeln!(md, "Every `Sampling` choice with the default method: host ns/pixel (timed like the methods above) and its ratio to `center` on the same scene, rays averaged per pixel, and the error against the {n} × {n}-ray box-filtered reference in linear light (`reference::aa`) in 8-bit levels, the largest channel difference per pixel, over all pixels and over the pixels `adaptive:4` traced with the grid (the measurement of `cargo run --release --example aa_table`; scenes wider than 256 pixels, adaptive sampling's row buffer, at 256 wide). The chart's two panels at the bottom right plot the mean error against ns/pixel and against rays/pixel.\n")?;
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

// ---------------------------------------------------------------------------------

struct Args {
    quick: bool,
    out: PathBuf,
}

impl Args {
    /// Timed renders per point (interleaved rounds).
    fn runs(&self) -> usize {
        if self.quick {
            1
        } else {
            15
        }
    }
}

fn parse_args() -> Result<Args, String> {
    let mut args = Args {
        quick: false,
        out: PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../docs")),
    };
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--quick" => args.quick = true,
            "--out" => args.out = PathBuf::from(it.next().ok_or("--out needs a directory")?),
            _ => {
                return Err(format!(
                    "unknown argument `{a}`; usage: speed_vs_accuracy [--quick] [--out DIR]"
                ))
            }
        }
    }
    Ok(args)
}

fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    format!(
        "{cpu}, {cores} cores available, {} {}",
        std::env::consts::OS,
        std::env::consts::ARCH
    )
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let args = parse_args()?;
    let runs = args.runs();
    std::fs::create_dir_all(&args.out)?;
    // Errors first (one trace per method and scene), then the timing rounds.
    let files = SCENES
        .iter()
        .map(|scene| scene_file::load::<MAX_SPHERES, 0, 0, 0>(standard::path(scene)))
        .collect::<Result<Vec<_>, _>>()?;
    let mut points: Vec<Point3> = Vec::new();
    let mut cases = Vec::new();
    for (scene, file) in SCENES.iter().zip(&files) {
        let (s, c) = (&file.scene, &file.camera);
        let reference = reference::render(s, c);
        let pixels = u64::from(c.size().width) * u64::from(c.size().height);
        let methods = std::iter::once((BASELINE.to_string(), None, Method::LITERAL, false))
            .chain(Method::ALL.iter().map(|m| (m.to_string(), Some(*m), *m, true)));
        for (label, tag, method, culling) in methods {
            let (coverage, shade) = errors(s, c, method, culling, &reference);
            points.push(Point3 {
                scene,
                label,
                method: tag,
                ns: f64::NAN,
                coverage,
                shade,
                pixels,
            });
            cases.push((file, method, culling));
        }
    }
    // Interleaved rounds (every scene and method once per round), then the median per
    // point: a burst of load from other processes hits all points alike.
    let mut samples = vec![Vec::new(); cases.len()];
    for _ in 0..runs {
        for (k, (file, method, culling)) in cases.iter().enumerate() {
            let options = Options::DEFAULT.with_span_culling(*culling);
            samples[k].push(time_render(&file.scene, &file.camera, *method, options, 1));
        }
    }
    for (p, mut times) in points.iter_mut().zip(samples) {
        times.sort_by(f64::total_cmp);
        p.ns = times[times.len() / 2];
        eprintln!(
            "{:8} {:34} {:8.2} ns/pixel  coverage {:6}  shade {:3}",
            p.scene, p.label, p.ns, p.coverage, p.shade
        );
    }

    // Growth curve: the first n spheres of crowd.
    let crowd = scene_file::load::<MAX_SPHERES, 0, 0, 0>(standard::path("crowd"))?;
    let counts: &[usize] = if args.quick {
        &[1, 64]
    } else {
        &[1, 2, 4, 8, 16, 32, 48, 64]
    };
    let direct_fd = Method::new(Stepping::Direct, SphereTest::ForwardDiff, Sqrt::Exact);
    let mut growth = Vec::new();
    for (name, method, culling) in [
        (
            format!("default {}", Method::TARGET_DEFAULT),
            Method::TARGET_DEFAULT,
            true,
        ),
        ("literal baseline, no culling".to_string(), Method::LITERAL, false),
        (direct_fd.to_string(), direct_fd, true),
    ] {
        for &n in counts {
            let mut scene: Scene<MAX_SPHERES> = Scene::new(crowd.scene.background());
            for sphere in crowd.scene.spheres().iter().take(n) {
                scene.push(*sphere)?;
            }
            let options = Options::DEFAULT.with_span_culling(culling);
            let ns = time_render(&scene, &crowd.camera, method, options, runs.min(7));
            eprintln!("growth {name:34} n={n:2} {ns:8.2} ns/pixel");
            growth.push((n, name.clone(), ns));
        }
    }

    // The sphere tests' own cost, without span culling (every sphere at every pixel):
    // forward differences against the robust test on lab and crowd.
    let mut isolated = Vec::new();
    for scene in ["lab", "crowd"] {
        let file = scene_file::load::<MAX_SPHERES, 0, 0, 0>(standard::path(scene))?;
        for stepping in [Stepping::Direct, Stepping::Incremental] {
            let robust = Method::new(stepping, SphereTest::Robust, Sqrt::Exact);
            let fd = Method::new(stepping, SphereTest::ForwardDiff, Sqrt::Exact);
            let unculled = Options::DEFAULT.with_span_culling(false);
            let r = time_render(&file.scene, &file.camera, robust, unculled, runs);
            let f = time_render(&file.scene, &file.camera, fd, unculled, runs);
            isolated.push((scene, stepping, r, f));
        }
    }

    // The lit scenes: every method with each secondary origin, and the literal baseline
    // (no culling, closest-hit shadow rays), errors first, then interleaved timing.
    let literal = Options::DEFAULT
        .with_span_culling(false)
        .with_shadow_any_hit(false);
    let mut lit = Vec::new();
    let mut lit_cases = Vec::new();
    for scene in FEATURE_SCENES {
        let file = standard::load_full(scene);
        let reference = reference::render(&file.scene, &file.camera);
        let methods = std::iter::once((BASELINE.to_string(), "convex", None, Method::LITERAL, literal))
            .chain(ORIGINS.iter().flat_map(|&(name, origin)| {
                Method::ALL.iter().map(move |m| {
                    (
                        m.to_string(),
                        name,
                        Some(*m),
                        *m,
                        Options::DEFAULT.with_secondary(origin),
                    )
                })
            }));
        let file = std::rc::Rc::new(file);
        for (label, origin, tag, method, options) in methods {
            let (over_2, color_max, color_mean) =
                lit_errors(&file.scene, &file.camera, method, options, &reference);
            lit.push(LitPoint {
                scene,
                origin,
                label,
                method: tag,
                ns: f64::NAN,
                over_2,
                color_max,
                color_mean,
            });
            lit_cases.push((file.clone(), method, options));
        }
    }
    let mut samples = vec![Vec::new(); lit_cases.len()];
    for _ in 0..runs {
        for (k, (file, method, options)) in lit_cases.iter().enumerate() {
            samples[k].push(time_render(&file.scene, &file.camera, *method, *options, 1));
        }
    }
    for (p, mut times) in lit.iter_mut().zip(samples) {
        times.sort_by(f64::total_cmp);
        p.ns = times[times.len() / 2];
        eprintln!(
            "{:8} {:34} {:12} {:8.2} ns/pixel  >2 levels {:6}  max {:3}",
            p.scene, p.label, p.origin, p.ns, p.over_2, p.color_max
        );
    }

    // The sampling axis: errors against the reference first, then interleaved timing
    // rounds of every scene and sampling choice.
    let reference_rays = if args.quick { 4 } else { aa::REFERENCE_RAYS };
    let feature_files: Vec<standard::FullSceneFile> = FEATURE_SCENES
        .iter()
        .map(|scene| standard::load_full(scene))
        .collect();
    let mut sampled = Vec::new();
    let mut sampled_cases: Vec<Box<dyn Fn() -> f64 + '_>> = Vec::new();
    for (scene, file) in SCENES.iter().zip(&files) {
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

    let cycles = estimated_cycles(&Path::new(env!("CARGO_MANIFEST_DIR")).join("data/cycles_cortex_m4.txt"))?;
    write_outputs(&args, &points, &lit, &growth, &cycles, &isolated, &sampled)?;
    Ok(())
}

/// (scene, stepping, robust ns/pixel, forward-diff ns/pixel), both without culling.
type Isolated = (&'static str, Stepping, f64, f64);

fn write_outputs(
    args: &Args,
    points: &[Point3],
    lit: &[LitPoint],
    growth: &[(usize, String, f64)],
    cycles: &[(String, String, f64)],
    isolated: &[Isolated],
    sampled: &[SamplingPoint],
) -> Result<(), Box<dyn std::error::Error>> {
    let command = if args.quick {
        "cargo run --release --example speed_vs_accuracy -- --quick"
    } else {
        "cargo run --release --example speed_vs_accuracy"
    };
    // CSV.
    let mut csv = String::from("scene,method,culling,ns_per_pixel,speedup_vs_baseline,coverage_errors,coverage_error_fraction,max_shade_error,pareto_coverage,pareto_shade\n");
    // Markdown.
    let mut md = String::new();
    writeln!(md, "# Speed against accuracy\n")?;
    let runs = args.runs();
    writeln!(md, "Made by `{command}` on {} ({runs} timed renders per point, median; into an in-memory Rgb565 frame buffer).", machine())?;
    writeln!(md, "Errors are against the accuracy lab's independent `f64` reference renderer (`embedded_raytracer_lab::reference`: the seed's camera, robust test and Lab #1 shading in `f64`; undecidable pixels not counted): **coverage** = pixels whose hit sphere differs from the reference's, **shade** = the largest 8-bit channel difference where the hit sphere agrees. Speed-up = baseline ns/pixel ÷ method ns/pixel, same process. The baseline is the seed taken literally: world-space stepping, the quadratic against every sphere at every pixel, libm square root, no span culling. *P* marks the Pareto front for coverage / shade: no other method is at least as accurate and more than 5 % faster (the timing noise of this shared machine), or more accurate and not slower. The chart's grey line is the strict front of the measured medians.\n")?;
    writeln!(md, "![speed against accuracy](speed_vs_accuracy.png)\n")?;
    let ns_of = |scene: &str, label: &str| {
        points
            .iter()
            .find(|p| p.scene == scene && p.label == label)
            .map(|p| p.ns)
    };
    for scene in SCENES {
        let pts: Vec<&Point3> = points.iter().filter(|p| p.scene == scene).collect();
        let base = ns_of(scene, BASELINE).unwrap_or(f64::NAN);
        let on_front = |metric: usize| {
            let xy: Vec<(f64, f64)> = pts
                .iter()
                .map(|p| {
                    (
                        p.ns,
                        if metric == 0 {
                            p.coverage as f64
                        } else {
                            f64::from(p.shade)
                        },
                    )
                })
                .collect();
            xy.iter().map(|p| on_noisy_front(*p, &xy)).collect::<Vec<bool>>()
        };
        let (fc, fs) = (on_front(0), on_front(1));
        writeln!(md, "## {scene}\n")?;
        writeln!(
            md,
            "| method | ns/pixel | speed-up | coverage errors | max shade error | Pareto |"
        )?;
        writeln!(md, "|---|---:|---:|---:|---:|---|")?;
        for (k, p) in pts.iter().enumerate() {
            let default = if p.method == Some(Method::TARGET_DEFAULT) {
                " (default)"
            } else {
                ""
            };
            let front = match (fc[k], fs[k]) {
                (true, true) => "P / P",
                (true, false) => "P / –",
                (false, true) => "– / P",
                (false, false) => "",
            };
            writeln!(
                md,
                "| {}{default} | {:.2} | {:.2}× | {} | {} | {front} |",
                p.label,
                p.ns,
                base / p.ns,
                p.coverage,
                p.shade
            )?;
            writeln!(
                csv,
                "{},{},{},{:.3},{:.3},{},{:.6},{},{},{}",
                p.scene,
                p.method.map_or("baseline".to_string(), |m| m.to_string()),
                p.method.is_some(),
                p.ns,
                base / p.ns,
                p.coverage,
                p.coverage as f64 / p.pixels as f64,
                p.shade,
                fc[k],
                fs[k]
            )?;
        }
        writeln!(md)?;
    }
    // The lit scenes.
    let mut lit_csv = String::from(
        "\nlit_scene,method,secondary,ns_per_pixel,speedup_vs_baseline,over_2_levels,max_error,mean_error\n",
    );
    for scene in FEATURE_SCENES {
        let base = lit
            .iter()
            .find(|p| p.scene == scene && p.method.is_none())
            .map_or(f64::NAN, |p| p.ns);
        writeln!(md, "## {scene} (lights, a checkered floor, mirrors)\n")?;
        writeln!(md, "Errors outside the reference's undecidable band; speed-up against the literal baseline (every object tested for every ray, closest-hit shadow rays, no culling).\n")?;
        writeln!(
            md,
            "| method | secondary rays | ns/pixel | speed-up | pixels > 2 levels off | max error | mean error |"
        )?;
        writeln!(md, "|---|---|---:|---:|---:|---:|---:|")?;
        for p in lit.iter().filter(|p| p.scene == scene) {
            let default = if p.method == Some(Method::TARGET_DEFAULT) && p.origin == "convex" {
                " (default)"
            } else {
                ""
            };
            writeln!(
                md,
                "| {}{default} | {} | {:.2} | {:.2}× | {} | {} | {:.3} |",
                p.label,
                p.origin,
                p.ns,
                base / p.ns,
                p.over_2,
                p.color_max,
                p.color_mean
            )?;
            writeln!(
                lit_csv,
                "{},{},{},{:.3},{:.3},{},{},{:.4}",
                p.scene,
                p.method.map_or("baseline".to_string(), |m| m.to_string()),
                p.origin,
                p.ns,
                base / p.ns,
                p.over_2,
                p.color_max,
                p.color_mean
            )?;
        }
        writeln!(md)?;
    }
    // Growth table.
    writeln!(
        md,
        "## Growth: ns/pixel against sphere count (the first n spheres of `crowd`)\n"
    )?;
    let mut names: Vec<&String> = growth.iter().map(|g| &g.1).collect();
    names.dedup();
    let counts: Vec<usize> = growth.iter().filter(|g| &g.1 == names[0]).map(|g| g.0).collect();
    write!(md, "| method |")?;
    for n in &counts {
        write!(md, " n = {n} |")?;
    }
    writeln!(md, "\n|---|{}", "---:|".repeat(counts.len()))?;
    for name in &names {
        write!(md, "| {name} |")?;
        for g in growth.iter().filter(|g| &g.1 == *name) {
            write!(md, " {:.2} |", g.2)?;
        }
        writeln!(md)?;
    }
    // The speed targets the project set itself, as measured.
    let default = Method::TARGET_DEFAULT.to_string();
    let ratio = |scene: &str, a: &str, b: &str| Some(ns_of(scene, a)? / ns_of(scene, b)?);
    writeln!(md, "\n## Targets (measured in this run)\n")?;
    if let Some(r) = ratio("lab", BASELINE, &default) {
        writeln!(md, "- default ({default}) on `lab`: {r:.2}× faster per pixel than the literal baseline (target ≥ 8×).")?;
    }
    for stepping in [Stepping::Direct, Stepping::Incremental] {
        for scene in ["lab", "crowd"] {
            if let Some(r) = ratio(
                scene,
                &format!("{stepping}/robust/exact"),
                &format!("{stepping}/forward-diff/exact"),
            ) {
                writeln!(md, "- {stepping}/forward-diff/exact vs {stepping}/robust/exact on `{scene}`: {r:.2}× faster (target ≥ 2×).")?;
            }
        }
    }
    for (scene, stepping, r, f) in isolated {
        writeln!(
            md,
            "- the same without span culling (the tests' own cost, every sphere at every pixel), {stepping} stepping on `{scene}`: robust {r:.2}, forward-diff {f:.2} ns/pixel, {:.2}× faster.",
            r / f
        )?;
    }
    if let Some(r) = ns_of("crowd", &default)
        .zip(ns_of("lab", &default))
        .map(|(c, l)| c / l)
    {
        writeln!(
            md,
            "- default on `crowd` (64 spheres) costs {r:.2}× its ns/pixel on `lab` (target ≤ 4×)."
        )?;
    }
    for scene in FEATURE_SCENES {
        let find = |f: &dyn Fn(&LitPoint) -> bool| lit.iter().find(|p| p.scene == scene && f(p));
        if let (Some(d), Some(b)) = (
            find(&|p| p.method == Some(Method::TARGET_DEFAULT) && p.origin == "convex"),
            find(&|p| p.method.is_none()),
        ) {
            writeln!(md, "- default on `{scene}`: {:.2}× faster per pixel than the literal baseline (target ≥ 3×); {} pixels more than 2 levels off the reference outside its undecidable band (target 0).", b.ns / d.ns, d.over_2)?;
        }
    }
    let worst_default = points
        .iter()
        .filter(|p| p.method == Some(Method::TARGET_DEFAULT))
        .map(|p| (p.coverage, p.shade))
        .fold((0, 0), |a, b| (a.0.max(b.0), a.1.max(b.1)));
    writeln!(md, "- default's worst case over the standard scenes: {} coverage errors, max shade error {} levels (target 0 and ≤ 1).", worst_default.0, worst_default.1)?;

    // Growth CSV rows appended as their own block.
    writeln!(csv, "\ngrowth_method,spheres,ns_per_pixel")?;
    for g in growth {
        writeln!(csv, "{},{},{:.3}", g.1, g.0, g.2)?;
    }

    csv.push_str(&lit_csv);
    write_sampling(&mut md, &mut csv, sampled)?;
    let out = &args.out;
    std::fs::write(out.join("speed_vs_accuracy.csv"), csv)?;
    std::fs::write(out.join("speed_vs_accuracy.md"), &md)?;
    plot(
        points,
        lit,
        growth,
        cycles,
        sampled,
        &out.join("speed_vs_accuracy.png"),
    )?;
    println!("{md}");
    println!("wrote {}/speed_vs_accuracy.{{csv,md,png}}", out.display());
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
