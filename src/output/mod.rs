//! Rows into targets: the sinks (`sink`: a `DrawTarget`, a caller's band buffer, a
//! callback) and the ordered dither for low-depth displays (`dither`).

pub mod dither;
pub(crate) mod sink;
