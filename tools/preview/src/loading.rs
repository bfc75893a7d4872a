//! Loading the scene file: the scene through the type the render CLI would draw it
//! with, its camera and its motion; a frame of the motion; the file's modification time
//! (the reload's trigger).

use std::borrow::Cow;
use std::path::Path;
use std::time::SystemTime;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_raytracer::{
    motion::{Animation, MotionError},
    scene_file::{self, MAX_MOTIONS},
    Arithmetic, Camera, CameraParams, Method, Render, Scene,
};
use embedded_raytracer_scenes::{FullSceneFile, MAX_DEPTH, MAX_LIGHTS, MAX_PLANES, MAX_SPHERES};

/// The scene type with every capacity the host tools have.
pub type FullScene = Scene<MAX_SPHERES, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>;

/// A loaded scene, through the type the render CLI would draw it with.
#[derive(Clone)]
pub enum Loaded {
    /// No light, plane or mirror: the spheres-only type, whose loop is Lab #1's.
    Spheres(Box<Scene<MAX_SPHERES>>),
    /// Lights, planes or mirrors: the full type.
    Full(Box<FullScene>),
}

impl Loaded {
    /// Loads a scene file with the full capacities; returns the scene, its camera and
    /// its motion.
    pub fn load(path: &Path) -> Result<(Loaded, CameraParams, Animation<MAX_MOTIONS>), String> {
        let file: Box<FullSceneFile> = Box::new(scene_file::load(path).map_err(|e| e.to_string())?);
        let params = *file.camera.params();
        let animation = file.animation.clone();
        let scene = match file.spheres_only() {
            Some(spheres) => Loaded::Spheres(Box::new(spheres.scene)),
            None => Loaded::Full(Box::new(file.scene)),
        };
        Ok((scene, params, animation))
    }

    /// The scene and camera parameters of frame `frame` of `animation`, applied to this
    /// scene and `params` (the library's `apply_frame`: the render CLI's and the
    /// boards' frame).
    pub fn at_frame(
        &self,
        animation: &Animation<MAX_MOTIONS>,
        params: &CameraParams,
        frame: u32,
    ) -> Result<(Loaded, CameraParams), MotionError> {
        let mut at = *params;
        let moved = match self {
            Loaded::Spheres(base) => {
                let mut scene = base.clone();
                animation.apply_frame(&**base, params, frame, &mut *scene, &mut at)?;
                Loaded::Spheres(scene)
            }
            Loaded::Full(base) => {
                let mut scene = base.clone();
                animation.apply_frame(&**base, params, frame, &mut *scene, &mut at)?;
                Loaded::Full(scene)
            }
        };
        Ok((moved, at))
    }

    /// Whether the scene is drawn through the full type (lights, planes or mirrors):
    /// the one whose shadow and reflection rays the secondary origin decides.
    pub fn has_features(&self) -> bool {
        matches!(self, Loaded::Full(_))
    }

    /// The arithmetic a frame of `method` is drawn in (the integer kernel's rule).
    pub fn arithmetic(&self, camera: &Camera, method: Method) -> Arithmetic {
        match self {
            Loaded::Spheres(scene) => Render::<'_, MAX_SPHERES>::new(&**scene, camera)
                .with_method(method)
                .arithmetic(),
            Loaded::Full(scene) => {
                Render::<'_, MAX_SPHERES, Rgb888, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>::new(&**scene, camera)
                    .with_method(method)
                    .arithmetic()
            }
        }
    }
}

/// The scene and camera of frame `frame` of `animation`: for a still scene `scene`
/// through `camera` (the user's view of the file's camera); for one that moves, the
/// motion's frame applied to them.
pub fn moment<'a>(
    scene: &'a Loaded,
    animation: &Animation<MAX_MOTIONS>,
    camera: &Camera,
    frame: u32,
) -> Result<(Cow<'a, Loaded>, Camera), String> {
    if animation.is_still() {
        return Ok((Cow::Borrowed(scene), *camera));
    }
    let (scene, params) = scene
        .at_frame(animation, camera.params(), frame)
        .map_err(|e| format!("frame {}: {e}", u64::from(frame) + 1))?;
    let camera = params
        .build()
        .map_err(|e| format!("camera at frame {}: {e}", u64::from(frame) + 1))?;
    Ok((Cow::Owned(scene), camera))
}

/// The file's modification time, if it has one.
pub fn mtime(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}
