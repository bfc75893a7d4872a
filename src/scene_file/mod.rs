//! TOML scene files (feature `std`, host only): the format of `scenes/*.toml`.
//!
//! ```toml
//! background = [0, 0, 0]        # optional, default black
//!
//! [camera]
//! eye = [0.0, 0.0, 5.0]
//! look_at = [0.0, 0.0, 0.0]
//! up = [0.0, 1.0, 0.0]          # optional, default +y
//! fov_y_deg = 60.0
//! # fov_x_deg = 80.0            # optional: non-square pixels
//! width = 320
//! height = 240
//!
//! [[sphere]]
//! center = [0.0, 0.0, 0.0]
//! radius = 1.0
//! color = [255, 64, 64]         # 8-bit sRGB
//! ```
//!
//! Lights, planes and mirrors are optional keys; a file without them is spheres under
//! the Lab #1 headlight, whatever the scene type it is loaded into:
//!
//! ```toml
//! ambient = 0.1                 # optional, 0 … 1
//! max_depth = 2                 # optional, 0 … 8 (and at most the scene type's D)
//! shadows = true                # optional
//!
//! [[light]]
//! type = "directional"          # or "point"
//! direction = [-1.0, -2.0, -1.0]  # directional only: the way the light travels
//! # position = [2.0, 5.0, 3.0]   # point only
//! intensity = 0.8               # optional, default 1, ≥ 0
//!
//! [[sphere]]                    # as above, plus optionally:
//! specular = 0.5                # 0 … 1, default 0
//! shininess = 32                # ≥ 1, default 32
//! reflect = 0.3                 # 0 … 1, default 0 (needs D ≥ 1)
//!
//! [[plane]]
//! point = [0.0, -1.0, 0.0]
//! normal = [0.0, 1.0, 0.0]      # not zero
//! color = [220, 220, 220]
//! checker = [40, 40, 40]        # optional second colour
//! checker_size = 1.0            # optional, default 1, > 0 (only with `checker`)
//! # specular, shininess and reflect as for spheres
//! ```
//!
//! A scene may move ([`motion`](crate::motion)): each `[[motion]]` table moves one
//! sphere or the camera, in file order, and `[animation]` says how it is played:
//!
//! ```toml
//! [animation]                   # optional
//! fps = 25                      # optional, default 25, > 0
//! frames = 50                   # optional, default one loop of the longest period
//!
//! [[motion]]
//! kind = "circle"               # sphere[0] circles `center` in its horizontal plane
//! sphere = 0                    # the sphere's index, from 0 in file order
//! center = [0.0, 0.5, 0.0]
//! radius = 1.5
//! period = 4.0                  # seconds a turn, > 0
//! phase = 0.25                  # optional, turns along at t = 0, default 0
//!
//! [[motion]]
//! kind = "bounce"               # up `height` and back every `period` seconds
//! sphere = 1
//! height = 1.2
//! period = 1.0
//!
//! [[motion]]
//! kind = "orbit"                # the camera orbits its look_at about `up`
//! period = 10.0
//! ```
//!
//! At most [`MAX_MOTIONS`] motions; a field another kind takes is refused rather than
//! ignored (`motion[1].center: a bounce has no center`).
//!
//! The scene type's capacities are the loader's limits: [`parse`]`::<N, L, P, D>` reads
//! at most `N` spheres, `L` lights and `P` planes (each counted while parsing, so a huge
//! file is refused at entry `N + 1`) and accepts `reflect > 0` only if `D ≥ 1`.
//!
//! Every fixed-length array must have exactly its length, every number must fit its
//! type (an `f32` field refuses `1e39` rather than reading it as infinity), and [`load`]
//! reads only a regular file of at most [`MAX_FILE_SIZE`] bytes. [`parse`] takes text
//! of any length: a front end without a file system (a web page) that parses untrusted
//! text refuses text longer than [`MAX_FILE_SIZE`] bytes itself.
//!
//! Every error names the field (`camera.fov_y_deg`, `sphere[2].radius`,
//! `light[1].direction`, `plane[0].normal`, with `sphere[k]` counting from 0 in file
//! order), the line where the parser knows it, and the reason:
//!
//! ```
//! use embedded_raytracer::scene_file::parse;
//!
//! let text = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov_y_deg = 60\nwidth = 4\nheight = 3\n\
//!             [[sphere]]\ncenter = [0, 0, 0]\nradius = 0\ncolor = [255, 0, 0]\n";
//! let err = parse::<4, 0, 0, 0>(text).unwrap_err();
//! assert_eq!(err.field.as_deref(), Some("sphere[0].radius"));
//! assert_eq!(err.to_string(), "sphere[0].radius: radius must be greater than 0");
//!
//! let lit = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov_y_deg = 60\nwidth = 4\nheight = 3\n\
//!            [[light]]\ntype = \"point\"\ndirection = [0, -1, 0]\n";
//! let err = parse::<4, 2, 1, 2>(lit).unwrap_err();
//! assert_eq!(err.to_string(), "light[0].direction: a point light has no direction (give `position`)");
//! ```

use std::fmt;
use std::path::PathBuf;
use std::string::{String, ToString};

use crate::camera::Camera;
use crate::motion::Animation;
use crate::scene::Scene;
use crate::scene_file::schema::RawScene;

mod convert; // the raw tables through the checked constructors: scene, camera, animation
mod io; // `load`: a regular file of at most `MAX_FILE_SIZE` bytes
mod precheck; // the scan that refuses a hostile text before the TOML parser allocates
mod schema; // the format as serde structs; TOML into them, errors with field and line
mod values; // the strict value types: exact-length and capped arrays, numbers that fit

pub use io::{load, MAX_FILE_SIZE};

/// The most `[[motion]]` tables a scene file may have: the capacity of
/// [`SceneFile::animation`].
pub const MAX_MOTIONS: usize = 8;

/// A loaded scene file: the scene (with capacities `N` spheres, `L` lights, `P`
/// planes, reflection depth `D`), its camera and its animation.
#[derive(Clone, Debug)]
pub struct SceneFile<const N: usize, const L: usize = 0, const P: usize = 0, const D: usize = 0> {
    /// The objects, lights, background and settings.
    pub scene: Scene<N, L, P, D>,
    /// The validated camera.
    pub camera: Camera,
    /// The file's motions (none if it has no `[[motion]]`), frame rate and frames,
    /// checked against the scene: every sphere a motion names is in it.
    pub animation: Animation<MAX_MOTIONS>,
}

impl<const N: usize, const L: usize, const P: usize, const D: usize> SceneFile<N, L, P, D> {
    /// Whether the scene has a light, a plane or a mirror (`reflect > 0`): anything
    /// the spheres-only type `Scene<N>` cannot draw.
    #[must_use]
    pub fn has_features(&self) -> bool {
        !self.scene.lights().is_empty()
            || !self.scene.planes().is_empty()
            || self.scene.spheres().iter().any(|s| s.material.reflect > 0.0)
    }

    /// The same file as the spheres-only type `SceneFile<N>`, or `None` when it has a
    /// light, a plane or a mirror ([`has_features`](Self::has_features)).
    ///
    /// Rendered through `Scene<N>`, it draws with the Lab #1 loop: the pixels of a file
    /// of spheres alone. Without lights the settings and the spheres' highlights change
    /// no pixel, so nothing the picture depends on is dropped.
    #[must_use]
    pub fn spheres_only(&self) -> Option<SceneFile<N>> {
        if self.has_features() {
            return None;
        }
        let mut scene = Scene::new(self.scene.background());
        for sphere in self.scene.spheres() {
            // Cannot fail: the same capacity, spheres already checked, no mirror.
            scene.push(*sphere).ok()?;
        }
        Some(SceneFile {
            scene,
            camera: self.camera,
            animation: self.animation.clone(),
        })
    }
}

/// Why a scene file is refused: the file, the field, the line and the reason.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneFileError {
    /// The file, when the error came from [`load`].
    pub path: Option<PathBuf>,
    /// The field, e.g. `camera.width` or `sphere[2].radius`, when one is to blame.
    pub field: Option<String>,
    /// 1-based line number, when the parser knows it.
    pub line: Option<usize>,
    /// What is wrong.
    pub reason: String,
}

impl fmt::Display for SceneFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(path) = &self.path {
            write!(f, "{}: ", path.display())?;
        }
        if let Some(line) = self.line {
            write!(f, "line {line}: ")?;
        }
        if let Some(field) = &self.field {
            write!(f, "{field}: ")?;
        }
        f.write_str(&self.reason)
    }
}

impl std::error::Error for SceneFileError {}

impl SceneFileError {
    fn field(field: impl Into<String>, reason: impl ToString) -> Self {
        Self {
            path: None,
            field: Some(field.into()),
            line: None,
            reason: reason.to_string(),
        }
    }
}

/// Parses a scene file's text into a scene with capacities `N` spheres, `L` lights,
/// `P` planes and reflection depth `D`, and its camera.
///
/// The text may be of any length. A caller with untrusted text and no file to
/// [`load`] (a web page) refuses text longer than [`MAX_FILE_SIZE`] bytes before
/// calling, as [`load`] does: the scan before the TOML parser bounds how many values
/// the parser builds by the capacities, not the length of a string or of the scan.
pub fn parse<const N: usize, const L: usize, const P: usize, const D: usize>(
    text: &str,
) -> Result<SceneFile<N, L, P, D>, SceneFileError> {
    let raw: RawScene<N, L, P> = schema::deserialize(text)?;
    convert::scene_file(&raw)
}

#[cfg(test)]
mod tests;
