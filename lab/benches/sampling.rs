//! The cost of anti-aliasing: `Center`, `Grid(4)` and `Adaptive(4)` on `lab` (Lab #1
//! loop) and `shadows` (features path), each scene at its own size, rendered into an
//! in-memory Rgb565 frame buffer; ratios to `Center` taken in the same run.
//!
//! ```text
//! cargo bench --bench sampling
//! ```
//!
//! Criterion times each render; then [`ROUNDS`] interleaved rounds draw the three
//! renders of a scene one after the other, and each ratio is the median over the rounds
//! of the per-round ratio (frames drawn moments apart: steady on a shared machine).

use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, Throughput};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_raytracer::{Camera, Render, Sampling, Scene};

use embedded_raytracer_scenes as standard;

use embedded_raytracer_lab::slice_target;
use slice_target::SliceTarget;

/// Rounds of the interleaved measurement.
const ROUNDS: usize = 15;

fn choices() -> [(&'static str, Sampling); 3] {
    [
        ("center", Sampling::Center),
        (
            "grid:4",
            Sampling::Grid(embedded_raytracer::SubSamples::new(4).unwrap()),
        ),
        (
            "adaptive:4",
            Sampling::Adaptive(embedded_raytracer::SubSamples::new(4).unwrap()),
        ),
    ]
}

/// Draws a whole frame; returns the time it took.
fn draw<const N: usize, const L: usize, const P: usize, const D: usize>(
    render: &Render<'_, N, Rgb565, L, P, D>,
    buf: &mut [Rgb565],
    size: Size,
) -> Duration {
    let start = Instant::now();
    let mut target = SliceTarget { buf, size };
    let Ok(()) = render.draw(&mut target);
    std::hint::black_box(&target.buf);
    start.elapsed()
}

fn scene<const N: usize, const L: usize, const P: usize, const D: usize>(
    c: &mut Criterion,
    name: &str,
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
) -> Vec<(String, f64, f64, f64)> {
    let size = camera.size();
    let pixels = u64::from(size.width) * u64::from(size.height);
    let mut buf = vec![Rgb565::BLACK; pixels as usize];
    let renders = choices().map(|(label, s)| {
        (
            label,
            Render::<N, Rgb565, L, P, D>::new(scene, camera).with_sampling(s),
        )
    });
    let mut group = c.benchmark_group(format!("sampling-{name}"));
    group.throughput(Throughput::Elements(pixels));
    for (label, render) in &renders {
        group.bench_function(BenchmarkId::from_parameter(label), |b| {
            b.iter_custom(|iters| (0..iters).map(|_| draw(render, &mut buf, size)).sum())
        });
    }
    group.finish();
    // Interleaved rounds: ratio to Center per round, then the median and quartiles.
    let mut ratios: Vec<Vec<f64>> = vec![Vec::new(); renders.len()];
    for _ in 0..ROUNDS {
        let times: Vec<f64> = renders
            .iter()
            .map(|(_, r)| draw(r, &mut buf, size).as_secs_f64())
            .collect();
        for (k, t) in times.iter().enumerate() {
            ratios[k].push(t / times[0]);
        }
    }
    renders
        .iter()
        .zip(ratios)
        .map(|((label, _), mut v)| {
            v.sort_by(f64::total_cmp);
            let at = |q: usize| v[(v.len() - 1) * q / 4];
            (format!("{name} {label}"), at(2), at(1), at(3))
        })
        .collect()
}

fn main() {
    let mut c = Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(200))
        .measurement_time(Duration::from_millis(700))
        .configure_from_args();
    let lab = standard::load("lab");
    let shadows = standard::load_full("shadows");
    let mut rows = scene(&mut c, "lab", &lab.scene, &lab.camera);
    rows.extend(scene(&mut c, "shadows", &shadows.scene, &shadows.camera));
    c.final_summary();
    println!("\n| scene, sampling | time / Center (median of {ROUNDS} interleaved rounds) | quartiles |");
    println!("|---|---:|---|");
    for (label, median, q1, q3) in rows {
        println!("| {label} | {median:.2}× | {q1:.2}–{q3:.2} |");
    }
}
