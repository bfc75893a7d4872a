//! The rule for a frame the integer kernel draws: its quantisation compared, and each
//! changed sphere's old and new cut.

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::VecView;

use crate::integer::{IntSphere, Quantisation};
use crate::method::dispatch::dispatch;
use crate::render::Render;

use super::plan::Probe;
use super::{Changes, Incremental, STRIP_SETUP};

/// What the integer kernel's per-frame rule said of a frame, as far as the plan knows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum IntRule {
    /// Not asked (the method is `f32`, or the scene has features).
    Unknown,
    /// The rule does not take the frame: the `f32` method draws it.
    Refused,
    /// The rule takes the frame with this quantisation.
    Took(Quantisation),
}

impl<const N: usize, const L: usize, const P: usize, const D: usize> Incremental<N, L, P, D> {
    /// The rule for a frame the integer kernel can draw, or `None` where neither frame
    /// is the integer kernel's (the `f32` rule then applies).
    ///
    /// Its frame-wide quantisation is equal in both frames, else the whole frame is
    /// drawn; the regions are each changed sphere's old and new cut (the columns its
    /// rows are culled to). A frame the kernel's rule leaves to the `f32` method after
    /// one it drew is drawn whole, or refused where the `f32` method refuses it: the
    /// plan reports every refusal the render makes. The shown frame's rule is the one
    /// its own plan found (the same scene, camera and options): only its changed
    /// spheres' cuts are computed again.
    // Inlined, as `Render::draw` is: with a constant method only its code is linked.
    #[inline(always)]
    pub(super) fn plan_integer<C>(
        &self,
        render: &Render<'_, N, C, L, P, D>,
        target: Rectangle,
        offset: Point,
        picture: Option<&mut VecView<IntSphere>>,
    ) -> Option<Changes> {
        let (camera, scene, options) = (render.camera(), render.scene(), render.options());
        let size = camera.size();
        let shown = match &self.shown {
            Some(shown) if shown.same_frame(render, target, offset) => shown,
            // The whole frame, if the integer kernel's rule takes it.
            _ => {
                let key = match picture {
                    Some(buf) => {
                        crate::integer::picture(buf, scene.spheres(), camera, options, |_| false, |_, _| {})
                    }
                    None => {
                        crate::integer::regions::<N>(scene.spheres(), camera, options, |_| false, |_, _| {})
                    }
                }?;
                return Some(Changes::full_with(size, IntRule::Took(key)));
            }
        };
        let changed = |k: usize| shown.changed(scene, k);
        let mut plan = Changes::empty(size, STRIP_SETUP.one_frame, 0);
        let mut ok = true;
        let mut add = |rows: (u32, u32), cut| ok &= plan.push_cut(rows, cut);
        // Each frame's quantisation, found with its changed spheres' cuts: the cuts are
        // the plan only if the two quantisations are equal.
        let new_key = match picture {
            Some(buf) => crate::integer::picture(buf, scene.spheres(), camera, options, changed, &mut add),
            None => crate::integer::regions::<N>(scene.spheres(), camera, options, changed, &mut add),
        };
        let old_key = match shown.int_rule {
            IntRule::Took(key) => {
                crate::integer::cuts(shown.scene.spheres(), camera, options, changed, &mut add);
                Some(key)
            }
            IntRule::Refused => None,
            IntRule::Unknown => {
                crate::integer::regions::<N>(shown.scene.spheres(), camera, options, changed, &mut add)
            }
        };
        let rule = new_key.map_or(IntRule::Refused, IntRule::Took);
        match (old_key, new_key) {
            (None, None) => return None,
            (Some(a), Some(b)) if a == b => {}
            (_, Some(_)) => return Some(Changes::full_with(size, rule)),
            (Some(_), None) => {
                let probe = Probe {
                    scene,
                    camera,
                    sampling: render.sampling(),
                    options,
                };
                let mut plan = match dispatch(render.method(), probe) {
                    Ok(_) => Changes::full(size),
                    Err(why) => Changes::refusal(size, why),
                };
                plan.int_rule = rule;
                return Some(plan);
            }
        }
        if let Some(stale) = self.stale {
            ok &= plan.push_rect(stale);
        }
        if !ok {
            return Some(Changes::full_with(size, rule));
        }
        plan.merge();
        plan.int_rule = rule;
        Some(plan)
    }
}
