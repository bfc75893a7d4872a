//! The features path's row tracer ([`LitRow`]): per row the planes' and the shadows'
//! spans, per pixel the primary ray's closest hit over the spheres and planes.
//!
//! A plane covers one side of its horizon line, and `d·n` is linear along the row, so
//! its span is found once per row ([`plane_span`]), enlarged by the stepping's error
//! bound. The pixel's colour is the shading loop's (`color.rs`), its shadow rays the
//! occlusion tests' (`occlusion.rs`).

use embedded_graphics::pixelcolor::Rgb888;

use crate::math::vec3::Vec3;
use crate::math::SqrtFn;
use crate::method::intersect::TestStrategy;
use crate::trace::frame::FrameSphere;
use crate::trace::lit::consts::{FramePlane, LitSphere};
use crate::trace::lit::exact::{closest_twins, Objects};
use crate::trace::lit::exit::{far_root, Exit};
use crate::trace::lit::frame::LitFrame;
use crate::trace::lit::object::{LastOccluder, ObjectId};
use crate::trace::scanline::RowTracer;

/// One row of the scene-features path: the planes' spans, the shadow spans and, per
/// light, the object that last shadowed a pixel of the row.
///
/// The last occluder is tested first: neighbouring pixels are usually shadowed by the
/// same one. `F`: the scene type has no reflections, and the floor's pixels take the
/// frame's floor constants where it has them (`LitFrame::floor`, `floor.rs`).
pub(super) struct LitRow<
    'f,
    's,
    T: TestStrategy,
    Q,
    O,
    const N: usize,
    const L: usize,
    const P: usize,
    const D: usize,
    const F: bool,
> {
    pub(super) f: &'f LitFrame<'s, T, N, L, P>,
    /// Per plane: columns `[lo, lo + len)` whose rays can hit it.
    spans: [(u32, u32); P],
    /// Per light: the object that last blocked its shadow ray on this row.
    pub(super) occluder: [LastOccluder; L],
    marker: core::marker::PhantomData<(Q, O)>,
}

impl<
        'f,
        's,
        T: TestStrategy,
        Q: SqrtFn,
        O: Exit,
        const N: usize,
        const L: usize,
        const P: usize,
        const D: usize,
        const F: bool,
    > LitRow<'f, 's, T, Q, O, N, L, P, D, F>
{
    /// Row `j`: the planes' spans, widening the row's traced union `[lo_all, hi_all)`,
    /// and the shadow spans.
    #[inline(never)]
    pub(super) fn new(f: &'f LitFrame<'s, T, N, L, P>, j: u32, lo_all: &mut u32, hi_all: &mut u32) -> Self {
        let mut spans = [(0, 0); P];
        for (span, plane) in spans.iter_mut().zip(f.planes) {
            if let Some((lo, hi)) = plane_span(f, plane, j) {
                *span = (lo, hi - lo);
                *lo_all = (*lo_all).min(lo);
                *hi_all = (*hi_all).max(hi);
            }
        }
        // The shadow spans of this row (where the first plane is in view at all).
        let floor_in_view = spans.first().is_some_and(|&(_, len)| len > 0);
        for (row, sils) in f.shadow_rows.iter().zip(f.shadow).take(f.lights.len()) {
            let mut count = 0;
            if floor_in_view {
                for (k, sil) in sils.iter().enumerate().take(f.spheres.len()) {
                    if let (Some((lo, hi)), Some(slot)) = (sil.row_span(j, f.i0, f.i1), row.spans.get(count))
                    {
                        slot.set((ObjectId::new(k), lo, hi - lo));
                        count += 1;
                    }
                }
            }
            row.count.set(count);
        }
        Self {
            f,
            spans,
            occluder: [LastOccluder::NONE; L],
            marker: core::marker::PhantomData,
        }
    }

    /// The object a ray from `o` along `dir` meets first, and where; `from` is the
    /// object `o` lies on (`inside`: on a sphere's inner surface).
    pub(super) fn closest(
        &self,
        o: Vec3,
        dir: Vec3,
        from: ObjectId,
        inside: bool,
    ) -> Option<(ObjectId, f32)> {
        let f = self.f;
        if f.twins {
            return self.closest_twins(o, dir, from, inside);
        }
        let a = dir.dot(dir);
        let mut best = None;
        let mut t_max = f32::INFINITY;
        for (k, s) in f.spheres.iter().enumerate() {
            let t = if !O::TESTS_SELF && ObjectId::new(k) == from {
                // Leaving the outside: convex, never met again. Leaving the inner
                // surface: met at the far root, directly.
                if !inside {
                    continue;
                }
                let t = far_root(&s.geom, o, dir, a);
                (t > 0.0 && t < t_max).then_some(t)
            } else {
                T::ray::<Q>(&s.geom.seen_from(o), dir, a, t_max)
            };
            if let Some(t) = t {
                t_max = t;
                best = Some((ObjectId::new(k), t));
            }
        }
        let n = f.spheres.len();
        for (k, plane) in f.planes.iter().enumerate() {
            if !O::TESTS_SELF && ObjectId::new(n + k) == from {
                continue; // a ray leaving a plane never meets it again
            }
            let t = plane.t_from(o, dir);
            if t > 0.0 && t < t_max {
                t_max = t;
                best = Some((ObjectId::new(n + k), t));
            }
        }
        best
    }

    /// [`Self::closest`] in a frame with coincident objects ([`Ties`]).
    ///
    /// An object with a lower-numbered twin is left out (the twin computes the same bits
    /// and wins the tie), and the twin of the surface the ray leaves is that surface.
    ///
    /// [`Ties`]: crate::trace::lit::ties::Ties
    #[inline(always)]
    fn closest_twins(&self, o: Vec3, dir: Vec3, from: ObjectId, inside: bool) -> Option<(ObjectId, f32)> {
        closest_twins::<T, Q>(&self.objects(), o, dir, from, inside)
    }

    /// The frame's objects and ties as the exact paths read them.
    #[inline(always)]
    pub(super) fn objects(&self) -> Objects<'_, T> {
        let f = self.f;
        Objects {
            spheres: f.spheres,
            planes: f.planes,
            sphere_twin: &f.ties.sphere_twin,
            plane_twin: &f.ties.plane_twin,
            tests_self: O::TESTS_SELF,
            far: None,
        }
    }
}

impl<
        's,
        T: TestStrategy,
        Q: SqrtFn,
        O: Exit,
        const N: usize,
        const L: usize,
        const P: usize,
        const D: usize,
        const F: bool,
    > RowTracer<'s, T, LitSphere> for LitRow<'_, 's, T, Q, O, N, L, P, D, F>
{
    #[inline(always)]
    fn background(&self) -> Rgb888 {
        self.f.background
    }

    #[inline(always)]
    fn pixel(
        &mut self,
        sphere_hit: Option<(usize, f32, &'s FrameSphere<T, LitSphere>)>,
        i: u32,
        d: Vec3,
    ) -> (Option<(usize, f32)>, Rgb888) {
        let best = self.primary::<true>(sphere_hit, i, d);
        (best.map(|(k, t)| (k.index(), t)), self.color(best, d, i))
    }

    #[inline(always)]
    fn color(
        &mut self,
        sphere_hit: Option<(usize, f32, &'s FrameSphere<T, LitSphere>)>,
        i: u32,
        d: Vec3,
    ) -> Rgb888 {
        let best = self.primary::<true>(sphere_hit, i, d);
        self.shade(best, d, i)
    }

    #[inline(always)]
    fn identified(
        &mut self,
        sphere_hit: Option<(usize, f32, &'s FrameSphere<T, LitSphere>)>,
        i: u32,
        d: Vec3,
    ) -> (u32, Rgb888) {
        let best = self.primary::<true>(sphere_hit, i, d);
        self.color_identified::<true>(best, d, i)
    }

    #[inline(always)]
    fn sub_sample(
        &mut self,
        sphere_hit: Option<(usize, f32, &'s FrameSphere<T, LitSphere>)>,
        d: Vec3,
    ) -> (u32, Rgb888) {
        let best = self.primary::<false>(sphere_hit, 0, d);
        self.color_identified::<false>(best, d, 0)
    }
}

impl<
        's,
        T: TestStrategy,
        Q: SqrtFn,
        O: Exit,
        const N: usize,
        const L: usize,
        const P: usize,
        const D: usize,
        const F: bool,
    > LitRow<'_, 's, T, Q, O, N, L, P, D, F>
{
    /// The closest hit of the primary ray `d`: the sphere hit, then the planes (with
    /// `CULL`, only those whose row span holds column `i`).
    #[inline(always)]
    fn primary<const CULL: bool>(
        &self,
        sphere_hit: Option<(usize, f32, &'s FrameSphere<T, LitSphere>)>,
        i: u32,
        d: Vec3,
    ) -> Option<(ObjectId, f32)> {
        let mut best = sphere_hit.map(|(k, t, _)| (ObjectId::new(k), t));
        let mut t_max = best.map_or(f32::INFINITY, |(_, t)| t);
        let n = self.f.spheres.len();
        for (k, (plane, &(lo, len))) in self.f.planes.iter().zip(&self.spans).enumerate() {
            if !CULL || i.wrapping_sub(lo) < len {
                // t = (q·n)/(d·n): positive where d·n has the sign of q·n.
                let t = plane.s / d.dot(plane.n);
                if t > 0.0 && t < t_max {
                    t_max = t;
                    best = Some((ObjectId::new(n + k), t));
                }
            }
        }
        best
    }
}

/// Row `j`'s columns whose rays can hit `plane`, clamped to the visible ones; `None` if
/// none can.
///
/// The ideal direction `F + i·du + j·dv` makes `d·n = A + i·B` linear in the column; a
/// ray hits where `σ·d·n > 0` (`σ` the sign of `q·n`). The computed `d·n` is within
/// `dn_margin` of the ideal one (the stepping's bound `E` on `|d − ideal|` with
/// `|n| = 1`, plus the dot product's rounding), so columns with `σ(A + iB) > −margin`
/// are kept; computed in `f64`, once per row and plane.
fn plane_span<T: TestStrategy, const N: usize, const L: usize, const P: usize>(
    f: &LitFrame<'_, T, N, L, P>,
    plane: &FramePlane,
    j: u32,
) -> Option<(u32, u32)> {
    let (i0, i1) = (f.i0, f.i1);
    if !(plane.s != 0.0) {
        return None; // the eye is on the plane (or NaN): no ray hits it at t > 0
    }
    if !f.span_culling {
        return Some((i0, i1));
    }
    let c = f.camera;
    let n = [f64::from(plane.n.x), f64::from(plane.n.y), f64::from(plane.n.z)];
    let dot = |v: Vec3| f64::from(v.x) * n[0] + f64::from(v.y) * n[1] + f64::from(v.z) * n[2];
    let sigma = if plane.s > 0.0 { 1.0 } else { -1.0 };
    let a = sigma * (dot(c.first_direction()) + f64::from(j) * dot(c.scanline_step()));
    let b = sigma * dot(c.pixel_step());
    let m = f.dn_margin;
    // σ(A + iB) > −m  ⇔  i·b > −m − a.
    let x = (-m - a) / b;
    let (lo, hi) = if b > 0.0 {
        // i > x: from ⌊x⌋ (one column of slack) on.
        (libm::floor(x), f64::from(i1))
    } else if b < 0.0 {
        // i < x: up to ⌊x⌋ + 1 (exclusive), one column of slack.
        (f64::from(i0), libm::floor(x) + 2.0)
    } else if a > -m {
        (f64::from(i0), f64::from(i1))
    } else {
        return None;
    };
    // Clamp with comparisons (a NaN bound keeps the whole row: conservative).
    let lo = if lo > f64::from(i0) { lo as u32 } else { i0 };
    let hi = if hi < f64::from(i1) { hi as u32 } else { i1 };
    (lo < hi).then_some((lo, hi))
}
