//! The standard scenes for host tools, tests and benchmarks: their names (one order for
//! every table and chart), the sphere capacity the host loads scene files with, and
//! loading a standard scene by name.
//!
//! Included with `#[path]` by the host examples, `tests/common/mod.rs` and the benches.

#![allow(dead_code)]

use embedded_raytracer::scene_file::{self, SceneFile};

/// The standard scenes (`scenes/NAME.toml`), in the order of every table.
pub const SCENES: [&str; 5] = ["lab", "far", "grazing", "drift", "crowd"];

/// How many spheres a host tool accepts from a scene file (the render CLI's and the
/// simulator's limit; at least every standard scene's count).
pub const MAX_SPHERES: usize = 256;

/// The path of standard scene `name`.
pub fn path(name: &str) -> String {
    format!("{}/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"))
}

/// Standard scene `name`, loaded from its file (panics with the loader's message if the
/// file is broken: the standard scenes are part of the repository).
pub fn load(name: &str) -> SceneFile<MAX_SPHERES> {
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
