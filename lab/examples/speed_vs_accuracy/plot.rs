//! The chart: plotters draws the shapes into an RGB buffer (no font features); the
//! labels are drawn afterwards with embedded-graphics' built-in 6x10 mono font, and the
//! PNG is written through the simulator. Three rows of seven panels: coverage and shade
//! per scene, the growth curve, the legend, the estimated-cycles panels; the lit
//! scenes per secondary origin and the sampling axis.

use std::path::Path;

use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::text::Text;
use embedded_graphics_simulator::{OutputSettings, SimulatorDisplay};
use embedded_raytracer::SphereTest;
use embedded_raytracer_scenes::{FEATURE_SCENES, SCENES};
use plotters::prelude::*;

use crate::measure::{LitPoint, Point3, ORIGINS};
use crate::panels::{draw_growth, draw_panel, symlog, test_color};
use crate::sampling::{draw_sampling, sampling_legend, SamplingPoint};

/// The chart's width and height in pixels.
const W: u32 = 2800;
const H: u32 = 1230;

/// The scene of the estimated-cycles panels.
const CYCLES_SCENE: &str = "lab";

/// A text drawn over the chart after plotters, at a pixel position.
pub struct Label {
    pub x: i32,
    pub y: i32,
    pub text: String,
    pub color: Rgb888,
}

/// What plotters' drawing returns.
pub type DrawResult<T> = Result<T, Box<dyn std::error::Error>>;

/// Draws the chart of `points`, `lit`, `growth`, `cycles` and `sampled` into the PNG at
/// `path`.
pub fn plot(
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
