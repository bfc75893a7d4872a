//! `scenes/shadows.toml` compiled in (firmware has no file system). The numbers are the
//! file's; the lab's host test `board_examples` loads the file and fails if any differs.

use embedded_graphics::{geometry::Size, pixelcolor::Rgb888};
use embedded_raytracer::{CameraParams, Light, Material, Plane, Scene, Settings, Sphere, Vec3};

const fn sphere(c: [f32; 3], radius: f32, color: [u8; 3], material: [f32; 3]) -> Sphere {
    Sphere::new(
        Vec3::new(c[0], c[1], c[2]),
        radius,
        Rgb888::new(color[0], color[1], color[2]),
    )
    .with_material(Material::new(material[0], material[1], material[2]))
}

/// `scenes/shadows.toml`: 4 spheres (specular, shininess, reflect), a sun and a lamp,
/// a checkered floor, hard shadows, no mirrors.
pub static SHADOWS: Scene<4, 2, 1, 0> = Scene::from_arrays(
    [
        sphere([0.0, 1.0, 0.0], 1.0, [230, 60, 50], [0.6, 48.0, 0.0]),
        sphere([-2.0, 0.6, 0.9], 0.6, [60, 200, 90], [0.3, 16.0, 0.0]),
        sphere([1.6, 1.45, 0.5], 0.5, [70, 110, 240], [0.8, 96.0, 0.0]),
        sphere([0.9, 0.35, 2.0], 0.35, [240, 210, 60], [0.0, 32.0, 0.0]),
    ],
    [
        Light::directional(Vec3::new(1.0, -1.4, -0.6), 0.75),
        Light::point(Vec3::new(3.0, 3.5, 3.5), 0.45),
    ],
    [Plane::new(
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        Rgb888::new(225, 225, 215),
    )
    .with_checker(Rgb888::new(70, 70, 80), 1.0)],
    Rgb888::new(24, 34, 56),
    Settings::DEFAULT
        .with_ambient(0.12)
        .with_max_depth(0)
        .with_shadows(true),
);

/// The camera of `scenes/shadows.toml`.
pub const SHADOWS_CAMERA: CameraParams = CameraParams::new(
    Vec3::new(0.0, 4.0, 6.8),
    Vec3::new(0.0, 0.5, 0.3),
    Vec3::new(0.0, 1.0, 0.0),
    // Same conversion as the scene-file loader: f32::to_radians.
    45.0 * (core::f32::consts::PI / 180.0),
    Size::new(240, 240),
);
