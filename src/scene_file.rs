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
//! Every error names the field (`camera.fov_y_deg`, `sphere[2].radius`, with
//! `sphere[k]` counting from 0 in file order), the line where the parser knows it,
//! and the reason:
//!
//! ```
//! use embedded_raytracer::scene_file::parse;
//!
//! let text = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov_y_deg = 60\nwidth = 4\nheight = 3\n\
//!             [[sphere]]\ncenter = [0, 0, 0]\nradius = 0\ncolor = [255, 0, 0]\n";
//! let err = parse::<4>(text).unwrap_err();
//! assert_eq!(err.field.as_deref(), Some("sphere[0].radius"));
//! assert_eq!(err.to_string(), "sphere[0].radius: radius must be greater than 0");
//! ```

use std::fmt;
use std::path::{Path, PathBuf};
use std::string::{String, ToString};
use std::vec::Vec;
use std::{format, fs};

use embedded_graphics::{geometry::Size, pixelcolor::Rgb888};
use serde::Deserialize;

use crate::camera::{Camera, CameraParams};
use crate::error::CameraError;
use crate::scene::Scene;
use crate::sphere::Sphere;
use crate::vec3::Vec3;

/// A loaded scene file: the scene and its camera.
#[derive(Clone, Debug)]
pub struct SceneFile<const N: usize> {
    /// The spheres and background.
    pub scene: Scene<N>,
    /// The validated camera.
    pub camera: Camera,
}

/// Why a scene file was rejected: the file, the field, the line and the reason.
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

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    #[serde(default)]
    background: [u8; 3],
    camera: RawCamera,
    #[serde(default)]
    sphere: Vec<RawSphere>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCamera {
    eye: [f32; 3],
    look_at: [f32; 3],
    #[serde(default = "default_up")]
    up: [f32; 3],
    fov_y_deg: f32,
    fov_x_deg: Option<f32>,
    width: u32,
    height: u32,
}

fn default_up() -> [f32; 3] {
    [0.0, 1.0, 0.0]
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSphere {
    center: [f32; 3],
    radius: f32,
    color: [u8; 3],
}

fn vec3(v: [f32; 3]) -> Vec3 {
    Vec3::new(v[0], v[1], v[2])
}

fn rgb(c: [u8; 3]) -> Rgb888 {
    Rgb888::new(c[0], c[1], c[2])
}

/// Parses a scene file's text into a scene of capacity `N` and its camera.
pub fn parse<const N: usize>(text: &str) -> Result<SceneFile<N>, SceneFileError> {
    let raw: RawScene = deserialize(text)?;

    let c = &raw.camera;
    let mut params = CameraParams::new(
        vec3(c.eye),
        vec3(c.look_at),
        vec3(c.up),
        c.fov_y_deg.to_radians(),
        Size::new(c.width, c.height),
    );
    if let Some(fov_x) = c.fov_x_deg {
        params = params.with_fov_x(fov_x.to_radians());
    }
    let camera =
        Camera::from_params(params).map_err(|e| SceneFileError::field(camera_field(e, c.width), e))?;

    let mut scene = Scene::new(rgb(raw.background));
    if raw.sphere.len() > N {
        return Err(SceneFileError::field(
            "sphere",
            format!("{} spheres, but at most {N} are supported", raw.sphere.len()),
        ));
    }
    for (k, s) in raw.sphere.iter().enumerate() {
        let sphere = Sphere::try_new(vec3(s.center), s.radius, rgb(s.color)).map_err(|e| {
            let key = match e {
                crate::SphereError::NotFinite if !vec3(s.center).is_finite() => "center",
                _ => "radius",
            };
            SceneFileError::field(format!("sphere[{k}].{key}"), e)
        })?;
        scene
            .push(sphere)
            .map_err(|e| SceneFileError::field(format!("sphere[{k}]"), e))?;
    }
    Ok(SceneFile { scene, camera })
}

/// Reads and parses a scene file; errors carry the path.
pub fn load<const N: usize>(path: impl AsRef<Path>) -> Result<SceneFile<N>, SceneFileError> {
    let path = path.as_ref();
    let with_path = |mut e: SceneFileError| {
        e.path = Some(path.to_path_buf());
        e
    };
    let text = fs::read_to_string(path).map_err(|e| {
        with_path(SceneFileError {
            path: None,
            field: None,
            line: None,
            reason: format!("cannot read the file: {e}"),
        })
    })?;
    parse(&text).map_err(with_path)
}

/// The scene-file key of a camera error, as `camera.<key>`; a resolution error names
/// the dimension that is out of range.
fn camera_field(e: CameraError, width: u32) -> String {
    let width_ok = (1..=crate::camera::MAX_RESOLUTION).contains(&width);
    let key = match e {
        CameraError::ZeroResolution | CameraError::ResolutionTooLarge if width_ok => "height",
        CameraError::ZeroResolution | CameraError::ResolutionTooLarge => "width",
        _ => e.file_key(),
    };
    format!("camera.{key}")
}

/// TOML → raw structs, with the failing field's path and line.
fn deserialize(text: &str) -> Result<RawScene, SceneFileError> {
    let line_of = |e: &toml::de::Error| {
        e.span()
            .map(|s| text.get(..s.start).unwrap_or(text).matches('\n').count() + 1)
    };
    let de = toml::Deserializer::parse(text).map_err(|e| SceneFileError {
        path: None,
        field: None,
        line: line_of(&e),
        reason: format!("not valid TOML: {}", e.message().trim()),
    })?;
    serde_path_to_error::deserialize(de).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.inner();
        SceneFileError {
            path: None,
            field: (path != ".").then_some(path),
            line: line_of(inner),
            reason: inner.message().trim().to_string(),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"
background = [10, 20, 30]
[camera]
eye = [0.0, 0.0, 5.0]
look_at = [0.0, 0.0, 0.0]
fov_y_deg = 60.0
width = 32
height = 24
[[sphere]]
center = [0.0, 0.0, 0.0]
radius = 1.0
color = [255, 64, 64]
"#;

    fn err(text: &str) -> SceneFileError {
        match parse::<4>(text) {
            Ok(_) => panic!("accepted:\n{text}"),
            Err(e) => e,
        }
    }

    #[test]
    fn parses_the_documented_format() {
        let f = parse::<4>(GOOD).unwrap();
        assert_eq!(f.scene.spheres().len(), 1);
        assert_eq!(f.scene.background(), Rgb888::new(10, 20, 30));
        assert_eq!(f.camera.size(), Size::new(32, 24));
        assert_eq!(f.camera.params().up, Vec3::new(0.0, 1.0, 0.0));
    }

    #[test]
    fn errors_name_field_and_line() {
        let e = err(&GOOD.replace("width = 32", "width = 32\nzoom = 2"));
        assert_eq!(e.field.as_deref(), Some("camera.zoom"));
        assert!(e.reason.contains("unknown field `zoom`"), "{e}");
        assert_eq!(e.line, Some(8));

        let e = err(&GOOD.replace("width = 32", "width = \"wide\""));
        assert_eq!(e.field.as_deref(), Some("camera.width"), "{e}");
        assert_eq!(e.line, Some(7));

        let e = err(&GOOD.replace("eye = [0.0, 0.0, 5.0]\n", ""));
        assert!(e.reason.contains("missing field `eye`"), "{e}");

        let e = err(&GOOD.replace("radius = 1.0", "radius = 0.0"));
        assert_eq!(e.to_string(), "sphere[0].radius: radius must be greater than 0");

        let e = err(&GOOD.replace("[255, 64, 64]", "[256, 64, 64]"));
        assert_eq!(e.field.as_deref(), Some("sphere[0].color[0]"), "{e}");

        let e = err(&GOOD.replace("fov_y_deg = 60.0", "fov_y_deg = 180.0"));
        assert_eq!(e.field.as_deref(), Some("camera.fov_y_deg"));

        let e = err(&GOOD.replace("look_at = [0.0, 0.0, 0.0]", "look_at = [0.0, 0.0, 5.0]"));
        assert_eq!(e.field.as_deref(), Some("camera.look_at"));

        let e = err(&GOOD.replace("fov_y_deg", "up = [0.0, 0.0, 2.0]\nfov_y_deg"));
        assert_eq!(e.field.as_deref(), Some("camera.up"));

        let e = err(&GOOD.replace("height = 24", "height = 0"));
        assert_eq!(e.field.as_deref(), Some("camera.height"));
        let e = err(&GOOD.replace("width = 32", "width = 9000"));
        assert_eq!(e.field.as_deref(), Some("camera.width"));

        let e = err("this is [not toml");
        assert!(e.reason.starts_with("not valid TOML"), "{e}");
        assert_eq!(e.line, Some(1));

        let e = err(&GOOD.replace("center = [0.0, 0.0, 0.0]", "center = [nan, 0.0, 0.0]"));
        assert_eq!(e.field.as_deref(), Some("sphere[0].center"));
    }

    #[test]
    fn too_many_spheres() {
        let sphere = GOOD.split_once("[[sphere]]").unwrap().1;
        let text = format!("{GOOD}[[sphere]]{sphere}[[sphere]]{sphere}");
        assert_eq!(parse::<3>(&text).unwrap().scene.spheres().len(), 3);
        assert_eq!(parse::<2>(&text).unwrap_err().field.as_deref(), Some("sphere"));
    }
}
