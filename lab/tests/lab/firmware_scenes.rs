//! The firmware's compiled-in scenes (`lab/src/scenes.rs`) are exactly the
//! standard scene files: every number, bit for bit, and each scene type's capacities
//! exactly what its file holds.

use embedded_raytracer_lab::scenes;
use embedded_raytracer_lab::standard;

use embedded_raytracer::{scene_file, CameraParams, Scene};

/// `file` loaded as the compiled-in scene's own type (so the loader applies that
/// type's defaults, e.g. the reflection depth of a type without mirrors) must equal
/// the compiled-in scene and camera in every bit.
pub(crate) fn same<const N: usize, const L: usize, const P: usize, const D: usize>(
    file: &str,
    scene: &Scene<N, L, P, D>,
    camera: CameraParams,
) {
    let loaded: scene_file::SceneFile<N, L, P, D> =
        scene_file::load(standard::path(file)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(loaded.scene.spheres(), scene.spheres(), "{file}: spheres differ");
    assert_eq!(loaded.scene.lights(), scene.lights(), "{file}: lights differ");
    assert_eq!(loaded.scene.planes(), scene.planes(), "{file}: planes differ");
    assert_eq!(
        loaded.scene.background(),
        scene.background(),
        "{file}: background differs"
    );
    assert_eq!(
        loaded.scene.settings(),
        scene.settings(),
        "{file}: settings differ"
    );
    // `==` on `f32` equates 0.0 and -0.0; `{:?}` prints each value's shortest
    // round-trip form (and the sign of zero), so equal text is equal bits.
    assert_eq!(
        format!("{:?}", loaded.scene),
        format!("{scene:?}"),
        "{file}: a number differs in its bits"
    );
    // Exact capacities: the type holds what the file has, nothing spare.
    assert_eq!(
        (scene.spheres().len(), scene.lights().len(), scene.planes().len()),
        (N, L, P),
        "{file}: capacities are not the file's counts"
    );
    // The depth capacity is what the file traces: its `max_depth` (0 without mirrors,
    // and a type with D = 0 refuses a mirror when the file is loaded).
    assert_eq!(usize::from(scene.max_depth()), D, "{file}: depth capacity");
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

struct Same(Vec<&'static str>);

impl scenes::EachScene for Same {
    fn scene<const N: usize, const L: usize, const P: usize, const D: usize>(
        &mut self,
        name: &'static str,
        scene: &'static Scene<N, L, P, D>,
        camera: CameraParams,
    ) {
        same(name, scene, camera);
        self.0.push(name);
    }
}

#[test]
fn compiled_in_scenes_match_the_files() {
    let mut checked = Same(Vec::new());
    scenes::for_each(&mut checked);
    // Every standard scene file has its compiled-in copy, in the same order.
    assert_eq!(checked.0, standard::SCENES);
}

#[test]
fn compiled_in_feature_scenes_match_the_files() {
    let mut checked = Same(Vec::new());
    scenes::for_each_feature(&mut checked);
    assert_eq!(checked.0, standard::FEATURE_SCENES);
}
