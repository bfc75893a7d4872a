//! The firmware's compiled-in scenes (`lab/src/scenes.rs`) are exactly the
//! standard scene files: every number, bit for bit (the motions too), and each scene
//! type's capacities exactly what its file holds.

use embedded_raytracer_lab::scenes;
use embedded_raytracer_scenes as standard;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_raytracer::motion::Animation;
use embedded_raytracer::{scene_file, Arithmetic, CameraParams, Method, Render, Scene};

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

/// A moving scene's compiled-in copy: the scene at rest and camera as [`same`] checks
/// them, and the motion, frame rate and frames bit for bit.
struct SameMoving(Vec<&'static str>);

impl scenes::EachMovingScene for SameMoving {
    fn scene<const N: usize, const L: usize, const P: usize, const D: usize, const M: usize>(
        &mut self,
        name: &'static str,
        scene: &'static Scene<N, L, P, D>,
        camera: CameraParams,
        animation: &Animation<M>,
    ) {
        same(name, scene, camera);
        let loaded: scene_file::SceneFile<N, L, P, D> =
            scene_file::load(standard::path(name)).unwrap_or_else(|e| panic!("{e}"));
        let file = &loaded.animation;
        // `{:?}` prints each number's shortest round-trip form: equal text is equal bits.
        assert_eq!(
            format!("{:?}", file.motions()),
            format!("{:?}", animation.motions()),
            "{name}: motions differ"
        );
        assert_eq!(file.fps().to_bits(), animation.fps().to_bits(), "{name}: fps");
        assert_eq!(file.frames(), animation.frames(), "{name}: frames");
        // Exact capacity: the type holds the file's motions, nothing spare.
        assert_eq!(animation.motions().len(), M, "{name}: motion capacity");
        self.0.push(name);
    }
}

#[test]
fn compiled_in_moving_scenes_match_the_files() {
    let mut checked = SameMoving(Vec::new());
    scenes::for_each_moving(&mut checked);
    assert_eq!(checked.0, scenes::MOVING_SCENES);
    // Every scene file with a motion has its compiled-in copy (the scenes crate's
    // list holds every file of `scenes/`, which its own test checks).
    for (name, text) in standard::TEXTS {
        let file: standard::FullSceneFile = scene_file::parse(text).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(
            file.animation.is_still() || scenes::MOVING_SCENES.contains(&name),
            "{name} moves but is not compiled in"
        );
    }
}

/// `circling` is a Lab #1 scene the integer kernel draws at every moment of its loop.
#[test]
fn the_integer_kernel_draws_every_frame_of_circling() {
    let animation = &scenes::CIRCLING_ANIMATION;
    let (mut scene, mut params) = (scenes::CIRCLING.clone(), scenes::CIRCLING_CAMERA);
    for k in 0..animation.frames() {
        animation
            .apply_frame(
                &scenes::CIRCLING,
                &scenes::CIRCLING_CAMERA,
                k,
                &mut scene,
                &mut params,
            )
            .unwrap();
        let camera = params.build().unwrap();
        let render = Render::<_, Rgb888>::new(&scene, &camera).with_method(Method::INTEGER);
        assert_eq!(render.arithmetic(), Arithmetic::Integer, "frame {k}");
    }
}

/// `bounce`: at every moment the ball is at least a sixth of the image across (40 px
/// at 240×240) and wholly in the image, and half a bounce lifts it well up the image.
#[test]
fn the_bouncing_ball_is_large_and_in_view_at_every_frame() {
    let animation = &scenes::BOUNCE_ANIMATION;
    let (mut scene, mut params) = (scenes::BOUNCE.clone(), scenes::BOUNCE_CAMERA);
    let size = scenes::BOUNCE_CAMERA.size;
    let mut tops = Vec::new();
    for k in 0..animation.frames() {
        animation
            .apply_frame(
                &scenes::BOUNCE,
                &scenes::BOUNCE_CAMERA,
                k,
                &mut scene,
                &mut params,
            )
            .unwrap();
        let camera = params.build().unwrap();
        let (mut x, mut y) = ((i32::MAX, i32::MIN), (i32::MAX, i32::MIN));
        Render::<_, Rgb888, 1, 1, 0>::new(&scene, &camera).trace(|s| {
            if s.hit.is_some_and(|h| h.index == 0) {
                x = (x.0.min(s.pixel.x), x.1.max(s.pixel.x));
                y = (y.0.min(s.pixel.y), y.1.max(s.pixel.y));
            }
        });
        let (w, h) = (x.1 - x.0 + 1, y.1 - y.0 + 1);
        assert!(w >= 40 && h >= 40, "frame {k}: the ball is {w}x{h} px");
        assert!(
            x.0 > 0 && y.0 > 0 && x.1 < size.width as i32 - 1 && y.1 < size.height as i32 - 1,
            "frame {k}: the ball leaves the image ({x:?}, {y:?})"
        );
        tops.push(y.0);
    }
    // Frame 15 of 30 at 25 fps is t = 0.6 s, the top of the 1.2 s bounce.
    assert!(tops[0] - tops[15] > 40, "{tops:?}");
}
