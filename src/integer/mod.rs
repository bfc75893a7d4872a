//! The integer kernel ([`Arithmetic::Integer`](crate::method::Arithmetic::Integer)):
//! Lab #1 on spheres in integer arithmetic only, for chips without an FPU (where every
//! `f32` operation is a library call: `docs/firmware.md`, "The integer kernel").
//!
//! Per frame (in `f64`, once) the scene is expressed in the camera's basis and
//! quantised, as finely as the integer ranges allow ([`frame`]: the rule and its
//! bounds); per row each sphere's discriminant is evaluated exactly where its span
//! starts, and per pixel stepped by exact forward differences ([`row`]); the closest
//! hit is shaded in Q16 ([`shade`]). Everything after the quantisation is exact integer
//! arithmetic.
//!
//! Where the rule does not hold (non-square pixels, an eye inside or beside a sphere,
//! a sphere too small or too close for the bounds at the scene's extent, a scene with
//! lights, planes or mirrors) the frame is drawn by the `f32` method instead
//! ([`render_or_f32`]); [`render`] runs the kernel alone.

mod frame;
mod row;
mod shade;
mod strip;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::Vec;

use frame::Refusal;
pub(crate) use frame::{cuts, picture, regions, IntFrame, IntSphere, Quantisation};
use row::{draw_rows, Active};
pub(crate) use strip::fill_strips;

use crate::camera::Camera;
use crate::math::SqrtFn;
use crate::method::intersect::TestStrategy;
use crate::method::stepping::Stepper;
use crate::scene::sphere::Sphere;
use crate::scene::Scene;
use crate::trace::frame::{hull, visible};
use crate::trace::options::Options;
use crate::trace::scanline::RowSink;

/// Draws a frame of a scene without lights, planes or mirrors with the integer kernel
/// where its rule takes the frame, else with the f32 method `S`, `T`, `Q`.
///
/// Out of line, and so are both paths: the f32 path's per-sphere constants and the
/// integer kernel's are never on the stack together (a `Scene<64>` would not fit a
/// 16 KiB Cortex-M0 otherwise).
#[inline(never)]
pub(crate) fn render_or_f32<
    const N: usize,
    const L: usize,
    const P: usize,
    const D: usize,
    K: RowSink,
    S: Stepper,
    T: TestStrategy,
    Q: SqrtFn,
    I: Iterator<Item = Rectangle> + Clone,
>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    options: Options,
    clips: I,
    offset: Point,
    sink: &mut K,
) -> Result<(), K::Error> {
    let (spheres, background) = (scene.spheres(), scene.background());
    if let Some(done) = render::<N, K, I>(spheres, background, camera, options, clips.clone(), offset, sink) {
        return done;
    }
    f32_frame::<N, L, P, D, K, S, T, Q, I>(scene, camera, options, clips, offset, sink)
}

/// The f32 method's frame, out of line (see [`render_or_f32`]).
#[inline(never)]
fn f32_frame<
    const N: usize,
    const L: usize,
    const P: usize,
    const D: usize,
    K: RowSink,
    S: Stepper,
    T: TestStrategy,
    Q: SqrtFn,
    I: Iterator<Item = Rectangle> + Clone,
>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    options: Options,
    clips: I,
    offset: Point,
    sink: &mut K,
) -> Result<(), K::Error> {
    crate::trace::lab1::render::<N, L, P, D, K, S, T, Q, crate::trace::rows::CenterRows, I>(
        scene,
        camera,
        options,
        (clips, crate::trace::rows::CenterRows),
        offset,
        sink,
    )
}

/// Draws the part of a frame each of `clips` shows (a scene without lights, planes or
/// mirrors) with the integer kernel, its per-frame rule and quantisation once for all of
/// them, or returns `None` (nothing drawn) where its rule does not take the frame.
///
/// Out of line: its per-sphere buffers live in its own stack frame, never beside the
/// `f32` path's (which runs only after this has returned).
#[inline(never)]
pub(crate) fn render<const N: usize, K: RowSink, I: Iterator<Item = Rectangle> + Clone>(
    spheres: &[Sphere],
    background: Rgb888,
    camera: &Camera,
    options: Options,
    clips: I,
    offset: Point,
    sink: &mut K,
) -> Option<Result<(), K::Error>> {
    let mut int_spheres: Vec<IntSphere, N> = Vec::new();
    let Some(bound) = clips.clone().reduce(hull) else {
        return Some(Ok(()));
    };
    match IntFrame::new(
        int_spheres.as_mut_view(),
        spheres,
        background,
        camera,
        options,
        bound,
        offset,
    ) {
        Ok(frame) => Some(draw_clips::<N, K, I>(frame, clips, sink)),
        Err(Refusal::Invisible) => Some(Ok(())),
        Err(Refusal::Bounds) => None,
    }
}

/// The rows of each of `clips` that the frame shows.
#[inline(always)]
fn draw_clips<const N: usize, K: RowSink, I: Iterator<Item = Rectangle>>(
    mut frame: IntFrame<'_>,
    clips: I,
    sink: &mut K,
) -> Result<(), K::Error> {
    let mut active: Vec<Active<'_>, N> = Vec::new();
    for clip in clips {
        let Some((i0, i1, j0, j1)) = visible(frame.camera.size(), frame.offset, clip) else {
            continue;
        };
        (frame.i0, frame.i1, frame.j0, frame.j1) = (i0, i1, j0, j1);
        draw_rows(&frame, active.as_mut_view(), sink)?;
    }
    Ok(())
}
