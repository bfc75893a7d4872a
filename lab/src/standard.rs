//! The standard scenes for host tools, tests and benchmarks: their names (one order for
//! every table and chart), the capacities the host loads scene files with, and loading
//! a standard scene by name.
//!
//! Included with `#[path]` by the host examples, `tests/api/common.rs` and the benches.

#![allow(dead_code)]

use embedded_raytracer::scene_file::{self, SceneFile};

/// The standard spheres-only scenes (`scenes/NAME.toml`), in the order of every table:
/// Lab #1 shading, loaded as `Scene<MAX_SPHERES>` (the firmware's hash table is made
/// from these).
pub const SCENES: [&str; 5] = ["lab", "far", "grazing", "drift", "crowd"];

/// The standard scenes with lights, a floor and mirrors, loaded as the full type
/// ([`FullSceneFile`]), in the order of every table: `shadows` (a directional and a
/// point light over a checkered floor), `mirrors` (mirror spheres, `max_depth = 3`).
pub const FEATURE_SCENES: [&str; 2] = ["shadows", "mirrors"];

/// How many spheres a host tool accepts from a scene file (the render CLI's and the
/// simulator's limit; at least every standard scene's count).
pub const MAX_SPHERES: usize = 256;

/// How many lights a host tool accepts from a scene file.
pub const MAX_LIGHTS: usize = 8;

/// How many planes a host tool accepts from a scene file.
pub const MAX_PLANES: usize = 8;

/// The reflection depth a host tool's scene type can trace: every `max_depth` a scene
/// file may ask for.
pub const MAX_DEPTH: usize = embedded_raytracer::MAX_DEPTH as usize;

/// A scene file loaded with every capacity a host tool has.
pub type FullSceneFile = SceneFile<MAX_SPHERES, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>;

/// The path of standard scene `name`.
pub fn path(name: &str) -> String {
    format!("{}/../scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"))
}

/// Standard spheres-only scene `name` ([`SCENES`]), loaded from its file (panics with
/// the loader's message if the file is broken: the standard scenes are part of the
/// repository).
pub fn load(name: &str) -> SceneFile<MAX_SPHERES> {
    scene_file::load(path(name)).unwrap_or_else(|e| panic!("{e}"))
}

/// Any standard scene `name` ([`SCENES`] or [`FEATURE_SCENES`]), loaded with the full
/// capacities (panics with the loader's message if the file is broken).
pub fn load_full(name: &str) -> FullSceneFile {
    scene_file::load(path(name)).unwrap_or_else(|e| panic!("{e}"))
}

/// The method flags of the host tools' usage, every choice listed from the method's
/// own tables: `[--stepping a|b|c] [--sphere-test …] [--sqrt …]`.
pub fn method_flags() -> String {
    use embedded_raytracer::{SphereTest, Sqrt, Stepping};
    format!(
        "[--stepping {}] [--sphere-test {}] [--sqrt {}]",
        Stepping::NAMES.join("|"),
        SphereTest::NAMES.join("|"),
        Sqrt::NAMES.join("|")
    )
}
