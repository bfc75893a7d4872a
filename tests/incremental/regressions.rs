//! Minimal sequences where an incremental frame once left the display different from
//! the full render (or reported a refused frame as drawn): each frame is drawn through
//! `Incremental::draw` and through `update` with `Changes::draw_band`, and compared
//! with its full render, every pixel.

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_raytracer::{
    BandError, Camera, FrameError, Light, Material, Method, Plane, Render, Sampling, Scene, Settings, Sphere,
    SphereTest, Sqrt, Stepping, Vec3,
};

use crate::sequences::{Check, Drift, Target};

const WHITE: Rgb888 = Rgb888::new(255, 255, 255);

fn camera(eye: Vec3, fov_y: f32, size: Size) -> Camera {
    Camera::new(eye, Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), fov_y, size).unwrap()
}

/// Draws `scenes` in turn; the pixels each frame's two displays differ from its full
/// render by, as `[(drawn, banded)]`.
fn drift<const N: usize, const L: usize, const P: usize, const D: usize>(
    scenes: &[Scene<N, L, P, D>],
    camera: &Camera,
    method: Method,
    sampling: Sampling,
) -> Vec<(usize, usize)> {
    let size = camera.size();
    let mut check = Check::new(size, Target::whole(size), size.height, Rgb565::BLACK);
    scenes
        .iter()
        .map(|scene| {
            let render = Render::<N, Rgb565, L, P, D>::new(scene, camera)
                .with_method(method)
                .with_sampling(sampling);
            let Drift { drawn, banded, .. } = check.frame(&render).unwrap();
            (drawn, banded)
        })
        .collect()
}

/// Asserts that every case drew every frame exactly, naming each case that did not.
fn exact(cases: Vec<(String, Vec<(usize, usize)>)>) {
    let wrong: Vec<_> = cases
        .iter()
        .filter(|(_, drift)| drift.iter().any(|&d| d != (0, 0)))
        .map(|(what, drift)| format!("{what}: {drift:?}"))
        .collect();
    assert!(
        wrong.is_empty(),
        "pixels differing from the full render, per frame (drawn, banded):\n{}",
        wrong.join("\n")
    );
}

/// A sphere smaller than a pixel lying between two rows' centre lines: no centre ray
/// meets it, but the sub-pixel rays of the rows beside it do, so the sampling's
/// footprint must be planned from the ellipse's vertical extent, not from the rows
/// whose centre line cuts it.
#[test]
fn a_silhouette_between_two_rows_is_redrawn_under_grid_and_adaptive() {
    let camera = camera(Vec3::new(0.0, 0.0, 10.0), 0.8, Size::new(16, 16));
    let at =
        |x: f32| Scene::<3>::from_array([Sphere::new(Vec3::new(x, 0.0, 0.0), 0.2, WHITE)], Rgb888::BLACK);
    let frames = [at(0.264), at(-1.321)];
    exact(
        [
            Sampling::grid(2).unwrap(),
            Sampling::adaptive(2).unwrap(),
            Sampling::grid(4).unwrap(),
        ]
        .into_iter()
        .map(|sampling| {
            (
                format!("{sampling:?}"),
                drift(&frames, &camera, Method::F32, sampling),
            )
        })
        .collect(),
    );
}

/// Adaptive sampling of a Lab #1 frame takes its edges from the silhouettes unless two
/// spheres (nearly) touch, when the whole frame shares samples between neighbours: a
/// sphere that makes or breaks contact changes edge pixels of spheres that never moved.
#[test]
fn spheres_coming_into_contact_switch_the_whole_frame_s_adaptive_rule() {
    let camera = camera(Vec3::new(0.0, 0.0, 6.0), 0.8, Size::new(64, 48));
    let with = |y: f32| {
        Scene::<3>::from_array(
            [
                Sphere::new(Vec3::new(-1.5, 0.8, 0.0), 0.4, Rgb888::new(200, 50, 50)),
                Sphere::new(Vec3::new(-1.5, y, 0.0), 0.4, Rgb888::new(50, 200, 50)),
                Sphere::new(Vec3::new(1.0, 0.0, 0.0), 1.2, Rgb888::new(60, 90, 250)),
            ],
            Rgb888::BLACK,
        )
    };
    // Apart, touching, apart again.
    let mut cases = Vec::new();
    for frames in [[with(-0.5), with(0.0)], [with(0.0), with(-0.5)]] {
        for n in [2, 4] {
            let sampling = Sampling::adaptive(n).unwrap();
            let what = format!("{sampling:?}, from y = {}", frames[0].spheres()[1].center.y);
            cases.push((what, drift(&frames, &camera, Method::F32, sampling)));
        }
    }
    exact(cases);
}

/// Adaptive sampling's shared samples mark every pixel meeting a small silhouette's
/// bounding box (widened by a pixel) as an edge pixel: with a large, sheared culling
/// ellipse (a narrow field of view, the lecture notes' tests' margins) that box reaches beyond
/// the ellipse and its pad, and must be redrawn when the sphere moves.
#[test]
fn adaptive_small_silhouette_boxes_are_redrawn() {
    let camera = camera(Vec3::new(0.0, 0.0, 10.0), 0.012, Size::new(64, 64));
    let big = Sphere::new(Vec3::new(0.05, 0.05, -2.0), 0.15, Rgb888::new(255, 200, 120));
    let tiny = |x: f32, y: f32| Sphere::new(Vec3::new(x, y, 0.0), 1e-5, WHITE);
    let sampling = Sampling::adaptive(2).unwrap();

    let lab1 = |x, y| Scene::<3>::from_array([big, tiny(x, y)], Rgb888::BLACK);
    let frames = [
        lab1(-0.001_596_899_1, 0.011_775_923),
        lab1(0.013_115_373, -0.000_766_179_7),
    ];
    let method = Method::new(Stepping::Direct, SphereTest::Algebraic, Sqrt::Fast);
    let mut cases = vec![(
        "Lab #1, direct/algebraic/fast".to_string(),
        drift(&frames, &camera, method, sampling),
    )];

    // The features path (a light, shadows off) always shares samples.
    let shiny = Material::new(0.8, 20.0, 0.0);
    let lit = |x, y| {
        let mut scene: Scene<3, 2, 1> = Scene::from_array(
            [big.with_material(shiny), tiny(x, y).with_material(shiny)],
            Rgb888::BLACK,
        );
        scene
            .push_light(Light::directional(Vec3::new(-1.0, -1.0, -1.0), 0.9))
            .unwrap();
        scene
            .set_settings(Settings::DEFAULT.with_shadows(false).with_max_depth(0))
            .unwrap();
        scene
    };
    let frames = [
        lit(0.029_468_28, -0.003_130_471_8),
        lit(-0.015_957_914, 0.010_499_439),
    ];
    let method = Method::new(Stepping::Direct, SphereTest::Geometric, Sqrt::Exact);
    cases.push((
        "lit, direct/geometric/exact".to_string(),
        drift(&frames, &camera, method, sampling),
    ));
    exact(cases);
}

/// The lecture notes' algebraic and geometric tests are far from exact when a shadow ray's
/// distance is large against the radius: their false shadows move with the sphere,
/// outside the region an exact shadow test can darken.
#[test]
fn the_lecture_notes_tests_false_shadows_are_redrawn() {
    let camera = camera(Vec3::new(0.0, 30.0, 60.0), 1.2, Size::new(48, 48));
    let red = Rgb888::new(220, 40, 40);
    let lamp = Vec3::new(-9.877_849, 195.518_72, -23.738_338);
    let at = |x: f32, z: f32| {
        let mut scene: Scene<3, 2, 1> = Scene::from_array(
            [Sphere::new(Vec3::new(x, 194.804_37, z), 0.023_937_557, red)],
            Rgb888::BLACK,
        );
        scene.push_light(Light::point(lamp, 1.0)).unwrap();
        scene
            .push_plane(Plane::new(
                Vec3::ZERO,
                Vec3::new(0.0, 1.0, 0.0),
                Rgb888::new(200, 200, 200),
            ))
            .unwrap();
        scene
    };
    let frames = [at(-9.877_849, -23.738_338), at(-9.875_315, -23.720_015)];
    let mut cases = Vec::new();
    for test in [SphereTest::Algebraic, SphereTest::Geometric] {
        for sampling in [Sampling::Center, Sampling::grid(2).unwrap()] {
            let method = Method::new(Stepping::Direct, test, Sqrt::Exact);
            cases.push((
                format!("{method} {sampling:?}"),
                drift(&frames, &camera, method, sampling),
            ));
        }
    }
    exact(cases);
}

/// The integer kernel's frame followed by one its rule does not take and the `f32`
/// fallback refuses (a sphere `10³⁰` away beside near ones): reported as refused, as
/// `Method::F32` reports it, on both paths, and nothing drawn.
#[test]
fn a_refused_frame_after_an_integer_frame_is_reported_as_refused() {
    let camera = camera(Vec3::new(0.0, 0.0, 6.0), 0.8, Size::new(32, 32));
    let red = Rgb888::new(220, 40, 40);
    let first = Scene::<3>::from_array(
        [
            Sphere::new(Vec3::new(-1.0, 0.0, 0.0), 0.6, red),
            Sphere::new(Vec3::new(1.0, 0.0, 0.0), 0.6, red),
        ],
        Rgb888::BLACK,
    );
    let refused = Scene::<3>::from_array(
        [
            Sphere::new(Vec3::new(-1.0, -1.0, 0.0), 0.6, red),
            Sphere::new(Vec3::new(0.0, 0.0, -1e30), 0.6, red),
        ],
        Rgb888::BLACK,
    );
    let why = Render::<3, Rgb565>::new(&refused, &camera)
        .with_method(Method::F32)
        .check()
        .unwrap_err();
    assert!(matches!(why, FrameError::Magnitudes { .. }));
    for method in [Method::F32, Method::INTEGER] {
        let mut shown = embedded_raytracer::Incremental::new();
        let mut display = crate::framebuffer::Buffer::new(camera.size(), Rgb565::BLACK);
        let render = |scene| Render::<3, Rgb565>::new(scene, &camera).with_method(method);
        assert!(shown.draw(&render(&first), &mut display).unwrap().full);
        let stats = shown.draw(&render(&refused), &mut display).unwrap();
        assert_eq!(
            (stats.refused, stats.full, stats.sent),
            (Some(why), false, 0),
            "{method}: {stats:?}"
        );

        let mut banded = embedded_raytracer::Incremental::new();
        assert!(banded.update(&render(&first)).is_full());
        let changes = banded.update(&render(&refused));
        assert_eq!(
            (changes.refused(), changes.is_full()),
            (Some(why), false),
            "{method}"
        );
        let mut band = vec![Rgb565::BLACK; 32 * 32];
        assert_eq!(
            changes.draw_band(&render(&refused), 0..32, &mut band),
            Err(BandError::Frame(why)),
            "{method}"
        );
    }
    // And the sequence on both paths, with the frame after it drawn whole again.
    exact(vec![(
        "integer".to_string(),
        drift(
            &[first.clone(), refused, first],
            &camera,
            Method::INTEGER,
            Sampling::Center,
        ),
    )]);
}
