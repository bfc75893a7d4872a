//! The library's API and behaviour tests, one binary (one link instead of one per
//! file): the camera, the sphere tests, rendering into every colour format, clipping,
//! bands, scale, culling, the scene features, and a frame drawn into the desktop
//! simulator's headless display. Incremental frames have a binary of their own
//! (`tests/incremental`); the tests against the f64 reference live in the lab.
//!
//! Each scene type and target type a test draws with builds the whole kernel once more,
//! so a scene is declared with the capacity of a type already in use (`Scene<0, 1, 1>`,
//! `Scene<2, 0, 0, 1>`) unless its capacity is what it tests. Once a type has lights,
//! planes or depth (the lit path), an empty list draws alike whatever its capacity;
//! whether it has any is the choice between the Lab #1 loop and the lit path.

#[cfg(feature = "std")] // the standard scenes are scene files
mod band;
mod camera;
mod clip;
mod common;
mod intersect;
mod lit;
mod render;
mod scale;
#[cfg(feature = "std")] // the standard scenes are scene files
mod simulator;
#[cfg(feature = "std")] // the standard scenes are scene files
mod speed;
