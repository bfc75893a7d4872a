//! The standard scenes' texts for the page's menu (it has no file system) and the
//! capacities the host tools load scene files with, so that the page draws a file
//! through the render CLI's scene type.
//!
//! Stop-gap until the shared scene crate (`scenes/`) is in the workspace; this module
//! then goes and the page uses that crate's list.

/// Every scene file of `scenes/`, by name, with its text.
pub const TEXTS: [(&str, &str); 9] = [
    ("lab", include_str!("../../../scenes/lab.toml")),
    ("far", include_str!("../../../scenes/far.toml")),
    ("grazing", include_str!("../../../scenes/grazing.toml")),
    ("drift", include_str!("../../../scenes/drift.toml")),
    ("crowd", include_str!("../../../scenes/crowd.toml")),
    ("shadows", include_str!("../../../scenes/shadows.toml")),
    ("mirrors", include_str!("../../../scenes/mirrors.toml")),
    ("bounce", include_str!("../../../scenes/bounce.toml")),
    ("circling", include_str!("../../../scenes/circling.toml")),
];

/// How many spheres a host tool accepts from a scene file.
pub const MAX_SPHERES: usize = 256;

/// How many lights a host tool accepts from a scene file.
pub const MAX_LIGHTS: usize = 8;

/// How many planes a host tool accepts from a scene file.
pub const MAX_PLANES: usize = 8;

/// The reflection depth a host tool's scene type can trace.
pub const MAX_DEPTH: usize = embedded_raytracer::MAX_DEPTH as usize;
