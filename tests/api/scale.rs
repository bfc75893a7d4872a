//! Scale does not matter: a standard scene scaled by any power of two from 2⁻⁶⁰ to 2⁶⁰
//! (centres, radii, the eye and the look-at point) draws the same picture — the same
//! sphere and colour at every pixel, `t` scaled by the same power of two — with every
//! camera-relative method. (World-space stepping is the slides' drift by design: its
//! error grows with `|eye|`, see `lab/tests/lab/stability.rs`.)

#[cfg(feature = "std")]
use crate::common;

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
#[cfg(feature = "std")]
use embedded_raytracer::{CameraParams, Method, Stepping};
use embedded_raytracer::{Render, Scene, Sphere, Vec3};

#[cfg(feature = "std")]
fn scaled<const N: usize>(scene: &Scene<N>, s: f32) -> Scene<N> {
    let mut out = Scene::new(scene.background());
    for sphere in scene.spheres() {
        out.push(Sphere::new(sphere.center * s, sphere.radius * s, sphere.color))
            .unwrap();
    }
    out
}

#[test]
#[cfg(feature = "std")]
fn every_power_of_two_scale_draws_the_same_picture() {
    for name in common::SCENES {
        let file = common::load(name);
        let camera = common::shrink(&file.camera, 64, 48);
        for k in [-60, -45, -30, -15, 15, 30, 45, 60] {
            let s = 2f32.powi(k);
            let scene = scaled(&file.scene, s);
            let p = camera.params();
            let big = CameraParams {
                eye: p.eye * s,
                look_at: p.look_at * s,
                ..*p
            }
            .build()
            .unwrap_or_else(|e| panic!("{name} × 2^{k}: {e:?}"));
            for method in Method::ALL.iter().filter(|m| m.stepping != Stepping::WorldSpace) {
                let want = common::trace(Render::<_, Rgb888>::new(&file.scene, &camera).with_method(*method));
                let got = common::trace(Render::<_, Rgb888>::new(&scene, &big).with_method(*method));
                for (n, (a, b)) in want.iter().zip(&got).enumerate() {
                    let t_scaled = a.0.map(|(i, t)| (i, (f32::from_bits(t) * s).to_bits()));
                    assert_eq!(
                        (t_scaled, a.1),
                        (b.0, b.1),
                        "{name} × 2^{k} {method}: pixel {n} differs"
                    );
                }
            }
        }
    }
}

/// The two scenes a hostile user found: a sphere of radius 10³⁰ around the eye (every
/// pixel shows its inside), and a sphere 3·10¹⁹ away with radius 2·10¹⁹ (it fills the
/// view, as the same geometry scaled by 1/10 does).
#[test]
fn huge_magnitudes_render_what_they_show() {
    let camera = embedded_raytracer::Camera::new(
        Vec3::ZERO,
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::new(0.0, 1.0, 0.0),
        1.0,
        embedded_graphics::prelude::Size::new(17, 13),
    )
    .unwrap();
    let count = |scene: &Scene<1>| {
        let mut hits = 0;
        Render::<1, Rgb888>::new(scene, &camera).trace(|s| hits += usize::from(s.hit.is_some()));
        hits
    };
    let red = Rgb888::new(255, 0, 0);
    let inside: Scene<1> =
        Scene::from_array([Sphere::new(Vec3::new(0.5, 0.0, 0.0), 1e30, red)], Rgb888::BLACK);
    assert_eq!(count(&inside), 17 * 13);
    let far: Scene<1> = Scene::from_array(
        [Sphere::new(Vec3::new(0.0, 0.0, -3e19), 2e19, red)],
        Rgb888::BLACK,
    );
    let tenth: Scene<1> = Scene::from_array(
        [Sphere::new(Vec3::new(0.0, 0.0, -3e18), 2e18, red)],
        Rgb888::BLACK,
    );
    assert_eq!(count(&tenth), 17 * 13);
    assert_eq!(count(&far), 17 * 13);
}
