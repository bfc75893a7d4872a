//! The fast path changes no pixel: span culling is proven bit for bit against the
//! unculled render (every method, every standard scene, randomized scenes including an
//! eye inside a sphere, spheres behind the eye and spheres crossing the eye plane), and
//! the forward-differenced test is measured against the robust test as a function of
//! its anchor interval K.

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_raytracer::AUTO_FD_CAPACITY;
#[cfg(feature = "bench-baselines")]
use embedded_raytracer::FD_ANCHOR_INTERVAL;
use embedded_raytracer::{
    Camera, Light, Method, Options, Render, Scene, Sphere, SphereTest, Sqrt, Stepping, Vec3,
};

use crate::common;
use common::{load, shrink, Traced, SCENES};
#[cfg(feature = "bench-baselines")]
use common::{random_case, Rng};

/// Every pixel of `scene` through `camera` with `method` and the given options.
fn trace_with<const N: usize>(
    scene: &Scene<N>,
    camera: &Camera,
    method: Method,
    options: Options,
) -> Vec<Traced> {
    common::trace(
        Render::new(scene, camera)
            .with_method(method)
            .with_options(options),
    )
}

#[cfg(feature = "bench-baselines")]
/// With span culling on (the default) or off.
fn trace<const N: usize>(scene: &Scene<N>, camera: &Camera, method: Method, culling: bool) -> Vec<Traced> {
    trace_with(scene, camera, method, Options::DEFAULT.with_span_culling(culling))
}

#[cfg(feature = "bench-baselines")]
/// With anchor interval `k`.
fn trace_k<const N: usize>(scene: &Scene<N>, camera: &Camera, method: Method, k: u32) -> Vec<Traced> {
    trace_with(scene, camera, method, Options::DEFAULT.with_anchor_interval(k))
}

/// The methods whose pixels do not depend on where a row's evaluation starts: all but
/// the forward-differenced ones (their anchors sit at the span starts by design).
#[cfg(feature = "bench-baselines")]
fn span_invariant(m: &Method) -> bool {
    !matches!(m.sphere_test, SphereTest::ForwardDiff | SphereTest::Auto)
}

#[test]
#[cfg(feature = "bench-baselines")]
fn culling_changes_no_pixel_on_the_standard_scenes() {
    for name in SCENES {
        let file = load(name);
        // drift at full size is 2 Mpixel: render its central 480x270 window of the same
        // pixel pitch instead (same eye, same world-space rounding magnitudes).
        let camera = if name == "drift" {
            shrink(&file.camera, 480, 270)
        } else {
            file.camera
        };
        for method in Method::ALL.iter().filter(|m| span_invariant(m)) {
            let culled = trace(&file.scene, &camera, *method, true);
            let full = trace(&file.scene, &camera, *method, false);
            let diff = culled.iter().zip(&full).filter(|(a, b)| a != b).count();
            assert_eq!(diff, 0, "{name} {method}: {diff} pixels changed by culling");
        }
    }
}

#[test]
#[cfg(feature = "bench-baselines")]
fn culling_changes_no_pixel_on_random_scenes() {
    // More cases and another seed from the environment for a longer soak, e.g.
    // `SPEED_CASES=5000 SPEED_SEED=7 cargo test --release --test speed random`.
    let env = |k: &str| std::env::var(k).ok().and_then(|v| v.parse::<u64>().ok());
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15 ^ env("SPEED_SEED").unwrap_or(0));
    let mut hits = 0usize;
    for case in 0..env("SPEED_CASES").unwrap_or(60) {
        let (scene, camera) = random_case(&mut rng);
        for method in Method::ALL.iter().filter(|m| span_invariant(m)) {
            let culled = trace(&scene, &camera, *method, true);
            let full = trace(&scene, &camera, *method, false);
            hits += full.iter().filter(|p| p.0.is_some()).count();
            let diff: Vec<_> = culled
                .iter()
                .zip(&full)
                .enumerate()
                .filter(|(_, (a, b))| a != b)
                .map(|(k, (a, b))| (k, *a, *b))
                .take(3)
                .collect();
            assert!(
                diff.is_empty(),
                "case {case} {method}: culling changed pixels {diff:?}\n{scene:?}\n{camera:?}"
            );
        }
    }
    // The scenes are not empty: many rays hit (else the comparison proves nothing).
    assert!(hits > 100_000, "only {hits} hits");
}

/// Pixels whose hit/miss differs, and pixels whose colour differs, between two traces.
fn compare(a: &[Traced], b: &[Traced]) -> (usize, usize, u8) {
    let coverage = a
        .iter()
        .zip(b)
        .filter(|(x, y)| x.0.is_some() != y.0.is_some())
        .count();
    let shade = a.iter().zip(b).filter(|(x, y)| x.1 != y.1).count();
    // Largest channel difference among pixels both traces hit on the same sphere.
    let level = a
        .iter()
        .zip(b)
        .filter(|(x, y)| x.0.map(|h| h.0) == y.0.map(|h| h.0))
        .map(|(x, y)| {
            let d = |p: u8, q: u8| p.abs_diff(q);
            d(x.1.r(), y.1.r())
                .max(d(x.1.g(), y.1.g()))
                .max(d(x.1.b(), y.1.b()))
        })
        .max()
        .unwrap_or(0);
    (coverage, shade, level)
}

/// The measurement K is chosen from (prints a table with `--nocapture`): coverage flips
/// and colour differences of the forward-differenced test against the robust test on
/// every standard scene, for K = 1 … 8192. The chosen K must be as good as K = 1.
#[test]
#[cfg(feature = "bench-baselines")]
fn forward_diff_error_against_k() {
    let fd = Method::new(Stepping::Incremental, SphereTest::ForwardDiff, Sqrt::Exact);
    let robust = Method::new(Stepping::Incremental, SphereTest::Robust, Sqrt::Exact);
    println!("scene       K  coverage  colour  max-level");
    for name in SCENES {
        let file = load(name);
        let camera = if name == "drift" {
            shrink(&file.camera, 480, 270)
        } else {
            file.camera
        };
        let reference = trace_k(&file.scene, &camera, robust, 1);
        let at_one = compare(&trace_k(&file.scene, &camera, fd, 1), &reference);
        for k in [1, 2, 4, 8, 16, 32, 64, 256, 1024, 8192] {
            let (coverage, shade, level) = compare(&trace_k(&file.scene, &camera, fd, k), &reference);
            println!("{name:8} {k:6} {coverage:9} {shade:7} {level:10}");
            if k == FD_ANCHOR_INTERVAL {
                // The chosen K: no more coverage flips than K = 1, colours within one level.
                assert!(
                    coverage <= at_one.0 && level <= 1,
                    "{name} K={k}: {coverage}/{shade}/{level} vs K=1 {at_one:?}"
                );
            }
        }
        // A coverage flip only at the silhouette: a handful per scene at most.
        assert!(at_one.0 <= 8, "{name}: {at_one:?}");
    }
}

/// Where the forward differences break: a sphere filling an 8192-wide row with no
/// re-anchoring (K = 8192) flips edge pixels against the robust test; the default K does not.
#[test]
#[cfg(feature = "bench-baselines")]
fn forward_diff_breaks_without_anchors_on_a_huge_row() {
    let (scene, camera) = common::huge_row();
    let fd = Method::new(Stepping::Direct, SphereTest::ForwardDiff, Sqrt::Exact);
    let robust = Method::new(Stepping::Direct, SphereTest::Robust, Sqrt::Exact);
    let reference = trace_k(&scene, &camera, robust, 1);
    let k = FD_ANCHOR_INTERVAL;
    let (good, _, _) = compare(&trace_k(&scene, &camera, fd, k), &reference);
    let (bad, _, _) = compare(&trace_k(&scene, &camera, fd, 8192), &reference);
    println!("8192-wide row: K={k} {good} flips, K=8192 {bad} flips");
    assert!(good <= 2, "K = {k}: {good}");
    assert!(bad > good, "K = 8192 should break: {bad}");
}

fn trace_method<const N: usize>(scene: &Scene<N>, camera: &Camera, method: Method) -> Vec<Traced> {
    trace_with(scene, camera, method, Options::DEFAULT)
}

/// The first `count` spheres of `crowd` as a `Scene<M>`.
fn crowd_prefix<const M: usize>(crowd: &Scene<{ common::MAX_SPHERES }>, count: usize) -> Scene<M> {
    let mut scene = Scene::new(crowd.background());
    for s in &crowd.spheres()[..count] {
        scene.push(*s).unwrap();
    }
    scene
}

/// `Auto` by the scene's size (`AUTO_FD_CAPACITY`): a scene of more spheres than that
/// is drawn with the robust test for every sphere, one of at most that many with
/// forward differences, whatever the scene type's capacity. Bit for bit, with every
/// stepping and root; each comparison could fail, since forward differences and the
/// robust test round `crowd` differently.
#[test]
fn auto_takes_robust_above_its_capacity() {
    let crowd = load("crowd");
    assert_eq!(crowd.scene.spheres().len(), 64);
    assert_eq!(AUTO_FD_CAPACITY, 32);
    let camera = &crowd.camera;
    for stepping in Stepping::ALL {
        for sqrt in Sqrt::ALL {
            let with = |test| Method::new(stepping, test, sqrt);
            let name = format!("{stepping}/{sqrt}");
            // 64 spheres, in the host's 256-sphere type and in a 64-sphere one.
            let auto = trace_method(&crowd.scene, camera, with(SphereTest::Auto));
            let robust = trace_method(&crowd.scene, camera, with(SphereTest::Robust));
            let fd = trace_method(&crowd.scene, camera, with(SphereTest::ForwardDiff));
            assert!(auto == robust, "crowd {name}: auto differs from robust");
            assert!(
                fd != robust,
                "crowd {name}: forward-diff equals robust, nothing tested"
            );
            let exact: Scene<64> = crowd_prefix(&crowd.scene, 64);
            assert!(
                trace_method(&exact, camera, with(SphereTest::Auto)) == robust,
                "Scene<64> {name}"
            );
            // 33 spheres: still above.
            let above: Scene<64> = crowd_prefix(&crowd.scene, 33);
            let auto = trace_method(&above, camera, with(SphereTest::Auto));
            let robust = trace_method(&above, camera, with(SphereTest::Robust));
            assert!(auto == robust, "33 {name}: auto differs from robust");
            assert!(
                trace_method(&above, camera, with(SphereTest::ForwardDiff)) != robust,
                "33 {name}: forward-diff equals robust, nothing tested"
            );
            // 32 spheres: forward differences, in a type above the limit (its frame sized
            // by the limit) and in one at it.
            let at: Scene<64> = crowd_prefix(&crowd.scene, 32);
            let auto = trace_method(&at, camera, with(SphereTest::Auto));
            let fd = trace_method(&at, camera, with(SphereTest::ForwardDiff));
            let robust = trace_method(&at, camera, with(SphereTest::Robust));
            assert!(
                auto == fd,
                "32 in Scene<64> {name}: auto differs from forward-diff"
            );
            assert!(
                fd != robust,
                "32 {name}: forward-diff equals robust, nothing tested"
            );
            let small: Scene<32> = crowd_prefix(&crowd.scene, 32);
            assert!(
                trace_method(&small, camera, with(SphereTest::Auto)) == fd,
                "Scene<32> {name}"
            );
        }
    }
    // The path of scenes with lights follows the same rule.
    let lit = |count: usize| {
        let mut scene: Scene<64, 1> = Scene::new(crowd.scene.background());
        for s in &crowd.scene.spheres()[..count] {
            scene.push(*s).unwrap();
        }
        scene
            .push_light(Light::directional(Vec3::new(-1.0, -1.0, -1.0), 1.0))
            .unwrap();
        scene
    };
    let method = |test| Method::new(Stepping::Direct, test, Sqrt::Exact);
    for (count, equal, other) in [
        (64, SphereTest::Robust, SphereTest::ForwardDiff),
        (32, SphereTest::ForwardDiff, SphereTest::Robust),
    ] {
        let scene = lit(count);
        let render = |test| common::trace(Render::new(&scene, camera).with_method(method(test)));
        let auto = render(SphereTest::Auto);
        assert!(
            auto == render(equal),
            "lit, {count} spheres: auto differs from {equal}"
        );
        assert!(
            auto != render(other),
            "lit, {count} spheres: {equal} equals {other}, nothing tested"
        );
    }
}

/// `Auto` is forward differences for every sphere whose bound allows it (all of the
/// lab scene's), and the robust test for a sphere containing the eye: bit for bit.
#[test]
fn auto_picks_forward_diff_or_robust_per_sphere() {
    let lab = load("lab");
    for stepping in [Stepping::Direct, Stepping::Incremental] {
        for sqrt in [Sqrt::Exact, Sqrt::Fast] {
            let auto = trace_method(
                &lab.scene,
                &lab.camera,
                Method::new(stepping, SphereTest::Auto, sqrt),
            );
            let fd = trace_method(
                &lab.scene,
                &lab.camera,
                Method::new(stepping, SphereTest::ForwardDiff, sqrt),
            );
            assert!(
                auto == fd,
                "lab {stepping}/{sqrt}: auto differs from forward-diff"
            );
        }
    }
    // The eye inside the only sphere: Auto must fall back to the robust test.
    let inside: Scene<1> = Scene::from_array(
        [Sphere::new(Vec3::new(0.1, 0.2, 0.3), 2.0, Rgb888::WHITE)],
        Rgb888::BLACK,
    );
    let camera = Camera::new(
        Vec3::ZERO,
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::new(0.0, 1.0, 0.0),
        1.2,
        Size::new(64, 48),
    )
    .unwrap();
    let auto = trace_method(
        &inside,
        &camera,
        Method::new(Stepping::Direct, SphereTest::Auto, Sqrt::Exact),
    );
    let robust = trace_method(
        &inside,
        &camera,
        Method::new(Stepping::Direct, SphereTest::Robust, Sqrt::Exact),
    );
    let fd = trace_method(
        &inside,
        &camera,
        Method::new(Stepping::Direct, SphereTest::ForwardDiff, Sqrt::Exact),
    );
    assert!(
        auto.iter().all(|p| p.0.is_some()),
        "inside a sphere every ray hits it"
    );
    assert!(auto == robust, "eye inside: auto differs from robust");
    // (and the fallback is observable: forward differences round differently here)
    assert!(
        fd != robust,
        "forward-diff happens to equal robust: the test above proves nothing"
    );
}

/// The default method meets the accuracy target against the robust test on every
/// standard scene: no coverage flip, colours within one level.
#[test]
fn default_method_matches_robust_within_one_level() {
    for name in SCENES {
        let file = load(name);
        let camera = if name == "drift" {
            shrink(&file.camera, 480, 270)
        } else {
            file.camera
        };
        let default = trace_method(&file.scene, &camera, Method::TARGET_DEFAULT);
        let robust = trace_method(
            &file.scene,
            &camera,
            Method::new(Stepping::Direct, SphereTest::Robust, Sqrt::Exact),
        );
        let (coverage, _, level) = compare(&default, &robust);
        assert_eq!(coverage, 0, "{name}: coverage");
        assert!(level <= 1, "{name}: {level} levels");
    }
}

/// A clipped draw (the image placed partly off the target) gives exactly the pixels of
/// the full render where they are visible, with culling and forward differences
/// (`tests/api/clip.rs` does this for every method on random scenes).
#[test]
fn clipped_draw_matches_the_full_render() {
    use embedded_graphics::mock_display::MockDisplay;
    let lab = load("lab");
    let camera = shrink(&lab.camera, 60, 40);
    for method in [
        Method::TARGET_DEFAULT,
        Method::LITERAL,
        Method::new(Stepping::Incremental, SphereTest::ForwardDiff, Sqrt::Fast),
    ] {
        let full = trace_method(&lab.scene, &camera, method);
        let mut display = MockDisplay::<Rgb888>::new();
        let offset = Point::new(-13, -7);
        Render::new(&lab.scene, &camera)
            .with_method(method)
            .with_offset(offset)
            .draw(&mut display)
            .unwrap();
        let mut checked = 0;
        for (k, p) in full.iter().enumerate() {
            let at = Point::new((k % 60) as i32, (k / 60) as i32) + offset;
            if at.x >= 0 && at.y >= 0 && at.x < 64 && at.y < 64 {
                // Every method, forward differences included (their anchors sit at
                // the whole image's span starts), matches exactly.
                assert_eq!(display.get_pixel(at), Some(p.1), "{method} at {at:?}");
                checked += 1;
            }
        }
        assert_eq!(checked, 47 * 33);
    }
}
