//! The integer kernel (`Arithmetic::Integer`) against the f64 reference: where its
//! per-frame rule takes a frame, no coverage error and every shade within one level;
//! the rule's limits (distance/radius, resolution, field of view, scene extent) at the
//! points where it stops taking the frame; clip and band change no pixel.

use crate::common;

use common::{load, SCENES};
use embedded_graphics::geometry::Size;
use embedded_graphics::pixelcolor::Rgb888;
use embedded_raytracer::{Arithmetic, CameraParams, Method, Render, SphereTest, Sqrt, Stepping, Vec3};
use embedded_raytracer_lab::reference;
use embedded_raytracer_lab::reference::sweeps::{integer_limit, integer_sweep, IntegerSweep};

/// Every standard scene at its own size and at 240×240: the rule's choice, and where
/// it takes the integer kernel, 0 coverage errors and ≤ 1 level against the reference.
#[test]
fn standard_scenes_against_reference() {
    for name in SCENES {
        let file = load(name);
        for size in [file.camera.size(), Size::new(240, 240)] {
            let camera = common::at_size(file.camera.params(), size);
            let render = Render::<_, Rgb888>::new(&file.scene, &camera).with_method(Method::INTEGER);
            let chosen = render.arithmetic();
            let reference = reference::render(&file.scene, &camera);
            let m = reference::compare(&render, &reference);
            println!(
                "{name} {}x{}: {chosen}, coverage errors {}, shade max {}, color max {}, undecidable {}",
                size.width, size.height, m.coverage_errors, m.shade_max, m.color_max, m.undecidable
            );
            // The rule takes every standard scene but `grazing` (the eye 0.023 above a
            // sphere: its silhouette is not bounded).
            let expected = if name == "grazing" {
                Arithmetic::F32
            } else {
                Arithmetic::Integer
            };
            assert_eq!(chosen, expected, "{name} {size:?}");
            exact_where_chosen(&format!("{name} {size:?}"), chosen, &m);
            assert_eq!(m.bad_samples, 0);
            assert_eq!(m.non_finite, 0);
        }
    }
}

/// Where the rule takes the integer kernel it draws what the reference draws: no
/// coverage error, shades within one level.
fn exact_where_chosen(what: &str, chosen: Arithmetic, m: &reference::Metrics) {
    if chosen == Arithmetic::Integer {
        assert_eq!(m.coverage_errors, 0, "{what}: {m:?}");
        assert!(m.shade_max <= 1, "{what}: {m:?}");
    }
}

/// A sweep of `reference::sweeps::integer_sweep`: exact wherever chosen, and the rule
/// stops taking the frame once and for all; `(last taken, first refused)`.
fn limits(kind: IntegerSweep) -> (f64, f64) {
    let points = integer_sweep(kind);
    for p in &points {
        println!(
            "{} {:.0}: integer {}, {:?}",
            kind.name(),
            p.value,
            p.integer,
            p.metrics.coverage_errors
        );
        let chosen = if p.integer {
            Arithmetic::Integer
        } else {
            Arithmetic::F32
        };
        exact_where_chosen(&format!("{} {}", kind.name(), p.value), chosen, &p.metrics);
    }
    let (last, refused) = integer_limit(&points);
    let (last, refused) = (
        last.expect("taken at the sweep's start"),
        refused.expect("refused at its end"),
    );
    assert!(last < refused, "{kind:?}: taken again after refusing: {points:?}");
    (last, refused)
}

/// Distance/radius: one sphere filling half of a 64×64 image, ever farther and
/// smaller (16 ratios 10^(k/4) from 10; a narrower field of view than the last is
/// below the camera's `MIN_PIXEL_SIZE`). The rule's shade bound needs `ρ = λ·r` of
/// about a thousand units and its grazing ring (see `fixed.rs`) a few thousand, and
/// `λ·|L| ≤ 2²⁵`: the integer kernel is taken up to 10^4 and refused from
/// 10^4.25 ≈ 17,783 (measured), exact up to there.
#[test]
fn distance_radius_limit() {
    let (last, refused) = limits(IntegerSweep::DistanceRadius);
    assert!(
        (9_000.0..11_000.0).contains(&last),
        "last distance/radius taken: {last}"
    );
    assert!(
        (17_000.0..18_000.0).contains(&refused),
        "first refused: {refused}"
    );
}

/// Scene extent: the lab's yellow sphere (radius 0.35, 3.5 from the eye) with a second
/// sphere ever farther behind it (scaled to keep its size on screen). One `λ` serves
/// the frame and must hold the farthest sphere, so the near one's `ρ` shrinks: the rule
/// takes the frame up to an extent (farthest |L| + r) of 1,928 near-sphere radii and
/// refuses it from 3,429 (measured; the near sphere's grazing ring, see `fixed.rs`,
/// decides), exact up to there.
#[test]
fn scene_extent_limit() {
    let (last, refused) = limits(IntegerSweep::Extent);
    assert!(
        (1_900.0..2_000.0).contains(&last),
        "last extent/radius taken: {last}"
    );
    assert!((3_400.0..3_500.0).contains(&refused), "first refused: {refused}");
}

/// Field of view: two lab spheres from 10° to 170° (square pixels, 96×96). The shade's
/// one division keeps about 15 bits of `a·ρ` at the image's corner and fewer towards
/// its centre, where `a` is smaller by `1 + R²/Fz²` (R the corner's distance, Fz the
/// focal length): the rule takes the frame up to 130° and refuses it from 140°
/// (measured), exact up to there.
#[test]
fn field_of_view_limit() {
    assert_eq!(limits(IntegerSweep::FieldOfView), (130.0, 140.0));
}

/// Resolution: the lab scene from 16×16 to 8192×8192 pixels (the integer pixel unit
/// 2⁻ᵏ shrinks as the image grows, so `|d| ≤ 2²⁶` holds at every size up to
/// `MAX_RESOLUTION`): chosen at every size. The reference comparison runs on a strip
/// of rows through the spheres (the whole image at the small sizes).
#[test]
fn resolution_never_limits() {
    let file = load("lab");
    for n in [16u32, 64, 256, 1024, 4096, 8192] {
        let params = CameraParams {
            size: Size::new(n, n),
            ..*file.camera.params()
        };
        let camera = params.build().unwrap();
        let render = Render::<_, Rgb888>::new(&file.scene, &camera).with_method(Method::INTEGER);
        assert_eq!(render.arithmetic(), Arithmetic::Integer, "{n}×{n}");
        if n <= 256 {
            let m = reference::compare(&render, &reference::render(&file.scene, &camera));
            exact_where_chosen(&format!("{n}×{n}"), Arithmetic::Integer, &m);
        }
    }
}

/// The camera with a horizontal field of view of its own: pixels that are not square,
/// which the integer rule refuses.
fn non_square_pixels(params: &CameraParams) -> CameraParams {
    CameraParams {
        fov_x: Some(1.5),
        ..*params
    }
}

/// Non-square pixels and an eye inside a sphere are drawn in
/// `f32` (the rule refuses them), and the picture is then exactly the `f32` method's.
#[test]
fn refused_frames_are_the_f32_methods() {
    let file = load("lab");
    let wide = non_square_pixels(file.camera.params());
    let inside = CameraParams {
        eye: Vec3::new(0.0, 0.0, 0.5),
        ..*file.camera.params()
    };
    for params in [wide, inside] {
        let camera = params.build().unwrap();
        let int = Render::<_, Rgb888>::new(&file.scene, &camera).with_method(Method::INTEGER);
        assert_eq!(int.arithmetic(), Arithmetic::F32);
        let f32_method = Method::INTEGER.with_arithmetic(Arithmetic::F32);
        let float = Render::<_, Rgb888>::new(&file.scene, &camera).with_method(f32_method);
        assert!(common::trace(int) == common::trace(float));
    }
}

/// A small sphere at a wide angle beside a far, large one: one `λ` for the frame leaves
/// the small sphere few units (`ρ` in the thousands), and its quantisation moves the
/// shade of hits near its rim by more than a level (measured: 201 against the
/// reference's 199 at pixel (27, 36) under a rule without the grazing ring). The rule
/// refuses the frame, which is then exactly the `f32` method's; with the far sphere
/// closer (a smaller extent) it takes the frame and stays within one level.
#[test]
fn grazing_ring_of_a_coarsely_quantised_sphere() {
    use embedded_raytracer::{Scene, Sphere};
    let scene_with = |far_z: f32, far_r: f32| {
        let mut scene: Scene<2> = Scene::new(Rgb888::new(0, 0, 0));
        for sphere in [
            Sphere::new(Vec3::new(-2.469, 2.5, 1.5), 1.0, Rgb888::new(255, 255, 255)),
            Sphere::new(Vec3::new(0.0, 0.0, far_z), far_r, Rgb888::new(200, 120, 60)),
        ] {
            scene.push(sphere).unwrap();
        }
        scene
    };
    let camera = CameraParams::new(
        Vec3::new(0.0, 0.0, 5.0),
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        120f32.to_radians(),
        Size::new(160, 160),
    )
    .build()
    .unwrap();
    let far = scene_with(5.0 - 8091.1, 404.6);
    let int = Render::<_, Rgb888>::new(&far, &camera).with_method(Method::INTEGER);
    assert_eq!(int.arithmetic(), Arithmetic::F32);
    let f32_method = Method::INTEGER.with_arithmetic(Arithmetic::F32);
    let float = Render::<_, Rgb888>::new(&far, &camera).with_method(f32_method);
    assert!(common::trace(int) == common::trace(float));

    let near = scene_with(5.0 - 80.911, 4.046);
    let int = Render::<_, Rgb888>::new(&near, &camera).with_method(Method::INTEGER);
    assert_eq!(int.arithmetic(), Arithmetic::Integer);
    let m = reference::compare(&int, &reference::render(&near, &camera));
    exact_where_chosen("near", Arithmetic::Integer, &m);
}

/// `draw_integer` draws exactly what `draw` with `Method::INTEGER` draws wherever the
/// rule takes the frame (every standard scene at 240×240, drawn at an offset on a
/// larger target so the clip cuts it too), and where the rule refuses (grazing; lab
/// with non-square pixels), for sub-pixel sampling and for scenes with features it
/// returns `Refused` without writing a pixel.
#[test]
fn draw_integer_is_the_integer_method_or_refuses() {
    use embedded_graphics::prelude::Point;
    use embedded_raytracer::IntegerError;
    let draw = |render: Render<'_, { common::MAX_SPHERES }, Rgb888>| {
        let mut frame = common::Frame::new(Size::new(250, 230));
        let result = render.with_offset(Point::new(17, -9)).draw_integer(&mut frame);
        (result, frame)
    };
    let mut checked = 0;
    for name in SCENES {
        let file = load(name);
        let camera = common::at_size(file.camera.params(), Size::new(240, 240));
        let render = Render::<_, Rgb888>::new(&file.scene, &camera).with_method(Method::INTEGER);
        let (result, frame) = draw(render);
        if render.arithmetic() == Arithmetic::Integer {
            let mut expected = common::Frame::new(frame.size);
            embedded_graphics::Drawable::draw(&render.with_offset(Point::new(17, -9)), &mut expected)
                .unwrap();
            assert_eq!(result, Ok(()), "{name}");
            assert!(
                frame.buf == expected.buf,
                "{name}: not the integer method's pixels"
            );
            assert!(frame.writes > 0, "{name}");
            checked += 1;
        } else {
            assert_eq!(name, "grazing");
            assert_eq!(result, Err(IntegerError::Refused), "{name}");
            assert_eq!(frame.writes, 0, "{name}: a refused frame wrote pixels");
        }
    }
    assert_eq!(checked, SCENES.len() - 1, "every standard scene but grazing");
    // Non-square pixels: refused, nothing written.
    let file = load("lab");
    let wide = non_square_pixels(file.camera.params()).build().unwrap();
    let (result, frame) = draw(Render::new(&file.scene, &wide));
    assert_eq!(result, Err(IntegerError::Refused));
    assert_eq!(frame.writes, 0);
    // Sub-pixel sampling, which the integer kernel does not trace: refused.
    let camera = file.camera;
    let sampling = embedded_raytracer::Sampling::adaptive(4).unwrap();
    let (result, frame) = draw(Render::new(&file.scene, &camera).with_sampling(sampling));
    assert_eq!(result, Err(IntegerError::Refused));
    assert_eq!(frame.writes, 0);
    // A scene with lights, a floor and mirrors: refused.
    for name in common::FEATURE_SCENES {
        let file = common::load_full(name);
        let camera = file.camera;
        let mut frame = common::Frame::new(camera.size());
        let result = Render::<_, Rgb888, _, _, _>::new(&file.scene, &camera).draw_integer(&mut frame);
        assert_eq!(result, Err(IntegerError::Refused), "{name}");
        assert_eq!(frame.writes, 0, "{name}");
    }
}

/// `Render::draw_band_integer` traces, band by band (several heights, the last band
/// shorter), the pixels of `draw_band` with `Method::INTEGER` wherever the rule takes the
/// frame (every standard scene but grazing at 240×240), whatever the render's own method;
/// where it refuses (grazing, non-square pixels, sub-pixel sampling, a scene with lights,
/// a floor and mirrors) it returns `Refused` and leaves the buffer as it was; a bad band
/// is `draw_band`'s error.
#[test]
fn draw_band_integer_is_the_integer_methods_band_or_refuses() {
    use embedded_raytracer::{BandError, IntegerError};
    const FILL: Rgb888 = Rgb888::new(1, 2, 3);
    let mut checked = 0;
    for name in SCENES {
        let file = load(name);
        let camera = common::at_size(file.camera.params(), Size::new(240, 240));
        let render = Render::<_, Rgb888>::new(&file.scene, &camera).with_method(Method::INTEGER);
        let f32_render = render.with_method(Method::new(Stepping::Direct, SphereTest::Auto, Sqrt::Exact));
        let taken = render.arithmetic() == Arithmetic::Integer;
        for band_rows in [1, 16, 20, 77, 240] {
            let mut start = 0;
            while start < 240 {
                let rows = start..(start + band_rows).min(240);
                let len = 240 * rows.len();
                let (mut band, mut expected) = (vec![FILL; len], vec![FILL; len]);
                let result = render.draw_band_integer(rows.clone(), &mut band);
                // Whatever the render's own method (here the f32 default): the same band.
                let mut from_f32 = vec![FILL; len];
                let f32_result = f32_render.draw_band_integer(rows.clone(), &mut from_f32);
                assert_eq!(f32_result, result, "{name} {rows:?}");
                assert!(
                    from_f32 == band,
                    "{name} {rows:?}: depends on the render's method"
                );
                if taken {
                    render.draw_band(rows.clone(), &mut expected).unwrap();
                    assert_eq!(result, Ok(()), "{name} {rows:?}");
                    assert!(band == expected, "{name} {rows:?}: not the integer method's band");
                } else {
                    assert_eq!(name, "grazing");
                    assert_eq!(result, Err(IntegerError::Refused), "{name} {rows:?}");
                    assert!(
                        band.iter().all(|&p| p == FILL),
                        "{name}: a refused band was written"
                    );
                }
                start = rows.end;
            }
        }
        checked += usize::from(taken);
        // A band past the image, a buffer of the wrong size: draw_band's errors.
        assert_eq!(
            render.draw_band_integer(230..241, &mut vec![FILL; 240 * 11]),
            Err(IntegerError::Target(BandError::Rows {
                start: 230,
                end: 241,
                height: 240
            }))
        );
        assert_eq!(
            render.draw_band_integer(0..2, &mut vec![FILL; 240]),
            Err(IntegerError::Target(BandError::BufferSize {
                expected: 480,
                found: 240
            }))
        );
    }
    assert_eq!(checked, SCENES.len() - 1, "every standard scene but grazing");
    // Non-square pixels, sub-pixel sampling and scenes with features: refused, the buffer
    // untouched.
    let file = load("lab");
    let wide = non_square_pixels(file.camera.params()).build().unwrap();
    let mut band = vec![FILL; 320 * 10];
    assert_eq!(
        Render::new(&file.scene, &wide).draw_band_integer(0..10, &mut band),
        Err(IntegerError::Refused)
    );
    assert!(band.iter().all(|&p| p == FILL));
    let sampling = embedded_raytracer::Sampling::adaptive(4).unwrap();
    let mut band = vec![FILL; 320 * 10];
    assert_eq!(
        Render::new(&file.scene, &file.camera)
            .with_sampling(sampling)
            .draw_band_integer(0..10, &mut band),
        Err(IntegerError::Refused)
    );
    assert!(band.iter().all(|&p| p == FILL));
    for name in common::FEATURE_SCENES {
        let file = common::load_full(name);
        let camera = file.camera;
        let mut band = vec![FILL; camera.size().width as usize * 3];
        let render = Render::<_, Rgb888, _, _, _>::new(&file.scene, &camera);
        assert_eq!(
            render.draw_band_integer(0..3, &mut band),
            Err(IntegerError::Refused),
            "{name}"
        );
        assert!(band.iter().all(|&p| p == FILL), "{name}");
    }
}
