//! The three ray–sphere tests against hand-computed values, with both square roots.

use embedded_graphics::pixelcolor::Rgb888;
use embedded_raytracer::{Scene, Sphere, SphereError, SphereTest, Sqrt, Vec3};

const TESTS: [SphereTest; 3] = [SphereTest::Algebraic, SphereTest::Geometric, SphereTest::Robust];
const RED: Rgb888 = Rgb888::new(255, 0, 0);

fn sphere(x: f32, y: f32, z: f32, r: f32) -> Sphere {
    Sphere::try_new(Vec3::new(x, y, z), r, RED).unwrap()
}

/// Every exact-sqrt test gives `expected` (within `tol`) for the ray `o + t·d`.
fn check(s: Sphere, o: Vec3, d: Vec3, expected: Option<f32>, tol: f32) {
    for test in TESTS {
        let got = s.intersect(o, d, test, Sqrt::Exact);
        match (got, expected) {
            (None, None) => {}
            (Some(t), Some(e)) => assert!((t - e).abs() <= tol, "{test:?}: t = {t}, expected {e}"),
            _ => panic!("{test:?}: got {got:?}, expected {expected:?} for {s:?} o={o:?} d={d:?}"),
        }
    }
}

const O: Vec3 = Vec3::ZERO;
const FWD: Vec3 = Vec3::new(0.0, 0.0, -1.0);

#[test]
fn miss() {
    check(sphere(0.0, 3.0, -5.0, 1.0), O, FWD, None, 0.0);
    check(sphere(1.0001, 0.0, -5.0, 1.0), O, FWD, None, 0.0);
}

#[test]
fn hit_front() {
    // Entry at z = −4: t = 4 for a unit direction, 2 for a direction of length 2.
    check(sphere(0.0, 0.0, -5.0, 1.0), O, FWD, Some(4.0), 1e-6);
    check(sphere(0.0, 0.0, -5.0, 1.0), O, FWD * 2.0, Some(2.0), 1e-6);
    // Off-axis: ray (0,0,−1) from (0.6,0,0) to a unit sphere at (0,0,−5): entry at
    // z = −5 + √(1 − 0.36) = −4.2.
    check(
        sphere(0.0, 0.0, -5.0, 1.0),
        Vec3::new(0.6, 0.0, 0.0),
        FWD,
        Some(4.2),
        1e-5,
    );
}

#[test]
fn tangent() {
    // Grazes (0, 0, −5): discriminant exactly 0 in f32, one root t = 5, no NaN.
    check(sphere(1.0, 0.0, -5.0, 1.0), O, FWD, Some(5.0), 1e-6);
}

#[test]
fn eye_inside_gets_exit_hit() {
    check(sphere(0.0, 0.0, 0.0, 2.0), O, FWD, Some(2.0), 1e-6);
    check(sphere(0.0, 0.0, -1.0, 2.0), O, FWD, Some(3.0), 1e-6);
    check(sphere(0.0, 0.0, 1.0, 2.0), O, FWD, Some(1.0), 1e-6);
}

#[test]
fn behind_the_eye() {
    check(sphere(0.0, 0.0, 5.0, 1.0), O, FWD, None, 0.0);
    // Just behind, overlapping the eye's plane but not the eye.
    check(sphere(0.0, 0.0, 1.5, 1.0), O, FWD, None, 0.0);
}

#[test]
fn eye_on_the_surface() {
    // Looking into the sphere: the far side at t = 2; looking away: nothing.
    check(sphere(0.0, 0.0, -1.0, 1.0), O, FWD, Some(2.0), 1e-6);
    check(sphere(0.0, 0.0, 1.0, 1.0), O, FWD, None, 0.0);
}

#[test]
fn overlapping_spheres_closest_wins() {
    let mut scene: Scene<3> = Scene::new(Rgb888::new(0, 0, 0));
    scene.push(sphere(0.0, 0.0, -10.0, 2.0)).unwrap(); // entry t = 8
    scene.push(sphere(0.0, 0.0, -7.0, 2.0)).unwrap(); // entry t = 5, overlaps the first
    scene.push(sphere(0.0, 0.0, -20.0, 1.0)).unwrap(); // far behind both
    for test in TESTS {
        for sqrt in [Sqrt::Exact, Sqrt::Fast] {
            let hit = scene.closest_hit(O, FWD, test, sqrt).unwrap();
            assert_eq!(hit.index, 1, "{test:?} {sqrt:?}");
            let tol = if sqrt == Sqrt::Exact { 1e-5 } else { 5.0 * 0.0607 };
            assert!((hit.t - 5.0).abs() <= tol, "{test:?} {sqrt:?}: t = {}", hit.t);
        }
    }
    // The order of the spheres does not matter.
    let mut reversed: Scene<3> = Scene::new(Rgb888::new(0, 0, 0));
    for s in scene.spheres().iter().rev() {
        reversed.push(*s).unwrap();
    }
    assert_eq!(
        reversed
            .closest_hit(O, FWD, SphereTest::Robust, Sqrt::Exact)
            .unwrap()
            .index,
        1
    );
}

/// Algebraic and Robust decide hit/miss without a square root, so `Fast` only moves
/// `t` (by at most the root's 6.07 %); Geometric normalises the ray with it, so its
/// `t_ca` is off too.
#[test]
fn fast_sqrt_moves_t_within_its_bound() {
    let s = sphere(0.3, 0.2, -5.0, 1.0);
    for test in [SphereTest::Algebraic, SphereTest::Robust] {
        let exact = s.intersect(O, FWD, test, Sqrt::Exact).unwrap();
        let fast = s.intersect(O, FWD, test, Sqrt::Fast).unwrap();
        // t = (b − √disc)/a: an error of +6.07 % in √disc moves t by ≤ 0.0607·√disc/a.
        let root = 2.0 * (1.0f32 - 0.13).sqrt(); // chord length for this offset
        assert!(
            (fast - exact).abs() <= 0.0607 * root / 2.0 + 1e-5,
            "{test:?}: {fast} vs {exact}"
        );
    }
}

#[test]
fn checked_constructor() {
    assert_eq!(
        Sphere::try_new(Vec3::ZERO, 0.0, RED),
        Err(SphereError::RadiusNotPositive)
    );
    assert_eq!(
        Sphere::try_new(Vec3::ZERO, -1.0, RED),
        Err(SphereError::RadiusNotPositive)
    );
    assert_eq!(
        Sphere::try_new(Vec3::ZERO, f32::NAN, RED),
        Err(SphereError::NotFinite)
    );
    assert_eq!(
        Sphere::try_new(Vec3::new(f32::INFINITY, 0.0, 0.0), 1.0, RED),
        Err(SphereError::NotFinite)
    );
    let mut scene: Scene<1> = Scene::new(RED);
    assert!(scene.push(Sphere::new(Vec3::ZERO, 0.0, RED)).is_err());
    scene.push(sphere(0.0, 0.0, 0.0, 1.0)).unwrap();
    assert_eq!(
        scene.push(sphere(0.0, 0.0, 0.0, 1.0)).unwrap_err().to_string(),
        "too many spheres: the scene holds at most 1"
    );
}

/// Degenerate spheres made with the unchecked `const fn new` never panic and never
/// report a NaN hit.
#[test]
fn unchecked_degenerate_spheres_do_not_panic() {
    for r in [0.0f32, -1.0, f32::NAN, f32::INFINITY, 1e-30, 1e30] {
        let s = Sphere::new(Vec3::new(0.0, 0.0, -5.0), r, RED);
        for test in TESTS {
            for sqrt in [Sqrt::Exact, Sqrt::Fast] {
                if let Some(t) = s.intersect(O, FWD, test, sqrt) {
                    assert!(t > 0.0 && t.is_finite(), "r={r} {test:?}: t={t}");
                }
            }
        }
    }
}
