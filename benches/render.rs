//! Nanoseconds per pixel of every method on every standard scene, rendered into an
//! in-memory Rgb565 frame buffer, and every method's ratio to the **baseline** — the
//! seed's algorithm taken literally (world-space stepping, the quadratic against every
//! sphere at every pixel, libm square root, no span culling) — measured in the same run.
//!
//! ```text
//! cargo bench                      # all scenes, all methods, then the ratio table
//! cargo bench -- lab/              # one scene (criterion's filter)
//! ```
//!
//! The table at the end uses, per benchmark, the median over criterion's samples (and
//! warm-up calls) of the time per iteration: robust to bursts of load on a shared machine.

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, Throughput};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_raytracer::{Method, Options, Render};

#[path = "../examples/common/standard.rs"]
mod standard;
use standard::SCENES;
const BASELINE: &str = "baseline";

#[path = "../examples/common/slice_target.rs"]
mod slice_target;
use slice_target::SliceTarget;

thread_local! {
    /// Per benchmark id: ns/pixel of every timed call (one criterion sample or warm-up).
    static SAMPLES: RefCell<BTreeMap<(String, String), Vec<f64>>> = const { RefCell::new(BTreeMap::new()) };
}

fn main() {
    let mut c = Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(200))
        .measurement_time(Duration::from_millis(700))
        .configure_from_args();

    for name in SCENES {
        let file = standard::load(name);
        let size = file.camera.size();
        let pixels = u64::from(size.width) * u64::from(size.height);
        let mut buf = vec![Rgb565::BLACK; pixels as usize];

        let mut group = c.benchmark_group(name);
        group.throughput(Throughput::Elements(pixels));
        let cases = std::iter::once((BASELINE.to_string(), Method::LITERAL, false))
            .chain(Method::ALL.iter().map(|m| (m.to_string(), *m, true)));
        for (label, method, culling) in cases {
            group.bench_function(BenchmarkId::from_parameter(&label), |b| {
                b.iter_custom(|iters| {
                    let render = Render::new(&file.scene, &file.camera)
                        .with_method(method)
                        .with_options(Options::DEFAULT.with_span_culling(culling));
                    let start = Instant::now();
                    for _ in 0..iters {
                        let mut target = SliceTarget { buf: &mut buf, size };
                        let Ok(()) = render.draw(&mut target);
                        std::hint::black_box(&target.buf);
                    }
                    let elapsed = start.elapsed();
                    SAMPLES.with(|t| {
                        t.borrow_mut()
                            .entry((name.to_string(), label.clone()))
                            .or_default()
                            .push(elapsed.as_nanos() as f64 / (iters * pixels) as f64);
                    });
                    elapsed
                })
            });
        }
        group.finish();
    }
    c.final_summary();
    print_ratios();
}

/// ns/pixel and the ratio baseline/method (how many times faster), per scene.
fn print_ratios() {
    SAMPLES.with(|t| {
        let t = t.borrow();
        let ns = |scene: &str, label: &str| {
            t.get(&(scene.to_string(), label.to_string())).map(|v| {
                let mut v = v.clone();
                v.sort_by(f64::total_cmp);
                v[v.len() / 2]
            })
        };
        println!("\nns/pixel and speed-up over the literal baseline (same run; median of the timed calls)");
        for scene in SCENES {
            let Some(base) = ns(scene, BASELINE) else { continue };
            println!(
                "\n{scene}: {BASELINE} = {} (no culling) {base:.2} ns/pixel",
                Method::LITERAL
            );
            println!("  {:34} {:>10} {:>9}", "method", "ns/pixel", "speed-up");
            for label in Method::ALL.iter().map(|m| m.to_string()) {
                if let Some(v) = ns(scene, &label) {
                    let mark = if label == Method::DEFAULT.to_string() {
                        "  (default)"
                    } else {
                        ""
                    };
                    println!("  {label:34} {v:10.2} {:8.2}x{mark}", base / v);
                }
            }
        }
    });
}
