//! Incremental frames, one binary beside the API tests' (the two build in parallel):
//! after any sequence of frames the display holds the last frame's full render, bit for
//! bit.
//!
//! - `frames`: every method, sampling and arithmetic, in 16-, 24- and 1-bit colour, whole,
//!   offset and clipped; and less traced and sent than the whole frame.
//! - `sequences`: random sequences, each frame against its full render.
//! - `regressions`: the minimal sequences that once drifted.
//!
//! Each scene type and colour type a test draws with builds the whole kernel once more
//! (every method and sampling, for each sink), so the tests share a few types: a scene
//! is declared with the capacity of a type in use (`Scene<3>`, `Scene<3, 2, 1>`) unless
//! its capacity is what it tests, and the random sequences keep theirs, which their
//! seeds depend on.

#[path = "../api/common.rs"]
mod common;
mod framebuffer;
mod frames;
mod regressions;
mod sequences;
