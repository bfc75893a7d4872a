//! The firmware's compiled-in scenes (`examples/common/scenes.rs`) are exactly the
//! standard scene files: every number, bit for bit.

#[path = "../examples/common/scenes.rs"]
mod scenes;

mod common;

use embedded_raytracer::{CameraParams, Scene};

fn same<const N: usize>(file: &str, scene: &Scene<N>, camera: CameraParams) {
    let loaded = common::load(file);
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
    struct Same(Vec<&'static str>);
    impl scenes::EachScene for Same {
        fn scene<const N: usize>(
            &mut self,
            name: &'static str,
            scene: &'static Scene<N>,
            camera: CameraParams,
        ) {
            same(name, scene, camera);
            self.0.push(name);
        }
    }
    let mut checked = Same(Vec::new());
    scenes::for_each(&mut checked);
    // Every standard scene file has its compiled-in copy, in the same order.
    assert_eq!(checked.0, common::SCENES);
}
