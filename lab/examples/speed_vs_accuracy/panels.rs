//! One panel of the chart: a method's markers (colour = sphere test, shape = stepping,
//! filled = exact square root) on log time against `log10(1 + error)`, with the Pareto
//! front; the growth curve's panel; the log axes' ticks.

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_raytracer::{SphereTest, Sqrt, Stepping};
use plotters::prelude::*;

use crate::measure::Point3;
use crate::plot::{DrawResult, Label};

/// The colour of a sphere test's markers.
pub fn test_color(t: Option<SphereTest>) -> RGBColor {
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
pub fn symlog(e: f64) -> f64 {
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

/// Tick values for a log axis between `lo` and `hi`: 1-2-5 per decade.
pub fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
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

/// A tick's label: whole numbers from 1 up, the shortest decimal below.
pub fn fmt_tick(t: f64) -> String {
    if t >= 1.0 {
        format!("{t:.0}")
    } else {
        format!("{t}")
    }
}

/// One panel of methods: `xy` holds each point of `pts` as (time, `symlog` error),
/// `title` above, `x_name` under the `x` axis.
pub fn draw_panel<DB: DrawingBackend>(
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

/// The growth panel: ns/pixel against the sphere count, one line a method.
pub fn draw_growth<DB: DrawingBackend>(
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
