//! What the API tests share: the standard scenes
//! and tracing a render into comparable pixels.

#![allow(dead_code)]

// Scene files need the `std` feature; the list itself does not.
#[cfg(feature = "std")]
use embedded_raytracer::scene_file::{self, SceneFile};

/// The standard scenes' list (names, capacities, texts), read alone: the scenes crate
/// that holds it depends on the library, which its own tests must not depend on.
#[path = "../../scenes/src/list.rs"]
mod standard;

#[allow(unused_imports)]
pub use standard::{FEATURE_SCENES, MAX_SPHERES, SCENES};

/// Every capacity a scene file may ask for.
#[cfg(feature = "std")]
pub type FullSceneFile = SceneFile<
    MAX_SPHERES,
    { standard::MAX_LIGHTS },
    { standard::MAX_PLANES },
    { embedded_raytracer::MAX_DEPTH as usize },
>;

/// Standard scene `name`, parsed from its text with the capacities `N`, `L`, `P`, `D`.
#[cfg(feature = "std")]
fn parse<const N: usize, const L: usize, const P: usize, const D: usize>(
    name: &str,
) -> SceneFile<N, L, P, D> {
    let text = standard::text(name).unwrap_or_else(|| panic!("no standard scene `{name}`"));
    scene_file::parse(text).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Spheres-only scene `name`.
#[cfg(feature = "std")]
pub fn load(name: &str) -> SceneFile<MAX_SPHERES> {
    parse(name)
}

/// Any standard scene `name`, with every capacity.
#[cfg(feature = "std")]
pub fn load_full(name: &str) -> FullSceneFile {
    parse(name)
}

#[path = "helpers.rs"]
mod helpers;
pub use helpers::*;
