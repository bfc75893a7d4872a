//! A point light on a surface (a lamp resting on the floor, a lamp on a sphere): the
//! shadow segment ends exactly on that surface, open at the lamp. The kernel and the
//! `f64` reference decide such a (light, object) pair by the side the segment reaches
//! the lamp from, not by a root at `t ≈ dist`; these tests check that no pixel a lamp
//! lights turns to a random shadow speckle, for the default method, the textbook ε and
//! grid sampling, over lamp positions on and near every kind of surface.

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::Size;
use embedded_raytracer::{Camera, Light, Method, Options, Render, Sampling, Scene, SecondaryOrigin, Vec3};
use embedded_raytracer_lab::reference::{self, ReferenceImage};

use embedded_raytracer_scenes::{self as standard, FullSceneFile};

const CONVEX: SecondaryOrigin = SecondaryOrigin::Convex;
const EPS: SecondaryOrigin = SecondaryOrigin::TEXTBOOK;

/// The `shadows` scene with its point light moved to `at`.
fn with_lamp(f: &FullSceneFile, at: Vec3) -> FullScene {
    let scene = &f.scene;
    let mut out: FullScene = Scene::new(scene.background());
    out.set_settings(scene.settings()).unwrap();
    for s in scene.spheres() {
        out.push(*s).unwrap();
    }
    for l in scene.lights() {
        out.push_light(match *l {
            Light::Point { intensity, .. } => Light::point(at, intensity),
            other => other,
        })
        .unwrap();
    }
    for p in scene.planes() {
        out.push_plane(*p).unwrap();
    }
    out
}

type FullScene = Scene<
    { standard::MAX_SPHERES },
    { standard::MAX_LIGHTS },
    { standard::MAX_PLANES },
    { standard::MAX_DEPTH },
>;

/// The kernel's pixels, row-major.
fn pixels(scene: &FullScene, camera: &Camera, secondary: SecondaryOrigin, sampling: Sampling) -> Vec<Rgb888> {
    let mut out = Vec::new();
    Render::<
        { standard::MAX_SPHERES },
        Rgb888,
        { standard::MAX_LIGHTS },
        { standard::MAX_PLANES },
        { standard::MAX_DEPTH },
    >::new(scene, camera)
    .with_method(Method::TARGET_DEFAULT)
    .with_options(Options::DEFAULT.with_secondary(secondary))
    .with_sampling(sampling)
    .trace(|s| out.push(s.color));
    out
}

/// Decidable pixels more than 2 levels off the reference.
fn over_2(scene: &FullScene, camera: &Camera, truth: &ReferenceImage, secondary: SecondaryOrigin) -> usize {
    let render = Render::<
        { standard::MAX_SPHERES },
        Rgb888,
        { standard::MAX_LIGHTS },
        { standard::MAX_PLANES },
        { standard::MAX_DEPTH },
    >::new(scene, camera)
    .with_method(Method::TARGET_DEFAULT)
    .with_options(Options::DEFAULT.with_secondary(secondary));
    reference::compare(&render, truth).over_2
}

/// Pixels of two renders more than 2 levels apart in some channel.
fn differ(a: &[Rgb888], b: &[Rgb888]) -> usize {
    a.iter()
        .zip(b)
        .filter(|(a, b)| a.r().abs_diff(b.r()) > 2 || a.g().abs_diff(b.g()) > 2 || a.b().abs_diff(b.b()) > 2)
        .count()
}

/// A shrunk camera of the `shadows` scene.
fn small(camera: &Camera, size: u32) -> Camera {
    let mut p = *camera.params();
    p.size = Size::new(size, size);
    p.build().unwrap()
}

/// Lamps on the red sphere and on the floor (the two cases), at 240×240: no
/// decidable pixel more than 2 levels off the reference with the default convex exit
/// or the textbook ε, the reference deciding all but a sliver (before the rule it
/// marked every pixel the lamp lights as undecidable: 17,826 and 5,665), and the
/// picture the same as with the lamp moved by 10⁻⁴, for one ray per pixel and for
/// `Grid(4)` (before: 4,610 / 673 pixels apart with the convex exit, 5,360 / 2,141
/// with ε, 10,074 / 3,149 with `Grid(4)`). The floor lamp moves 10⁻⁴ up; the sphere's
/// moves 10⁻⁴ along the surface, which leaves it 5·10⁻⁹ outside: it then also lights
/// the grazing directions within `√(2·5·10⁻⁹)` rad of its tangent plane, under a
/// pixel (moved 10⁻⁴ outward, that wedge is 0.8° wide and rightly lights 145 pixels
/// more). Measured: 0 off; 40 and 26 undecidable; 0 pixels apart (2 and 4 with
/// `Grid(4)`: the light moved by 10⁻⁴ changes the shading there by a level or more).
#[test]
fn a_lamp_on_a_surface_casts_no_speckle() {
    let f = standard::load_full("shadows");
    for (on, near, apart) in [
        (Vec3::new(1.0, 1.0, 0.0), Vec3::new(1.0, 1.0, 0.0001), 2),
        (Vec3::new(3.0, 0.0, 3.5), Vec3::new(3.0, 0.0001, 3.5), 8),
    ] {
        let (a, b) = (with_lamp(&f, on), with_lamp(&f, near));
        let truth = reference::render(&a, &f.camera);
        assert!(
            truth.undecidable() < 100,
            "{on:?}: {} undecidable",
            truth.undecidable()
        );
        for secondary in [CONVEX, EPS] {
            assert_eq!(
                over_2(&a, &f.camera, &truth, secondary),
                0,
                "{on:?} {secondary:?}"
            );
            let d = differ(
                &pixels(&a, &f.camera, secondary, Sampling::Center),
                &pixels(&b, &f.camera, secondary, Sampling::Center),
            );
            assert!(
                d <= 2,
                "{on:?} {secondary:?}: {d} pixels apart from the lamp off the surface"
            );
        }
        let g = Sampling::grid(4).unwrap();
        let d = differ(
            &pixels(&a, &f.camera, CONVEX, g),
            &pixels(&b, &f.camera, CONVEX, g),
        );
        assert!(
            d <= apart,
            "{on:?} Grid(4): {d} pixels apart from the lamp off the surface"
        );
    }
}

/// Lamp positions on and near every kind of surface of the `shadows` scene: on each
/// sphere (on its top, its side toward the camera and its underside) and on the floor
/// (in the open and next to the resting sphere's contact point), each moved along the
/// surface's normal by 0, ±10⁻⁶, ±10⁻⁵, ±10⁻⁴ (within the on-surface bound, ≈ 2.6·10⁻⁴
/// here), ±10⁻³ and ±10⁻² (beyond it): no decidable pixel more than 2 levels off the
/// reference, for the convex exit and the textbook ε.
fn sweep(size: u32, offsets: &[f32]) -> (usize, usize) {
    let f = standard::load_full("shadows");
    let camera = small(&f.camera, size);
    let mut sites: Vec<(Vec3, Vec3)> = Vec::new();
    for s in f.scene.spheres() {
        for n in [
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.6, 0.0, 0.8),
            Vec3::new(0.0, -0.6, 0.8),
        ] {
            sites.push((s.center + n * s.radius, n));
        }
    }
    let up = Vec3::new(0.0, 1.0, 0.0);
    for at in [
        Vec3::new(3.0, 0.0, 3.5),
        Vec3::new(-1.0, 0.0, 1.5),
        Vec3::new(0.05, 0.0, 0.05),
    ] {
        sites.push((at, up));
    }
    let (mut cases, mut undecidable) = (0, 0);
    for (at, n) in sites {
        for &k in offsets {
            let scene = with_lamp(&f, at + n * k);
            let truth = reference::render(&scene, &camera);
            undecidable += truth.undecidable();
            for secondary in [CONVEX, EPS] {
                let o = over_2(&scene, &camera, &truth, secondary);
                assert_eq!(o, 0, "lamp at {at:?} + {k}·{n:?}, {secondary:?}");
                cases += 1;
            }
        }
    }
    (cases, undecidable)
}

/// [`sweep`] at 40×40 over offsets 0, ±10⁻⁵ and ±10⁻³ (150 renders). Measured: 0 off
/// in every render; 810 undecidable pixels in all (of 240,000). Before the rule, 62 of
/// the renders had pixels off, up to 637 of the 1,600.
#[test]
fn lamps_on_and_near_every_surface_cast_no_speckle() {
    let (cases, undecidable) = sweep(40, &[0.0, 1e-5, -1e-5, 1e-3, -1e-3]);
    println!("{cases} renders, {undecidable} undecidable pixels");
}

/// [`sweep`] at 120×120 over every offset (330 renders). Measured: 0 off in every
/// render; 9,841 undecidable pixels in all (0.2 % of 4,752,000).
#[test]
#[ignore = "long: cargo test --release -p embedded-raytracer-lab --test lab lamps_on_and_near_every_surface_native -- --ignored"]
fn lamps_on_and_near_every_surface_native() {
    let offsets = [
        0.0, 1e-6, -1e-6, 1e-5, -1e-5, 1e-4, -1e-4, 1e-3, -1e-3, 1e-2, -1e-2,
    ];
    let (cases, undecidable) = sweep(120, &offsets);
    println!("{cases} renders, {undecidable} undecidable pixels");
}

/// A lamp within the on-surface bound of a surface but off it (the bound grows with
/// the frame's lengths: a plane given by a point far along it, a lamp far from the
/// eye) is decided by the side it lies on, not as if it lay on the surface: a ceiling
/// under the lamp shades everything below it, and a lamp just inside an opaque sphere
/// lights nothing outside. Each picture must equal the same scene with the lamp's
/// intensity 0 (before: 51,460, 52,390 and 52,771 of 57,600 pixels lit through), and
/// the ceiling given by a far point must draw as the one given by a near point.
#[test]
fn a_lamp_off_a_surface_within_the_bound_is_on_its_side() {
    let scene = |lamp: [f32; 3], intensity: f32, extra: &str| {
        format!(
            "background = [24, 34, 56]\nambient = 0.12\nshadows = true\n\
             [camera]\neye = [0.0, 3.0, 6.8]\nlook_at = [0.0, 0.5, 0.3]\nfov_y_deg = 45.0\n\
             width = 96\nheight = 96\n\
             [[light]]\ntype = \"point\"\nposition = [{:?}, {:?}, {:?}]\nintensity = {intensity:?}\n\
             [[sphere]]\ncenter = [0.0, 1.0, 0.0]\nradius = 1.0\ncolor = [230, 60, 50]\n\
             [[plane]]\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\n\
             color = [225, 225, 215]\nchecker = [70, 70, 80]\n{extra}",
            lamp[0], lamp[1], lamp[2]
        )
    };
    let ceiling = |y: f32, x: f32| {
        format!(
            "[[plane]]\npoint = [{x:?}, {y:?}, 0.0]\nnormal = [0.0, -1.0, 0.0]\ncolor = [200, 200, 200]\n"
        )
    };
    let shade = |gap: f32| {
        format!(
            "[[sphere]]\ncenter = [3.0, {:?}, 3.5]\nradius = 1.0\ncolor = [90, 90, 90]\n",
            3.5 + 1.0 + gap
        )
    };
    let draw = |text: &str| {
        let file: FullSceneFile =
            embedded_raytracer::scene_file::parse(text).unwrap_or_else(|e| panic!("{e}"));
        pixels(&file.scene, &file.camera, CONVEX, Sampling::Center)
    };
    let cases = [
        // A ceiling 4 under the lamp, given by a point 10¹⁰ along it.
        ([0.0, 9.0, 0.0], ceiling(5.0, 1e10)),
        // A lamp 10⁶ up, 10 above a ceiling.
        ([0.0, 1e6, 0.0], ceiling(999_990.0, 0.0)),
        // A lamp 10⁻⁴ and 10⁻⁵ inside an opaque sphere, near its bottom.
        ([3.0, 3.5, 3.5], shade(-1e-4)),
        ([3.0, 3.5, 3.5], shade(-1e-5)),
    ];
    for (lamp, extra) in &cases {
        let lit = draw(&scene(*lamp, 1.0, extra));
        let off = draw(&scene(*lamp, 0.0, extra));
        assert_eq!(differ(&lit, &off), 0, "lamp {lamp:?} with {extra}");
    }
    let near = draw(&scene([0.0, 9.0, 0.0], 1.0, &ceiling(5.0, 0.0)));
    let far = draw(&scene([0.0, 9.0, 0.0], 1.0, &ceiling(5.0, 1e10)));
    assert_eq!(differ(&near, &far), 0);
}

/// A unit sphere resting on a checkered floor, a point light at `lamp`, seen straight
/// down from `eye` above the origin at 64×64, the view about 8 wide at the floor.
fn unit_sphere_seen_from_above(eye: f32, lamp: [f32; 3]) -> FullSceneFile {
    let text = format!(
        "background = [24, 34, 56]\nambient = 0.12\nshadows = true\n\
         [camera]\neye = [0.0, {eye:?}, 0.0]\nlook_at = [0.0, 0.0, 0.0]\nup = [0.0, 0.0, -1.0]\n\
         fov_y_deg = {:?}\nwidth = 64\nheight = 64\n\
         [[light]]\ntype = \"point\"\nposition = [{:?}, {:?}, {:?}]\nintensity = 1.0\n\
         [[sphere]]\ncenter = [0.0, 1.0, 0.0]\nradius = 1.0\ncolor = [230, 60, 50]\n\
         [[plane]]\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\n\
         color = [225, 225, 215]\nchecker = [70, 70, 80]\n",
        458.0 / eye,
        lamp[0],
        lamp[1],
        lamp[2]
    );
    embedded_raytracer::scene_file::parse(&text).unwrap_or_else(|e| panic!("{e}"))
}

/// A lamp near a sphere, within the on-surface bound, the bound made large by an eye
/// 10⁴ away (2⁻¹⁶ of the frame's lengths: about 0.3 for this unit sphere): the
/// segment is decided by the sphere's true geometry, not as if it passed through the
/// lamp. Lamps 0.3, 0.1 and 10⁻² outside the sphere (the line's root nearest the lamp,
/// from `g = |P − C|² − r²` kept from `f64`) and 0.2 inside it (the segment's origin
/// outside it), seen from above at 64×64: no decidable pixel more than 2 levels off
/// the reference. Measured: 0 off, 262 undecidable pixels at most; before, the floor
/// was shaded as if the sphere were a ball around the lamp, 782, 432 and 64 pixels
/// off. (The textbook ε is not checked: its 10⁻³ is below the rounding this far out.)
#[test]
fn a_lamp_near_a_sphere_seen_from_far_away_casts_its_own_shadow() {
    for gap in [0.3f32, 0.1, 1e-2, -0.2] {
        let file = unit_sphere_seen_from_above(1e4, [1.0 + gap, 1.0, 0.0]);
        let truth = reference::render(&file.scene, &file.camera);
        let off = over_2(&file.scene, &file.camera, &truth, CONVEX);
        println!("gap {gap}: {off} off, {} undecidable", truth.undecidable());
        assert_eq!(off, 0, "lamp {gap} off the sphere");
        assert!(
            truth.undecidable() <= 300,
            "gap {gap}: {} undecidable",
            truth.undecidable()
        );
    }
}

/// The rule above against geometry it does not use: lamps near a sphere but clearly off
/// it, inside the on-surface bound only because the eye is far (10⁴ and 10⁵: a bound
/// of about 0.3 and 3 for this unit sphere), every other pixel through the sphere's
/// ray–sphere test in `f64` with its own error band — the reference with the lamp ties
/// switched off ([`reference::render_without_lamp_ties`]). Lamps above, beside and
/// below the sphere's equator, outside and inside it: no pixel that reference decides
/// is more than 2 levels off the kernel. Without the ties the reference is in doubt
/// wherever a segment passes within the hit point's rounding of the sphere, which near
/// the lamp is most of the floor; it still decides at least 100 pixels of every case.
/// Measured: 0 off in every case; decided 1,384–4,096 of the 4,096 pixels from 10⁴,
/// 149–208 from 10⁵.
#[test]
fn a_lamp_near_a_sphere_agrees_with_the_reference_without_lamp_ties() {
    let cases: [(f32, [f32; 3], &[f32]); 4] = [
        (1e4, [1.0, 0.0, 0.0], &[0.25, 0.1, 0.03, 1e-2, -0.05, -0.2]),
        (1e4, [0.6, 0.8, 0.0], &[0.2, 0.05, 1e-2, -0.1]),
        (1e4, [0.0, -0.6, 0.8], &[0.2, 0.05, -0.1]),
        (1e5, [0.8, 0.0, 0.6], &[2.0, 0.5, 0.1, -0.5]),
    ];
    for (eye, dir, gaps) in cases {
        for &gap in gaps {
            let at = [
                dir[0] * (1.0 + gap),
                1.0 + dir[1] * (1.0 + gap),
                dir[2] * (1.0 + gap),
            ];
            let file = unit_sphere_seen_from_above(eye, at);
            let lamp = reference::D3::of(Vec3::new(at[0], at[1], at[2]));
            let centre = reference::D3::of(Vec3::new(0.0, 1.0, 0.0));
            let eye_at = reference::D3::of(Vec3::new(0.0, eye, 0.0));
            assert!(
                reference::lit::lamp_on_sphere(lamp, eye_at, centre, 1.0),
                "eye {eye}, lamp {at:?}: not within the on-surface bound, so not a test of it"
            );
            let truth =
                reference::render_without_lamp_ties(&file.scene, &file.camera).expect("a valid camera");
            let off = over_2(&file.scene, &file.camera, &truth, CONVEX);
            println!(
                "eye {eye}, lamp {at:?}: {off} off, {} undecidable",
                truth.undecidable()
            );
            assert_eq!(off, 0, "eye {eye}, lamp {at:?}");
            assert!(
                truth.undecidable() + 100 <= 64 * 64,
                "eye {eye}, lamp {at:?}: {} of 4,096 undecidable, too few to check",
                truth.undecidable()
            );
        }
    }
}
