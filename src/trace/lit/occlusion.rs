//! The row tracer's shadow tests: whether a shadow ray ([`ShadowRay`]) is blocked, any
//! hit, with the row's shadow spans and its last occluder per light.
//!
//! A shadow ray takes [`LitRow::shadowed`]: the plain test ([`LitRow::occluded`]),
//! inlined into the shading loop, or out of line the exact path
//! ([`LitRow::occluded_exact`]) for a light the frame's ties concern and for a point
//! light's segment beyond its far limit (tested from the lamp's end).

use crate::math::SqrtFn;
use crate::method::intersect::TestStrategy;
use crate::trace::lit::consts::FrameLight;
use crate::trace::lit::exact::{occluded_exact, Lamp, Objects};
use crate::trace::lit::exit::{far_root, Exit};
use crate::trace::lit::object::{LastOccluder, ObjectId};
use crate::trace::lit::row::LitRow;
use crate::trace::lit::shadow::ShadowRay;

impl<
        T: TestStrategy,
        Q: SqrtFn,
        O: Exit,
        const N: usize,
        const L: usize,
        const P: usize,
        const D: usize,
        const F: bool,
    > LitRow<'_, '_, T, Q, O, N, L, P, D, F>
{
    /// Whether object `k` crosses the open segment of `ray` (its `from`/`inside` as for
    /// [`Self::closest`]).
    #[inline(always)]
    pub(super) fn blocks(&self, k: ObjectId, ray: ShadowRay) -> bool {
        let ShadowRay {
            o,
            l,
            dist,
            from,
            inside,
        } = ray;
        let f = self.f;
        if let Some(s) = f.spheres.get(k.index()) {
            if !O::TESTS_SELF && k == from {
                if !inside {
                    return false;
                }
                let t = far_root(&s.geom, o, l, l.dot(l));
                return t > 0.0 && t < dist;
            }
            // A segment wholly inside a sphere ends before its far root: `t < dist` fails.
            T::ray::<Q>(&s.geom.seen_from(o), l, l.dot(l), dist).is_some()
        } else if let Some(plane) = k
            .index()
            .checked_sub(f.spheres.len())
            .and_then(|p| f.planes.get(p))
        {
            if !O::TESTS_SELF && k == from {
                return false;
            }
            let t = plane.t_from(o, l);
            t > 0.0 && t < dist
        } else {
            false
        }
    }

    /// Whether the light's shadow ray is blocked: [`Self::occluded`], or for a light
    /// whose shadow rays need the frame's ties or a segment beyond the far limit
    /// (`far`), [`Self::occluded_exact`].
    ///
    /// A branch on a per-frame mask, not a call through a pointer: the plain test is
    /// inlined into the shading loop, its ray in registers (a frame without ties never
    /// takes the other branch).
    ///
    /// The ray comes as a function that builds it, called in each branch: the exact
    /// path takes it in memory, and built once before the branch its stores would be
    /// paid by every shadow ray.
    #[inline(always)]
    pub(super) fn shadowed(
        &mut self,
        light: usize,
        ray: impl Fn() -> ShadowRay,
        far: bool,
        column: Option<u32>,
    ) -> bool {
        if far || self.f.exact_lights & (1 << light.min(31)) != 0 {
            self.occluded_exact(light, ray(), far)
        } else {
            self.occluded(light, ray(), column)
        }
    }

    /// Whether the light's shadow ray is blocked, any hit.
    ///
    /// For a primary ray's hit on the first plane (`column` is its column), only the
    /// spheres whose shadow span on this row holds the column can block it, then the
    /// other planes; otherwise the light's last occluder first, then every object until
    /// one blocks. The literal baseline tests every object, as a closest-hit search
    /// would. Any hit: the order of the tests changes no answer.
    #[inline(always)]
    pub(super) fn occluded(&mut self, light: usize, ray: ShadowRay, column: Option<u32>) -> bool {
        let f = self.f;
        let n = f.spheres.len();
        let count = n + f.planes.len();
        if !f.any_hit {
            let mut blocked = false;
            for k in (0..count).map(ObjectId::new) {
                blocked |= self.blocks(k, ray);
            }
            return blocked;
        }
        if let (Some(i), true, Some(row)) = (column, ray.from == ObjectId::new(n), f.shadow_rows.get(light)) {
            for slot in row.spans.iter().take(row.count.get()) {
                let (k, lo, len) = slot.get();
                if i.wrapping_sub(lo) < len && self.blocks(k, ray) {
                    return true;
                }
            }
            // The first plane is the ray's own (convex: never met again) unless the
            // exit rule tests it.
            let first = usize::from(!O::TESTS_SELF);
            return (n + first..count).map(ObjectId::new).any(|k| self.blocks(k, ray));
        }
        let cached = self.occluder.get(light).copied().unwrap_or(LastOccluder::NONE);
        if let Some(c) = cached.get() {
            if self.blocks(c, ray) {
                return true;
            }
        }
        for k in (0..count).map(ObjectId::new) {
            if !cached.holds(k) && self.blocks(k, ray) {
                if let Some(c) = self.occluder.get_mut(light) {
                    *c = LastOccluder::of(k);
                }
                return true;
            }
        }
        false
    }

    /// [`Self::occluded`] for a light whose shadow rays need the frame's ties
    /// ([`Ties`]) — its lamp lies on some object, or the frame has coincident objects —
    /// and for a point light's segment longer than its far limit ([`FAR_FACTOR`],
    /// `far`), which is tested from the lamp's end.
    ///
    /// Every object is tested (no shadow span, no cached occluder): an object with a
    /// lower-numbered twin is left out, the twin of the surface the ray leaves is that
    /// surface, and an object the lamp lies on is decided by the side the segment
    /// reaches the lamp from.
    ///
    /// Out of line, one call site: only a frame with ties or a segment beyond the far
    /// limit (no standard scene has one) takes it, and the plain test keeps its ray in
    /// registers.
    ///
    /// [`Ties`]: crate::trace::lit::ties::Ties
    /// [`FAR_FACTOR`]: crate::trace::lit::consts::FAR_FACTOR
    #[inline(never)]
    pub(super) fn occluded_exact(&self, light: usize, ray: ShadowRay, far: bool) -> bool {
        let f = self.f;
        let (Some(on_sphere), Some(sphere_g), Some(on_plane), Some(at)) = (
            f.ties.on_sphere.get(light),
            f.ties.sphere_g.get(light),
            f.ties.on_plane.get(light),
            f.lights.get(light).map(FrameLight::at),
        ) else {
            return false;
        };
        let objects = Objects {
            far: far.then_some(at),
            ..self.objects()
        };
        occluded_exact::<T, Q>(
            &objects,
            Lamp {
                on_sphere,
                sphere_g,
                on_plane,
                at,
            },
            ray,
        )
    }
}
