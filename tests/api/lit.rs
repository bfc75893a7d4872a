//! The scene-features path (lights, shadows, planes, mirrors): the rules of the spec
//! checked on hand-made scenes, and the invariants every method keeps — a pixel never
//! depends on clip, band, span culling or the any-hit shortcut.

use crate::common;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
#[cfg(feature = "bench-baselines")]
use embedded_raytracer::SphereTest;
use embedded_raytracer::{
    Camera, Light, Material, Method, Options, Plane, Render, Scene, SceneError, SecondaryOrigin, Settings,
    SettingsError, Sphere, Vec3,
};

use common::Frame;

/// Spheres on a checkered floor — one resting on it, one a mirror, one sunk into it —
/// under a directional and a point light.
fn floor_scene() -> Scene<4, 2, 1, 3> {
    let mut s = Scene::new(Rgb888::new(20, 30, 60));
    s.push(
        Sphere::new(Vec3::new(0.0, 0.0, 0.0), 1.0, Rgb888::new(255, 64, 64))
            .with_material(Material::new(0.5, 32.0, 0.0)),
    )
    .unwrap();
    s.push(
        Sphere::new(Vec3::new(2.2, 0.0, -1.0), 1.0, Rgb888::new(200, 200, 255))
            .with_material(Material::new(0.8, 64.0, 0.6)),
    )
    .unwrap();
    s.push(Sphere::new(
        Vec3::new(-2.0, -0.5, 0.5),
        0.5,
        Rgb888::new(64, 255, 64),
    ))
    .unwrap();
    s.push(Sphere::new(
        Vec3::new(-1.0, -1.2, 2.0),
        0.5,
        Rgb888::new(255, 255, 64),
    ))
    .unwrap();
    s.push_light(Light::directional(Vec3::new(-1.0, -2.0, -1.0), 0.7))
        .unwrap();
    s.push_light(Light::point(Vec3::new(3.0, 4.0, 4.0), 0.5)).unwrap();
    s.push_plane(
        Plane::new(
            Vec3::new(0.0, -1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Rgb888::new(220, 220, 220),
        )
        .with_checker(Rgb888::new(40, 40, 40), 1.0),
    )
    .unwrap();
    s
}

fn floor_camera(width: u32, height: u32) -> Camera {
    Camera::new(
        Vec3::new(0.0, 1.5, 7.0),
        Vec3::ZERO,
        Vec3::new(0.0, 1.0, 0.0),
        0.8,
        Size::new(width, height),
    )
    .unwrap()
}

/// A pixel never depends on the clip, the offset or the band it is drawn in, and span
/// culling and the any-hit shadow shortcut change no pixel: every method, bit for bit.
#[test]
fn every_method_draws_the_same_pixels_whatever_the_clip_band_or_shortcut() {
    let scene = floor_scene();
    let camera = floor_camera(64, 48);
    for method in Method::ALL {
        let render = Render::new(&scene, &camera).with_method(method);
        let whole = common::trace(render);
        // Any-hit shadow rays change no pixel; nor does span culling, except for the
        // forward-differenced tests, whose anchors sit at the span starts.
        #[cfg(feature = "bench-baselines")]
        {
            let differing = |options: Options| {
                let other = common::trace(render.with_options(options));
                whole.iter().zip(&other).filter(|(a, b)| a != b).count()
            };
            assert_eq!(
                differing(Options::DEFAULT.with_shadow_any_hit(false)),
                0,
                "{method}: any-hit"
            );
            if !matches!(method.sphere_test, SphereTest::ForwardDiff | SphereTest::Auto) {
                let literal = Options::DEFAULT
                    .with_span_culling(false)
                    .with_shadow_any_hit(false);
                assert_eq!(differing(literal), 0, "{method}: the literal loop");
            }
        }
        // A clipped, offset draw.
        let clip = Rectangle::new(Point::new(9, 5), Size::new(41, 30));
        let offset = Point::new(3, -2);
        let mut frame = Frame::new(Size::new(70, 50));
        render
            .with_offset(offset)
            .draw(&mut frame.clipped(&clip))
            .unwrap();
        let visible = Rectangle::new(offset, camera.size()).intersection(&clip);
        for p in visible.points() {
            let q = p - offset;
            assert_eq!(
                frame.get(p),
                Some(whole[(q.y * 64 + q.x) as usize].1),
                "{method}: {q:?}"
            );
        }
        // Bands of 7 rows.
        let mut band = vec![Rgb888::BLACK; 64 * 7];
        for j0 in (0..48).step_by(7) {
            let j1 = (j0 + 7).min(48);
            let buf = &mut band[..64 * (j1 - j0) as usize];
            render.draw_band(j0..j1, buf).unwrap();
            for (k, c) in buf.iter().enumerate() {
                assert_eq!(
                    *c,
                    whole[j0 as usize * 64 + k].1,
                    "{method}: band {j0}, pixel {k}"
                );
            }
        }
    }
}

/// Without lights, the features path shades with Lab #1 (sphere: outward normal) — the
/// same picture as the Lab #1 loop of a `Scene<N>`, within one level (the normal is
/// formed from the hit point here, from `L·w` there), with the same hits.
#[test]
fn without_lights_a_mirrorless_scene_is_lab1() {
    let spheres = [
        Sphere::new(Vec3::new(0.0, 0.0, 0.0), 1.0, Rgb888::new(255, 64, 64)),
        Sphere::new(Vec3::new(1.2, 0.5, -1.5), 1.0, Rgb888::new(64, 64, 255)),
    ];
    let lab: Scene<2> = Scene::from_array(spheres, Rgb888::new(0, 0, 0));
    let featured: Scene<2, 0, 0, 1> =
        Scene::from_arrays(spheres, [], [], Rgb888::new(0, 0, 0), Settings::DEFAULT);
    let camera = Camera::new(
        Vec3::new(0.0, 0.0, 5.0),
        Vec3::ZERO,
        Vec3::new(0.0, 1.0, 0.0),
        1.0,
        Size::new(80, 60),
    )
    .unwrap();
    let a = common::trace(Render::new(&lab, &camera));
    let b = common::trace(Render::new(&featured, &camera));
    let mut hits = 0;
    for (k, (x, y)) in a.iter().zip(&b).enumerate() {
        assert_eq!(x.0.map(|h| h.0), y.0.map(|h| h.0), "pixel {k}: hit");
        hits += usize::from(x.0.is_some());
        for (p, q) in [(x.1.r(), y.1.r()), (x.1.g(), y.1.g()), (x.1.b(), y.1.b())] {
            assert!(p.abs_diff(q) <= 1, "pixel {k}: {:?} vs {:?}", x.1, y.1);
        }
    }
    assert!(hits > 500, "the spheres fill the view: {hits}");
}

/// A full mirror at the deepest level shows the background; half a mirror mixes it in
/// (`(1 − r)·local + r·background`, rounded once).
#[test]
fn at_max_depth_the_background_stands_in_for_the_reflection() {
    let bg = Rgb888::new(0, 0, 200);
    let camera = Camera::new(
        Vec3::new(0.0, 0.0, 5.0),
        Vec3::ZERO,
        Vec3::new(0.0, 1.0, 0.0),
        0.5,
        Size::new(9, 9),
    )
    .unwrap();
    let centre = |reflect: f32| {
        let mut s: Scene<2, 0, 0, 1> = Scene::new(bg);
        s.push(
            Sphere::new(Vec3::ZERO, 1.0, Rgb888::new(255, 100, 0))
                .with_material(Material::new(0.0, 32.0, reflect)),
        )
        .unwrap();
        s.set_settings(Settings::DEFAULT.with_max_depth(0)).unwrap();
        let mut c = None;
        Render::<2, Rgb888, 0, 0, 1>::new(&s, &camera).trace(|p| {
            if p.pixel == Point::new(4, 4) {
                c = Some(p.color)
            }
        });
        c.unwrap()
    };
    assert_eq!(centre(1.0), bg);
    // Facing the eye, Lab #1 gives the full colour: ½·(255, 100, 0) + ½·(0, 0, 200).
    assert_eq!(centre(0.5), Rgb888::new(128, 50, 100));
    assert_eq!(centre(0.0), Rgb888::new(255, 100, 0));
}

/// The floor's checker cells follow the specified basis (normal +y: `a = x`,
/// `e₁ = n × x = −z`, `e₂ = n × e₁ = −x`), including at negative coordinates, where
/// `floor` is not truncation; no ray above the horizon hits the floor.
#[test]
fn checker_cells_and_horizon() {
    let mut s: Scene<0, 1, 1> = Scene::new(Rgb888::new(1, 2, 3));
    let (even, odd) = (Rgb888::new(200, 200, 200), Rgb888::new(100, 0, 0));
    s.push_plane(
        Plane::new(Vec3::new(0.0, -1.0, 0.0), Vec3::new(0.0, 1.0, 0.0), even).with_checker(odd, 1.0),
    )
    .unwrap();
    // Looking straight down from y = 1: the view is the floor 2 below.
    let camera = Camera::new(
        Vec3::new(0.25, 1.0, 0.25),
        Vec3::new(0.25, -1.0, 0.25),
        Vec3::new(0.0, 0.0, -1.0),
        1.2,
        Size::new(40, 40),
    )
    .unwrap();
    Render::<0, Rgb888, 1, 1>::new(&s, &camera).trace(|p| {
        let hit = p.hit.expect("looking down: every ray hits the floor");
        assert_eq!(hit.index, 0);
        // Where the ray meets y = −1, and the expected cell; Lab #1 facing the eye
        // straight down scales by n·(−w) ≈ 1 at the centre, ≥ 0.3 everywhere.
        let at = Vec3::new(0.25, 1.0, 0.25) + p.direction * hit.t;
        let (x1, x2) = (-at.z, -at.x);
        let parity = (x1.floor() + x2.floor()).rem_euclid(2.0);
        // Skip pixels whose point is within rounding of a cell edge.
        let edge = |x: f32| (x - x.round()).abs() < 1e-3;
        if edge(x1) || edge(x2) {
            return;
        }
        let base = if parity == 0.0 { even } else { odd };
        let hue = |c: Rgb888| (c.r() > c.g(), c.g() > 0);
        assert_eq!(hue(p.color), hue(base), "pixel {:?} at {at:?}", p.pixel);
    });
    // Looking level: the upper half is sky, the lower half floor.
    let level = Camera::new(
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::new(0.0, 1.0, 0.0),
        1.0,
        Size::new(20, 20),
    )
    .unwrap();
    Render::<0, Rgb888, 1, 1>::new(&s, &level).trace(|p| {
        assert_eq!(p.hit.is_some(), p.pixel.y >= 10, "pixel {:?}", p.pixel);
    });
}

/// A floor point under a sphere is shadowed from a light straight above: it gets the
/// ambient term only; with shadows off it is lit. Light inside a sphere is not blocked
/// by that sphere.
#[test]
fn shadows_follow_the_segment_rule() {
    let grey = Rgb888::new(200, 200, 200);
    let build = |shadows: bool, light: Light| {
        let mut s: Scene<1, 1, 1> = Scene::new(Rgb888::new(0, 0, 0));
        s.push(Sphere::new(Vec3::new(0.0, 1.0, 0.0), 0.5, grey)).unwrap();
        s.push_plane(Plane::new(Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), grey))
            .unwrap();
        s.push_light(light).unwrap();
        s.set_settings(
            Settings::DEFAULT
                .with_ambient(0.1)
                .with_shadows(shadows)
                .with_max_depth(0),
        )
        .unwrap();
        s
    };
    // Looking straight down at the floor point under the sphere, from the side so the
    // sphere does not hide it: eye at (3, 0.01, 0) looking at the origin.
    let camera = Camera::new(
        Vec3::new(3.0, 0.01, 0.0),
        Vec3::ZERO,
        Vec3::new(0.0, 1.0, 0.0),
        0.05,
        Size::new(3, 3),
    )
    .unwrap();
    let centre = |s: &Scene<1, 1, 1>| {
        let mut c = None;
        Render::<1, Rgb888, 1, 1>::new(s, &camera).trace(|p| {
            if p.pixel == Point::new(1, 1) {
                assert_eq!(p.hit.map(|h| h.index), Some(1), "the floor");
                c = Some(p.color);
            }
        });
        c.unwrap()
    };
    let down = Light::directional(Vec3::new(0.0, -1.0, 0.0), 1.0);
    // Shadowed: 200 × 0.1 = 20. Lit: 200 × (0.1 + 1) = 220.
    assert_eq!(centre(&build(true, down)), Rgb888::new(20, 20, 20));
    assert_eq!(centre(&build(false, down)), Rgb888::new(220, 220, 220));
    // A point light inside the sphere: the segment from the floor crosses the sphere's
    // surface once — blocked; a point light between floor and sphere — lit.
    let inside = Light::point(Vec3::new(0.0, 1.0, 0.0), 0.5);
    assert_eq!(centre(&build(true, inside)), Rgb888::new(20, 20, 20));
    // Between floor and sphere, straight above the point: 200 × (0.1 + 0.5) = 120.
    let below = Light::point(Vec3::new(0.0, 0.3, 0.0), 0.5);
    assert_eq!(centre(&build(true, below)), Rgb888::new(120, 120, 120));
}

/// The eye inside a mirror sphere: every ray meets the inner surface, the reflected
/// rays meet it again (the convex exit's far root), and with a light inside the sphere
/// the inner surface is lit; nothing panics and every pixel is the sphere.
#[test]
fn eye_inside_a_mirror_sphere() {
    let mut s: Scene<1, 1, 0, 4> = Scene::new(Rgb888::new(0, 0, 0));
    s.push(
        Sphere::new(Vec3::ZERO, 5.0, Rgb888::new(100, 150, 200)).with_material(Material::new(0.3, 16.0, 0.5)),
    )
    .unwrap();
    s.push_light(Light::point(Vec3::new(1.0, 2.0, 0.0), 1.0)).unwrap();
    s.set_settings(Settings::DEFAULT.with_max_depth(4)).unwrap();
    let camera = Camera::new(
        Vec3::new(0.0, 0.0, 2.0),
        Vec3::ZERO,
        Vec3::new(0.0, 1.0, 0.0),
        1.4,
        Size::new(24, 24),
    )
    .unwrap();
    for origin in [SecondaryOrigin::Convex, SecondaryOrigin::TEXTBOOK] {
        let mut lit = 0;
        Render::<1, Rgb888, 1, 0, 4>::new(&s, &camera)
            .with_options(Options::DEFAULT.with_secondary(origin))
            .trace(|p| {
                assert_eq!(p.hit.map(|h| h.index), Some(0));
                // Each level keeps half; 4 levels of the inner surface and then the
                // black background: at least ambient 0.1 × (1 − ½⁴) of the colour.
                assert!(p.color.b() >= 18, "{origin:?} {:?}: {:?}", p.pixel, p.color);
                lit += usize::from(p.color.b() > 60);
            });
        assert!(
            lit > 100,
            "{origin:?}: the light inside lights the inner surface ({lit})"
        );
    }
}

/// Typed errors for mirrors without depth, settings beyond the type's depth, full
/// light and plane lists.
#[test]
fn scene_errors() {
    let mirror =
        Sphere::new(Vec3::ZERO, 1.0, Rgb888::new(1, 1, 1)).with_material(Material::new(0.0, 32.0, 0.5));
    let mut plain: Scene<1, 1, 1> = Scene::new(Rgb888::new(0, 0, 0));
    assert_eq!(plain.push(mirror), Err(SceneError::MirrorWithoutDepth));
    assert_eq!(plain.max_depth(), 0);
    assert_eq!(
        plain.set_settings(Settings::DEFAULT),
        Err(SceneError::Settings(SettingsError::MaxDepth { max: 0 }))
    );
    let mut deep: Scene<1, 1, 1, 2> = Scene::new(Rgb888::new(0, 0, 0));
    assert_eq!(deep.max_depth(), 2);
    deep.push(mirror).unwrap();
    deep.push_light(Light::point(Vec3::ZERO, 1.0)).unwrap();
    assert_eq!(
        deep.push_light(Light::point(Vec3::ZERO, 1.0)),
        Err(SceneError::TooManyLights { capacity: 1 })
    );
    assert!(matches!(
        deep.push_light(Light::directional(Vec3::ZERO, 1.0)),
        Err(SceneError::Light(_))
    ));
    let floor = Plane::new(Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), Rgb888::new(1, 1, 1));
    deep.push_plane(floor).unwrap();
    assert_eq!(
        deep.push_plane(floor),
        Err(SceneError::TooManyPlanes { capacity: 1 })
    );
    assert!(matches!(
        deep.set_settings(Settings::DEFAULT.with_ambient(-0.1)),
        Err(SceneError::Settings(SettingsError::Ambient))
    ));
}

/// Culling (sphere spans, plane spans, shadow spans) and the any-hit shortcut change no
/// pixel on random scenes: spheres above, on, in and under a random floor, point lights
/// high and low (inside spheres too), directional lights down to grazing, cameras
/// anywhere, every fourth scene with shadows off (its shadow spans are not built). The
/// robust, algebraic and geometric tests in turn, bit for bit against the literal loop.
#[test]
#[cfg(feature = "bench-baselines")]
fn culling_changes_no_pixel_on_random_lit_scenes() {
    let mut rng = common::Rng(0x5eed_1175);
    let mut shadowed = 0;
    for case in 0..120 {
        let mut s: Scene<6, 2, 2, 2> = Scene::new(Rgb888::new(10, 20, 30));
        let n = Vec3::new(rng.range(-0.3, 0.3), 1.0, rng.range(-0.3, 0.3));
        let floor_y = rng.range(-2.0, 0.0);
        s.push_plane(
            Plane::new(Vec3::new(0.0, floor_y, 0.0), n, Rgb888::new(200, 200, 200))
                .with_checker(Rgb888::new(50, 50, 50), rng.range(0.3, 2.0)),
        )
        .unwrap();
        if rng.next() < 0.3 {
            s.push_plane(Plane::new(
                Vec3::new(0.0, 0.0, -8.0),
                Vec3::new(0.0, 0.2, 1.0),
                Rgb888::new(90, 200, 90),
            ))
            .unwrap();
        }
        for _ in 0..1 + (rng.next() * 5.0) as usize {
            let r = rng.range(0.2, 1.5);
            let centre = Vec3::new(
                rng.range(-3.0, 3.0),
                floor_y + rng.range(-r, 3.0),
                rng.range(-4.0, 2.0),
            );
            let reflect = if rng.next() < 0.3 { 0.5 } else { 0.0 };
            s.push(
                Sphere::new(centre, r, Rgb888::new(250, 120, 60))
                    .with_material(Material::new(0.4, 20.0, reflect)),
            )
            .unwrap();
        }
        for _ in 0..1 + (rng.next() * 2.0) as usize {
            let light = if rng.next() < 0.5 {
                Light::directional(
                    Vec3::new(rng.range(-1.0, 1.0), -rng.range(0.02, 2.0), rng.range(-1.0, 1.0)),
                    0.7,
                )
            } else {
                Light::point(
                    Vec3::new(
                        rng.range(-4.0, 4.0),
                        floor_y + rng.range(0.1, 6.0),
                        rng.range(-4.0, 4.0),
                    ),
                    0.6,
                )
            };
            s.push_light(light).unwrap();
        }
        if case % 4 == 3 {
            let settings = s.settings().with_shadows(false);
            s.set_settings(settings).unwrap();
        }
        let eye = Vec3::new(
            rng.range(-6.0, 6.0),
            floor_y + rng.range(0.2, 5.0),
            rng.range(4.0, 9.0),
        );
        let Ok(camera) = Camera::new(
            eye,
            Vec3::new(0.0, floor_y, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            rng.range(0.3, 1.6),
            Size::new(40, 30),
        ) else {
            continue;
        };
        // The robust test and the two that cancel squares (the largest margin the
        // shadow regions must cover); the forward-differenced tests anchor at span
        // starts, so culling moves their bits.
        let test = [SphereTest::Robust, SphereTest::Algebraic, SphereTest::Geometric][case % 3];
        let method = Method::new(
            embedded_raytracer::Stepping::Direct,
            test,
            embedded_raytracer::Sqrt::Exact,
        );
        let render = Render::new(&s, &camera).with_method(method);
        let culled = common::trace(render);
        let literal = common::trace(
            render.with_options(
                Options::DEFAULT
                    .with_span_culling(false)
                    .with_shadow_any_hit(false),
            ),
        );
        for (k, (a, b)) in culled.iter().zip(&literal).enumerate() {
            assert_eq!(
                a,
                b,
                "case {case}, pixel {k}: spheres {:?} lights {:?} planes {:?} camera {:?}",
                s.spheres(),
                s.lights(),
                s.planes(),
                camera.params()
            );
        }
        shadowed += culled
            .iter()
            .filter(|p| p.0.is_some_and(|h| h.0 == s.spheres().len()) && p.1.r() < 60)
            .count();
    }
    assert!(shadowed > 1000, "the cases have shadows on the floor: {shadowed}");
}

/// A checker far finer than a pixel and than `f32` resolves (`checker_size = 1e-30`)
/// draws what the plane's docs say: both cell indices saturate to the same odd number,
/// so every pixel off the plane's axes shows the plane's own colour — each pixel the
/// one the same scene without a checker draws — and no noise.
#[test]
fn a_checker_finer_than_f32_resolves_draws_the_planes_colour() {
    let (even, odd) = (Rgb888::new(220, 220, 220), Rgb888::new(40, 40, 40));
    let floor = |checker: Option<Rgb888>, color: Rgb888| {
        let mut s: Scene<0, 1, 1, 0> = Scene::new(Rgb888::new(20, 30, 60));
        s.push_light(Light::directional(Vec3::new(-1.0, -2.0, -1.0), 0.8))
            .unwrap();
        let plane = Plane::new(Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), color);
        s.push_plane(match checker {
            Some(c) => plane.with_checker(c, 1e-30),
            None => plane,
        })
        .unwrap();
        s
    };
    // Looking down at the plane's point, so all four quadrants are in view.
    let camera = Camera::new(
        Vec3::new(0.3, 6.0, 0.7),
        Vec3::ZERO,
        Vec3::new(0.0, 0.0, -1.0),
        1.0,
        Size::new(48, 48),
    )
    .unwrap();
    let trace = |s: &Scene<0, 1, 1, 0>| {
        let mut out = Vec::new();
        Render::<0, Rgb888, 1, 1, 0>::new(s, &camera).trace(|x| out.push(x));
        out
    };
    let (shown, plain) = (trace(&floor(Some(odd), even)), trace(&floor(None, even)));
    let mut floor_pixels = 0;
    for (s, e) in shown.iter().zip(&plain) {
        if let Some(hit) = s.hit {
            // Off the axes through the plane's point (x = 0 or z = 0 on this floor).
            let p = camera.eye() + s.direction * hit.t;
            if p.x.abs() < 1e-3 || p.z.abs() < 1e-3 {
                continue;
            }
            floor_pixels += 1;
        }
        assert_eq!(s.color, e.color, "{:?}", s.pixel);
    }
    assert!(floor_pixels > 1000, "{floor_pixels} floor pixels");
}

/// A plane is where it is, not where its point is: a tilted, checkered floor given by a
/// point 2²⁷ away along it draws as the same floor given by its point nearest the
/// origin — the frame anchors it near the eye, its cells moved by whole pairs — where
/// the `f32` plane test from the far point misplaced it by units (every floor pixel
/// wrong).
#[test]
fn a_plane_is_where_it_is_not_where_its_point_is() {
    let (even, odd) = (Rgb888::new(220, 220, 220), Rgb888::new(40, 40, 40));
    let floor = |point: Vec3| {
        let mut s: Scene<1, 1, 1, 0> = Scene::new(Rgb888::new(20, 30, 60));
        s.push_light(Light::directional(Vec3::new(-1.0, -2.0, -1.0), 0.8))
            .unwrap();
        s.push(Sphere::new(
            Vec3::new(0.0, 1.0, 0.0),
            0.8,
            Rgb888::new(200, 40, 40),
        ))
        .unwrap();
        // Through the origin, tilted: (0, 2²⁷, −2²⁷) lies on it exactly.
        s.push_plane(Plane::new(point, Vec3::new(0.0, 1.0, 1.0), even).with_checker(odd, 0.5))
            .unwrap();
        s
    };
    let camera = Camera::new(
        Vec3::new(0.3, 4.0, 6.0),
        Vec3::ZERO,
        Vec3::new(0.0, 1.0, 0.0),
        1.0,
        Size::new(48, 48),
    )
    .unwrap();
    let colours = |s: &Scene<1, 1, 1, 0>| {
        let mut out = Vec::new();
        Render::<1, Rgb888, 1, 1, 0>::new(s, &camera).trace(|x| out.push(x.color));
        out
    };
    let far = 134_217_728.0; // 2²⁷: a multiple of the checker's period of 1
    let (near, far) = (
        colours(&floor(Vec3::ZERO)),
        colours(&floor(Vec3::new(0.0, far, -far))),
    );
    let apart = near.iter().zip(&far).filter(|(a, b)| a != b).count();
    // Both cell colours in view, lit (the background and the sphere besides).
    let mut distinct = near.clone();
    distinct.sort_by_key(|c| (c.r(), c.g(), c.b()));
    distinct.dedup();
    assert!(distinct.len() >= 4, "{distinct:?}");
    assert!(
        apart <= near.len() / 100,
        "{apart} of {} pixels differ",
        near.len()
    );
}

/// In a scene type without reflections, a floor without a highlight is shaded from the
/// frame's floor constants where a `DrawTarget` draws it (the colour runs), and by the
/// general shading where a render is traced (the samples): both the same pixels, bit
/// for bit, on random lit scenes — suns the floor faces and faces away from, lamps
/// above and below it, a second plane, shadows on and off, both exits, every method,
/// and floors with a highlight (the general shading out of line in both).
#[test]
fn the_floor_constants_draw_what_the_general_shading_does() {
    let mut rng = common::Rng(0xf1_00f5);
    let (mut floor_pixels, mut shadowed) = (0, 0);
    for case in 0..48 {
        let mut s: Scene<4, 3, 2> = Scene::new(Rgb888::new(10, 20, 30));
        let n = Vec3::new(rng.range(-0.4, 0.4), 1.0, rng.range(-0.4, 0.4));
        let floor_y = rng.range(-2.0, 0.0);
        let floor = Plane::new(Vec3::new(0.0, floor_y, 0.0), n, Rgb888::new(200, 190, 180));
        let floor = if case % 3 == 0 {
            floor
        } else {
            floor.with_checker(Rgb888::new(50, 60, 70), rng.range(0.3, 2.0))
        };
        let floor = if case % 7 == 6 {
            floor.with_material(Material::new(0.5, 24.0, 0.0))
        } else {
            floor
        };
        s.push_plane(floor).unwrap();
        if rng.next() < 0.3 {
            s.push_plane(Plane::new(
                Vec3::new(0.0, 0.0, -8.0),
                Vec3::new(0.0, 0.2, 1.0),
                Rgb888::new(90, 200, 90),
            ))
            .unwrap();
        }
        for _ in 0..1 + (rng.next() * 4.0) as usize {
            let r = rng.range(0.2, 1.5);
            let centre = Vec3::new(
                rng.range(-3.0, 3.0),
                floor_y + rng.range(-r, 3.0),
                rng.range(-4.0, 2.0),
            );
            s.push(
                Sphere::new(centre, r, Rgb888::new(250, 120, 60))
                    .with_material(Material::new(0.4, 20.0, 0.0)),
            )
            .unwrap();
        }
        for _ in 0..1 + (rng.next() * 3.0) as usize {
            // Down onto the floor, or (one in five) up from under it.
            let down = if rng.next() < 0.2 { 1.0 } else { -1.0 };
            let light = if rng.next() < 0.5 {
                Light::directional(
                    Vec3::new(
                        rng.range(-1.0, 1.0),
                        down * rng.range(0.02, 2.0),
                        rng.range(-1.0, 1.0),
                    ),
                    rng.range(0.2, 0.8),
                )
            } else {
                Light::point(
                    Vec3::new(
                        rng.range(-4.0, 4.0),
                        floor_y - down * rng.range(0.1, 6.0),
                        rng.range(-4.0, 4.0),
                    ),
                    rng.range(0.2, 0.8),
                )
            };
            s.push_light(light).unwrap();
        }
        if case % 4 == 3 {
            let settings = s.settings().with_shadows(false);
            s.set_settings(settings).unwrap();
        }
        let eye = Vec3::new(
            rng.range(-6.0, 6.0),
            floor_y + rng.range(0.2, 5.0),
            rng.range(4.0, 9.0),
        );
        let Ok(camera) = Camera::new(
            eye,
            Vec3::new(0.0, floor_y, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            rng.range(0.3, 1.6),
            Size::new(32, 24),
        ) else {
            continue;
        };
        let method = Method::ALL[case % Method::ALL.len()];
        let origin = if case % 5 == 4 {
            SecondaryOrigin::TEXTBOOK
        } else {
            SecondaryOrigin::Convex
        };
        let render = Render::new(&s, &camera)
            .with_method(method)
            .with_options(Options::DEFAULT.with_secondary(origin));
        let traced = common::trace(render);
        let mut frame = Frame::new(camera.size());
        render.draw(&mut frame).unwrap();
        for (k, p) in traced.iter().enumerate() {
            let at = Point::new(k as i32 % 32, k as i32 / 32);
            assert_eq!(
                frame.get(at),
                Some(p.1),
                "case {case}, {method}, pixel {at:?}: spheres {:?} lights {:?} planes {:?} camera {:?}",
                s.spheres(),
                s.lights(),
                s.planes(),
                camera.params()
            );
        }
        let on_floor = traced
            .iter()
            .filter(|p| p.0.is_some_and(|h| h.0 == s.spheres().len()));
        floor_pixels += on_floor.clone().count();
        shadowed += on_floor.filter(|p| p.1.r() < 60).count();
    }
    // The cases draw the floor, and shadows on it.
    assert!(floor_pixels > 10_000, "floor pixels: {floor_pixels}");
    assert!(shadowed > 200, "floor pixels in shadow: {shadowed}");
}
