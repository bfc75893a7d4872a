//! What the integration tests share: the standard scenes (`embedded-raytracer-scenes`)
//! and tracing a render into comparable pixels.

#![allow(dead_code)]

use embedded_raytracer_scenes as standard;

#[allow(unused_imports)]
pub use standard::{load, load_full, path, FEATURE_SCENES, MAX_SPHERES, SCENES};

#[path = "../../../tests/api/helpers.rs"]
mod helpers;
pub use helpers::*;
