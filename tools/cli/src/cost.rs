//! How long a render may take, bounded from the scene's counts: rays per pixel ×
//! object tests per ray × the measured cost of a test.
//!
//! - **Rays per pixel**: `center` 1; `grid:N` N²; `adaptive:N` at most 1 + N² (the
//!   centre ray, and the grid where an edge may cross the pixel).
//! - **Object tests per ray**: a spheres-only scene (the Lab #1 loop) tests each of its
//!   S spheres at most once per ray. A scene with lights, planes or mirrors tests the S
//!   spheres and P planes for the ray, then, where it hits, one shadow ray per light
//!   (L), and a mirror reflects it up to `max_depth` (D) times, each bounce testing as
//!   much again: at most (D + 1) × (1 + L) × (S + P). At the limits (S = 256, L = 8,
//!   P = 8, D = 8) that is 9 × 9 × 264 = 21,384 tests per ray.
//! - **Cost of a test**: [`NS_PER_TEST`], the most CPU time per counted test measured
//!   on the worst scenes (`tools/cli/bench.sh` prints the measurement: see
//!   docs/cli.md), a shading's and a pixel's share included.

use embedded_graphics::geometry::Size;
use embedded_raytracer::Sampling;

use embedded_raytracer_scenes::{FullSceneFile, MAX_DEPTH, MAX_LIGHTS, MAX_PLANES, MAX_SPHERES};

/// Nanoseconds per counted object test, the most measured (release build, one thread,
/// the shared 2-core AMD EPYC VM of docs/cli.md), rounded up: 0.27 ms a pixel for 256
/// mirror spheres around the eye, 8 point lights, 8 mirror planes and `max_depth = 8`
/// (21,384 counted tests: 12.6 ns) measured under load; on a quieter machine the same
/// scene took 6.7 ns of CPU a test and docs/cli_worst_case.toml 5.8 ns.
pub const NS_PER_TEST: f64 = 13.0;

/// A render whose bound exceeds this many seconds of CPU prints the bound first.
pub const WARN_SECONDS: u32 = 10;

/// The bound of one render.
pub struct Bound {
    pub pixels: u64,
    pub rays_per_pixel: u64,
    pub tests_per_ray: u64,
}

/// At most how many rays `sampling` traces for a pixel.
pub fn rays_per_pixel(sampling: Sampling) -> u64 {
    match sampling {
        Sampling::Center => 1,
        Sampling::Grid(n) => u64::from(n.get() * n.get()),
        Sampling::Adaptive(n) => 1 + u64::from(n.get() * n.get()),
        // A sampling this build does not know: the most rays any takes.
        _ => 1 + 16,
    }
}

/// At most how many object tests a ray costs in a scene with these counts (module docs).
pub fn tests_per_ray(spheres: usize, lights: usize, planes: usize, max_depth: usize, features: bool) -> u64 {
    if !features {
        return spheres as u64;
    }
    (max_depth as u64 + 1) * (1 + lights as u64) * (spheres + planes) as u64
}

impl Bound {
    /// The bound of `file` drawn at `size` with `sampling`.
    pub fn of(file: &FullSceneFile, size: Size, sampling: Sampling) -> Self {
        let scene = &file.scene;
        Self {
            pixels: u64::from(size.width) * u64::from(size.height),
            rays_per_pixel: rays_per_pixel(sampling),
            tests_per_ray: tests_per_ray(
                scene.spheres().len(),
                scene.lights().len(),
                scene.planes().len(),
                usize::from(scene.max_depth()),
                file.has_features(),
            ),
        }
    }

    /// The bound in seconds of CPU time.
    pub fn cpu_seconds(&self) -> f64 {
        self.pixels as f64 * self.rays_per_pixel as f64 * self.tests_per_ray as f64 * NS_PER_TEST * 1e-9
    }

    /// The line printed before a long render.
    pub fn estimate(&self, threads: usize) -> String {
        let cpu = self.cpu_seconds();
        format!(
            "ertrace: estimate: at most {} of CPU time ({} on {threads} thread{}): {} pixels x {} ray{} x {} object tests x {NS_PER_TEST} ns",
            duration(cpu),
            duration(cpu / threads as f64),
            if threads == 1 { "" } else { "s" },
            self.pixels,
            self.rays_per_pixel,
            if self.rays_per_pixel == 1 { "" } else { "s" },
            self.tests_per_ray,
        )
    }
}

/// `s` seconds as `12.3 s`, `4.5 min` or `6.7 h`.
pub fn duration(s: f64) -> String {
    if s < 120.0 {
        format!("{s:.1} s")
    } else if s < 7200.0 {
        format!("{:.1} min", s / 60.0)
    } else {
        format!("{:.1} h", s / 3600.0)
    }
}

/// The worst case at the limits, per sampling, for `--help`.
pub fn help_text() -> String {
    let tests = tests_per_ray(MAX_SPHERES, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH, true);
    let pixels = u64::from(embedded_raytracer::MAX_RESOLUTION).pow(2);
    let at = |sampling: Sampling| {
        let bound = Bound {
            pixels,
            rays_per_pixel: rays_per_pixel(sampling),
            tests_per_ray: tests,
        };
        format!("{sampling} {}", duration(bound.cpu_seconds()))
    };
    format!(
        "Worst case proven from the limits: rays per pixel (center 1, grid:N N^2, adaptive:N
at most 1 + N^2) x object tests per ray ((max_depth + 1) x (1 + lights) x (spheres +
planes) = 9 x 9 x 264 = {tests}) x {NS_PER_TEST} ns a test (the most measured): at 8192x8192
at most {}, {}, {} of CPU time (divide by the threads for the wall time).",
        at(Sampling::Center),
        at(Sampling::grid(4).expect("4 is a grid size")),
        at(Sampling::adaptive(4).expect("4 is a grid size")),
    )
}
