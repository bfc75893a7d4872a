//! Tracing at its three rates: per frame, per row and per pixel.
//!
//! Per frame `frame` (the visible part of the image and each sphere's constants), per
//! row `scanline` (the row's active spheres), per pixel the closest hit, shaded by
//! `shade`; `lab1` is the spheres-only frame, `lit` the same loop's features path
//! (lights, shadows, planes, mirrors).

pub(crate) mod frame;
pub(crate) mod lab1;
pub mod lit;
pub mod options;
pub(crate) mod rows;
pub(crate) mod scanline;
pub mod shade;
