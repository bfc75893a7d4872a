//! A pixel is a function of the scene, the camera, the method and the pixel — never of
//! the clip rectangle or the offset it was drawn with: every method, bit for bit.

use crate::common;

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raytracer::{Camera, Method, Render, Scene};
#[cfg(feature = "bench-baselines")]
use embedded_raytracer::{Options, SphereTest, Sqrt, Stepping};

use common::{random_case, Frame, Rng};

/// Draws `scene` placed at `offset` on a `target_size` frame through the clip `clip`
/// and checks every visible pixel against the whole render's; returns how many were
/// compared.
fn check_clip<const N: usize>(
    scene: &Scene<N>,
    camera: &Camera,
    method: Method,
    offset: Point,
    target_size: Size,
    clip: Rectangle,
) -> usize {
    let whole = common::trace(Render::new(scene, camera).with_method(method));
    let mut frame = Frame::new(target_size);
    Render::new(scene, camera)
        .with_method(method)
        .with_offset(offset)
        .draw(&mut frame.clipped(&clip))
        .unwrap();
    let image = Rectangle::new(offset, camera.size());
    let visible = image.intersection(&clip).intersection(&frame.bounding_box());
    let width = camera.size().width as i32;
    let mut compared = 0;
    for p in frame.bounding_box().points() {
        let got = frame.get(p);
        if visible.contains(p) {
            let q = p - offset;
            let want = whole[(q.y * width + q.x) as usize].1;
            assert_eq!(
                got,
                Some(want),
                "{method}: pixel {q:?} drawn at {p:?} with clip {clip:?} differs from the whole render"
            );
            compared += 1;
        } else {
            assert_eq!(got, None, "{method}: {p:?} outside the clip was written");
        }
    }
    assert_eq!(frame.writes, compared, "{method}: a pixel was written twice");
    compared
}

/// The lab scene, clipped on every side and offset, with every method: the forward
/// differences' anchors sit at the whole image's span starts, so even they match.
#[test]
#[cfg(feature = "std")]
fn clipped_and_offset_draws_equal_the_whole_render_on_lab() {
    let lab = common::load("lab");
    let camera = common::shrink(&lab.camera, 96, 72);
    let target = Size::new(110, 90);
    let cases = [
        (
            Point::new(0, 0),
            Rectangle::new(Point::new(13, 7), Size::new(50, 40)),
        ),
        (Point::new(-13, -7), Rectangle::new(Point::zero(), target)),
        (
            Point::new(20, 10),
            Rectangle::new(Point::new(41, 0), Size::new(3, 90)),
        ),
        (
            Point::new(5, 3),
            Rectangle::new(Point::new(60, 30), Size::new(200, 1)),
        ),
    ];
    for method in Method::ALL.into_iter().chain([Method::INTEGER]) {
        for (offset, clip) in cases {
            assert!(check_clip(&lab.scene, &camera, method, offset, target, clip) > 0);
        }
    }
}

/// Random scenes (spheres behind, around and containing the eye, far and tiny) ×
/// random clip rectangles and offsets × every method. More with `CLIP_CASES=N`.
#[test]
fn clipped_draws_equal_the_whole_render_on_random_scenes() {
    let cases = std::env::var("CLIP_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(40u64);
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    let mut compared = 0;
    for _ in 0..cases {
        let (scene, camera) = random_case(&mut rng);
        let size = camera.size();
        let target = Size::new(size.width + 8, size.height + 8);
        for method in Method::ALL.into_iter().chain([Method::INTEGER]) {
            let offset = Point::new(rng.range(-10.0, 10.0) as i32, rng.range(-10.0, 10.0) as i32);
            let x0 = rng.range(-4.0, size.width as f32) as i32;
            let y0 = rng.range(-4.0, size.height as f32) as i32;
            let clip = Rectangle::new(
                Point::new(x0, y0),
                Size::new(rng.range(1.0, 80.0) as u32, rng.range(1.0, 60.0) as u32),
            );
            compared += check_clip(&scene, &camera, method, offset, target, clip);
        }
    }
    assert!(compared > 0);
}

/// Cases where the forward differences' pixels depended on the clip when they were
/// anchored at the first *visible* column of each span: random scenes (found by
/// searching 4,000 seeds of `random_case`) where a left clip at `x0` changed a
/// default-method pixel, and an unanchored 8192-wide row (K = 8192) where it changed
/// 183 pixels of `direct/forward-diff/exact`.
#[test]
#[cfg(feature = "bench-baselines")]
fn pinned_cases_where_the_clip_used_to_move_pixels() {
    let full_width = |x0: i32, size: Size| Rectangle::new(Point::new(x0, 0), size);
    for (seed, x0) in [(575u64, 41), (684, 2), (1461, 18)] {
        let mut rng = Rng(0x9E37_79B9_7F4A_7C15 ^ seed.wrapping_mul(0x1234_5678_9abc_def1));
        let (scene, camera) = random_case(&mut rng);
        let size = camera.size();
        check_clip(
            &scene,
            &camera,
            Method::TARGET_DEFAULT,
            Point::zero(),
            size,
            full_width(x0, size),
        );
    }
    let (scene, camera) = common::huge_row();
    let fd = Method::new(Stepping::Direct, SphereTest::ForwardDiff, Sqrt::Exact);
    let options = Options::DEFAULT.with_anchor_interval(8192);
    let whole = common::trace(Render::new(&scene, &camera).with_method(fd).with_options(options));
    for x0 in [1, 7, 100, 2730, 4099] {
        let mut frame = Frame::new(camera.size());
        let clip = full_width(x0, camera.size());
        Render::new(&scene, &camera)
            .with_method(fd)
            .with_options(options)
            .draw(&mut frame.clipped(&clip))
            .unwrap();
        for p in clip.intersection(&frame.bounding_box()).points() {
            assert_eq!(
                frame.get(p),
                Some(whole[(p.y * 8192 + p.x) as usize].1),
                "x0 {x0}: {p:?}"
            );
        }
    }
}
