//! Nanoseconds per pixel of the kernel, rendered into an in-memory Rgb565 frame buffer,
//! as ratios to baselines measured in the same run:
//!
//! - **Lab #1 scenes** ([`SCENES`]): every method against the **baseline** — the seed's
//!   algorithm taken literally (world-space stepping, the quadratic against every sphere
//!   at every pixel, libm square root, no span culling).
//! - **Feature scenes** ([`FEATURE_SCENES`], at their own size): the default render
//!   against the same scene traced **literally** — the default method with every object
//!   tested for every ray (no span culling: spheres' and planes' spans) and closest-hit
//!   shadow rays (`Options::DEFAULT.with_span_culling(false).with_shadow_any_hit(false)`)
//!   — and against the seed's method traced that way; and the default render of the
//!   same scene with `shadows = false` (`no-shadow-rays`), whose time the literal
//!   render's is set against: about the speed-up if shadow rays cost nothing.
//! - **Feature cost** (group `features`): the `mirrors` scene's camera and spheres, one
//!   feature added at a time, each through the smallest scene type that holds it —
//!   (a) spheres only (`Scene<N>`, the Lab #1 loop), (b) + the floor, (c) + the lights
//!   without shadows, (d) + shadows, (e) + mirrors (the whole scene file) — as ratios
//!   to (a): what each feature costs per pixel.
//!
//! ```text
//! cargo bench                      # everything, then the ratio tables
//! cargo bench -- lab/              # one group (criterion's filter)
//! cargo bench -- 'shadows/|mirrors/|features/'
//! ```
//!
//! The Lab #1 table at the end uses, per benchmark, the median over criterion's samples
//! (and warm-up calls) of the time per iteration: robust to bursts of load on a shared
//! machine. The feature tables come from interleaved rounds after criterion's runs
//! (`interleave`): a ratio is taken between frames drawn moments apart.

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use criterion::{measurement::WallTime, BenchmarkGroup, BenchmarkId, Criterion, Throughput};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_raytracer::{Camera, Material, Method, Options, Render, Scene};

use embedded_raytracer_scenes as standard;
use standard::{FullSceneFile, FEATURE_SCENES, MAX_DEPTH, MAX_LIGHTS, MAX_PLANES, MAX_SPHERES, SCENES};

use embedded_raytracer_lab::slice_target;
use slice_target::SliceTarget;

/// The Lab #1 scenes' baseline: the seed's method, no culling.
const BASELINE: &str = "baseline";
/// The feature scenes' default render.
const DEFAULT: &str = "default";
/// The feature scenes traced literally: the default method, literal options.
const LITERAL: &str = "literal";
/// The feature scenes traced literally with the seed's method.
const LITERAL_SEED: &str = "literal-seed";
/// The feature scenes' default render of the same scene with `shadows = false`: no
/// shadow ray at all (every light reaches every point, so its shading is if anything
/// dearer), so the literal render's time over it is about the speed-up the default
/// would have if its shadow rays cost nothing.
const NO_SHADOW_RAYS: &str = "no-shadow-rays";
/// The literal options: every object tested for every ray, closest-hit shadow rays.
const LITERAL_OPTIONS: Options = Options::DEFAULT
    .with_span_culling(false)
    .with_shadow_any_hit(false);

/// The feature-cost series: its scene, its benchmark labels in order, what each adds.
const SERIES_SCENE: &str = "mirrors";
const FEATURES: &str = "features";
const STEPS: [(&str, &str); 5] = [
    ("a-spheres", "spheres only (Lab #1 loop)"),
    ("b-floor", "+ checkered floor"),
    ("c-lights", "+ lights, no shadows"),
    ("d-shadows", "+ shadows"),
    ("e-mirrors", "+ mirrors (the scene file)"),
];

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
        let mut group = c.benchmark_group(name);
        let cases = std::iter::once((BASELINE.to_string(), Method::LITERAL, false))
            .chain(Method::ALL.iter().map(|m| (m.to_string(), *m, true)));
        for (label, method, culling) in cases {
            let render = Render::new(&file.scene, &file.camera)
                .with_method(method)
                .with_options(Options::DEFAULT.with_span_culling(culling));
            bench(&mut group, name, &label, &render, &file.camera);
        }
        group.finish();
    }

    let files = FEATURE_SCENES.map(|name| (name, standard::load_full(name)));
    // Each feature scene without its shadows (everything else as loaded).
    let unshadowed = files.each_ref().map(|(name, file)| {
        let mut scene = file.scene.clone();
        let settings = scene.settings().with_shadows(false);
        scene
            .set_settings(settings)
            .unwrap_or_else(|e| panic!("{name} without shadows: {e}"));
        scene
    });
    let file = standard::load_full(SERIES_SCENE);
    let camera = &file.camera;
    let size = camera.size();
    let spheres: Scene<MAX_SPHERES> = stage(&file, Stage::Spheres);
    let floor: Scene<MAX_SPHERES, 0, MAX_PLANES> = stage(&file, Stage::Floor);
    let lights: Scene<MAX_SPHERES, MAX_LIGHTS, MAX_PLANES> = stage(&file, Stage::Lights);
    let shadows: Scene<MAX_SPHERES, MAX_LIGHTS, MAX_PLANES> = stage(&file, Stage::Shadows);
    let mirrors: Scene<MAX_SPHERES, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH> = stage(&file, Stage::Mirrors);
    // Every feature benchmark also goes into the interleaved rounds (see `interleave`).
    let mut frames: Vec<Frame<'_>> = Vec::new();
    for ((name, file), unshadowed) in files.iter().zip(&unshadowed) {
        let mut group = c.benchmark_group(*name);
        let cases = [
            (DEFAULT, Method::TARGET_DEFAULT, Options::DEFAULT, &file.scene),
            (LITERAL, Method::TARGET_DEFAULT, LITERAL_OPTIONS, &file.scene),
            (LITERAL_SEED, Method::LITERAL, LITERAL_OPTIONS, &file.scene),
            (
                NO_SHADOW_RAYS,
                Method::TARGET_DEFAULT,
                Options::DEFAULT,
                unshadowed,
            ),
        ];
        for (label, method, options, scene) in cases {
            let render = Render::new(scene, &file.camera)
                .with_method(method)
                .with_options(options);
            bench(&mut group, name, label, &render, &file.camera);
            frames.push(Frame::new(name, label, render, file.camera.size()));
        }
        group.finish();
    }

    let mut group = c.benchmark_group(FEATURES);
    let [a, b, cc, d, e] = STEPS.map(|(label, _)| label);
    let (ra, rb, rc) = (
        Render::new(&spheres, camera),
        Render::new(&floor, camera),
        Render::new(&lights, camera),
    );
    let (rd, re) = (Render::new(&shadows, camera), Render::new(&mirrors, camera));
    bench(&mut group, FEATURES, a, &ra, camera);
    bench(&mut group, FEATURES, b, &rb, camera);
    bench(&mut group, FEATURES, cc, &rc, camera);
    bench(&mut group, FEATURES, d, &rd, camera);
    bench(&mut group, FEATURES, e, &re, camera);
    group.finish();
    frames.extend([
        Frame::new(FEATURES, a, ra, size),
        Frame::new(FEATURES, b, rb, size),
        Frame::new(FEATURES, cc, rc, size),
        Frame::new(FEATURES, d, rd, size),
        Frame::new(FEATURES, e, re, size),
    ]);

    c.final_summary();
    print_ratios();
    print_feature_ratios(&interleave(&mut frames));
}

/// Times `render` drawing a whole frame into an Rgb565 buffer, recording ns/pixel of
/// every timed call under `(scene, label)`.
fn bench<const N: usize, const L: usize, const P: usize, const D: usize>(
    group: &mut BenchmarkGroup<'_, WallTime>,
    scene: &str,
    label: &str,
    render: &Render<'_, N, Rgb565, L, P, D>,
    camera: &Camera,
) {
    let size = camera.size();
    let pixels = u64::from(size.width) * u64::from(size.height);
    let mut buf = vec![Rgb565::BLACK; pixels as usize];
    group.throughput(Throughput::Elements(pixels));
    group.bench_function(BenchmarkId::from_parameter(label), |b| {
        b.iter_custom(|iters| {
            let start = Instant::now();
            for _ in 0..iters {
                let mut target = SliceTarget { buf: &mut buf, size };
                let Ok(()) = render.draw(&mut target);
                std::hint::black_box(&target.buf);
            }
            let elapsed = start.elapsed();
            SAMPLES.with(|t| {
                t.borrow_mut()
                    .entry((scene.to_string(), label.to_string()))
                    .or_default()
                    .push(elapsed.as_nanos() as f64 / (iters * pixels) as f64);
            });
            elapsed
        })
    });
}

/// One frame of one benchmark, drawn on demand for the interleaved rounds.
struct Frame<'a> {
    group: &'static str,
    label: &'static str,
    pixels: u64,
    /// Draws the frame into its own buffer; returns the time it took.
    draw: Box<dyn FnMut() -> Duration + 'a>,
}

impl<'a> Frame<'a> {
    fn new<const N: usize, const L: usize, const P: usize, const D: usize>(
        group: &'static str,
        label: &'static str,
        render: Render<'a, N, Rgb565, L, P, D>,
        size: Size,
    ) -> Self {
        let pixels = u64::from(size.width) * u64::from(size.height);
        let mut buf = vec![Rgb565::BLACK; pixels as usize];
        let draw = move || {
            let start = Instant::now();
            let mut target = SliceTarget { buf: &mut buf, size };
            let Ok(()) = render.draw(&mut target);
            std::hint::black_box(&target.buf);
            start.elapsed()
        };
        Self {
            group,
            label,
            pixels,
            draw: Box::new(draw),
        }
    }
}

/// Rounds of the interleaved measurement.
const ROUNDS: usize = 31;
/// How long one benchmark's turn in a round lasts at least: short frames are drawn
/// several times in a turn, so that no turn is a single scheduler time slice.
const TURN: Duration = Duration::from_millis(5);

/// Per benchmark `(group, label)` that criterion ran (its filter decides), ns/pixel in
/// each of [`ROUNDS`] rounds; each round gives every such benchmark one turn, one after
/// the other, of as many frames as criterion's median says fill [`TURN`]. A ratio of
/// two benchmarks taken within each round, then its median over the rounds, compares
/// frames drawn moments apart: on a shared machine whose load changes over seconds
/// that is far steadier than a ratio of two criterion runs made a second or more apart.
fn interleave(frames: &mut [Frame<'_>]) -> BTreeMap<(String, String), Vec<f64>> {
    // Frames per turn; 0 for a benchmark criterion did not run.
    let reps: Vec<u32> = frames
        .iter()
        .map(|f| {
            median(f.group, f.label).map_or(0, |ns| {
                let frame_ns = ns * f.pixels as f64;
                (TURN.as_nanos() as f64 / frame_ns).ceil().max(1.0) as u32
            })
        })
        .collect();
    let mut rounds: BTreeMap<(String, String), Vec<f64>> = BTreeMap::new();
    for _ in 0..ROUNDS {
        for (frame, &reps) in frames.iter_mut().zip(&reps).filter(|(_, &reps)| reps > 0) {
            let elapsed: Duration = (0..reps).map(|_| (frame.draw)()).sum();
            let ns = elapsed.as_nanos() as f64 / (u64::from(reps) * frame.pixels) as f64;
            rounds
                .entry((frame.group.to_string(), frame.label.to_string()))
                .or_default()
                .push(ns);
        }
    }
    rounds
}

/// The median and the quartiles of `v` (sorted in place).
fn quartiles(v: &mut [f64]) -> (f64, f64, f64) {
    v.sort_by(f64::total_cmp);
    let at = |q: usize| v[(v.len() - 1) * q / 4];
    (at(2), at(1), at(3))
}

/// Per round, `rounds[num] / rounds[den]`: median and quartiles over the rounds.
fn round_ratio(
    rounds: &BTreeMap<(String, String), Vec<f64>>,
    group: &str,
    num: &str,
    den: &str,
) -> Option<(f64, f64, f64)> {
    let get = |label: &str| rounds.get(&(group.to_string(), label.to_string()));
    let (n, d) = (get(num)?, get(den)?);
    let mut r: Vec<f64> = n.iter().zip(d).map(|(n, d)| n / d).collect();
    Some(quartiles(&mut r))
}

/// The median ns/pixel of `label` over the rounds.
fn round_ns(rounds: &BTreeMap<(String, String), Vec<f64>>, group: &str, label: &str) -> Option<f64> {
    let mut v = rounds.get(&(group.to_string(), label.to_string()))?.clone();
    Some(quartiles(&mut v).0)
}

/// The feature scenes' speed-up over their literal tracing and the feature series'
/// cost relative to (a), from the interleaved rounds.
fn print_feature_ratios(rounds: &BTreeMap<(String, String), Vec<f64>>) {
    if rounds.is_empty() {
        return;
    }
    println!(
        "\nInterleaved: {ROUNDS} rounds, each giving every benchmark below a turn of at least {} ms; \
ns/pixel is the median over the rounds, a ratio the median (and quartiles) over the rounds of the \
ratio within a round",
        TURN.as_millis()
    );
    for scene in FEATURE_SCENES {
        let Some(default) = round_ns(rounds, scene, DEFAULT) else {
            continue;
        };
        println!(
            "\n{scene}: {DEFAULT} = {} (span culling, any-hit shadow rays) {default:.2} ns/pixel",
            Method::TARGET_DEFAULT
        );
        println!("  traced literally (no culling, closest-hit shadow rays):");
        println!(
            "  {:14} {:28} {:>10} {:>9}  quartiles",
            "", "method", "ns/pixel", "speed-up"
        );
        for (label, method) in [(LITERAL, Method::TARGET_DEFAULT), (LITERAL_SEED, Method::LITERAL)] {
            if let (Some(v), Some((r, lo, hi))) = (
                round_ns(rounds, scene, label),
                round_ratio(rounds, scene, label, DEFAULT),
            ) {
                let method = method.to_string();
                println!("  {label:14} {method:28} {v:10.2} {r:8.2}x  {lo:.2}–{hi:.2}");
            }
        }
        if let (Some(v), Some((r, lo, hi))) = (
            round_ns(rounds, scene, NO_SHADOW_RAYS),
            round_ratio(rounds, scene, LITERAL, NO_SHADOW_RAYS),
        ) {
            println!(
                "  the default without any shadow ray (shadows = false) {v:.2} ns/pixel; \
the literal render's time over it, about the speed-up if shadow rays cost nothing: {r:.2}x ({lo:.2}–{hi:.2})"
            );
        }
    }
    if round_ns(rounds, FEATURES, STEPS[0].0).is_none() {
        return;
    }
    println!("\n{FEATURES}: the {SERIES_SCENE} scene's camera, one feature added at a time (default method)");
    println!(
        "  {:12} {:30} {:>10} {:>9}  quartiles",
        "step", "scene", "ns/pixel", "× (a)"
    );
    for (label, what) in STEPS {
        if let (Some(v), Some((r, lo, hi))) = (
            round_ns(rounds, FEATURES, label),
            round_ratio(rounds, FEATURES, label, STEPS[0].0),
        ) {
            println!("  {label:12} {what:30} {v:10.2} {r:8.2}x  {lo:.2}–{hi:.2}");
        }
    }
}

/// A step of the feature-cost series.
#[derive(Clone, Copy, PartialEq, PartialOrd)]
enum Stage {
    Spheres,
    Floor,
    Lights,
    Shadows,
    Mirrors,
}

/// The scene file's spheres and background with the features up to `stage`: its
/// planes from `Floor`, its lights from `Lights` (shadows off until `Shadows`), its
/// mirror weights and `max_depth` at `Mirrors`. Before `Mirrors` nothing reflects.
fn stage<const L: usize, const P: usize, const D: usize>(
    file: &FullSceneFile,
    stage: Stage,
) -> Scene<MAX_SPHERES, L, P, D> {
    let full = &file.scene;
    let mirrors = stage >= Stage::Mirrors;
    let matte = |m: Material| {
        if mirrors {
            m
        } else {
            Material { reflect: 0.0, ..m }
        }
    };
    let mut scene = Scene::new(full.background());
    let fail = |e| panic!("{SERIES_SCENE} at this stage: {e}");
    for sphere in full.spheres() {
        let mut sphere = *sphere;
        sphere.material = matte(sphere.material);
        scene.push(sphere).unwrap_or_else(fail);
    }
    if stage >= Stage::Floor {
        for plane in full.planes() {
            let mut plane = *plane;
            plane.material = matte(plane.material);
            scene.push_plane(plane).unwrap_or_else(fail);
        }
    }
    if stage >= Stage::Lights {
        for light in full.lights() {
            scene.push_light(*light).unwrap_or_else(fail);
        }
    }
    let settings = full.settings();
    scene
        .set_settings(
            settings
                .with_shadows(settings.shadows && stage >= Stage::Shadows)
                .with_max_depth(if mirrors { settings.max_depth } else { 0 }),
        )
        .unwrap_or_else(fail);
    scene
}

/// The median ns/pixel of benchmark `(scene, label)`.
fn median(scene: &str, label: &str) -> Option<f64> {
    SAMPLES.with(|t| {
        t.borrow().get(&(scene.to_string(), label.to_string())).map(|v| {
            let mut v = v.clone();
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        })
    })
}

/// ns/pixel and every method's speed-up (baseline/method) on the Lab #1 scenes.
fn print_ratios() {
    if SCENES.iter().all(|scene| median(scene, BASELINE).is_none()) {
        return;
    }
    println!("\nns/pixel and speed-up over the literal baseline (same run; median of the timed calls)");
    for scene in SCENES {
        let Some(base) = median(scene, BASELINE) else {
            continue;
        };
        println!(
            "\n{scene}: {BASELINE} = {} (no culling) {base:.2} ns/pixel",
            Method::LITERAL
        );
        println!("  {:34} {:>10} {:>9}", "method", "ns/pixel", "speed-up");
        for label in Method::ALL.iter().map(|m| m.to_string()) {
            if let Some(v) = median(scene, &label) {
                let mark = if label == Method::TARGET_DEFAULT.to_string() {
                    "  (default)"
                } else {
                    ""
                };
                println!("  {label:34} {v:10.2} {:8.2}x{mark}", base / v);
            }
        }
    }
}
