//! What the API tests share: the standard scenes
//! and tracing a render into comparable pixels.

#![allow(dead_code)]

/// The standard scenes (`scenes/*.toml`), by name, as the lab's tables order them.
#[cfg(feature = "std")]
mod standard {
    use embedded_raytracer::scene_file::{self, SceneFile};

    /// The spheres-only scenes.
    pub const SCENES: [&str; 5] = ["lab", "far", "grazing", "drift", "crowd"];
    /// The scenes with lights, a floor and mirrors.
    pub const FEATURE_SCENES: [&str; 2] = ["shadows", "mirrors"];
    /// The sphere capacity the scene files are loaded with (every standard scene fits).
    pub const MAX_SPHERES: usize = 256;
    /// Every capacity a scene file may ask for.
    pub type FullSceneFile = SceneFile<MAX_SPHERES, 8, 8, { embedded_raytracer::MAX_DEPTH as usize }>;

    /// The path of standard scene `name`.
    pub fn path(name: &str) -> String {
        format!("{}/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"))
    }

    /// Spheres-only scene `name`, loaded from its file.
    pub fn load(name: &str) -> SceneFile<MAX_SPHERES> {
        scene_file::load(path(name)).unwrap_or_else(|e| panic!("{e}"))
    }

    /// Any standard scene `name`, loaded with every capacity.
    pub fn load_full(name: &str) -> FullSceneFile {
        scene_file::load(path(name)).unwrap_or_else(|e| panic!("{e}"))
    }
}

#[cfg(feature = "std")]
#[allow(unused_imports)]
pub use standard::{load, load_full, path, FEATURE_SCENES, MAX_SPHERES, SCENES};

#[path = "helpers.rs"]
mod helpers;
pub use helpers::*;
