//! The lab's tests, one binary (one link instead of one per file): the library against
//! the f64 reference, the reference's own rules, the stability sweeps at each method's
//! failure point (the slow ones `#[ignore]`d, run by `.ci/run`), the firmware's
//! compiled-in scenes and hashes against the host, the cycle model and the boards' band
//! splits.

// The RP2040 board's compiled-in scene, which its orbit (`rp2040_split`) reads as
// `crate::scenes`, as in the firmware.
#[path = "../../../boards/rp2040/src/scenes.rs"]
mod scenes;

mod animation;
mod auto;
mod band_wire;
mod board_examples;
mod board_scenes;
mod coincident;
mod common;
mod cycle_model;
mod far_objects;
mod firmware_hashes;
mod firmware_scenes;
mod integer;
mod lamp_on_surface;
mod lit_stability;
mod properties;
mod reference_lit;
mod rp2040_split;
mod sampling;
mod stability;
