//! The lab of `embedded-raytracer`: what proves the library exact and fast.
//!
//! - [`reference`] (host): an independent `f64` reference renderer, the error metrics
//!   that compare a render with it, and the stability sweeps that find where each
//!   method fails.
//! - [`hash`]: [`hash::PixelHash`], the display-sized FNV-1a target whose hash the QEMU
//!   firmware prints and the host recomputes.
//! - [`scenes`]: the standard scenes (`scenes/*.toml`) compiled in, for firmware (their
//!   names and files: the `embedded-raytracer-scenes` crate).
//! - [`aa`], [`cycle_model`], [`qemu_output`], [`slice_target`] (host): the
//!   anti-aliasing measurement, the Cortex-M4 cycle model, the QEMU output parser and a
//!   slice target for benchmarks, shared by the lab's examples, benches and tests.
//!
//! Nothing here is part of the library's API; the library never depends on the lab.
#![cfg_attr(not(feature = "std"), no_std)]
// `!(x > bound)` is deliberate, as in the library: it rejects NaN along with out-of-range values.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod hash;
pub mod scenes;

#[cfg(feature = "std")]
pub mod aa;
#[cfg(feature = "std")]
pub mod cycle_model;
#[cfg(feature = "std")]
pub mod qemu_output;
#[cfg(feature = "std")]
pub mod reference;
#[cfg(feature = "std")]
pub mod slice_target;
