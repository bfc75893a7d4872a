//! The standard scenes (`scenes/*.toml`) as `static`s for firmware, which has no file
//! system: the five Lab #1 scenes ([`for_each`]), the two with lights, a floor and
//! mirrors ([`for_each_feature`]) and the two that move, with their motion as
//! constants ([`for_each_moving`]), each in the scene type of its exact capacities. The
//! numbers are copied from the TOML files; `lab/tests/lab/firmware_scenes.rs` loads every file
//! and fails if any number here differs, so the two cannot diverge.
//!
//! Included with `#[path]` by the firmware examples and the host tests.

#![allow(dead_code)]

use embedded_graphics::{geometry::Size, pixelcolor::Rgb888};
use embedded_raytracer::motion::{Animation, Bounce, Circle, Motion, Orbit};
use embedded_raytracer::{
    CameraParams, Light, Material, Method, Options, Plane, Scene, SecondaryOrigin, Settings, Sphere, Vec3,
};

const fn sphere(c: [f32; 3], radius: f32, color: [u8; 3]) -> Sphere {
    Sphere::new(
        Vec3::new(c[0], c[1], c[2]),
        radius,
        Rgb888::new(color[0], color[1], color[2]),
    )
}

/// A sphere with a material: `specular`, `shininess`, `reflect` as in the file (the
/// loader's defaults where the file gives none: 0, 32, 0).
const fn lit_sphere(c: [f32; 3], radius: f32, color: [u8; 3], material: [f32; 3]) -> Sphere {
    sphere(c, radius, color).with_material(Material::new(material[0], material[1], material[2]))
}

const fn vec3(v: [f32; 3]) -> Vec3 {
    Vec3::new(v[0], v[1], v[2])
}

const fn rgb(c: [u8; 3]) -> Rgb888 {
    Rgb888::new(c[0], c[1], c[2])
}

const fn camera(
    eye: [f32; 3],
    look_at: [f32; 3],
    up: [f32; 3],
    fov_y_deg: f32,
    size: [u32; 2],
) -> CameraParams {
    CameraParams::new(
        Vec3::new(eye[0], eye[1], eye[2]),
        Vec3::new(look_at[0], look_at[1], look_at[2]),
        Vec3::new(up[0], up[1], up[2]),
        // Same conversion as the scene-file loader: f32::to_radians.
        fov_y_deg * (core::f32::consts::PI / 180.0),
        Size::new(size[0], size[1]),
    )
}

/// `scenes/lab.toml`.
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
/// The camera of `scenes/lab.toml`.
pub const LAB_CAMERA: CameraParams = camera(
    [0.0, 0.0, 5.0],
    [0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    60.0,
    [320, 240],
);

/// `scenes/far.toml`.
pub static FAR: Scene<1> = Scene::from_array(
    [sphere([0.0, 0.0, 0.0], 1.0, [255, 160, 64])],
    Rgb888::new(0, 0, 0),
);
/// The camera of `scenes/far.toml`.
pub const FAR_CAMERA: CameraParams = camera(
    [0.0, 0.0, 2000.0],
    [0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    0.1,
    [320, 240],
);

/// `scenes/grazing.toml`.
pub static GRAZING: Scene<3> = Scene::from_array(
    [
        sphere([0.0, 0.0, 0.0], 1.0, [255, 64, 64]),
        sphere([2.0, 0.0, 0.0], 1.0, [64, 255, 64]),
        sphere([0.9, 0.55, 0.45], 0.45, [64, 64, 255]),
    ],
    Rgb888::new(16, 16, 32),
);
/// The camera of `scenes/grazing.toml`.
pub const GRAZING_CAMERA: CameraParams = camera(
    [0.5, 0.3, 0.84],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    90.0,
    [320, 240],
);

/// `scenes/drift.toml`.
pub static DRIFT: Scene<5> = Scene::from_array(
    [
        sphere([1000.0, 1000.0, 995.0], 1.0, [255, 64, 64]),
        sphere([1001.2, 1000.6, 993.5], 1.0, [64, 255, 64]),
        sphere([998.3, 999.5, 994.2], 0.7, [64, 64, 255]),
        sphere([1000.5, 999.1, 996.6], 0.35, [255, 255, 64]),
        sphere([999.4, 1001.4, 992.0], 0.9, [64, 255, 255]),
    ],
    Rgb888::new(0, 0, 0),
);
/// The camera of `scenes/drift.toml`.
pub const DRIFT_CAMERA: CameraParams = camera(
    [1000.0, 1000.0, 1000.0],
    [1000.0, 1000.0, 995.0],
    [0.0, 1.0, 0.0],
    60.0,
    [1920, 1080],
);

/// `scenes/crowd.toml`.
pub static CROWD: Scene<64> = Scene::from_array(
    [
        sphere([-7.0, 0.0, -7.0], 0.55, [64, 64, 255]),
        sphere([-5.0, 0.39, -7.0], 0.8, [91, 64, 244]),
        sphere([-3.0, 0.49, -7.0], 0.7, [118, 64, 233]),
        sphere([-1.0, 0.21, -7.0], 0.6, [145, 64, 222]),
        sphere([1.0, -0.22, -7.0], 0.85, [173, 64, 212]),
        sphere([3.0, -0.49, -7.0], 0.75, [200, 64, 201]),
        sphere([5.0, -0.39, -7.0], 0.65, [227, 64, 190]),
        sphere([7.0, 0.01, -7.0], 0.55, [255, 64, 180]),
        sphere([-7.0, 0.28, -5.0], 0.7, [64, 91, 244]),
        sphere([-5.0, 0.5, -5.0], 0.6, [91, 91, 233]),
        sphere([-3.0, 0.34, -5.0], 0.85, [118, 91, 222]),
        sphere([-1.0, -0.08, -5.0], 0.75, [145, 91, 212]),
        sphere([1.0, -0.44, -5.0], 0.65, [173, 91, 201]),
        sphere([3.0, -0.46, -5.0], 0.55, [200, 91, 190]),
        sphere([5.0, -0.14, -5.0], 0.8, [227, 91, 180]),
        sphere([7.0, 0.29, -5.0], 0.7, [255, 91, 169]),
        sphere([-7.0, 0.47, -3.0], 0.85, [64, 118, 233]),
        sphere([-5.0, 0.43, -3.0], 0.75, [91, 118, 222]),
        sphere([-3.0, 0.07, -3.0], 0.65, [118, 118, 212]),
        sphere([-1.0, -0.34, -3.0], 0.55, [145, 118, 201]),
        sphere([1.0, -0.5, -3.0], 0.8, [173, 118, 190]),
        sphere([3.0, -0.28, -3.0], 0.7, [200, 118, 180]),
        sphere([5.0, 0.16, -3.0], 0.6, [227, 118, 169]),
        sphere([7.0, 0.47, -3.0], 0.85, [255, 118, 158]),
        sphere([-7.0, 0.49, -1.0], 0.65, [64, 145, 222]),
        sphere([-5.0, 0.21, -1.0], 0.55, [91, 145, 212]),
        sphere([-3.0, -0.22, -1.0], 0.8, [118, 145, 201]),
        sphere([-1.0, -0.49, -1.0], 0.7, [145, 145, 190]),
        sphere([1.0, -0.39, -1.0], 0.6, [173, 145, 180]),
        sphere([3.0, 0.01, -1.0], 0.85, [200, 145, 169]),
        sphere([5.0, 0.4, -1.0], 0.75, [227, 145, 158]),
        sphere([7.0, 0.48, -1.0], 0.65, [255, 145, 147]),
        sphere([-7.0, 0.34, 1.0], 0.8, [64, 173, 212]),
        sphere([-5.0, -0.08, 1.0], 0.7, [91, 173, 201]),
        sphere([-3.0, -0.44, 1.0], 0.6, [118, 173, 190]),
        sphere([-1.0, -0.46, 1.0], 0.85, [145, 173, 180]),
        sphere([1.0, -0.14, 1.0], 0.75, [173, 173, 169]),
        sphere([3.0, 0.29, 1.0], 0.65, [200, 173, 158]),
        sphere([5.0, 0.5, 1.0], 0.55, [227, 173, 147]),
        sphere([7.0, 0.33, 1.0], 0.8, [255, 173, 137]),
        sphere([-7.0, 0.07, 3.0], 0.6, [64, 200, 201]),
        sphere([-5.0, -0.34, 3.0], 0.85, [91, 200, 190]),
        sphere([-3.0, -0.5, 3.0], 0.75, [118, 200, 180]),
        sphere([-1.0, -0.28, 3.0], 0.65, [145, 200, 169]),
        sphere([1.0, 0.16, 3.0], 0.55, [173, 200, 158]),
        sphere([3.0, 0.47, 3.0], 0.8, [200, 200, 147]),
        sphere([5.0, 0.43, 3.0], 0.7, [227, 200, 137]),
        sphere([7.0, 0.06, 3.0], 0.6, [255, 200, 126]),
        sphere([-7.0, -0.22, 5.0], 0.75, [64, 227, 190]),
        sphere([-5.0, -0.49, 5.0], 0.65, [91, 227, 180]),
        sphere([-3.0, -0.39, 5.0], 0.55, [118, 227, 169]),
        sphere([-1.0, 0.01, 5.0], 0.8, [145, 227, 158]),
        sphere([1.0, 0.4, 5.0], 0.7, [173, 227, 147]),
        sphere([3.0, 0.48, 5.0], 0.6, [200, 227, 137]),
        sphere([5.0, 0.21, 5.0], 0.85, [227, 227, 126]),
        sphere([7.0, -0.23, 5.0], 0.75, [255, 227, 115]),
        sphere([-7.0, -0.44, 7.0], 0.55, [64, 255, 180]),
        sphere([-5.0, -0.46, 7.0], 0.8, [91, 255, 169]),
        sphere([-3.0, -0.14, 7.0], 0.7, [118, 255, 158]),
        sphere([-1.0, 0.29, 7.0], 0.6, [145, 255, 147]),
        sphere([1.0, 0.5, 7.0], 0.85, [173, 255, 137]),
        sphere([3.0, 0.33, 7.0], 0.75, [200, 255, 126]),
        sphere([5.0, -0.09, 7.0], 0.65, [227, 255, 115]),
        sphere([7.0, -0.44, 7.0], 0.55, [255, 255, 105]),
    ],
    Rgb888::new(0, 0, 0),
);
/// The camera of `scenes/crowd.toml`.
pub const CROWD_CAMERA: CameraParams = camera(
    [0.0, 6.0, 14.0],
    [0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    60.0,
    [320, 240],
);

/// `scenes/shadows.toml`: 4 spheres, 2 lights, 1 plane, no mirror (`D = 0`: no
/// reflection loop; `max_depth` is the type's default, 0, as the loader gives it).
pub static SHADOWS: Scene<4, 2, 1, 0> = Scene::from_arrays(
    [
        lit_sphere([0.0, 1.0, 0.0], 1.0, [230, 60, 50], [0.6, 48.0, 0.0]),
        lit_sphere([-2.0, 0.6, 0.9], 0.6, [60, 200, 90], [0.3, 16.0, 0.0]),
        lit_sphere([1.6, 1.45, 0.5], 0.5, [70, 110, 240], [0.8, 96.0, 0.0]),
        lit_sphere([0.9, 0.35, 2.0], 0.35, [240, 210, 60], [0.0, 32.0, 0.0]),
    ],
    [
        Light::directional(vec3([1.0, -1.4, -0.6]), 0.75),
        Light::point(vec3([3.0, 3.5, 3.5]), 0.45),
    ],
    [
        Plane::new(vec3([0.0, 0.0, 0.0]), vec3([0.0, 1.0, 0.0]), rgb([225, 225, 215]))
            .with_checker(rgb([70, 70, 80]), 1.0),
    ],
    Rgb888::new(24, 34, 56),
    Settings::DEFAULT
        .with_ambient(0.12)
        .with_max_depth(0)
        .with_shadows(true),
);
/// The camera of `scenes/shadows.toml`.
pub const SHADOWS_CAMERA: CameraParams = camera(
    [0.0, 4.0, 6.8],
    [0.0, 0.5, 0.3],
    [0.0, 1.0, 0.0],
    45.0,
    [240, 240],
);

/// `scenes/mirrors.toml`: 5 spheres, 1 light, 1 plane, reflections 3 deep.
pub static MIRRORS: Scene<5, 1, 1, 3> = Scene::from_arrays(
    [
        lit_sphere([-0.7, 1.1, 0.0], 1.1, [200, 200, 210], [0.9, 128.0, 0.85]),
        lit_sphere([1.35, 0.7, 0.5], 0.7, [210, 190, 150], [0.8, 96.0, 0.7]),
        lit_sphere([0.6, 0.4, 2.1], 0.4, [220, 50, 60], [0.6, 48.0, 0.25]),
        lit_sphere([-2.3, 0.5, 1.4], 0.5, [50, 120, 230], [0.6, 48.0, 0.25]),
        lit_sphere([1.0, 0.45, -2.0], 0.45, [60, 200, 100], [0.5, 32.0, 0.2]),
    ],
    [Light::directional(vec3([-0.8, -1.5, -1.0]), 0.9)],
    [
        Plane::new(vec3([0.0, 0.0, 0.0]), vec3([0.0, 1.0, 0.0]), rgb([230, 230, 230]))
            .with_checker(rgb([40, 40, 50]), 1.0)
            .with_material(Material::new(0.0, 32.0, 0.15)),
    ],
    Rgb888::new(110, 150, 210),
    Settings::DEFAULT
        .with_ambient(0.15)
        .with_max_depth(3)
        .with_shadows(true),
);
/// The camera of `scenes/mirrors.toml`.
pub const MIRRORS_CAMERA: CameraParams = camera(
    [0.0, 3.2, 6.5],
    [0.0, 0.7, 0.2],
    [0.0, 1.0, 0.0],
    45.0,
    [240, 240],
);

/// `scenes/bounce.toml` at rest: 3 spheres (the ball resting on the floor), 1 light, 1
/// plane, no mirror.
pub static BOUNCE: Scene<3, 1, 1, 0> = Scene::from_arrays(
    [
        lit_sphere([0.0, 0.7, 0.5], 0.7, [230, 60, 50], [0.6, 48.0, 0.0]),
        lit_sphere([-1.9, 0.6, -0.6], 0.6, [60, 200, 90], [0.3, 16.0, 0.0]),
        lit_sphere([1.9, 0.45, -0.2], 0.45, [70, 110, 240], [0.8, 96.0, 0.0]),
    ],
    [Light::directional(vec3([0.5, -1.6, -0.7]), 0.85)],
    [
        Plane::new(vec3([0.0, 0.0, 0.0]), vec3([0.0, 1.0, 0.0]), rgb([225, 225, 215]))
            .with_checker(rgb([70, 70, 80]), 1.0),
    ],
    Rgb888::new(24, 34, 56),
    Settings::DEFAULT
        .with_ambient(0.15)
        .with_max_depth(0)
        .with_shadows(true),
);
/// The camera of `scenes/bounce.toml`.
pub const BOUNCE_CAMERA: CameraParams = camera(
    [0.0, 3.0, 7.0],
    [0.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
    45.0,
    [240, 240],
);
/// The motion of `scenes/bounce.toml`: the ball bounces 1.5 high every 1.2 s; 30
/// frames at 25 a second.
pub const BOUNCE_ANIMATION: Animation<1> = Animation::from_array([Motion::Bounce(Bounce::new(0, 1.5, 1.2))])
    .with_fps(25.0)
    .with_frames(30);
/// `bounce` seen by a camera that orbits it: the ball bounces as in
/// [`BOUNCE_ANIMATION`] and the camera turns once about the look-at point in the same
/// 1.2 s, so every frame is drawn whole. 10 frames (36° apart, one bounce): the
/// measurement of a lit frame from every side, not a frame rate to show.
pub const BOUNCE_ORBIT_ANIMATION: Animation<2> = Animation::from_array([
    Motion::Bounce(Bounce::new(0, 1.5, 1.2)),
    Motion::Orbit(Orbit::new(1.2)),
])
.with_fps(10.0 / 1.2)
.with_frames(10);

/// `scenes/circling.toml` at rest: Lab #1 spheres only.
pub static CIRCLING: Scene<3> = Scene::from_array(
    [
        sphere([0.0, 0.0, 1.2], 0.8, [255, 64, 64]),
        sphere([0.0, 0.0, -1.2], 0.6, [64, 64, 255]),
        sphere([2.6, 0.3, 0.0], 0.35, [255, 255, 64]),
    ],
    Rgb888::new(0, 0, 0),
);
/// The camera of `scenes/circling.toml`.
pub const CIRCLING_CAMERA: CameraParams = camera(
    [0.0, 3.0, 8.0],
    [0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    45.0,
    [240, 240],
);
/// The motion of `scenes/circling.toml`: the red and blue spheres on opposite points of
/// one circle (a turn in 4 s), the yellow one around both (a turn in 2 s); 100 frames
/// at 25 a second.
pub const CIRCLING_ANIMATION: Animation<3> = Animation::from_array([
    Motion::Circle(Circle::new(0, vec3([0.0, 0.0, 0.0]), 1.2, 4.0, 0.0)),
    Motion::Circle(Circle::new(1, vec3([0.0, 0.0, 0.0]), 1.2, 4.0, 0.5)),
    Motion::Circle(Circle::new(2, vec3([0.0, 0.3, 0.0]), 2.6, 2.0, 0.25)),
])
.with_fps(25.0)
.with_frames(100);

/// The standard scenes that move, in the order of [`for_each_moving`].
pub const MOVING_SCENES: [&str; 2] = ["bounce", "circling"];

/// Work done on each standard scene that moves, whatever its type.
pub trait EachMovingScene {
    /// Called once per moving standard scene with its name (the file's stem), the
    /// scene at rest, its camera and its motion.
    fn scene<const N: usize, const L: usize, const P: usize, const D: usize, const M: usize>(
        &mut self,
        name: &'static str,
        scene: &'static Scene<N, L, P, D>,
        camera: CameraParams,
        animation: &Animation<M>,
    );
}

/// Calls `work` on every standard scene that moves ([`MOVING_SCENES`]).
pub fn for_each_moving(work: &mut impl EachMovingScene) {
    work.scene("bounce", &BOUNCE, BOUNCE_CAMERA, &BOUNCE_ANIMATION);
    work.scene("circling", &CIRCLING, CIRCLING_CAMERA, &CIRCLING_ANIMATION);
}

/// Work done on each standard scene, whatever its type.
pub trait EachScene {
    /// Called once per standard scene with its name (the file's stem), the scene and
    /// its camera.
    fn scene<const N: usize, const L: usize, const P: usize, const D: usize>(
        &mut self,
        name: &'static str,
        scene: &'static Scene<N, L, P, D>,
        camera: CameraParams,
    );
}

/// Calls `work` on every standard scene, in the order of every table (the order of
/// `embedded_raytracer_scenes::SCENES`).
pub fn for_each(work: &mut impl EachScene) {
    work.scene("lab", &LAB, LAB_CAMERA);
    work.scene("far", &FAR, FAR_CAMERA);
    work.scene("grazing", &GRAZING, GRAZING_CAMERA);
    work.scene("drift", &DRIFT, DRIFT_CAMERA);
    work.scene("crowd", &CROWD, CROWD_CAMERA);
}

/// Calls `work` on every standard scene with lights, a floor and mirrors, in the order
/// of every table (`embedded_raytracer_scenes::FEATURE_SCENES`).
pub fn for_each_feature(work: &mut impl EachScene) {
    work.scene("shadows", &SHADOWS, SHADOWS_CAMERA);
    work.scene("mirrors", &MIRRORS, MIRRORS_CAMERA);
}

/// The renders measured on the scenes of [`for_each_feature`] (firmware and host
/// alike), each `(method, label suffix, options)` and labelled `METHOD` + suffix:
///
/// - `direct/auto/exact`: the default method and options;
/// - `direct/auto/exact+literal`: the default method with the literal options (no span
///   culling, closest-hit shadow rays: every object tested for every ray). Not the
///   default's pixels: the forward-differenced test anchors at span starts;
/// - `world-space/algebraic/exact+literal`: the seed's method with the literal options,
///   the benchmarks' baseline;
/// - `direct/auto/exact+epsilon`: the default with the textbook fixed epsilon for
///   secondary rays (`SecondaryOrigin::TEXTBOOK`).
pub const FEATURE_RENDERS: [(Method, &str, Options); 4] = [
    (Method::TARGET_DEFAULT, "", Options::DEFAULT),
    (Method::TARGET_DEFAULT, "+literal", LITERAL_OPTIONS),
    (Method::LITERAL, "+literal", LITERAL_OPTIONS),
    (
        Method::TARGET_DEFAULT,
        "+epsilon",
        Options::DEFAULT.with_secondary(SecondaryOrigin::TEXTBOOK),
    ),
];

/// Every object tested for every ray, closest-hit shadow rays.
const LITERAL_OPTIONS: Options = Options::DEFAULT
    .with_span_culling(false)
    .with_shadow_any_hit(false);
