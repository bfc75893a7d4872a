//! How a frame's rows are traced, and a ray's identity.
//!
//! The sampling's strategy trait [`Rows`], with the one-ray [`CenterRows`]; and a ray's
//! identity, which adaptive sampling compares between neighbouring pixels ([`Ident`],
//! [`Fnv`]).

use embedded_graphics::primitives::Rectangle;

use crate::math::SqrtFn;
use crate::method::intersect::TestStrategy;
use crate::method::stepping::Stepper;
use crate::trace::frame::Frame;
use crate::trace::scanline::{self, RowSink, RowTracer};
use crate::trace::shade::Shader;

/// A ray's identity accumulated along its path (see [`RowTracer::identified`]).
pub(crate) trait Ident {
    /// Whether this identity is kept (an identity that is not computes nothing).
    const KEPT: bool;
    fn mix(&mut self, x: u32);
    /// The ray sees detail finer than the pixel spacing (checker cells): its pixel is
    /// an edge pixel whatever its neighbours see.
    fn fine(&mut self);
}

/// FNV-1a-style mixing of 32-bit words from 0, and whether the ray saw detail finer
/// than a pixel.
///
/// 0 is the identity of a ray that hits nothing: every word mixed in is non-zero, and
/// an odd multiplier keeps it so.
pub(crate) struct Fnv(pub u32, pub bool);

/// The identity of a ray that saw detail finer than a pixel: its pixel is an edge
/// pixel (a hash that happens to equal it only adds one).
pub(crate) const FINE: u32 = u32::MAX;

impl Fnv {
    /// The identity as [`RowTracer::identified`] reports it.
    pub(crate) fn get(&self) -> u32 {
        if self.1 {
            FINE
        } else {
            self.0
        }
    }
}

impl Ident for Fnv {
    const KEPT: bool = true;
    #[inline(always)]
    fn mix(&mut self, x: u32) {
        self.0 = (self.0 ^ x).wrapping_mul(0x0100_0193);
    }
    #[inline(always)]
    fn fine(&mut self) {
        self.1 = true;
    }
}

/// How a frame's rows are traced: the sampling's strategy type.
pub(crate) trait Rows: Copy {
    /// The one-ray row loop (the only one the integer kernel has).
    const CENTER: bool;
    /// The part of the image the frame must trace for `clip` (adaptive sampling
    /// needs the ring of pixels around it).
    fn clip(&self, clip: Rectangle) -> Rectangle;
    /// Trace the frame's rows into `sink`; `tracer` as for [`scanline::draw_rows`].
    fn draw_rows<'s, const N: usize, K: RowSink, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X>(
        self,
        frame: &Frame<'s, T, Sh>,
        sink: &mut K,
        tracer: impl FnMut(u32, &mut u32, &mut u32) -> X,
    ) -> Result<(), K::Error>
    where
        X: RowTracer<'s, T, Sh>;
}

/// [`Sampling::Center`](crate::Sampling::Center): the scanline loop as it is.
#[derive(Clone, Copy)]
pub(crate) struct CenterRows;

impl Rows for CenterRows {
    const CENTER: bool = true;
    #[inline(always)]
    fn clip(&self, clip: Rectangle) -> Rectangle {
        clip
    }

    #[inline(always)]
    fn draw_rows<'s, const N: usize, K: RowSink, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X>(
        self,
        frame: &Frame<'s, T, Sh>,
        sink: &mut K,
        tracer: impl FnMut(u32, &mut u32, &mut u32) -> X,
    ) -> Result<(), K::Error>
    where
        X: RowTracer<'s, T, Sh>,
    {
        scanline::draw_rows::<N, K, S, T, Q, Sh, X>(frame, sink, tracer)
    }
}
