//! The root firmware example's compiled-in scene, and the STM32 board's that its
//! `band_cycles` band path traces, is `scenes/lab.toml`:
//! every number of each copy equals the file's, so that no copy can drift from it.

use embedded_raytracer::{CameraParams, Scene};
use embedded_raytracer_scenes as standard;

#[path = "../../../examples/stm32f407_st7789/scenes.rs"]
mod root_example;
// Its `bounce` scene is checked by `board_examples`, which uses this module.
#[path = "../../../boards/stm32f407/src/scenes.rs"]
pub(crate) mod stm32f407;

/// `scene` and `camera` against the file, bit for bit; the camera's size is the
/// firmware's to replace.
pub(crate) fn check(what: &str, scene: &Scene<5>, camera: CameraParams) {
    let file = standard::load("lab");
    let spheres = scene.spheres();
    assert_eq!(spheres.len(), file.scene.spheres().len(), "{what}: sphere count");
    for (k, (a, b)) in spheres.iter().zip(file.scene.spheres()).enumerate() {
        assert_eq!(
            a.center.x.to_bits(),
            b.center.x.to_bits(),
            "{what}: sphere[{k}].center.x"
        );
        assert_eq!(
            a.center.y.to_bits(),
            b.center.y.to_bits(),
            "{what}: sphere[{k}].center.y"
        );
        assert_eq!(
            a.center.z.to_bits(),
            b.center.z.to_bits(),
            "{what}: sphere[{k}].center.z"
        );
        assert_eq!(
            a.radius.to_bits(),
            b.radius.to_bits(),
            "{what}: sphere[{k}].radius"
        );
        assert_eq!(a.color, b.color, "{what}: sphere[{k}].color");
    }
    assert_eq!(scene.background(), file.scene.background(), "{what}: background");
    let p = file.camera.params();
    for (name, a, b) in [
        ("eye", camera.eye, p.eye),
        ("look_at", camera.look_at, p.look_at),
        ("up", camera.up, p.up),
    ] {
        assert_eq!(
            [a.x.to_bits(), a.y.to_bits(), a.z.to_bits()],
            [b.x.to_bits(), b.y.to_bits(), b.z.to_bits()],
            "{what}: camera.{name}"
        );
    }
    assert_eq!(
        camera.fov_y.to_bits(),
        p.fov_y.to_bits(),
        "{what}: camera.fov_y_deg"
    );
}

#[test]
fn every_boards_compiled_in_lab_scene_is_the_file() {
    check(
        "examples/stm32f407_st7789",
        &root_example::LAB,
        root_example::LAB_CAMERA,
    );
    check("boards/stm32f407", &stm32f407::LAB, stm32f407::LAB_CAMERA);
}
