//! `scenes/bounce.toml` compiled in (firmware has no file system): the scene at rest,
//! its camera and its motion. The numbers are the file's; the lab's host test
//! `board_examples` loads the file and fails if any differs.

use embedded_graphics::{geometry::Size, pixelcolor::Rgb888};
use embedded_raytracer::motion::{Animation, Bounce, Motion};
use embedded_raytracer::{CameraParams, Light, Material, Plane, Scene, Settings, Sphere, Vec3};

const fn sphere(c: [f32; 3], radius: f32, color: [u8; 3], material: [f32; 3]) -> Sphere {
    Sphere::new(
        Vec3::new(c[0], c[1], c[2]),
        radius,
        Rgb888::new(color[0], color[1], color[2]),
    )
    .with_material(Material::new(material[0], material[1], material[2]))
}

/// `scenes/bounce.toml` at rest: the ball resting on the checkered floor beside two
/// still spheres (specular, shininess, reflect), the sun, hard shadows, no mirrors.
pub static BOUNCE: Scene<3, 1, 1, 0> = Scene::from_arrays(
    [
        sphere([0.0, 0.7, 0.5], 0.7, [230, 60, 50], [0.6, 48.0, 0.0]),
        sphere([-1.9, 0.6, -0.6], 0.6, [60, 200, 90], [0.3, 16.0, 0.0]),
        sphere([1.9, 0.45, -0.2], 0.45, [70, 110, 240], [0.8, 96.0, 0.0]),
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
