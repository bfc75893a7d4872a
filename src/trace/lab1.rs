//! The spheres-only frame (Lab #1 shading), which the one dispatch (`dispatch.rs`)
//! calls with the method's strategy types for a scene without lights, planes or
//! mirrors.
//!
//! The frame's constants are built (`frame.rs`), then its rows traced by the
//! sampling's row loop with the Lab #1 tracer (`scanline.rs`).

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::Vec;

use crate::camera::Camera;
use crate::math::SqrtFn;
use crate::method::intersect::{Auto, Robust, TestStrategy, AUTO_FD_CAPACITY};
use crate::method::stepping::Stepper;
use crate::scene::Scene;
use crate::trace::frame::{frame_scale, hull, Frame, FrameSetup};
use crate::trace::options::Options;
use crate::trace::rows::Rows;
use crate::trace::scanline::{Lab1Row, RowSink};
use crate::trace::shade::Lab1;

/// Renders one frame of a scene without lights, planes or mirrors (Lab #1 on
/// spheres) with the strategy types the dispatch chose: stepping `S`, sphere test `T`,
/// square root `Q`.
///
/// Out of line: the per-sphere constants live in this function's own stack frame, so
/// a render pays for its own method's, not for the largest of all the methods the one
/// dispatch could have chosen (the stack each method takes: `docs/firmware.md`, "On a
/// Cortex-M4F", Stack).
#[inline(never)]
pub(crate) fn render<
    const N: usize,
    const L: usize,
    const P: usize,
    const D: usize,
    K: RowSink,
    S: Stepper,
    T: TestStrategy,
    Q: SqrtFn,
    G: Rows,
    I: Iterator<Item = Rectangle> + Clone,
>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    options: Options,
    (clips, rows): (I, G),
    offset: Point,
    sink: &mut K,
) -> Result<(), K::Error> {
    // `Auto` in a scene type above its limit (see `AUTO_FD_CAPACITY`); a capacity
    // within it never reaches the comparison.
    if T::AUTO && N > AUTO_FD_CAPACITY {
        return auto_above_limit::<N, L, P, D, K, S, Q, G, I>(
            scene,
            camera,
            options,
            (clips, rows),
            offset,
            sink,
        );
    }
    frame_of::<N, N, L, P, D, K, S, T, Q, G, I>(scene, camera, options, (clips, rows), offset, sink)
}

/// `Auto` in a scene type of more than [`AUTO_FD_CAPACITY`] spheres' capacity.
///
/// The robust test for a scene holding more than that many, else forward differences in
/// a frame sized for that many (not for the capacity).
#[inline(never)]
fn auto_above_limit<
    const N: usize,
    const L: usize,
    const P: usize,
    const D: usize,
    K: RowSink,
    S: Stepper,
    Q: SqrtFn,
    G: Rows,
    I: Iterator<Item = Rectangle> + Clone,
>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    options: Options,
    frame: (I, G),
    offset: Point,
    sink: &mut K,
) -> Result<(), K::Error> {
    // Each branch out of line, so that their frames never add up.
    if scene.spheres().len() > AUTO_FD_CAPACITY {
        render::<N, L, P, D, K, S, Robust, Q, G, I>(scene, camera, options, frame, offset, sink)
    } else {
        auto_within_limit::<N, L, P, D, K, S, Q, G, I>(scene, camera, options, frame, offset, sink)
    }
}

/// `Auto` in a frame sized for [`AUTO_FD_CAPACITY`] spheres (the scene holds at most
/// that many).
#[inline(never)]
fn auto_within_limit<
    const N: usize,
    const L: usize,
    const P: usize,
    const D: usize,
    K: RowSink,
    S: Stepper,
    Q: SqrtFn,
    G: Rows,
    I: Iterator<Item = Rectangle> + Clone,
>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    options: Options,
    frame: (I, G),
    offset: Point,
    sink: &mut K,
) -> Result<(), K::Error> {
    frame_of::<N, AUTO_FD_CAPACITY, L, P, D, K, S, Auto, Q, G, I>(scene, camera, options, frame, offset, sink)
}

/// [`render`]'s frame, its per-sphere data holding `M` spheres, at least the scene's
/// `scene.spheres().len()`.
#[inline(always)]
fn frame_of<
    const N: usize,
    const M: usize,
    const L: usize,
    const P: usize,
    const D: usize,
    K: RowSink,
    S: Stepper,
    T: TestStrategy,
    Q: SqrtFn,
    G: Rows,
    I: Iterator<Item = Rectangle> + Clone,
>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    options: Options,
    (clips, rows): (I, G),
    offset: Point,
    sink: &mut K,
) -> Result<(), K::Error> {
    // The per-frame sphere data lives here and the frame borrows it: built in place
    // once, never moved (a by-value `Frame` holding the `Vec` would be copied on
    // return, doubling the render's stack).
    let mut spheres = Vec::new();
    // The frame's scale, from the scene, camera and method alone (never the clip).
    let step_err = S::error_bound(camera);
    let (scale, culled) = match frame_scale::<N, L, P, D>(scene, camera, step_err, G::CENTER) {
        Ok(decided) => decided,
        Err(why) => return sink.refused(why),
    };
    // The frame over every clip's rows (its per-frame work once), then each clip's.
    let Some(bound) = clips.clone().map(|c| rows.clip(c)).reduce(hull) else {
        return Ok(());
    };
    let setup = FrameSetup {
        camera,
        options,
        step_err,
        scale,
        culled,
    };
    let Some(frame) = Frame::<T, Lab1>::new::<N, M, L, P, D, S>(scene, setup, bound, offset, &mut spheres)
    else {
        return Ok(()); // nothing visible
    };
    let (w, background) = (camera.w(), frame.background);
    for clip in clips {
        if let Some(frame) = frame.clipped(rows.clip(clip)) {
            rows.draw_rows::<M, K, S, T, Q, Lab1, _>(&frame, sink, |_, _, _| Lab1Row { w, background })?;
        }
    }
    Ok(())
}
