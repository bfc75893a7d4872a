//! Coincident objects — two spheres with the same centre and radius, two planes with
//! the same point and normal — are one surface: the picture shows the lower index's
//! colour, the same on every target, and no secondary ray leaving one twin meets the
//! other at `t ≈ 0` (which drew black acne dots: shadow rays blocked by the twin).

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_raytracer::{
    Camera, Method, Options, Render, Sampling, Scene, SecondaryOrigin, SphereTest, Sqrt, Stepping,
};
use embedded_raytracer_lab::reference;

use embedded_raytracer_scenes::{self as standard, MAX_DEPTH, MAX_LIGHTS, MAX_PLANES, MAX_SPHERES};

type Full = Scene<MAX_SPHERES, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>;

fn invert(c: Rgb888) -> Rgb888 {
    Rgb888::new(255 - c.r(), 255 - c.g(), 255 - c.b())
}

/// `scene` with a copy of every sphere and plane in the inverted colour, after the
/// originals (`after`) or before them; and the scene the picture must equal: the
/// original, or the original recoloured.
fn twinned(scene: &Full, after: bool) -> (Full, Full) {
    let build = |layers: &[bool]| {
        let mut out: Full = Scene::new(scene.background());
        out.set_settings(scene.settings()).unwrap();
        for l in scene.lights() {
            out.push_light(*l).unwrap();
        }
        for &inverted in layers {
            for s in scene.spheres() {
                let color = if inverted { invert(s.color) } else { s.color };
                out.push(embedded_raytracer::Sphere { color, ..*s }).unwrap();
            }
        }
        for &inverted in layers {
            for p in scene.planes() {
                let (color, checker) = if inverted {
                    (invert(p.color), p.checker.map(invert))
                } else {
                    (p.color, p.checker)
                };
                out.push_plane(embedded_raytracer::Plane { color, checker, ..*p })
                    .unwrap();
            }
        }
        out
    };
    if after {
        (build(&[false, true]), build(&[false]))
    } else {
        (build(&[true, false]), build(&[true]))
    }
}

fn pixels(
    scene: &Full,
    camera: &Camera,
    method: Method,
    secondary: SecondaryOrigin,
    sampling: Sampling,
) -> Vec<Rgb888> {
    let mut out = Vec::new();
    Render::<MAX_SPHERES, Rgb888, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>::new(scene, camera)
        .with_method(method)
        .with_options(Options::DEFAULT.with_secondary(secondary))
        .with_sampling(sampling)
        .trace(|s| out.push(s.color));
    out
}

/// Pixels where two renders differ at all.
fn differ(a: &[Rgb888], b: &[Rgb888]) -> usize {
    a.iter().zip(b).filter(|(a, b)| a != b).count()
}

/// Every standard scene with lights, a floor and mirrors, and Lab #1's, each object
/// doubled after and before the originals: the picture is, bit for bit, the one
/// without the twins in the lower index's colours — for the default method and the
/// robust and forward-differenced tests and the integer kernel (Lab #1's on an FPU-less
/// target; a lit scene is the `f32` path's), the convex exit and the textbook ε, one ray
/// per pixel at 96×96 and `Grid(4)` at 48×48 (adaptive sampling's rays are the grid's;
/// the smaller frame keeps its 16 rays a pixel to a third of the ray count). Measured
/// before the twins were one surface: `shadows` doubled after, 622 of the 96×96
/// pixels apart with the convex exit (black acne where shadow rays leaving one twin
/// met the other at `t ≈ 0`), 621 of them more than 2 levels off the reference.
#[test]
fn coincident_spheres_show_the_lower_index() {
    let methods = [
        Method::TARGET_DEFAULT,
        Method::new(Stepping::Direct, SphereTest::Robust, Sqrt::Exact),
        Method::new(Stepping::Direct, SphereTest::ForwardDiff, Sqrt::Exact),
        Method::INTEGER,
    ];
    for name in ["shadows", "mirrors", "lab"] {
        let f = standard::load_full(name);
        let at = |side| {
            let mut p = *f.camera.params();
            p.size = embedded_graphics::prelude::Size::new(side, side);
            p.build().unwrap()
        };
        let cases = [(Sampling::Center, at(96)), (Sampling::grid(4).unwrap(), at(48))];
        for after in [true, false] {
            let (doubled, single) = twinned(&f.scene, after);
            for method in methods {
                for secondary in [SecondaryOrigin::Convex, SecondaryOrigin::TEXTBOOK] {
                    for &(sampling, camera) in &cases {
                        let d = differ(
                            &pixels(&doubled, &camera, method, secondary, sampling),
                            &pixels(&single, &camera, method, secondary, sampling),
                        );
                        println!("{name} after {after} {method:?} {secondary:?} {sampling:?}: {d}");
                        assert_eq!(
                            d, 0,
                            "{name} (twins after: {after}) {method:?} {secondary:?} {sampling:?}"
                        );
                    }
                }
            }
        }
    }
}

/// The `f64` reference agrees: doubled scenes (lit and Lab #1) are decided as the
/// single ones, and the kernel has no coverage error and no decidable pixel more than
/// 2 levels off it.
#[test]
fn coincident_spheres_agree_with_the_reference() {
    for name in ["shadows", "mirrors", "lab"] {
        let f = standard::load_full(name);
        let mut p = *f.camera.params();
        p.size = embedded_graphics::prelude::Size::new(96, 96);
        let camera = p.build().unwrap();
        let (doubled, single) = twinned(&f.scene, true);
        let (truth, single_truth) = (
            reference::render(&doubled, &camera),
            reference::render(&single, &camera),
        );
        assert_eq!(truth.undecidable(), single_truth.undecidable(), "{name}");
        for secondary in [SecondaryOrigin::Convex, SecondaryOrigin::TEXTBOOK] {
            let render =
                Render::<MAX_SPHERES, Rgb888, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>::new(&doubled, &camera)
                    .with_options(Options::DEFAULT.with_secondary(secondary));
            let m = reference::compare(&render, &truth);
            assert_eq!(
                (m.over_2, m.coverage_errors),
                (0, 0),
                "{name} {secondary:?}: {m:?}"
            );
        }
    }
}
