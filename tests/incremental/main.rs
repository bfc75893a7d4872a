//! Incremental frames, one binary beside the API tests' (the two build in parallel):
//! after any sequence of frames the display holds the last frame's full render, bit for
//! bit.
//!
//! - `frames`: every method, sampling, arithmetic and colour format, whole, offset and
//!   clipped; and less traced and sent than the whole frame.
//! - `sequences`: random sequences, each frame against its full render.
//! - `regressions`: the minimal sequences that once drifted.

#[path = "../api/common.rs"]
mod common;
mod framebuffer;
mod frames;
mod regressions;
mod sequences;
