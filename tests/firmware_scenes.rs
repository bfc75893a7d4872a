//! The firmware's compiled-in scenes (`examples/common/scenes.rs`) are exactly the
//! standard scene files: every number, bit for bit.

#[path = "../examples/common/scenes.rs"]
mod scenes;

use embedded_raytracer::{scene_file, CameraParams, Scene};

fn same<const N: usize>(file: &str, scene: &Scene<N>, camera: CameraParams) {
    let loaded = scene_file::load::<64>(file).unwrap();
    assert_eq!(loaded.scene.spheres(), scene.spheres(), "{file}: spheres differ");
    assert_eq!(
        loaded.scene.background(),
        scene.background(),
        "{file}: background differs"
    );
    let p = *loaded.camera.params();
    // Compare bit patterns so even a last-ulp difference in a conversion fails.
    let bits = |c: CameraParams| {
        let v = |v: embedded_raytracer::Vec3| [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()];
        (
            v(c.eye),
            v(c.look_at),
            v(c.up),
            c.fov_y.to_bits(),
            c.fov_x.map(f32::to_bits),
            c.size,
        )
    };
    assert_eq!(bits(p), bits(camera), "{file}: camera differs");
}

#[test]
fn compiled_in_scenes_match_the_files() {
    same("scenes/lab.toml", &scenes::LAB, scenes::LAB_CAMERA);
    same("scenes/far.toml", &scenes::FAR, scenes::FAR_CAMERA);
    same("scenes/grazing.toml", &scenes::GRAZING, scenes::GRAZING_CAMERA);
    same("scenes/drift.toml", &scenes::DRIFT, scenes::DRIFT_CAMERA);
    same("scenes/crowd.toml", &scenes::CROWD, scenes::CROWD_CAMERA);
}
