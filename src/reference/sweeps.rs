//! Stability sweeps: each moves one parameter toward where the methods break and
//! measures every method against the `f64` reference. `tests/stability.rs` asserts
//! the failure points they find; `examples/accuracy_table.rs` prints them for the
//! README. Both call these functions, so the table and the assertions cannot diverge.

use std::vec::Vec;

use embedded_graphics::geometry::Size;
use embedded_graphics::pixelcolor::{Rgb888, RgbColor};

use super::{compare, intersect, render, render_params, Metrics, D3};
use crate::camera::{Camera, CameraParams, MIN_PIXEL_SIZE};
use crate::error::CameraError;
use crate::method::{Method, SphereTest, Sqrt, Stepping};
use crate::render::Render;
use crate::scene::Scene;
use crate::sphere::Sphere;
use crate::vec3::Vec3;

/// The six sphere-test × square-root combinations, with [`Stepping::Direct`] so the
/// stepping adds no error of its own.
#[must_use]
pub fn sphere_methods() -> [Method; 6] {
    let mut out = [Method::DEFAULT; 6];
    let tests = [SphereTest::Algebraic, SphereTest::Geometric, SphereTest::Robust];
    let sqrts = [Sqrt::Exact, Sqrt::Fast];
    for (k, slot) in out.iter_mut().enumerate() {
        let (t, q) = (tests.get(k / 2), sqrts.get(k % 2));
        if let (Some(&t), Some(&q)) = (t, q) {
            *slot = Method::new(Stepping::Direct, t, q);
        }
    }
    out
}

/// Vertical field of view (radians, `f32`) that gives pixels of `pixel` on the image
/// plane for an image `height` pixels tall.
#[must_use]
pub fn fov_for_pixel(pixel: f64, height: u32) -> f32 {
    (2.0 * (pixel * f64::from(height) / 2.0).atan()) as f32
}

/// Renders `scene` through `camera` with `method` and compares it with the reference.
#[must_use]
pub fn measure<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    method: Method,
) -> Metrics {
    let truth = render(scene, camera);
    compare(
        &Render::<N, Rgb888, L, P, D>::new(scene, camera).with_method(method),
        &truth,
    )
}

/// One sphere and a camera looking straight at it.
fn one_sphere(center: Vec3, radius: f32) -> Scene<1> {
    let mut scene = Scene::new(Rgb888::BLACK);
    // Valid by construction (finite, positive radius): `push` cannot fail here.
    let _ = scene.push(Sphere::new(center, radius, Rgb888::new(255, 160, 64)));
    scene
}

/// One point of the distance/radius sweep.
#[derive(Clone, Copy, Debug)]
pub struct DistancePoint {
    /// Distance from the eye to the centre, over the radius.
    pub ratio: f64,
    /// The method measured.
    pub method: Method,
    /// Pixels that show the sphere in the reference.
    pub sphere_pixels: usize,
    /// Sphere diameter on the image, in pixels.
    pub diameter_px: f64,
    /// The comparison.
    pub metrics: Metrics,
}

/// The distance/radius ratios swept: `10^(k/4)` from 10 to 1e5.
#[must_use]
pub fn distance_ratios() -> Vec<f64> {
    (4..=20).map(|k| 10f64.powf(f64::from(k) / 4.0)).collect()
}

/// A unit sphere at distance `ratio` straight ahead of an eye at the origin, on a
/// `size × size` image, the field of view narrowed so the sphere spans half the
/// image — until [`MIN_PIXEL_SIZE`] stops it (ratio ≳ 6.5e4 at 64 px: the sphere is
/// then ~21 px across at 1e5).
#[must_use]
pub fn distance_sweep(size: u32, methods: &[Method]) -> Vec<DistancePoint> {
    let mut out = Vec::new();
    for ratio in distance_ratios() {
        // Sphere diameter 2/ratio (radians) over half the image; pixels no smaller
        // than the kernel accepts (1 % margin for its f32 tan).
        let pixel = (4.0 / ratio / f64::from(size)).max(f64::from(MIN_PIXEL_SIZE) * 1.01);
        let fov = fov_for_pixel(pixel, size);
        // The centre sits off the pixel grid by a fraction of a pixel, so the
        // silhouette is not symmetric about pixel centres.
        let off = (0.37 * pixel * ratio) as f32;
        let scene = one_sphere(Vec3::new(off, off * 0.5, -(ratio as f32)), 1.0);
        let Ok(camera) = Camera::new(
            Vec3::ZERO,
            Vec3::new(0.0, 0.0, -1.0),
            Vec3::new(0.0, 1.0, 0.0),
            fov,
            Size::new(size, size),
        ) else {
            continue;
        };
        let truth = render(&scene, &camera);
        for &method in methods {
            let metrics = compare(
                &Render::<1, Rgb888>::new(&scene, &camera).with_method(method),
                &truth,
            );
            out.push(DistancePoint {
                ratio,
                method,
                sphere_pixels: truth.count_hits(0),
                diameter_px: 2.0 / ratio / pixel,
                metrics,
            });
        }
    }
    out
}

/// Where one method fails in the distance sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DistanceFailure {
    /// The method.
    pub method: Method,
    /// Smallest ratio with any coverage error (`None`: none in the sweep).
    pub first_error: Option<f64>,
    /// Smallest ratio where the errors reach half the sphere's pixels (the disc is
    /// lost, or as many pixels again are wrongly added).
    pub outright: Option<f64>,
    /// Largest ratio up to which there was no coverage error at all.
    pub clean_up_to: Option<f64>,
}

/// The failure points of each method in a distance sweep.
#[must_use]
pub fn distance_failures(points: &[DistancePoint], methods: &[Method]) -> Vec<DistanceFailure> {
    methods
        .iter()
        .map(|&method| {
            let mine: Vec<&DistancePoint> = points.iter().filter(|p| p.method == method).collect();
            let first_error = mine
                .iter()
                .find(|p| p.metrics.coverage_errors > 0)
                .map(|p| p.ratio);
            let outright = mine
                .iter()
                .find(|p| 2 * p.metrics.coverage_errors >= p.sphere_pixels)
                .map(|p| p.ratio);
            let clean_up_to = mine
                .iter()
                .take_while(|p| p.metrics.coverage_errors == 0)
                .last()
                .map(|p| p.ratio);
            DistanceFailure {
                method,
                first_error,
                outright,
                clean_up_to,
            }
        })
        .collect()
}

/// One point of the huge-sphere ("ground") sweep.
#[derive(Clone, Copy, Debug)]
pub struct GroundPoint {
    /// Sphere radius; the eye is 1 unit above its surface.
    pub radius: f64,
    /// The method measured.
    pub method: Method,
    /// The comparison.
    pub metrics: Metrics,
}

/// The ground radii swept.
pub const GROUND_RADII: [f64; 6] = [1e2, 1e3, 1e4, 1e5, 3e5, 1e6];

/// A sphere of radius `R` used as a ground: centre `(0, −R, 0)`, eye at height 1 above
/// it at the origin, looking 10 ahead and 6 down (31° below the horizon, which sits
/// just above the top of the 60° image: grazing rays at the top, `n_z` up to ≈ 0.87 at
/// the bottom), `size × size` pixels.
#[must_use]
pub fn ground_sweep(size: u32, methods: &[Method]) -> Vec<GroundPoint> {
    let mut out = Vec::new();
    for radius in GROUND_RADII {
        let scene = one_sphere(Vec3::new(0.0, -(radius as f32) - 1.0, 0.0), radius as f32);
        let Ok(camera) = Camera::new(
            Vec3::ZERO,
            Vec3::new(0.0, -6.0, -10.0),
            Vec3::new(0.0, 1.0, 0.0),
            core::f32::consts::FRAC_PI_3,
            Size::new(size, size),
        ) else {
            continue;
        };
        let truth = render(&scene, &camera);
        for &method in methods {
            let metrics = compare(
                &Render::<1, Rgb888>::new(&scene, &camera).with_method(method),
                &truth,
            );
            out.push(GroundPoint {
                radius,
                method,
                metrics,
            });
        }
    }
    out
}

/// One point of the stepping-drift sweep.
#[derive(Clone, Copy, Debug)]
pub struct DriftPoint {
    /// The stepping measured (with the robust test and exact root).
    pub stepping: Stepping,
    /// Distance of the eye from the world origin.
    pub eye_distance: f64,
    /// Pixels along the stepped direction (image `n × 1` for rows, `1 × n` for columns).
    pub pixels: u32,
    /// `true` for a column (`1 × n`, stepping scanlines), `false` for a row.
    pub column: bool,
    /// Pixel size on the image plane.
    pub pixel_size: f64,
    /// Largest drift, in pixels.
    pub drift: f64,
}

/// Eye distances from the origin swept for drift.
pub const DRIFT_EYE: [f64; 6] = [0.0, 1.0, 10.0, 100.0, 1e3, 1e4];
/// Image lengths swept for drift.
pub const DRIFT_PIXELS: [u32; 6] = [64, 256, 1024, 1920, 4096, 8192];

/// An oblique camera (view direction `(−1, −0.5, −2)`, so `u`, `v`, `w` all have
/// three non-zero world components and every add rounds) at `eye_distance` from the
/// origin along `(1, 1, 1)`.
#[must_use]
pub fn oblique_params(eye_distance: f64, fov_y: f32, size: Size) -> CameraParams {
    let e = (eye_distance / 3f64.sqrt()) as f32;
    let eye = Vec3::new(e, e, e);
    CameraParams::new(
        eye,
        Vec3::new(e - 1.0, e - 0.5, e - 2.0),
        Vec3::new(0.0, 1.0, 0.0),
        fov_y,
        size,
    )
}

/// Maximum drift of `stepping` over an image of `params` (empty scene: directions only).
#[must_use]
pub fn drift_of(params: CameraParams, stepping: Stepping) -> Option<f64> {
    let camera = params.build().ok()?;
    let empty: Scene<1> = Scene::new(Rgb888::BLACK);
    let truth = render_params(&empty, camera.params())?;
    let method = Method::new(stepping, SphereTest::Robust, Sqrt::Exact);
    Some(
        compare(
            &Render::<1, Rgb888>::new(&empty, &camera).with_method(method),
            &truth,
        )
        .drift_max,
    )
}

/// Stepping drift against the eye's distance from the origin and the image length,
/// for rows (`n × 1`) and columns (`1 × n`), with square pixels of a 60° field of
/// view across `n` and an oblique camera.
#[must_use]
pub fn drift_sweep(pixels: &[u32], eye_distances: &[f64]) -> Vec<DriftPoint> {
    let mut out = Vec::new();
    for &n in pixels {
        let pixel = 2.0 * (30f64.to_radians()).tan() / f64::from(n);
        for column in [false, true] {
            let size = if column { Size::new(1, n) } else { Size::new(n, 1) };
            let fov_y = fov_for_pixel(pixel, size.height);
            for &eye_distance in eye_distances {
                for stepping in [Stepping::WorldSpace, Stepping::Incremental, Stepping::Direct] {
                    let params = oblique_params(eye_distance, fov_y, size);
                    if let Some(drift) = drift_of(params, stepping) {
                        out.push(DriftPoint {
                            stepping,
                            eye_distance,
                            pixels: n,
                            column,
                            pixel_size: pixel,
                            drift,
                        });
                    }
                }
            }
        }
    }
    out
}

/// Drift at the narrowest field of view the camera accepts (pixels of
/// [`MIN_PIXEL_SIZE`] × 1.01), an `n × 1` row, eye at the origin: `(oblique, axis-aligned)`.
#[must_use]
pub fn narrow_fov_drift(n: u32, stepping: Stepping) -> (Option<f64>, Option<f64>) {
    let pixel = f64::from(MIN_PIXEL_SIZE) * 1.01;
    let size = Size::new(n, 1);
    let fov_y = fov_for_pixel(pixel, 1);
    let oblique = drift_of(oblique_params(0.0, fov_y, size), stepping);
    let aligned = drift_of(
        CameraParams::new(
            Vec3::ZERO,
            Vec3::new(0.0, 0.0, -1.0),
            Vec3::new(0.0, 1.0, 0.0),
            fov_y,
            size,
        ),
        stepping,
    );
    (oblique, aligned)
}

/// The smallest `|eye|` in `points` at which `stepping` drifts ≥ 1 px over `n` pixels
/// (rows or columns, whichever is first).
#[must_use]
pub fn first_pixel_drift(points: &[DriftPoint], stepping: Stepping, n: u32) -> Option<f64> {
    points
        .iter()
        .filter(|p| p.stepping == stepping && p.pixels == n && p.drift >= 1.0)
        .map(|p| p.eye_distance)
        .min_by(f64::total_cmp)
}

/// The largest drift of `stepping` anywhere in `points`.
#[must_use]
pub fn max_drift(points: &[DriftPoint], stepping: Stepping) -> f64 {
    points
        .iter()
        .filter(|p| p.stepping == stepping)
        .map(|p| p.drift)
        .fold(0.0, f64::max)
}

/// How closely one sphere test tells hit from miss near a silhouette.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GrazingResolution {
    /// The method.
    pub method: Method,
    /// Rays tried.
    pub rays: usize,
    /// Rays the method got wrong (hit vs miss) among the decidable ones.
    pub errors: usize,
    /// The largest relative clearance `| |perp| − r | / r` of a misclassified ray
    /// (0 when none): rays farther than this from the silhouette are always right.
    pub worst: f64,
}

/// Near-tangent rays: for a unit sphere at distance `distance`, rays from the origin
/// whose closest approach to the centre is `r·(1 ± 2⁻ᵏ)`, `k = 1 … 40`, at 16 angles
/// around the silhouette. The truth for each (`f32`) ray is the `f64` robust test of
/// exactly that ray; undecidable rays are skipped.
#[must_use]
pub fn grazing_resolution(distance: f32, method: Method) -> GrazingResolution {
    let sphere = Sphere::new(Vec3::new(0.0, 0.0, -distance), 1.0, Rgb888::WHITE);
    let center = D3::of(sphere.center);
    let big_d = f64::from(distance);
    let mut res = GrazingResolution {
        method,
        rays: 0,
        errors: 0,
        worst: 0.0,
    };
    for k in 1..=40 {
        for sign in [-1.0, 1.0] {
            let rho = 1.0 + sign * 2f64.powi(-k);
            if rho >= big_d {
                continue;
            }
            // Aim at the point at lateral distance s in the plane of the centre so the
            // closest approach is rho: s = rho·D/√(D² − rho²).
            let s = rho * big_d / (big_d * big_d - rho * rho).sqrt();
            for a in 0..16 {
                let phi = f64::from(a) * core::f64::consts::TAU / 16.0 + 0.1;
                let dir = Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, -distance);
                let truth = intersect(D3::default(), D3::of(dir), center, 1.0);
                if truth.undecidable {
                    continue;
                }
                res.rays += 1;
                let got = sphere.intersect(Vec3::ZERO, dir, method.sphere_test, method.sqrt);
                if got.is_some() != truth.t.is_some() {
                    res.errors += 1;
                    let perp = (1.0 - truth.disc).max(0.0).sqrt();
                    res.worst = res.worst.max((perp - 1.0).abs());
                }
            }
        }
    }
    res
}

/// Outcome of building a camera with `up` at `angle` radians from the view direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UpAnglePoint {
    /// Angle between `up` and the view direction.
    pub angle: f64,
    /// `Ok(drift)` (the default method's max drift over a 64×64 image, px) or the error.
    pub result: Result<f64, CameraError>,
}

/// The up-vector angles swept (radians).
pub const UP_ANGLES: [f64; 8] = [1e-2, 2e-3, 1.01e-3, 0.99e-3, 1e-4, 1e-5, 1e-6, 1e-7];

/// Builds an oblique 64×64 camera with `up` at each angle of [`UP_ANGLES`] from the
/// view direction and measures the default method's drift where it is accepted.
#[must_use]
pub fn up_angle_sweep() -> Vec<UpAnglePoint> {
    let w = D3::new(-1.0, -0.5, -2.0).normalize().unwrap_or_default();
    // A unit vector perpendicular to w, to tilt up away from w by `angle`.
    let side = w.cross(D3::new(0.0, 1.0, 0.0)).normalize().unwrap_or_default();
    UP_ANGLES
        .iter()
        .map(|&angle| {
            let up = w * angle.cos() + side * angle.sin();
            let params = CameraParams::new(
                Vec3::new(3.0, 2.0, 5.0),
                Vec3::new(2.0, 1.5, 3.0),
                Vec3::new(up.x as f32, up.y as f32, up.z as f32),
                1.0,
                Size::new(64, 64),
            );
            let result = params.build().map(|camera| {
                let empty: Scene<1> = Scene::new(Rgb888::BLACK);
                let truth = render(&empty, &camera);
                compare(&Render::<1, Rgb888>::new(&empty, &camera), &truth).drift_max
            });
            UpAnglePoint { angle, result }
        })
        .collect()
}
