//! Scenes beyond Lab #1 spheres: planes (checkered floors), lights with shadow rays,
//! and mirrors, chosen at compile time by the scene's type.
//!
//! A `Scene<N, L, P, D>` with any of `L`, `P`, `D` above 0 takes this path; a
//! `Scene<N>` never links it. The rates:
//!
//! - **Per frame** ([`render`]): the spheres' constants as for Lab #1 (`trace/frame.rs`,
//!   with [`LitSphere`]'s shading constants), each plane's and light's constants
//!   (`consts.rs`), the ties (`ties.rs`) and the shadow silhouettes (`shadow.rs`) —
//!   all in the frame's eye-relative, scaled units ([`Scale`]).
//! - **Per row** ([`LitRow`]): each plane's span and each shadow's.
//! - **Per pixel**: the closest hit over the active spheres (the method's own test, as
//!   in the Lab #1 loop) and the planes whose span holds the column; then the shading
//!   loop (`color.rs`): the local colour (`shading.rs`), and while the surface is a
//!   mirror and the depth allows, the reflected ray. In a scene type without
//!   reflections, a floor without a highlight is shaded from its per-frame constants
//!   (`floor.rs`) and the other pixels out of line.
//!
//! Secondary rays start on a surface (`exit.rs`); where a lamp lies on a surface, or
//! two objects coincide, the frame decides it exactly (`ties.rs`, `exact.rs`).
//!
//! [`Scale`]: crate::method::intersect::Scale

mod color;
mod consts;
mod exact;
mod exit;
mod floor;
mod frame;
mod object;
mod occlusion;
mod row;
mod shading;
pub(crate) mod shadow;
pub(crate) mod ties;

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::Vec;

use crate::camera::span::Silhouette;
use crate::camera::Camera;
use crate::math::{SqrtFn, UNIT_ROUNDOFF};
use crate::method::intersect::{Auto, Robust, TestStrategy, AUTO_FD_CAPACITY};
use crate::method::stepping::Stepper;
use crate::scene::sphere::Sphere;
use crate::scene::Scene;
use crate::trace::frame::{frame_scale, hull, Frame, FrameSetup};
use crate::trace::lit::consts::{Floor, FrameLight, FramePlane, LitSphere};
use crate::trace::lit::exit::{ConvexExit, EpsilonExit, Exit};
use crate::trace::lit::frame::LitFrame;
use crate::trace::lit::row::LitRow;
use crate::trace::lit::shadow::{shadow_silhouette, ShadowRow};
use crate::trace::lit::ties::Ties;
use crate::trace::options::{Options, SecondaryOrigin};
use crate::trace::rows::Rows;
use crate::trace::scanline::RowSink;
use crate::trace::shade::channels;

/// Renders one frame of a scene with lights, planes or mirrors.
///
/// Out of line, as `lab1::render` is: the per-sphere constants live in this
/// function's own stack frame, so a render pays for its own method's, not for the
/// largest of all the methods the one dispatch could have chosen.
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
    by_origin::<N, L, P, D, K, S, T, Q, G, I>(scene, camera, options, (clips, rows), offset, sink)
}

/// `Auto` in a scene type of more than [`AUTO_FD_CAPACITY`] spheres' capacity.
///
/// The robust test for a scene holding more than that many, else `Auto` (each branch
/// out of line, so that their frames never add up).
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
    if scene.spheres().len() > AUTO_FD_CAPACITY {
        render::<N, L, P, D, K, S, Robust, Q, G, I>(scene, camera, options, frame, offset, sink)
    } else {
        auto_within_limit::<N, L, P, D, K, S, Q, G, I>(scene, camera, options, frame, offset, sink)
    }
}

/// `Auto` in a scene holding at most [`AUTO_FD_CAPACITY`] spheres.
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
    by_origin::<N, L, P, D, K, S, Auto, Q, G, I>(scene, camera, options, frame, offset, sink)
}

/// [`render`]'s frame with the secondary rays' origin rule, chosen once per frame.
#[inline(always)]
fn by_origin<
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
    match options.secondary {
        SecondaryOrigin::Convex => render_with::<N, L, P, D, K, S, T, Q, ConvexExit, G, I>(
            scene,
            camera,
            options,
            0.0,
            (clips, rows),
            offset,
            sink,
        ),
        SecondaryOrigin::Epsilon(eps) => render_with::<N, L, P, D, K, S, T, Q, EpsilonExit, G, I>(
            scene,
            camera,
            options,
            eps,
            (clips, rows),
            offset,
            sink,
        ),
    }
}

/// The smallest sphere radius of a frame (`∞` without spheres), in scene units: with
/// the lamp's distance from the eye it sets the length beyond which a shadow segment is
/// tested from the lamp (`RADII_FACTOR` in `consts`), a frame-wide decision.
pub(crate) fn smallest_radius(spheres: &[Sphere]) -> f32 {
    spheres.iter().fold(f32::INFINITY, |r, s| r.min(s.radius))
}

/// [`render`]'s frame with the exit strategy `O`: the frame's constants (spheres,
/// planes, lights, ties and shadow silhouettes) once, then each clip's rows.
///
/// `eps` is [`SecondaryOrigin::Epsilon`]'s epsilon in scene units (0 for the convex
/// exit).
fn render_with<
    const N: usize,
    const L: usize,
    const P: usize,
    const D: usize,
    K: RowSink,
    S: Stepper,
    T: TestStrategy,
    Q: SqrtFn,
    O: Exit,
    G: Rows,
    I: Iterator<Item = Rectangle> + Clone,
>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    options: Options,
    eps: f32,
    (clips, rows): (I, G),
    offset: Point,
    sink: &mut K,
) -> Result<(), K::Error> {
    let eye = camera.eye();
    let mut spheres = Vec::new();
    // Secondary rays can meet any object: none is culled for the frame's scale.
    // The frame's scale, from the scene, camera and method alone (never the clip).
    let step_err = S::error_bound(camera);
    let (scale, culled) = match frame_scale::<N, L, P, D>(scene, camera, step_err, false) {
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
    let Some(frame) =
        Frame::<T, LitSphere>::new::<N, N, L, P, D, S>(scene, setup, bound, offset, &mut spheres)
    else {
        return Ok(()); // nothing visible
    };
    let mut planes: Vec<FramePlane, P> = Vec::new();
    for p in scene.planes() {
        // Never fails: the scene holds at most P planes.
        let _ = planes.push(FramePlane::new(p, eye, frame.scale).unwrap_or(FramePlane::NEVER));
    }
    let mut lights: Vec<FrameLight, L> = Vec::new();
    let smallest = smallest_radius(scene.spheres()) * frame.scale.0;
    for l in scene.lights() {
        if let Some(fl) = FrameLight::new(l, eye, frame.scale, smallest) {
            let _ = lights.push(fl);
        }
    }
    let ties = Ties::new(scene, eye, frame.scale.0);
    // The floor's pixels shaded from per-frame constants in a scene type without
    // reflections (the row loop below).
    let floor = if D == 0 {
        planes
            .first()
            .and_then(|plane| Floor::<L>::new(plane, &lights, ties.exact_mask()))
    } else {
        None
    };
    let size = camera.size();
    let d_max = f64::from(camera.first_direction().length())
        + f64::from(size.width) * f64::from(camera.pixel_step().length())
        + f64::from(size.height) * f64::from(camera.scanline_step().length());
    // Shadow spans: per light and sphere, the image region where the sphere's shadow on
    // the first plane can fall — outside it a floor pixel does not test that sphere. A
    // scene without shadows casts no shadow ray, so none is built (they stay `ALL`).
    let mut shadow = [[Silhouette::ALL; N]; L];
    if let (true, true, Some(floor)) = (scene.settings().shadows, options.span_culling, planes.first()) {
        for (row, light) in shadow.iter_mut().zip(&lights) {
            for (sil, fs) in row.iter_mut().zip(frame.spheres) {
                *sil = shadow_silhouette(light, &fs.geom, floor, camera, step_err);
            }
        }
    }
    let shadow_rows: [ShadowRow<N>; L] = core::array::from_fn(|_| ShadowRow::empty());
    let lit = LitFrame {
        spheres: frame.spheres,
        ties: &ties,
        exact_lights: ties.exact_mask(),
        twins: ties.twins,
        shadow: &shadow,
        shadow_rows: &shadow_rows,
        planes: &planes,
        floor: floor.as_ref(),
        lights: &lights,
        camera,
        w: camera.w(),
        background: frame.background,
        bg: channels(frame.background),
        ambient: scene.settings().ambient,
        max_depth: scene.max_depth(),
        shadows: scene.settings().shadows,
        any_hit: options.shadow_any_hit,
        span_culling: options.span_culling,
        eps: eps * frame.scale.0,
        dn_margin: f64::from(step_err) + 8.0 * f64::from(UNIT_ROUNDOFF) * d_max,
        i0: frame.i0,
        i1: frame.i1,
    };
    for clip in clips {
        let Some(frame) = frame.clipped(rows.clip(clip)) else {
            continue;
        };
        let lit = LitFrame {
            i0: frame.i0,
            i1: frame.i1,
            ..lit
        };
        // A scene type without reflections has a row loop whose floor pixels take the
        // floor's constants (`floor.rs`); one with them keeps the general shading
        // inlined for every pixel (its floor may be a mirror). One loop per scene type.
        if D == 0 {
            rows.draw_rows::<N, K, S, T, Q, LitSphere, _>(&frame, sink, |j, lo, hi| {
                LitRow::<T, Q, O, N, L, P, D, true>::new(&lit, j, lo, hi)
            })?;
        } else {
            rows.draw_rows::<N, K, S, T, Q, LitSphere, _>(&frame, sink, |j, lo, hi| {
                LitRow::<T, Q, O, N, L, P, D, false>::new(&lit, j, lo, hi)
            })?;
        }
    }
    Ok(())
}
