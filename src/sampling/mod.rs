//! Anti-aliasing: how many rays a pixel gets, chosen once per frame like the method.
//!
//! - [`Sampling::Center`] (default): one ray through the pixel centre — the row loop of
//!   `scanline.rs`, untouched.
//! - [`Sampling::Grid`]`(n)`: `n × n` rays at offsets `((a + ½)/n − ½, (b + ½)/n − ½)`
//!   pixel widths and heights from the centre along `u` and `−v`, averaged (box filter).
//! - [`Sampling::Adaptive`]`(n)`: exactly `Grid(n)`'s rays in edge pixels, the centre
//!   ray alone elsewhere.
//!
//! Each part in a file of its own, each rule's error bound on its type: the public
//! choice (`choice.rs`); a pixel's sub-pixel rays and their average in linear light
//! (`average.rs`); `Grid`'s rows (`grid.rs`); `Adaptive` on a Lab #1 scene, its edge
//! columns found per row from each sphere's rings (`span.rs`), the rings built once per
//! frame (`ring.rs`); `Adaptive` with lights, planes or mirrors, or on a frame the
//! silhouettes cannot decide, from samples shared between neighbours (`shared.rs`).

mod average;
mod choice;
mod grid;
mod ring;
mod shared;
mod span;

pub use choice::{Sampling, SamplingError, SubSamples};
pub(crate) use grid::GridRows;
pub use shared::ADAPTIVE_MAX_WIDTH;
pub(crate) use shared::{small_box, AdaptiveRows};
pub(crate) use span::{shares_samples, SpanAdaptiveRows};
