//! The standard scenes' list: their names in the order of every table, the capacities
//! a host loads them with, where their files lie and their texts.
//!
//! This file depends on nothing (not even the library): the library's API tests include
//! it with `#[path]`, the QEMU scripts (`.ci/firmware`, `.ci/firmware-m33`) read the
//! `SCENES` and `FEATURE_SCENES` lines with `sed` (keep each on one line), and a front
//! end without a file system parses [`TEXTS`] with `scene_file::parse`.

/// The standard spheres-only scenes (`scenes/NAME.toml`), in the order of every table:
/// Lab #1 shading, loaded as `Scene<MAX_SPHERES>` (the firmware's hash table is made
/// from these).
pub const SCENES: [&str; 5] = ["lab", "far", "grazing", "drift", "crowd"];

/// The standard scenes with lights, a floor and mirrors, loaded as the full type, in
/// the order of every table: `shadows` (a directional and a point light over a
/// checkered floor), `mirrors` (mirror spheres, `max_depth = 3`).
pub const FEATURE_SCENES: [&str; 2] = ["shadows", "mirrors"];

/// How many spheres a host tool accepts from a scene file (the render CLI's and the
/// simulator's limit; at least every standard scene's count).
pub const MAX_SPHERES: usize = 256;

/// How many lights a host tool accepts from a scene file.
pub const MAX_LIGHTS: usize = 8;

/// How many planes a host tool accepts from a scene file.
pub const MAX_PLANES: usize = 8;

/// The folder of the scene files, from the repository's root: scene `name` is
/// `scenes/NAME.toml`.
pub const DIR: &str = "scenes";

/// Every scene file of [`DIR`], by name, with its text: the standard scenes
/// ([`SCENES`], [`FEATURE_SCENES`]) and the scenes that move (`bounce`, `circling`).
pub const TEXTS: [(&str, &str); 9] = [
    ("lab", include_str!("../lab.toml")),
    ("far", include_str!("../far.toml")),
    ("grazing", include_str!("../grazing.toml")),
    ("drift", include_str!("../drift.toml")),
    ("crowd", include_str!("../crowd.toml")),
    ("shadows", include_str!("../shadows.toml")),
    ("mirrors", include_str!("../mirrors.toml")),
    ("bounce", include_str!("../bounce.toml")),
    ("circling", include_str!("../circling.toml")),
];

/// The text of scene file `name` ([`TEXTS`]), if there is one.
pub fn text(name: &str) -> Option<&'static str> {
    TEXTS.iter().find(|(n, _)| *n == name).map(|(_, text)| *text)
}
