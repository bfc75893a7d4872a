//! Camera: the seed's basis, pixel size, upper-left pixel centre and steps, and every
//! construction error.

use embedded_graphics::geometry::Size;
use embedded_raytracer::{Camera, CameraError, CameraParam, CameraParams, Vec3};
use embedded_raytracer::{MAX_FOV, MAX_RESOLUTION, MIN_PIXEL_SIZE, MIN_UP_ANGLE};

fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
    (a - b).length() <= tol
}

fn params() -> CameraParams {
    CameraParams::new(
        Vec3::new(1.0, 2.0, 3.0),
        Vec3::new(-2.0, 0.5, -4.0),
        Vec3::new(0.1, 1.0, 0.2),
        50f32.to_radians(),
        Size::new(320, 240),
    )
}

#[test]
fn basis_is_orthonormal_and_right_handed() {
    let cam = params().build().unwrap();
    let (u, v, w) = (cam.u(), cam.v(), cam.w());
    for (name, x) in [("u", u), ("v", v), ("w", w)] {
        assert!((x.length() - 1.0).abs() < 1e-6, "|{name}| = {}", x.length());
    }
    assert!(u.dot(v).abs() < 1e-6 && u.dot(w).abs() < 1e-6 && v.dot(w).abs() < 1e-6);
    // u = w × up (normalised), v = u × w: (u, v, −w) is a right-handed frame.
    assert!(
        close(u.cross(v), -w, 1e-6),
        "u × v = {:?}, −w = {:?}",
        u.cross(v),
        -w
    );
    // v points to the same side as up.
    assert!(v.dot(params().up) > 0.0);
    // w points at the look-at point.
    let to_target = params().look_at - params().eye;
    assert!(close(w * to_target.length(), to_target, 1e-5));
}

#[test]
fn seed_camera_looks_down_minus_z() {
    let cam = Camera::new(
        Vec3::new(0.0, 0.0, 5.0),
        Vec3::ZERO,
        Vec3::new(0.0, 1.0, 0.0),
        90f32.to_radians(),
        Size::new(4, 2),
    )
    .unwrap();
    assert_eq!(cam.w(), Vec3::new(0.0, 0.0, -1.0));
    assert_eq!(cam.u(), Vec3::new(1.0, 0.0, 0.0));
    assert_eq!(cam.v(), Vec3::new(0.0, 1.0, 0.0));
    // pixel_height = 2·tan(45°)/2 = 1; square pixels.
    assert!((cam.pixel_height() - 1.0).abs() < 1e-6);
    assert_eq!(cam.pixel_width(), cam.pixel_height());
    // Upper-left pixel centre: w − (W/2)·pw·u + (H/2)·ph·v + (pw/2)·u − (ph/2)·v
    // = (0,0,−1) + (−2 + 0.5, 1 − 0.5, 0) = (−1.5, 0.5, −1).
    assert!(close(cam.first_direction(), Vec3::new(-1.5, 0.5, -1.0), 1e-6));
    assert!(close(cam.upper_left_world(), Vec3::new(-1.5, 0.5, 4.0), 1e-6));
    assert!(close(cam.pixel_step(), Vec3::new(1.0, 0.0, 0.0), 1e-6));
    assert!(close(cam.scanline_step(), Vec3::new(0.0, -1.0, 0.0), 1e-6));
}

/// The stepped pixel centres (the slides' `pixelCenter += pw·u`,
/// `scanlineStart −= ph·v`, camera-relative) agree with the seed's direct formula.
#[test]
fn stepped_centres_match_direct_formula() {
    let cam = params().build().unwrap();
    let size = cam.size();
    let pw = cam.pixel_width();
    let mut row = cam.first_direction();
    let mut worst = 0.0f32;
    for j in 0..size.height {
        let mut d = row;
        for i in 0..size.width {
            let direct = cam.direction(i, j);
            worst = worst.max((d - direct).length() / pw);
            d += cam.pixel_step();
        }
        row += cam.scanline_step();
    }
    // Fully accumulated over 320 + 240 steps: well under a hundredth of a pixel here.
    assert!(
        worst < 0.01,
        "stepped centres drift {worst} px from the direct formula"
    );
    assert!(close(cam.direction(0, 0), cam.first_direction(), 1e-6));
    assert!(close(
        cam.upper_left_world() - cam.eye(),
        cam.first_direction(),
        1e-5
    ));
}

#[test]
fn non_square_pixels() {
    let cam = params().with_fov_x(80f32.to_radians()).build().unwrap();
    let pw = 2.0 * (40f32.to_radians()).tan() / 320.0;
    let ph = 2.0 * (25f32.to_radians()).tan() / 240.0;
    assert!((cam.pixel_width() - pw).abs() < 1e-7 * pw.max(1.0));
    assert!((cam.pixel_height() - ph).abs() < 1e-7);
    // The right edge of the image plane is at tan(fov_x/2).
    let last = cam.direction(319, 120);
    let right_edge = last.dot(cam.u()) + pw / 2.0;
    assert!((right_edge - 40f32.to_radians().tan()).abs() < 1e-5);
}

#[test]
fn tiny_images() {
    for size in [Size::new(1, 1), Size::new(1, 7), Size::new(7, 1)] {
        let cam = CameraParams { size, ..params() }.build().unwrap();
        if size == Size::new(1, 1) {
            // The only pixel's centre is the image centre: the ray is w.
            assert!(close(cam.direction(0, 0), cam.w(), 1e-6));
        }
    }
}

#[test]
fn every_error_case() {
    let p = params();
    let nan = f32::NAN;
    let cases: [(CameraParams, CameraError); 17] = [
        (
            CameraParams {
                eye: Vec3::new(nan, 0.0, 0.0),
                ..p
            },
            CameraError::NotFinite(CameraParam::Eye),
        ),
        (
            CameraParams {
                look_at: Vec3::new(0.0, f32::INFINITY, 0.0),
                ..p
            },
            CameraError::NotFinite(CameraParam::LookAt),
        ),
        (
            CameraParams {
                up: Vec3::new(0.0, 0.0, nan),
                ..p
            },
            CameraError::NotFinite(CameraParam::Up),
        ),
        (
            CameraParams { fov_y: nan, ..p },
            CameraError::NotFinite(CameraParam::FovY),
        ),
        (
            p.with_fov_x(f32::INFINITY),
            CameraError::NotFinite(CameraParam::FovX),
        ),
        (CameraParams { look_at: p.eye, ..p }, CameraError::EyeAtLookAt),
        (
            CameraParams { up: Vec3::ZERO, ..p },
            CameraError::UpParallelToView,
        ),
        (
            CameraParams {
                up: p.look_at - p.eye,
                ..p
            },
            CameraError::UpParallelToView,
        ),
        (
            CameraParams {
                up: p.eye - p.look_at,
                ..p
            },
            CameraError::UpParallelToView,
        ),
        (
            CameraParams { fov_y: 0.0, ..p },
            CameraError::FovOutOfRange(CameraParam::FovY),
        ),
        (
            CameraParams { fov_y: -0.5, ..p },
            CameraError::FovOutOfRange(CameraParam::FovY),
        ),
        (
            CameraParams {
                fov_y: core::f32::consts::PI,
                ..p
            },
            CameraError::FovOutOfRange(CameraParam::FovY),
        ),
        (
            p.with_fov_x(179.5f32.to_radians()),
            CameraError::FovOutOfRange(CameraParam::FovX),
        ),
        (
            CameraParams { fov_y: 1e-6, ..p },
            CameraError::FovTooNarrow(CameraParam::FovY),
        ),
        (
            CameraParams {
                size: Size::new(0, 10),
                ..p
            },
            CameraError::ZeroResolution,
        ),
        (
            CameraParams {
                size: Size::new(10, 0),
                ..p
            },
            CameraError::ZeroResolution,
        ),
        (
            CameraParams {
                size: Size::new(MAX_RESOLUTION + 1, 10),
                ..p
            },
            CameraError::ResolutionTooLarge,
        ),
    ];
    for (params, expected) in cases {
        let got = params.build();
        assert_eq!(got.err(), Some(expected), "{params:?}");
        // Each error says what is wrong, naming the field.
        let message = expected.to_string();
        assert!(!message.is_empty());
    }
    assert!(CameraError::FovOutOfRange(CameraParam::FovY)
        .to_string()
        .contains("fov_y_deg"));
    assert!(CameraError::UpParallelToView.to_string().contains("up"));
}

#[test]
fn limits_are_where_the_docs_say() {
    let p = params();
    // The widest accepted field of view is MAX_FOV itself.
    assert!(CameraParams { fov_y: MAX_FOV, ..p }.build().is_ok());
    // The narrowest: pixel height just at MIN_PIXEL_SIZE is accepted, half of it is not.
    let fov_at = |pixel: f32| 2.0 * (pixel * 240.0 / 2.0).atan();
    assert!(CameraParams {
        fov_y: fov_at(MIN_PIXEL_SIZE * 1.01),
        ..p
    }
    .build()
    .is_ok());
    assert_eq!(
        CameraParams {
            fov_y: fov_at(MIN_PIXEL_SIZE * 0.5),
            ..p
        }
        .build()
        .err(),
        Some(CameraError::FovTooNarrow(CameraParam::FovY))
    );
    // Up tilted from the view direction by 2·MIN_UP_ANGLE is accepted, by half of it refused.
    let w = (p.look_at - p.eye).try_normalize().unwrap();
    let side = w.cross(Vec3::new(0.0, 1.0, 0.0)).try_normalize().unwrap();
    let tilted = |angle: f32| w * angle.cos() + side * angle.sin();
    assert!(CameraParams {
        up: tilted(2.0 * MIN_UP_ANGLE),
        ..p
    }
    .build()
    .is_ok());
    assert_eq!(
        CameraParams {
            up: tilted(0.5 * MIN_UP_ANGLE),
            ..p
        }
        .build()
        .err(),
        Some(CameraError::UpParallelToView)
    );
    assert!(CameraParams {
        size: Size::new(MAX_RESOLUTION, MAX_RESOLUTION),
        ..p
    }
    .build()
    .is_ok());
}

/// No constructor lets a NaN out: a coarse sweep over awkward inputs either errors or
/// yields a camera whose every stored number is finite.
#[test]
fn no_nan_leaves_the_constructor() {
    let values = [0.0f32, -0.0, 1e-30, 1e-7, 1.0, -1.0, 1e7, 3e38, -3e38];
    let mut built = 0;
    for &a in &values {
        for &b in &values {
            let p = CameraParams {
                eye: Vec3::new(a, b, 1.0),
                look_at: Vec3::new(b, 0.0, a),
                up: Vec3::new(0.0, a, b),
                ..params()
            };
            if let Ok(cam) = p.build() {
                built += 1;
                for x in [cam.u(), cam.v(), cam.w(), cam.first_direction(), cam.pixel_step()] {
                    assert!(x.is_finite(), "{p:?} -> {x:?}");
                }
                assert!(cam.upper_left_world().is_finite());
            }
        }
    }
    assert!(built > 10, "only {built} cameras built");
}

/// Points far apart, or a huge or tiny `up`, are valid cameras: the view direction and
/// `up` are normalised without overflowing `|v|²` (which read as "same point" and
/// "parallel").
#[test]
fn far_eyes_and_extreme_up_vectors_are_normalised() {
    let size = Size::new(64, 48);
    let y = Vec3::new(0.0, 1.0, 0.0);
    let reference = Camera::new(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, y, 1.0, size).unwrap();
    for (eye, look_at, up) in [
        (Vec3::new(0.0, 0.0, 1e20), Vec3::ZERO, y),
        (Vec3::new(0.0, 0.0, 3e38), Vec3::new(0.0, 0.0, -3e38), y),
        (Vec3::new(0.0, 0.0, 1e-30), Vec3::ZERO, y),
        (Vec3::new(0.0, 0.0, 1e-45), Vec3::ZERO, y),
        (Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::new(0.0, 3e38, 0.0)),
        (Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::new(0.0, 1e-40, 0.0)),
    ] {
        let cam = Camera::new(eye, look_at, up, 1.0, size)
            .unwrap_or_else(|e| panic!("eye {eye:?}, look_at {look_at:?}, up {up:?}: {e}"));
        for (name, got, want) in [
            ("u", cam.u(), reference.u()),
            ("v", cam.v(), reference.v()),
            ("w", cam.w(), reference.w()),
        ] {
            assert_eq!(got, want, "{name} for eye {eye:?}, up {up:?}");
        }
    }
    // A huge `up` at 45° to the view is accepted with the direction of (0, 1, 1).
    let eye = Vec3::new(0.0, 0.0, 5.0);
    let huge = Camera::new(eye, Vec3::ZERO, Vec3::new(0.0, 3e38, 3e38), 1.0, size).unwrap();
    let plain = Camera::new(eye, Vec3::ZERO, Vec3::new(0.0, 1.0, 1.0), 1.0, size).unwrap();
    assert!(close(huge.v(), plain.v(), 1e-6));
    // The same point is still refused, and a zero up.
    assert_eq!(Camera::new(eye, eye, y, 1.0, size), Err(CameraError::EyeAtLookAt));
    assert_eq!(
        Camera::new(eye, Vec3::ZERO, Vec3::ZERO, 1.0, size),
        Err(CameraError::UpParallelToView)
    );
}
