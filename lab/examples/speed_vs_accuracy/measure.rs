//! Timing and errors: each method's time per pixel (the median of interleaved rounds)
//! and its errors against the `f64` reference, on the spheres-only scenes, on the
//! growing `crowd`, without span culling, and on the lit scenes with each secondary
//! origin.

use std::path::Path;
use std::time::Instant;

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_raytracer::{
    scene_file::{self, SceneFile},
    Camera, Method, Options, Render, Sampling, Scene, SecondaryOrigin, SphereTest, Sqrt, Stepping,
};
use embedded_raytracer_lab::cycle_model;
use embedded_raytracer_lab::reference::{self, compare, ReferenceImage};
use embedded_raytracer_lab::slice_target::SliceTarget;
use embedded_raytracer_scenes::{self as standard, FEATURE_SCENES, MAX_SPHERES, SCENES};

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
pub fn time_sampled<const N: usize, const L: usize, const P: usize, const D: usize>(
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
pub const ORIGINS: [(&str, SecondaryOrigin); 2] = [
    ("convex", SecondaryOrigin::Convex),
    ("epsilon 1e-3", SecondaryOrigin::TEXTBOOK),
];

/// One point of a lit scene: method × secondary origin (or the literal baseline).
pub struct LitPoint {
    pub scene: &'static str,
    pub origin: &'static str,
    pub label: String,
    pub method: Option<Method>,
    pub ns: f64,
    pub over_2: usize,
    pub color_max: u8,
    pub color_mean: f64,
}

/// `(scene, method, estimated Cortex-M4 cycles per pixel)` from the cycle model's data
/// file.
pub fn estimated_cycles(path: &Path) -> Result<Vec<(String, String, f64)>, String> {
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
pub struct Point3 {
    pub scene: &'static str,
    pub label: String,
    pub method: Option<Method>,
    pub ns: f64,
    pub coverage: usize,
    pub shade: u8,
    pub pixels: u64,
}

/// The label of the literal baseline's points.
pub const BASELINE: &str = "baseline (literal, no culling)";

/// One point of the growth curve: (spheres, method, ns/pixel).
pub type GrowthPoint = (usize, String, f64);

/// (scene, stepping, robust ns/pixel, forward-diff ns/pixel), both without culling.
pub type Isolated = (&'static str, Stepping, f64, f64);

/// Every method (and the literal baseline) on every spheres-only scene of `files`
/// ([`SCENES`] order): errors first (one trace per method and scene), then `runs`
/// interleaved timing rounds.
pub fn methods(files: &[SceneFile<MAX_SPHERES>], runs: usize) -> Vec<Point3> {
    let mut points: Vec<Point3> = Vec::new();
    let mut cases = Vec::new();
    for (scene, file) in SCENES.iter().zip(files) {
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
    points
}

/// The growth curve: ns/pixel of the default, the literal baseline and direct
/// forward differences on the first `n` spheres of `crowd`.
pub fn growth(quick: bool, runs: usize) -> Result<Vec<GrowthPoint>, Box<dyn std::error::Error>> {
    let crowd = scene_file::load::<MAX_SPHERES, 0, 0, 0>(standard::path("crowd"))?;
    let counts: &[usize] = if quick {
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
    Ok(growth)
}

/// The sphere tests' own cost, without span culling (every sphere at every pixel):
/// forward differences against the robust test on lab and crowd.
pub fn isolated(runs: usize) -> Result<Vec<Isolated>, Box<dyn std::error::Error>> {
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
    Ok(isolated)
}

/// The lit scenes: every method with each secondary origin, and the literal baseline
/// (no culling, closest-hit shadow rays), errors first, then interleaved timing.
pub fn lit(runs: usize) -> Vec<LitPoint> {
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
    lit
}
