//! Stability sweeps: each moves one parameter toward where the methods break and
//! measures every method against the `f64` reference. `lab/tests/lab/stability.rs` and (for
//! the secondary rays of lit scenes) `lab/tests/lab/lit_stability.rs` assert the failure
//! points they find; `lab/examples/accuracy_table.rs` prints them for the README. Both
//! call these functions, so the table and the assertions cannot diverge.

use std::vec::Vec;

use embedded_graphics::geometry::Size;
use embedded_graphics::pixelcolor::{Rgb888, RgbColor};

use super::{compare, intersect, render, render_params, Metrics, ReferenceImage, D3};
use embedded_raytracer::CameraError;
use embedded_raytracer::Light;
use embedded_raytracer::Material;
use embedded_raytracer::Plane;
use embedded_raytracer::SecondaryOrigin;
use embedded_raytracer::Sphere;
use embedded_raytracer::Vec3;
use embedded_raytracer::{Camera, CameraParams, MIN_PIXEL_SIZE};
use embedded_raytracer::{Method, SphereTest, Sqrt, Stepping};
use embedded_raytracer::{Options, Render};
use embedded_raytracer::{Scene, Settings};

/// The six sphere-test × square-root combinations, with [`Stepping::Direct`] so the
/// stepping adds no error of its own.
#[must_use]
pub fn sphere_methods() -> [Method; 6] {
    let mut out = [Method::TARGET_DEFAULT; 6];
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

// ---------------------------------------------------------------------------------
// Lit scenes: where secondary rays (shadow and reflection rays) fail.
// ---------------------------------------------------------------------------------

/// The secondary-ray origins the lit sweeps compare: the default convex exit and the
/// textbook epsilon, `10⁻³` scene units.
pub const SECONDARY: [SecondaryOrigin; 2] = [SecondaryOrigin::Convex, SecondaryOrigin::TEXTBOOK];

/// How a lit render differs from the reference, with the errors of a secondary ray's
/// origin told apart.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LitErrors {
    /// The comparison ([`Metrics::over_2`] counts every pixel more than 2 levels off
    /// outside the undecidable band).
    pub metrics: Metrics,
    /// Shadow acne: decidable pixels where the kernel is more than 2 levels darker than
    /// the reference (in some channel, and in none brighter): a shadow ray was blocked
    /// that the reference lets through to the light.
    pub acne: usize,
    /// Light leaks: decidable pixels where the kernel is more than 2 levels brighter
    /// (in some channel, in none darker) and the reference is in a shadow there (its
    /// colour with shadows off differs).
    pub leak: usize,
}

impl LitErrors {
    /// Pixels more than 2 levels off that are neither acne nor leaks.
    #[must_use]
    pub fn other(&self) -> usize {
        self.metrics.over_2.saturating_sub(self.acne + self.leak)
    }
}

/// Renders `scene` through `camera` with `method` and secondary rays leaving as
/// `secondary`, and compares it with `truth` (the scene's reference) and `unshadowed`
/// (the reference of the same scene with shadows off).
#[must_use]
pub fn lit_errors<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    truth: &ReferenceImage,
    unshadowed: &ReferenceImage,
    method: Method,
    secondary: SecondaryOrigin,
) -> LitErrors {
    let render = Render::<N, Rgb888, L, P, D>::new(scene, camera)
        .with_method(method)
        .with_options(Options::DEFAULT.with_secondary(secondary));
    let mut out = LitErrors {
        metrics: compare(&render, truth),
        ..LitErrors::default()
    };
    render.trace(|s| {
        let (Ok(i), Ok(j)) = (u32::try_from(s.pixel.x), u32::try_from(s.pixel.y)) else {
            return;
        };
        let (Some(r), Some(u)) = (truth.get(i, j), unshadowed.get(i, j)) else {
            return;
        };
        if r.undecidable {
            return;
        }
        let k = [s.color.r(), s.color.g(), s.color.b()];
        let c = [r.color.r(), r.color.g(), r.color.b()];
        let darker = k.iter().zip(c).any(|(&k, c)| u16::from(k) + 2 < u16::from(c));
        let brighter = k.iter().zip(c).any(|(&k, c)| u16::from(c) + 2 < u16::from(k));
        if darker && !brighter {
            out.acne += 1;
        } else if brighter && !darker && r.color != u.color {
            out.leak += 1;
        }
    });
    out
}

/// The same scene with shadows off.
#[must_use]
pub fn without_shadows<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
) -> Scene<N, L, P, D> {
    let mut out = scene.clone();
    // The scene's own settings with one flag changed: valid as they were.
    let _ = out.set_settings(scene.settings().with_shadows(false));
    out
}

/// The scene with every length multiplied by `k`: sphere centres and radii, plane
/// points and checker sizes, point lights' positions (directions and colours
/// unchanged). `None` if a scaled object is refused (non-finite, zero radius).
#[must_use]
pub fn scaled_scene<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    k: f32,
) -> Option<Scene<N, L, P, D>> {
    let mut out: Scene<N, L, P, D> = Scene::new(scene.background());
    out.set_settings(scene.settings()).ok()?;
    for s in scene.spheres() {
        out.push(Sphere {
            center: s.center * k,
            radius: s.radius * k,
            ..*s
        })
        .ok()?;
    }
    for l in scene.lights() {
        out.push_light(match *l {
            Light::Point { position, intensity } => Light::point(position * k, intensity),
            other => other,
        })
        .ok()?;
    }
    for p in scene.planes() {
        out.push_plane(Plane {
            point: p.point * k,
            checker_size: p.checker_size * k,
            ..*p
        })
        .ok()?;
    }
    Some(out)
}

/// The camera with its eye and look-at point multiplied by `k`, at `size` pixels (the
/// same view: the field of view is kept).
#[must_use]
pub fn scaled_camera(camera: &Camera, k: f32, size: Size) -> Option<Camera> {
    let p = *camera.params();
    CameraParams {
        eye: p.eye * k,
        look_at: p.look_at * k,
        size,
        ..p
    }
    .build()
    .ok()
}

/// One point of a lit sweep: the swept value, the secondary origin, the errors.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LitPoint {
    /// The swept parameter (a scale, an elevation in degrees, …).
    pub x: f64,
    /// How secondary rays left their surface.
    pub secondary: SecondaryOrigin,
    /// Against the reference.
    pub errors: LitErrors,
}

/// Measures `scene` through `camera` with the default method and each of [`SECONDARY`],
/// as points at `x`.
pub fn lit_points<const N: usize, const L: usize, const P: usize, const D: usize>(
    x: f64,
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    out: &mut Vec<LitPoint>,
) {
    let truth = render(scene, camera);
    let unshadowed = render(&without_shadows(scene), camera);
    for secondary in SECONDARY {
        out.push(LitPoint {
            x,
            secondary,
            errors: lit_errors(
                scene,
                camera,
                &truth,
                &unshadowed,
                Method::TARGET_DEFAULT,
                secondary,
            ),
        });
    }
}

/// The scales of the scale sweep: `10^(k/2)` from `10⁻³` to `10⁵`.
#[must_use]
pub fn lit_scales() -> Vec<f64> {
    (-6..=10).map(|k| 10f64.powf(f64::from(k) / 2.0)).collect()
}

/// The scene and its camera with every length multiplied by each of `scales`, the
/// image `size` pixels: every [`SECONDARY`] origin at every scale.
#[must_use]
pub fn scale_sweep<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    size: Size,
    scales: &[f64],
) -> Vec<LitPoint> {
    let mut out = Vec::new();
    for &k in scales {
        let (Some(s), Some(c)) = (
            scaled_scene(scene, k as f32),
            scaled_camera(camera, k as f32, size),
        ) else {
            continue;
        };
        lit_points(k, &s, &c, &mut out);
    }
    out
}

/// The elevations of the light-elevation sweep, in degrees above the floor.
pub const ELEVATIONS: [f64; 9] = [60.0, 30.0, 15.0, 8.0, 4.0, 2.0, 1.0, 0.5, 0.25];

/// The scene lit by one directional light at `elevation` degrees above its first plane
/// (from the side its first directional light comes from, along the plane), instead of
/// its own lights. `None` without a plane or a directional light.
#[must_use]
pub fn at_elevation<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    elevation: f64,
    intensity: f32,
) -> Option<Scene<N, L, P, D>> {
    let n = D3::of(scene.planes().first()?.normal).normalize()?;
    let sun = scene.lights().iter().find_map(|l| match *l {
        Light::Directional { direction, .. } => Some(D3::of(direction)),
        Light::Point { .. } => None,
    })?;
    // The sun's travel direction along the plane, then tilted down by the elevation.
    let along = (sun - n * sun.dot(n)).normalize()?;
    let e = elevation.to_radians();
    let d = along * e.cos() - n * e.sin();
    let mut out: Scene<N, L, P, D> = Scene::new(scene.background());
    out.set_settings(scene.settings()).ok()?;
    for s in scene.spheres() {
        out.push(*s).ok()?;
    }
    for p in scene.planes() {
        out.push_plane(*p).ok()?;
    }
    out.push_light(Light::directional(
        Vec3::new(d.x as f32, d.y as f32, d.z as f32),
        intensity,
    ))
    .ok()?;
    Some(out)
}

/// The scene under one directional light at each of `elevations` (degrees, see
/// [`at_elevation`]), multiplied by `scale`, the image `size` pixels.
#[must_use]
pub fn elevation_sweep<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    size: Size,
    scale: f32,
    elevations: &[f64],
) -> Vec<LitPoint> {
    let mut out = Vec::new();
    let (Some(base), Some(c)) = (scaled_scene(scene, scale), scaled_camera(camera, scale, size)) else {
        return out;
    };
    for &e in elevations {
        if let Some(s) = at_elevation(&base, e, 1.0) {
            lit_points(e, &s, &c, &mut out);
        }
    }
    out
}

/// Spheres of radius 1 resting on a checkered floor (centre height = radius) and sunk
/// into it (centre height 0.5 and 0), back-lit by the sun 30° above the floor so their
/// shadows fall toward the camera, which looks at the contact circles from about 18°
/// above the floor; every length multiplied by `k`.
#[must_use]
pub fn contact_scene(k: f32) -> Option<(Scene<3, 1, 1>, Camera)> {
    let mut scene: Scene<3, 1, 1> = Scene::new(Rgb888::new(24, 34, 56));
    for (x, y, c) in [
        (-2.3, 1.0, Rgb888::new(230, 60, 50)),
        (0.0, 0.5, Rgb888::new(60, 200, 90)),
        (2.3, 0.0, Rgb888::new(70, 110, 240)),
    ] {
        scene.push(Sphere::new(Vec3::new(x, y, 0.0) * k, k, c)).ok()?;
    }
    scene
        .push_plane(
            Plane::new(Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), Rgb888::new(225, 225, 215))
                .with_checker(Rgb888::new(70, 70, 80), k),
        )
        .ok()?;
    let e = 30f32.to_radians();
    scene
        .push_light(Light::directional(Vec3::new(0.2, -e.sin(), e.cos()), 0.9))
        .ok()?;
    let camera = Camera::new(
        Vec3::new(0.4, 3.2, 8.8) * k,
        Vec3::new(0.0, 0.3, 0.0) * k,
        Vec3::new(0.0, 1.0, 0.0),
        0.75,
        Size::new(120, 60),
    )
    .ok()?;
    Some((scene, camera))
}

/// The scales of the contact sweep: `10^(−k/2)` from 1 down to `10⁻⁴`.
#[must_use]
pub fn contact_scales() -> Vec<f64> {
    (0..=8).map(|k| 10f64.powf(-f64::from(k) / 2.0)).collect()
}

/// [`contact_scene`] at each of `scales`, every [`SECONDARY`] origin.
#[must_use]
pub fn contact_sweep(scales: &[f64]) -> Vec<LitPoint> {
    let mut out = Vec::new();
    for &k in scales {
        if let Some((s, c)) = contact_scene(k as f32) {
            lit_points(k, &s, &c, &mut out);
        }
    }
    out
}

/// The eye inside a mirror sphere (radius 5, reflect 0.8) with a red ball inside it,
/// lit by a point light inside, reflections 8 deep; every length multiplied by `k`.
#[must_use]
pub fn mirror_inside_scene(k: f32, size: Size) -> Option<(Scene<2, 1, 0, 8>, Camera)> {
    let mut scene: Scene<2, 1, 0, 8> = Scene::new(Rgb888::BLACK);
    scene.set_settings(Settings::DEFAULT.with_max_depth(8)).ok()?;
    scene
        .push(
            Sphere::new(Vec3::ZERO, 5.0 * k, Rgb888::new(200, 200, 200))
                .with_material(Material::new(0.3, 32.0, 0.8)),
        )
        .ok()?;
    scene
        .push(
            Sphere::new(Vec3::new(1.0, -1.0, -2.0) * k, k, Rgb888::new(230, 60, 50))
                .with_material(Material::new(0.3, 32.0, 0.0)),
        )
        .ok()?;
    scene
        .push_light(Light::point(Vec3::new(0.0, 3.0, 1.0) * k, 0.8))
        .ok()?;
    let camera = Camera::new(
        Vec3::new(0.0, 0.0, 3.0) * k,
        Vec3::ZERO,
        Vec3::new(0.0, 1.0, 0.0),
        1.0,
        size,
    )
    .ok()?;
    Some((scene, camera))
}

/// [`mirror_inside_scene`] at each of `scales`, every [`SECONDARY`] origin.
#[must_use]
pub fn mirror_inside_sweep(size: Size, scales: &[f64]) -> Vec<LitPoint> {
    let mut out = Vec::new();
    for &k in scales {
        if let Some((s, c)) = mirror_inside_scene(k as f32, size) {
            lit_points(k, &s, &c, &mut out);
        }
    }
    out
}

/// Where `secondary` first fails in a sweep, in the points' order: `(clean, first)`,
/// the last swept value before any pixel that `count` counts, and the first with one
/// (`None` if it never fails).
#[must_use]
pub fn lit_failure(
    points: &[LitPoint],
    secondary: SecondaryOrigin,
    count: impl Fn(&LitErrors) -> usize,
) -> (Option<f64>, Option<f64>) {
    let mut clean = None;
    for p in points.iter().filter(|p| p.secondary == secondary) {
        if count(&p.errors) > 0 {
            return (clean, Some(p.x));
        }
        clean = Some(p.x);
    }
    (clean, None)
}

/// One image row of the horizon measurement.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HorizonRow {
    /// The row (0 at the top; the horizon is between rows `H/2 − 1` and `H/2`).
    pub row: u32,
    /// The reference's hit distance at the row's centre pixel (`0`: no floor hit).
    pub distance: f64,
    /// How far along the floor the row's centre pixel reaches past the next row's
    /// (the pixel's footprint along the view), in checker cells.
    pub footprint_cells: f64,
    /// Largest relative error of the kernel's hit distance over the row's pixels where
    /// both show the floor.
    pub distance_rel_max: f64,
    /// Decidable pixels more than 2 levels off the reference.
    pub over_2: usize,
    /// Pixels the reference cannot decide.
    pub undecidable: usize,
}

/// A checkered floor (cells of 1, lit from overhead) seen by a camera 1 above it, tilted
/// so the horizon lies `offset` pixels above the centre of row `H/2` (`0.5`: a level
/// camera, the horizon across the middle of the image; near 0 the row's rays graze the
/// floor): per row from `H/2` down, the kernel (default method) against the reference.
#[must_use]
pub fn horizon_rows(width: u32, height: u32, offset: f64) -> Vec<HorizonRow> {
    let mut out = Vec::new();
    let mut scene: Scene<0, 1, 1> = Scene::new(Rgb888::new(110, 150, 210));
    let floor = Plane::new(Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), Rgb888::new(225, 225, 215))
        .with_checker(Rgb888::new(40, 40, 50), 1.0);
    let light = Light::directional(Vec3::new(0.3, -1.0, -0.2), 0.9);
    if scene.push_plane(floor).is_err() || scene.push_light(light).is_err() {
        return out;
    }
    // Pitched up by φ, the horizon appears at image height −tan φ: row H/2's centre is
    // at −ph/2, so tan φ = ph·(½ − offset).
    let fov = core::f32::consts::FRAC_PI_3;
    let ph = 2.0 * (f64::from(fov) / 2.0).tan() / f64::from(height.max(1));
    let rise = (10.0 * ph * (0.5 - offset)) as f32;
    let Ok(camera) = Camera::new(
        Vec3::new(0.37, 1.0, 0.21),
        Vec3::new(0.37, 1.0 + rise, 0.21 - 10.0),
        Vec3::new(0.0, 1.0, 0.0),
        fov,
        Size::new(width, height),
    ) else {
        return out;
    };
    let truth = render(&scene, &camera);
    let cam = truth.camera;
    let point = |i: u32, j: u32| {
        let r = truth.get(i, j)?;
        let d = cam.direction(i, j).normalize()?;
        (r.hit == Some(0)).then(|| cam.eye + d * r.distance)
    };
    let mid = width / 2;
    for j in height / 2..height {
        let mut row = HorizonRow {
            row: j,
            distance: truth.get(mid, j).map_or(0.0, |r| r.distance),
            ..HorizonRow::default()
        };
        if let (Some(a), Some(b)) = (point(mid, j), point(mid, j + 1)) {
            row.footprint_cells = (a - b).length();
        }
        out.push(row);
    }
    Render::<0, Rgb888, 1, 1>::new(&scene, &camera).trace(|s| {
        let (Ok(i), Ok(j)) = (u32::try_from(s.pixel.x), u32::try_from(s.pixel.y)) else {
            return;
        };
        let (Some(r), Some(row)) = (truth.get(i, j), out.iter_mut().find(|x| x.row == j)) else {
            return;
        };
        // The hit distance wherever both see the floor, in the band or not.
        if let (Some(h), Some(_)) = (s.hit, r.hit) {
            let distance = f64::from(h.t) * D3::of(s.direction).length();
            let rel = (distance - r.distance).abs() / r.distance;
            row.distance_rel_max = row.distance_rel_max.max(rel);
        }
        if r.undecidable {
            row.undecidable += 1;
            return;
        }
        let diff = |a: u8, b: u8| a.abs_diff(b) > 2;
        if diff(s.color.r(), r.color.r()) || diff(s.color.g(), r.color.g()) || diff(s.color.b(), r.color.b())
        {
            row.over_2 += 1;
        }
    });
    out
}

// ---------------------------------------------------------------------------------
// The integer kernel's range limits: where its per-frame rule stops taking the frame.
// ---------------------------------------------------------------------------------

/// One point of an integer-kernel sweep: the swept value, whether the rule took the
/// integer kernel, and the render's metrics against the reference.
#[derive(Clone, Copy, Debug)]
pub struct IntegerPoint {
    /// The swept value.
    pub value: f64,
    /// The rule took the integer kernel.
    pub integer: bool,
    /// The render against the reference.
    pub metrics: Metrics,
}

/// What an integer-kernel sweep varies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IntegerSweep {
    /// One sphere filling half of a 64×64 image, distance/radius 10^(k/4), k = 4…19.
    DistanceRadius,
    /// The lab's yellow sphere (r = 0.35) with a second sphere ever farther behind it
    /// (kept at the same size on screen), 96×96: the frame's extent (farthest
    /// `|L| + r`) over the near sphere's radius.
    Extent,
    /// The lab scene at 96×96 with a vertical field of view of 10° … 170°.
    FieldOfView,
}

impl IntegerSweep {
    /// Every sweep, in the table's order.
    pub const ALL: [IntegerSweep; 3] = [Self::DistanceRadius, Self::Extent, Self::FieldOfView];

    /// The swept quantity's name.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::DistanceRadius => "distance/radius",
            Self::Extent => "scene extent / radius",
            Self::FieldOfView => "field of view (°)",
        }
    }
}

/// `Method::INTEGER` over the sweep `kind`, each point against the reference.
#[must_use]
pub fn integer_sweep(kind: IntegerSweep) -> Vec<IntegerPoint> {
    let up = Vec3::new(0.0, 1.0, 0.0);
    let run = |value: f64, scene: &Scene<2>, params: CameraParams| {
        let camera = params.build().ok()?;
        let kernel = Render::<2, Rgb888>::new(scene, &camera).with_method(Method::INTEGER);
        let metrics = compare(&kernel, &render(scene, &camera));
        Some(IntegerPoint {
            value,
            integer: kernel.arithmetic() == embedded_raytracer::Arithmetic::Integer,
            metrics,
        })
    };
    let mut points = Vec::new();
    match kind {
        IntegerSweep::DistanceRadius => {
            for k in 4..=19 {
                let ratio = libm::pow(10.0, f64::from(k) / 4.0);
                let dist = 5.0f32;
                let radius = (f64::from(dist) / ratio) as f32;
                // The sphere spans half the image.
                let fov = 4.0 * libm::atanf(radius / dist);
                let scene = Scene::<2>::from_array(
                    [Sphere::new(Vec3::ZERO, radius, Rgb888::new(200, 150, 90))],
                    Rgb888::BLACK,
                );
                let params =
                    CameraParams::new(Vec3::new(0.0, 0.0, dist), Vec3::ZERO, up, fov, Size::new(64, 64));
                points.extend(run(ratio, &scene, params));
            }
        }
        IntegerSweep::Extent => {
            for k in 0..=16 {
                let far = libm::powf(10.0, 1.0 + k as f32 / 4.0);
                let scene = Scene::<2>::from_array(
                    [
                        Sphere::new(Vec3::new(0.5, -0.9, 1.6), 0.35, Rgb888::new(255, 255, 64)),
                        Sphere::new(
                            Vec3::new(-1.0, 0.5, 5.0 - far),
                            far * 0.2,
                            Rgb888::new(64, 255, 255),
                        ),
                    ],
                    Rgb888::BLACK,
                );
                let params = CameraParams::new(
                    Vec3::new(0.0, 0.0, 5.0),
                    Vec3::ZERO,
                    up,
                    60f32.to_radians(),
                    Size::new(96, 96),
                );
                points.extend(run(f64::from(far) * 1.2 / 0.35, &scene, params));
            }
        }
        IntegerSweep::FieldOfView => {
            let scene = Scene::<2>::from_array(
                [
                    Sphere::new(Vec3::ZERO, 1.0, Rgb888::new(255, 64, 64)),
                    Sphere::new(Vec3::new(0.5, -0.9, 1.6), 0.35, Rgb888::new(255, 255, 64)),
                ],
                Rgb888::BLACK,
            );
            for fov in (10..=170).step_by(10) {
                let params = CameraParams::new(
                    Vec3::new(0.0, 0.0, 5.0),
                    Vec3::ZERO,
                    up,
                    (fov as f32).to_radians(),
                    Size::new(96, 96),
                );
                points.extend(run(f64::from(fov), &scene, params));
            }
        }
    }
    points
}

/// The last swept value the rule takes and the first it refuses (`None` where the
/// sweep has none), given points in increasing difficulty.
#[must_use]
pub fn integer_limit(points: &[IntegerPoint]) -> (Option<f64>, Option<f64>) {
    let last = points.iter().rposition(|p| p.integer);
    let first_refused = points.iter().position(|p| !p.integer);
    (
        last.and_then(|k| points.get(k)).map(|p| p.value),
        first_refused.and_then(|k| points.get(k)).map(|p| p.value),
    )
}
