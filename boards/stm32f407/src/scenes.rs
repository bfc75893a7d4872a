//! `scenes/bounce.toml` (the firmware's animation) and `scenes/lab.toml` (traced by
//! `st7789_band::trace_band` for the lab's `band_cycles` firmware) compiled in
//! (firmware has no file system). The numbers are the files'; the lab's host tests
//! `board_examples` and `board_scenes` load the files and fail if any differs.

use embedded_graphics::{geometry::Size, pixelcolor::Rgb888};
use embedded_raytracer::motion::{Animation, Bounce, Motion};
use embedded_raytracer::{CameraParams, Light, Material, Plane, Scene, Settings, Sphere, Vec3};

const fn sphere(c: [f32; 3], radius: f32, color: [u8; 3]) -> Sphere {
    Sphere::new(
        Vec3::new(c[0], c[1], c[2]),
        radius,
        Rgb888::new(color[0], color[1], color[2]),
    )
}

/// `scenes/lab.toml`'s five spheres on black.
#[allow(dead_code)] // traced by `st7789_band::trace_band` only
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
#[allow(dead_code)] // traced by `st7789_band::trace_band` only
pub const LAB_CAMERA: CameraParams = CameraParams::new(
    Vec3::new(0.0, 0.0, 5.0),
    Vec3::new(0.0, 0.0, 0.0),
    Vec3::new(0.0, 1.0, 0.0),
    // Same conversion as the scene-file loader: f32::to_radians.
    60.0 * (core::f32::consts::PI / 180.0),
    Size::new(320, 240),
);

/// A sphere with a material: `specular`, `shininess`, `reflect` as in the file.
const fn lit_sphere(c: [f32; 3], radius: f32, color: [u8; 3], material: [f32; 3]) -> Sphere {
    sphere(c, radius, color).with_material(Material::new(material[0], material[1], material[2]))
}

/// `scenes/bounce.toml` at rest: the ball resting on the checkered floor beside two
/// still spheres (specular, shininess, reflect), the sun, hard shadows, no mirrors.
pub static BOUNCE: Scene<3, 1, 1, 0> = Scene::from_arrays(
    [
        lit_sphere([0.0, 0.7, 0.5], 0.7, [230, 60, 50], [0.6, 48.0, 0.0]),
        lit_sphere([-1.9, 0.6, -0.6], 0.6, [60, 200, 90], [0.3, 16.0, 0.0]),
        lit_sphere([1.9, 0.45, -0.2], 0.45, [70, 110, 240], [0.8, 96.0, 0.0]),
    ],
    [Light::directional(Vec3::new(0.5, -1.6, -0.7), 0.85)],
    [Plane::new(
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        Rgb888::new(225, 225, 215),
    )
    .with_checker(Rgb888::new(70, 70, 80), 1.0)],
    Rgb888::new(24, 34, 56),
    Settings::DEFAULT
        .with_ambient(0.15)
        .with_max_depth(0)
        .with_shadows(true),
);

/// The camera of `scenes/bounce.toml` (the firmware replaces its size with the panel's).
pub const BOUNCE_CAMERA: CameraParams = CameraParams::new(
    Vec3::new(0.0, 3.0, 7.0),
    Vec3::new(0.0, 1.0, 0.0),
    Vec3::new(0.0, 1.0, 0.0),
    // Same conversion as the scene-file loader: f32::to_radians.
    45.0 * (core::f32::consts::PI / 180.0),
    Size::new(240, 240),
);

/// The motion of `scenes/bounce.toml`: the ball bounces 1.5 high every 1.2 s; 30
/// frames at 25 a second, after which it repeats exactly.
pub const BOUNCE_ANIMATION: Animation<1> = Animation::from_array([Motion::Bounce(Bounce::new(0, 1.5, 1.2))])
    .with_fps(25.0)
    .with_frames(30);
