//! Stability tests: every method measured against the f64 reference
//! (`embedded_raytracer_lab::reference`) at the point where it fails. Each sweep is the
//! same code `lab/examples/accuracy_table.rs` prints into the README; the numbers in the
//! comments and messages were measured with `cargo run --release --features
//! tools --example accuracy_table` and by these tests.

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_raytracer::{
    Camera, CameraError, CameraParam, CameraParams, Method, Render, Scene, Sphere, SphereTest, Sqrt,
    Stepping, Vec3,
};
use embedded_raytracer::{MAX_FOV, MIN_PIXEL_SIZE};
use embedded_raytracer_lab::reference::sweeps::{self, *};
use embedded_raytracer_lab::reference::{self, intersect, D3};

fn m(stepping: Stepping, test: SphereTest, sqrt: Sqrt) -> Method {
    Method::new(stepping, test, sqrt)
}

fn direct(test: SphereTest, sqrt: Sqrt) -> Method {
    m(Stepping::Direct, test, sqrt)
}

use crate::common;
use common::load;

// ---------------------------------------------------------------------------------
// Distance/radius: a small sphere far away.
// ---------------------------------------------------------------------------------

/// Measured (64×64, sphere half the image wide, 17 ratios 10^(k/4)): the slides'
/// algebraic and geometric tests are exact to 100 and lose edge pixels from 178; at
/// 3162 half the disc is wrong; from 17783 every ray of the image is a "hit". The
/// robust test has no coverage error up to 1e5, with either square root.
#[test]
fn distance_sweep_pins_each_sphere_test() {
    let methods = sphere_methods();
    let points = distance_sweep(64, &methods);
    assert_eq!(points.len(), 17 * 6, "every ratio builds a valid camera");
    let failures = distance_failures(&points, &methods);
    let get = |t, q| *failures.iter().find(|f| f.method == direct(t, q)).unwrap();

    for (t, q) in [
        (SphereTest::Algebraic, Sqrt::Exact),
        (SphereTest::Algebraic, Sqrt::Fast),
        (SphereTest::Geometric, Sqrt::Exact),
    ] {
        let f = get(t, q);
        // Clean at 100, first wrong pixels at the next ratio, 177.8.
        assert_eq!(f.clean_up_to, Some(100.0), "{f:?}");
        let first = f.first_error.unwrap();
        assert!((177.0..178.0).contains(&first), "{t}/{q} first error at {first}");
        let outright = f.outright.unwrap();
        assert!(
            (3162.0..3163.0).contains(&outright),
            "{t}/{q} fails outright at {outright}"
        );
    }
    // Geometric with the fast root: the 6 % normalisation error costs pixels at once.
    let f = get(SphereTest::Geometric, Sqrt::Fast);
    assert_eq!(f.first_error, Some(10.0), "{f:?}");

    // All-or-nothing beyond ~1e4: every background pixel is classified a hit.
    for p in points
        .iter()
        .filter(|p| p.ratio > 17000.0 && p.method.sphere_test != SphereTest::Robust)
    {
        let background = p.metrics.pixels - p.sphere_pixels;
        assert_eq!(
            p.metrics.coverage_errors, background,
            "{} at {:.0}: {} errors, {} background pixels",
            p.method, p.ratio, p.metrics.coverage_errors, background
        );
    }

    // Robust: zero coverage errors outside the undecidable band over the whole sweep.
    for q in [Sqrt::Exact, Sqrt::Fast] {
        let f = get(SphereTest::Robust, q);
        assert_eq!(f.first_error, None, "{f:?}");
        assert_eq!(f.clean_up_to, Some(1e5), "{f:?}");
    }
    // The sphere is still ~21 px across at 1e5 (MIN_PIXEL_SIZE limits the zoom).
    let last = points.iter().find(|p| p.ratio == 1e5).unwrap();
    assert!(last.sphere_pixels > 300, "{} px at 1e5", last.sphere_pixels);
    assert!(
        (20.0..22.0).contains(&last.diameter_px),
        "{:.1} px",
        last.diameter_px
    );
}

/// The same sweep at 256×256 for every method of `Method::ALL`: the stepping adds nothing here
/// (axis-aligned camera at the origin), so every stepping fails where Direct does.
#[test]
#[ignore = "exhaustive: cargo test --release --test lab -- --ignored"]
fn distance_sweep_exhaustive() {
    let points = distance_sweep(256, &Method::ALL);
    let failures = distance_failures(&points, &Method::ALL);
    for f in &failures {
        match (f.method.sphere_test, f.method.sqrt) {
            // The robust test, and the forward-differenced one (same perpendicular-
            // distance discriminant, no `|L|² − t²` cancellation), with either root.
            (SphereTest::Robust | SphereTest::ForwardDiff | SphereTest::Auto, _) => {
                assert_eq!(f.first_error, None, "{f:?}")
            }
            (SphereTest::Geometric, Sqrt::Fast) => assert_eq!(f.first_error, Some(10.0), "{f:?}"),
            _ => {
                // More edge pixels than at 64 px: the first flip comes earlier.
                let first = f.first_error.unwrap();
                assert!((10.0..400.0).contains(&first), "{f:?}");
                let outright = f.outright.unwrap();
                assert!((1000.0..10000.0).contains(&outright), "{f:?}");
            }
        }
    }
}

// ---------------------------------------------------------------------------------
// A huge sphere as the ground, eye one unit above it.
// ---------------------------------------------------------------------------------

/// Measured: coverage is right for every exact method up to R = 1e6, and shading is
/// exact (the normal `(L·w − t·d·w)/r` divides the depth error by the huge radius),
/// but the hit distance degrades with R for all three tests because `c = |L|² − r²`
/// is formed in f32 (|L|² ≈ 1e12 has an ulp of 131072 while c ≈ 2e6): robust
/// 1.3e-4 at 1e4, 1.7e-3 at 1e5, 1.6e-2 at 1e6; algebraic/geometric ≈ 4× worse
/// (5.8e-2 at 1e6). With the fast root the algebraic and geometric near roots cancel
/// to negative values and the ray "sees through" the ground to its far side.
#[test]
fn ground_sweep_distance_and_shade() {
    let methods = sphere_methods();
    let points = ground_sweep(64, &methods);
    assert_eq!(points.len(), GROUND_RADII.len() * 6);
    let at = |r: f64, t, q| {
        points
            .iter()
            .find(|p| p.radius == r && p.method == direct(t, q))
            .unwrap()
            .metrics
    };
    for p in points.iter().filter(|p| p.method.sqrt == Sqrt::Exact) {
        let x = p.metrics;
        assert_eq!(x.coverage_errors, 0, "{} R={:e}: {x:?}", p.method, p.radius);
        assert_eq!(x.shade_max, 0, "{} R={:e}: {x:?}", p.method, p.radius);
        assert!(
            x.agreeing_hits > 1000,
            "the ground fills most of the image: {x:?}"
        );
    }
    // Robust: hit distance within 1e-3 up to R = 1e4 and from 1e5 beyond it.
    let robust = |r| at(r, SphereTest::Robust, Sqrt::Exact).distance_rel_max;
    assert!(robust(1e4) < 2e-4, "robust R=1e4: {:e}", robust(1e4));
    assert!(robust(1e5) > 1e-3, "robust R=1e5: {:e}", robust(1e5));
    assert!(
        (1e-2..3e-2).contains(&robust(1e6)),
        "robust R=1e6: {:e}",
        robust(1e6)
    );
    for t in [SphereTest::Algebraic, SphereTest::Geometric] {
        let d = |r| at(r, t, Sqrt::Exact).distance_rel_max;
        assert!(d(1e4) < 1e-3, "{t} R=1e4: {:e}", d(1e4));
        assert!(d(1e5) > 5e-3, "{t} R=1e5: {:e}", d(1e5));
        assert!(
            d(1e6) > 3.0 * robust(1e6),
            "{t} R=1e6: {:e} vs robust {:e}",
            d(1e6),
            robust(1e6)
        );
        // Fast root: sees through the ground (distance off by > 100×) already at R = 100.
        let fast = at(1e2, t, Sqrt::Fast);
        assert!(fast.distance_rel_max > 100.0, "{t}/fast R=100: {fast:?}");
        assert!(fast.shade_max > 50, "{t}/fast R=100: {fast:?}");
    }
    // Robust with the fast root: distance within its +6 % root error, shading ≤ 1 level.
    for r in GROUND_RADII {
        let x = at(r, SphereTest::Robust, Sqrt::Fast);
        assert_eq!(x.coverage_errors, 0, "robust/fast R={r:e}: {x:?}");
        assert!(x.distance_rel_max < 0.035, "robust/fast R={r:e}: {x:?}");
        assert!(x.shade_max <= 1, "robust/fast R={r:e}: {x:?}");
    }
}

// ---------------------------------------------------------------------------------
// Tangent and near-tangent rays, the eye inside or on a sphere, spheres behind the
// eye, touching and interpenetrating spheres.
// ---------------------------------------------------------------------------------

/// Near-tangent rays at relative clearances 2⁻¹ … 2⁻⁴⁰ from the silhouette. The
/// robust test is right for every ray farther than 5e-8·r from the silhouette at any
/// distance (f32's own resolution); the slides' tests lose resolution with the
/// square of the distance (measured: 8.8e-8 at D = 2, 1.9e-6 at 10, 1.2e-4 at 100)
/// and at D = 1e4 rays half a radius outside are hits.
#[test]
fn near_tangent_resolution() {
    for distance in [2.0, 10.0, 100.0, 1e4] {
        for method in sphere_methods() {
            let r = grazing_resolution(distance, method);
            assert!(r.rays > 1200, "{r:?}");
            match (method.sphere_test, method.sqrt) {
                (SphereTest::Robust, _) => assert!(r.worst < 5e-8, "D={distance}: {r:?}"),
                (SphereTest::Geometric, Sqrt::Fast) if distance >= 10.0 => {
                    assert!(r.worst >= 0.5, "D={distance}: {r:?}")
                }
                (SphereTest::Geometric, Sqrt::Fast) => assert!(r.worst > 1e-2, "D={distance}: {r:?}"),
                _ => {
                    let bound = match distance as u32 {
                        2 => 1e-7,
                        10 => 2e-6,
                        100 => 1.3e-4,
                        _ => 0.51,
                    };
                    assert!(r.worst <= bound, "D={distance}: {r:?}");
                    assert!(r.worst > bound / 10.0, "D={distance}: {r:?}");
                }
            }
        }
    }
}

/// A ray exactly tangent to the sphere (discriminant 0 in exact arithmetic): the
/// reference calls it undecidable; the kernel's tests call it a hit at the tangent
/// point (documented: a tangent ray is a hit).
#[test]
fn exactly_tangent_ray() {
    let sphere = Sphere::new(Vec3::new(0.0, 0.0, -5.0), 1.0, Rgb888::WHITE);
    let eye = Vec3::new(1.0, 0.0, 0.0);
    let dir = Vec3::new(0.0, 0.0, -1.0);
    let truth = intersect(D3::of(eye), D3::of(dir), D3::of(sphere.center), 1.0);
    assert!(truth.undecidable && truth.disc == 0.0, "{truth:?}");
    for method in sphere_methods() {
        let t = sphere.intersect(eye, dir, method.sphere_test, method.sqrt);
        assert_eq!(t, Some(5.0), "{method}: {t:?}");
    }
}

/// The eye inside a sphere sees the exit point, with every method; the exact methods
/// agree with the f64 reference to 1e-6, the fast root to its +6 %.
#[test]
fn eye_inside_sees_the_exit() {
    let sphere = Sphere::new(Vec3::new(0.2, -0.1, -0.3), 1.5, Rgb888::WHITE);
    for eye in [Vec3::new(0.2, -0.1, -0.3), Vec3::ZERO, Vec3::new(1.2, -0.1, -0.3)] {
        for dir in [
            Vec3::new(0.0, 0.0, -1.0),
            Vec3::new(0.3, -2.0, 0.5),
            Vec3::new(-1.0, 0.1, 0.0),
        ] {
            let truth = intersect(D3::of(eye), D3::of(dir), D3::of(sphere.center), 1.5)
                .t
                .unwrap();
            for method in sphere_methods() {
                let t = sphere
                    .intersect(eye, dir, method.sphere_test, method.sqrt)
                    .unwrap();
                let rel = (f64::from(t) - truth).abs() / truth;
                let bound = if method.sqrt == Sqrt::Exact { 1e-6 } else { 0.07 };
                assert!(
                    rel < bound,
                    "{method} eye {eye:?} dir {dir:?}: {t} vs {truth} ({rel:e})"
                );
            }
        }
    }
    // A rendered view from inside: every pixel shows the sphere (its inside, at the
    // 0.3 floor of Lab #1), for the default method.
    let mut scene: Scene<1> = Scene::new(Rgb888::BLACK);
    scene
        .push(Sphere::new(Vec3::ZERO, 2.0, Rgb888::new(200, 100, 50)))
        .unwrap();
    let camera = Camera::new(
        Vec3::new(0.5, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::new(0.0, 1.0, 0.0),
        1.5,
        Size::new(32, 24),
    )
    .unwrap();
    let x = measure(&scene, &camera, Method::TARGET_DEFAULT);
    assert_eq!(
        (x.coverage_errors, x.agreeing_hits, x.shade_max),
        (0, 32 * 24, 0),
        "{x:?}"
    );
}

/// The eye exactly on the surface (`c = 0`): rays into the sphere hit the far side,
/// rays out of it miss (`t = 0` is not `> 0`). A ray tangent at the eye (`b = 0`,
/// discriminant 0) is a miss for the exact tests — for the robust one because `q = 0`
/// makes `c/q` NaN (documented on `intersect_robust`) — but a hit at t ≈ 1e-19 for
/// every test with the fast root, whose √0 is 8.1e-20.
#[test]
fn eye_on_the_surface() {
    let sphere = Sphere::new(Vec3::ZERO, 1.0, Rgb888::WHITE);
    let eye = Vec3::new(0.0, 0.0, 1.0);
    for method in sphere_methods() {
        let (t, q) = (method.sphere_test, method.sqrt);
        let inward = sphere.intersect(eye, Vec3::new(0.0, 0.0, -1.0), t, q);
        let tol = if q == Sqrt::Exact { 1e-6 } else { 0.13 };
        assert!(
            inward.is_some_and(|x| (x - 2.0).abs() < tol),
            "{method}: {inward:?}"
        );
        let oblique = sphere.intersect(eye, Vec3::new(0.6, 0.0, -0.8), t, q);
        // Chord length 2·0.8 = 1.6 for a unit direction.
        assert!(
            oblique.is_some_and(|x| (x - 1.6).abs() < tol * 1.6),
            "{method}: {oblique:?}"
        );
        assert_eq!(
            sphere.intersect(eye, Vec3::new(0.0, 0.0, 1.0), t, q),
            None,
            "{method} outward"
        );
        let tangent = sphere.intersect(eye, Vec3::new(1.0, 0.0, 0.0), t, q);
        match (t, q) {
            // The fast root of 0 is 8.1e-20, not 0: every test then reports a hit at
            // t ≈ 1e-19, i.e. at the eye itself.
            (_, Sqrt::Fast) => {
                assert!(
                    tangent.is_some_and(|x| x < 1e-19),
                    "{method} tangent at the eye: {tangent:?}"
                )
            }
            _ => assert_eq!(tangent, None, "{method} tangent at the eye"),
        }
    }
}

/// Spheres behind the eye are never hit, by any method.
#[test]
fn spheres_behind_the_eye() {
    let mut scene: Scene<3> = Scene::new(Rgb888::new(1, 2, 3));
    for (z, r) in [(4.0, 1.0), (50.0, 10.0), (1e4, 100.0)] {
        scene
            .push(Sphere::new(Vec3::new(0.1, 0.0, z), r, Rgb888::WHITE))
            .unwrap();
    }
    let camera = Camera::new(
        Vec3::ZERO,
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::new(0.0, 1.0, 0.0),
        2.5,
        Size::new(16, 16),
    )
    .unwrap();
    for method in Method::ALL {
        let mut hits = 0;
        Render::<3, Rgb888>::new(&scene, &camera)
            .with_method(method)
            .trace(|s| hits += usize::from(s.hit.is_some()));
        assert_eq!(hits, 0, "{method}");
    }
}

/// Two spheres touching at one point and a third cutting into one of them: the
/// robust exact methods agree with the reference on every decidable pixel; the
/// touching point and the intersection curve are where depth ties happen.
#[test]
fn touching_and_interpenetrating_spheres() {
    let f = load("grazing");
    let truth = reference::render(&f.scene, &f.camera);
    for method in [
        Method::TARGET_DEFAULT,
        m(Stepping::Direct, SphereTest::Robust, Sqrt::Exact),
        m(Stepping::Direct, SphereTest::Algebraic, Sqrt::Exact),
        m(Stepping::Direct, SphereTest::Geometric, Sqrt::Exact),
    ] {
        let x = reference::compare(
            &Render::<_, Rgb888>::new(&f.scene, &f.camera).with_method(method),
            &truth,
        );
        assert_eq!(x.coverage_errors, 0, "{method}: {x:?}");
        assert!(x.shade_max <= 1, "{method}: {x:?}");
    }
    // Touching exactly, seen side on through the contact point: a depth tie the
    // reference cannot decide; the kernel picks the first sphere (strict `t < t_max`).
    let mut scene: Scene<2> = Scene::new(Rgb888::BLACK);
    scene
        .push(Sphere::new(Vec3::new(-1.0, 0.0, 0.0), 1.0, Rgb888::RED))
        .unwrap();
    scene
        .push(Sphere::new(Vec3::new(1.0, 0.0, 0.0), 1.0, Rgb888::GREEN))
        .unwrap();
    let camera = Camera::new(
        Vec3::new(0.0, 0.0, 10.0),
        Vec3::ZERO,
        Vec3::new(0.0, 1.0, 0.0),
        0.5,
        Size::new(1, 1),
    )
    .unwrap();
    let truth = reference::render(&scene, &camera);
    assert_eq!(truth.undecidable(), 1);
    let x = measure(&scene, &camera, Method::TARGET_DEFAULT);
    assert_eq!((x.undecidable, x.coverage_errors), (1, 0), "{x:?}");
}

// ---------------------------------------------------------------------------------
// Stepping drift.
// ---------------------------------------------------------------------------------

/// Measured with an oblique camera, rows `n × 1` and columns `1 × n` of square
/// pixels over a 60° field of view:
/// - `WorldSpace` first drifts ≥ 1 px at 1920 wide when `|eye|` = 100 (1.29 px in a
///   row, 5.4 px in a column; 0.15 px at `|eye|` = 10, so DESIGN.md's "≥ 1 px at
///   1920 once |eye| ≥ 10" is off by a decade for this camera); at 4096 from
///   `|eye|` = 10 (1.8 px); at 8192 with `|eye|` = 1e4 the whole row is lost.
/// - `Incremental` does not depend on `|eye|`; its rows accumulate one rounding per
///   pixel: 0.023 px at 1920, 0.14 px at 4096, 0.495 px at 8192.
/// - `Direct` stays ≤ 0.001 px everywhere.
#[test]
fn stepping_drift_against_eye_distance_and_resolution() {
    let points = drift_sweep(&DRIFT_PIXELS, &DRIFT_EYE);
    assert_eq!(points.len(), DRIFT_PIXELS.len() * 2 * DRIFT_EYE.len() * 3);
    let at = |s, n, e: f64, column| {
        points
            .iter()
            .find(|p| p.stepping == s && p.pixels == n && p.eye_distance == e && p.column == column)
            .unwrap()
            .drift
    };
    // WorldSpace: the failure points.
    assert_eq!(
        first_pixel_drift(&points, Stepping::WorldSpace, 1920),
        Some(100.0)
    );
    assert!(
        at(Stepping::WorldSpace, 1920, 10.0, false) < 1.0,
        "{}",
        at(Stepping::WorldSpace, 1920, 10.0, false)
    );
    assert!(
        at(Stepping::WorldSpace, 1920, 100.0, false) >= 1.0,
        "{}",
        at(Stepping::WorldSpace, 1920, 100.0, false)
    );
    assert_eq!(first_pixel_drift(&points, Stepping::WorldSpace, 4096), Some(10.0));
    assert_eq!(
        first_pixel_drift(&points, Stepping::WorldSpace, 256),
        Some(1000.0)
    );
    assert!(at(Stepping::WorldSpace, 8192, 1e4, false) > 8000.0);
    // Even at the origin, 8192 scanline steps of a column drift 1.5 px.
    assert!(
        at(Stepping::WorldSpace, 8192, 0.0, true) > 1.0,
        "{}",
        at(Stepping::WorldSpace, 8192, 0.0, true)
    );

    // Incremental: independent of |eye|, under a pixel at 8192.
    for n in DRIFT_PIXELS {
        for column in [false, true] {
            let d0 = at(Stepping::Incremental, n, 0.0, column);
            let d4 = at(Stepping::Incremental, n, 1e4, column);
            assert!((d0 - d4).abs() < 0.01 * d0.max(1e-3), "n={n}: {d0} vs {d4}");
        }
    }
    let inc = max_drift(&points, Stepping::Incremental);
    assert!(inc < 0.5, "Incremental max drift {inc} px");
    assert!(
        at(Stepping::Incremental, 8192, 0.0, false) > 0.4,
        "row accumulation is real"
    );
    assert!(at(Stepping::Incremental, 1920, 0.0, false) < 0.03);
    // Direct: bounded by a few f32 roundings of |d| ≈ 1.
    let dir = max_drift(&points, Stepping::Direct);
    assert!(dir < 0.002, "Direct max drift {dir} px");
}

/// At the narrowest field of view the camera accepts (pixels of MIN_PIXEL_SIZE),
/// an oblique camera makes `Incremental` (and `WorldSpace`) drift badly: each add of
/// `du` (≈ 1e-6) to a direction component of size ~0.5 rounds by up to 3e-8, 1/32 px,
/// and the roundings accumulate along the row — measured 0.26 px at 64 wide, 3.8 px
/// at 1024, 30 px at 8192. An axis-aligned camera is immune (0.06 px at 8192): `du`
/// only changes the x component, which stays small. `Direct` stays ≤ 0.05 px.
#[test]
fn narrow_fov_drift() {
    let (inc_oblique, inc_aligned) = sweeps::narrow_fov_drift(8192, Stepping::Incremental);
    let (inc_oblique, inc_aligned) = (inc_oblique.unwrap(), inc_aligned.unwrap());
    assert!(inc_oblique > 10.0, "Incremental, oblique, 8192: {inc_oblique} px");
    assert!(
        inc_aligned < 0.1,
        "Incremental, axis-aligned, 8192: {inc_aligned} px"
    );
    let inc_1024 = sweeps::narrow_fov_drift(1024, Stepping::Incremental).0.unwrap();
    assert!(inc_1024 > 1.0, "Incremental, oblique, 1024: {inc_1024} px");
    let inc_64 = sweeps::narrow_fov_drift(64, Stepping::Incremental).0.unwrap();
    assert!(
        (0.1..1.0).contains(&inc_64),
        "Incremental, oblique, 64: {inc_64} px"
    );
    for n in [64, 1024, 8192] {
        let (o, a) = sweeps::narrow_fov_drift(n, Stepping::Direct);
        assert!(o.unwrap() < 0.05 && a.unwrap() < 0.01, "Direct {n}: {o:?} {a:?}");
    }
}

// ---------------------------------------------------------------------------------
// Fast square roots.
// ---------------------------------------------------------------------------------

/// The error `Sqrt::Fast` adds, per sphere test, on the lab and grazing scenes
/// (Direct stepping). Measured: robust keeps coverage on the lab scene and costs up
/// to 12 levels of shade; on the grazing scene its depth errors (≤ 6 %) swap the
/// front sphere at 4 pixels near the interpenetration. Algebraic with the fast root
/// sees through the nearby sphere (271 pixels, near root cancelled below 0);
/// geometric's normalisation error loses more than a thousand edge pixels.
#[test]
fn fast_sqrt_cost_per_sphere_test() {
    let lab = load("lab");
    let grazing = load("grazing");
    for (name, f) in [("lab", &lab), ("grazing", &grazing)] {
        let truth = reference::render(&f.scene, &f.camera);
        let run = |t, q| {
            reference::compare(
                &Render::<_, Rgb888>::new(&f.scene, &f.camera).with_method(direct(t, q)),
                &truth,
            )
        };
        for t in [SphereTest::Algebraic, SphereTest::Geometric, SphereTest::Robust] {
            let (exact, fast) = (run(t, Sqrt::Exact), run(t, Sqrt::Fast));
            assert_eq!(exact.coverage_errors, 0, "{name} {t}/exact: {exact:?}");
            assert!(exact.shade_max <= 1, "{name} {t}/exact: {exact:?}");
            assert!(fast.shade_max > 1, "{name} {t}/fast must cost shade: {fast:?}");
            match (name, t) {
                ("lab", SphereTest::Robust) | ("lab", SphereTest::Algebraic) => {
                    assert_eq!(fast.coverage_errors, 0, "{name} {t}/fast: {fast:?}");
                    assert!(fast.shade_max <= 15, "{name} {t}/fast: {fast:?}");
                }
                ("grazing", SphereTest::Robust) => {
                    assert!(fast.coverage_errors <= 10, "{name} {t}/fast: {fast:?}");
                    // Only depth-order swaps where two spheres are within 0.1 % of each other.
                    assert!(fast.worst_error_margin < 1e-3, "{name} {t}/fast: {fast:?}");
                }
                ("grazing", SphereTest::Algebraic) => {
                    assert!(fast.coverage_errors > 200, "{name} {t}/fast: {fast:?}");
                    assert!(fast.distance_rel_max > 10.0, "{name} {t}/fast: {fast:?}");
                }
                (_, SphereTest::Geometric) => {
                    assert!(fast.coverage_errors > 1000, "{name} {t}/fast: {fast:?}")
                }
                _ => unreachable!(),
            }
        }
    }
}

// ---------------------------------------------------------------------------------
// The camera near its limits.
// ---------------------------------------------------------------------------------

/// `up` within 1e-2 … 1e-7 rad of the view direction: accepted down to 1.01e-3 (drift
/// under 0.001 px on a 64×64 image), refused from 0.99e-3 on.
#[test]
fn up_near_the_view_direction() {
    let points = up_angle_sweep();
    for p in &points {
        if p.angle > 1e-3 {
            let drift = p
                .result
                .unwrap_or_else(|e| panic!("angle {:e} refused: {e}", p.angle));
            assert!(drift < 1e-3, "angle {:e}: drift {drift}", p.angle);
        } else {
            assert_eq!(
                p.result,
                Err(CameraError::UpParallelToView),
                "angle {:e}",
                p.angle
            );
        }
    }
    assert!(points.iter().any(|p| p.angle == 1e-7));
}

fn sphere_scene() -> Scene<2> {
    let mut scene = Scene::new(Rgb888::new(0, 0, 40));
    scene
        .push(Sphere::new(
            Vec3::new(0.0, 0.0, -10.0),
            1.0,
            Rgb888::new(255, 64, 64),
        ))
        .unwrap();
    scene
        .push(Sphere::new(
            Vec3::new(0.3, 0.2, -9.0),
            0.4,
            Rgb888::new(64, 255, 64),
        ))
        .unwrap();
    scene
}

/// Fields of view near 0 and 180°: the narrowest accepted for 64 px (pixels just
/// above MIN_PIXEL_SIZE) and 179° (MAX_FOV) both render with no coverage error;
/// narrower and wider are refused.
#[test]
fn fov_near_its_limits() {
    let scene = sphere_scene();
    let base = |fov: f32| {
        CameraParams::new(
            Vec3::ZERO,
            Vec3::new(0.0, 0.0, -1.0),
            Vec3::new(0.0, 1.0, 0.0),
            fov,
            Size::new(64, 64),
        )
    };
    // Narrowest: the sphere's centre is 10 away, so the image shows 6e-4 of it.
    let narrow = fov_for_pixel(f64::from(MIN_PIXEL_SIZE) * 1.01, 64);
    let camera = base(narrow).build().unwrap();
    for method in Method::ALL {
        let x = measure(&scene, &camera, method);
        assert_eq!(x.coverage_errors, 0, "{method} at fov {narrow}: {x:?}");
        assert!(x.drift_max < 0.1, "{method} at fov {narrow}: {x:?}");
    }
    let too_narrow = fov_for_pixel(f64::from(MIN_PIXEL_SIZE) * 0.99, 64);
    assert_eq!(
        base(too_narrow).build(),
        Err(CameraError::FovTooNarrow(CameraParam::FovY))
    );

    let camera = base(MAX_FOV).build().unwrap();
    for method in [Method::TARGET_DEFAULT, direct(SphereTest::Robust, Sqrt::Exact)] {
        let x = measure(&scene, &camera, method);
        assert_eq!(x.coverage_errors, 0, "{method} at 179°: {x:?}");
        assert!(x.shade_max <= 1 && x.drift_max < 1e-3, "{method} at 179°: {x:?}");
    }
    assert_eq!(
        base(179.5f32.to_radians()).build(),
        Err(CameraError::FovOutOfRange(CameraParam::FovY))
    );
    assert_eq!(
        base(0.0).build(),
        Err(CameraError::FovOutOfRange(CameraParam::FovY))
    );
}

/// Non-square pixels (fov_x given), 1×1 and 1×N / N×1 images: every pixel once, no
/// coverage error, drift ≤ 0.001 px, for every method.
#[test]
fn odd_shapes() {
    let scene = sphere_scene();
    let look = |size: Size| {
        CameraParams::new(
            Vec3::new(0.5, 0.4, 0.0),
            Vec3::new(0.0, 0.0, -10.0),
            Vec3::new(0.0, 1.0, 0.0),
            0.3,
            size,
        )
    };
    let cases = [
        look(Size::new(48, 32)).with_fov_x(0.8),
        look(Size::new(32, 48)).with_fov_x(0.1),
        look(Size::new(1, 1)),
        look(Size::new(1, 97)),
        look(Size::new(97, 1)),
    ];
    for params in cases {
        let camera = params.build().unwrap();
        for method in Method::ALL {
            let x = measure(&scene, &camera, method);
            let n = (params.size.width * params.size.height) as usize;
            assert_eq!(
                (x.pixels, x.bad_samples, x.non_finite),
                (n, 0, 0),
                "{method} {:?}",
                params.size
            );
            // Geometric with the fast root fails everywhere (see the distance sweep).
            if (method.sphere_test, method.sqrt) != (SphereTest::Geometric, Sqrt::Fast) {
                assert_eq!(x.coverage_errors, 0, "{method} {:?}: {x:?}", params.size);
            }
            assert!(x.drift_max < 1e-3, "{method} {:?}: {x:?}", params.size);
        }
    }
}

// ---------------------------------------------------------------------------------
// The standard scenes.
// ---------------------------------------------------------------------------------

/// The default (`Direct/Auto/Exact`) and `Direct/Robust/Exact` have zero coverage
/// errors and at most one level of shade error on every standard scene.
/// `Incremental/Robust/Exact` (the default until this measurement) does not quite: its row accumulation (0.016 px on `drift`,
/// 1920 wide) flips pixels whose centre lies within that drift of a silhouette
/// (measured: 14 on `drift`, worst 6e-6 rad from the silhouette; 1 on `crowd`,
/// 1.7e-7 rad). This test pins that every such error is explained by its drift.
fn standard_scene(name: &str) {
    let f = load(name);
    let truth = reference::render(&f.scene, &f.camera);
    let run = |method| {
        reference::compare(
            &Render::<_, Rgb888>::new(&f.scene, &f.camera).with_method(method),
            &truth,
        )
    };
    let best = run(direct(SphereTest::Robust, Sqrt::Exact));
    assert_eq!(best.coverage_errors, 0, "{name} direct/robust/exact: {best:?}");
    assert!(best.shade_max <= 1, "{name} direct/robust/exact: {best:?}");
    let best = run(Method::TARGET_DEFAULT);
    assert_eq!(best.coverage_errors, 0, "{name} default: {best:?}");
    assert!(best.shade_max <= 1, "{name} default: {best:?}");
    let incremental = run(Method::new(
        Stepping::Incremental,
        SphereTest::Robust,
        Sqrt::Exact,
    ));
    // A drift of δ px moves a ray by δ·pixel angle; f32 directions add ~1e-7 rad.
    let pixel = truth.camera.pixel_width.max(truth.camera.pixel_height);
    let explained = incremental.drift_max * pixel + 1e-6;
    assert!(
        incremental.worst_error_margin <= explained,
        "{name} incremental: {} coverage errors, worst {:e} rad from a silhouette, drift explains {explained:e}: {incremental:?}",
        incremental.coverage_errors,
        incremental.worst_error_margin
    );
    assert!(incremental.shade_max <= 1, "{name} incremental: {incremental:?}");
}

#[test]
fn standard_scene_lab() {
    standard_scene("lab");
}

#[test]
fn standard_scene_far() {
    standard_scene("far");
}

#[test]
fn standard_scene_grazing() {
    standard_scene("grazing");
}

#[test]
fn standard_scene_crowd() {
    standard_scene("crowd");
}

/// 1920×1080: a few seconds in a debug build, so with the exhaustive tests.
#[test]
#[ignore = "exhaustive: cargo test --release --test lab -- --ignored"]
fn standard_scene_drift() {
    standard_scene("drift");
}
