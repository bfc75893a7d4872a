//! `scenes/circling.toml` compiled in (firmware has no file system): the scene at rest,
//! its camera and its motion. The numbers are the file's; the lab's host test
//! `board_examples` loads the file and fails if any differs.

use embedded_graphics::{geometry::Size, pixelcolor::Rgb888};
use embedded_raytracer::motion::{Animation, Circle, Motion};
use embedded_raytracer::{CameraParams, Scene, Sphere, Vec3};

const fn sphere(c: [f32; 3], radius: f32, color: [u8; 3]) -> Sphere {
    Sphere::new(
        Vec3::new(c[0], c[1], c[2]),
        radius,
        Rgb888::new(color[0], color[1], color[2]),
    )
}

/// `scenes/circling.toml` at rest: three spheres on black, no lights (the integer
/// kernel's kind of scene).
pub static CIRCLING: Scene<3> = Scene::from_array(
    [
        sphere([0.0, 0.0, 1.2], 0.8, [255, 64, 64]),
        sphere([0.0, 0.0, -1.2], 0.6, [64, 64, 255]),
        sphere([2.6, 0.3, 0.0], 0.35, [255, 255, 64]),
    ],
    Rgb888::new(0, 0, 0),
);

/// The camera of `scenes/circling.toml` (the firmware replaces its size with the
/// panel's).
pub const CIRCLING_CAMERA: CameraParams = CameraParams::new(
    Vec3::new(0.0, 3.0, 8.0),
    Vec3::new(0.0, 0.0, 0.0),
    Vec3::new(0.0, 1.0, 0.0),
    // Same conversion as the scene-file loader: f32::to_radians.
    45.0 * (core::f32::consts::PI / 180.0),
    Size::new(240, 240),
);

/// The motion of `scenes/circling.toml`: the red and blue spheres on opposite points of
/// one circle (a turn in 4 s), the yellow one around both (a turn in 2 s); 100 frames
/// at 25 a second, after which it repeats exactly.
pub const CIRCLING_ANIMATION: Animation<3> = Animation::from_array([
    Motion::Circle(Circle::new(0, Vec3::new(0.0, 0.0, 0.0), 1.2, 4.0, 0.0)),
    Motion::Circle(Circle::new(1, Vec3::new(0.0, 0.0, 0.0), 1.2, 4.0, 0.5)),
    Motion::Circle(Circle::new(2, Vec3::new(0.0, 0.3, 0.0), 2.6, 2.0, 0.25)),
])
.with_fps(25.0)
.with_frames(100);
