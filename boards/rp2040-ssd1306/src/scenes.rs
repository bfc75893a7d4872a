//! `scenes/lab.toml` compiled in (firmware has no file system). The numbers are the
//! file's; the lab's host test `board_examples` loads the file and fails if any differs.

use embedded_graphics::{geometry::Size, pixelcolor::Rgb888};
use embedded_raytracer::{CameraParams, Scene, Sphere, Vec3};

const fn sphere(c: [f32; 3], radius: f32, color: [u8; 3]) -> Sphere {
    Sphere::new(
        Vec3::new(c[0], c[1], c[2]),
        radius,
        Rgb888::new(color[0], color[1], color[2]),
    )
}

/// `scenes/lab.toml`'s five spheres on black.
pub static LAB: Scene<5> = Scene::from_array(
    [
        sphere([0.0, 0.0, 0.0], 1.0, [255, 64, 64]),
        sphere([1.2, 0.6, -1.5], 1.0, [64, 255, 64]),
        sphere([-1.7, -0.5, -0.8], 0.7, [64, 64, 255]),
        sphere([0.5, -0.9, 1.6], 0.35, [255, 255, 64]),
        sphere([-0.6, 1.4, -3.0], 0.9, [64, 255, 255]),
    ],
    Rgb888::new(0, 0, 0),
);

/// The camera of `scenes/lab.toml` (the firmware replaces its size with the panel's).
pub const LAB_CAMERA: CameraParams = CameraParams::new(
    Vec3::new(0.0, 0.0, 5.0),
    Vec3::new(0.0, 0.0, 0.0),
    Vec3::new(0.0, 1.0, 0.0),
    // Same conversion as the scene-file loader: f32::to_radians.
    60.0 * (core::f32::consts::PI / 180.0),
    Size::new(320, 240),
);
