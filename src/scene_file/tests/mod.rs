//! The scene-file tests, one file per part of the loader, and the scene texts they
//! share.

use std::format;
use std::string::ToString;

use embedded_graphics::{geometry::Size, pixelcolor::Rgb888};

use crate::math::vec3::Vec3;
use crate::motion::{Animation, Bounce, Circle, Motion, Orbit};
use crate::scene::light::Light;
use crate::scene::material::Material;
use crate::scene::plane::Plane;
use crate::scene::Settings;
use crate::scene_file::{parse, SceneFile, SceneFileError, MAX_FILE_SIZE, MAX_MOTIONS};

mod animation;
mod convert;
mod io;
mod precheck;
mod schema;
mod values;

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
    match parse::<4, 0, 0, 0>(text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}

/// Every light, plane, material and setting key at a non-default value: two lights,
/// a material, a checkered mirror floor and the settings.
const LIT: &str = r#"
ambient = 0.2
max_depth = 3
shadows = false
[camera]
eye = [0.0, 0.0, 5.0]
look_at = [0.0, 0.0, 0.0]
fov_y_deg = 60.0
width = 32
height = 24
[[light]]
type = "directional"
direction = [-1.0, -2.0, -1.0]
intensity = 0.8
[[light]]
type = "point"
position = [2.0, 5.0, 3.0]
intensity = 0.5
[[sphere]]
center = [0.0, 0.0, 0.0]
radius = 1.0
color = [255, 64, 64]
specular = 0.5
shininess = 16
reflect = 0.3
[[plane]]
point = [0.0, -1.0, 0.0]
normal = [0.0, 2.0, 0.0]
color = [220, 220, 220]
checker = [40, 40, 40]
checker_size = 2.0
specular = 0.25
shininess = 8
reflect = 0.1
"#;

/// The capacities the host tools load with, shrunk to the test files.
type Full = SceneFile<4, 2, 2, 8>;

fn full(text: &str) -> Result<Full, SceneFileError> {
    parse(text)
}

fn full_err(text: &str) -> SceneFileError {
    match full(text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}
