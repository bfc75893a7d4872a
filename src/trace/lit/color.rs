//! The row tracer's colour of a primary ray: the local colour, mixed with what the
//! reflected rays see while the surface is a mirror and the depth allows, rounded to
//! 8 bits once.
//!
//! A loop, not recursion: the stack does not grow with the depth. Reflected rays take
//! the method's single-ray test ([`LitRow::closest`]). Adaptive sampling's rays take a
//! copy that also records the ray's identity ([`LitRow::color_identified`]), so the
//! one-ray path's code stays as it is.

use embedded_graphics::pixelcolor::Rgb888;

use crate::math::vec3::Vec3;
use crate::math::SqrtFn;
use crate::method::intersect::TestStrategy;
use crate::trace::lit::exit::Exit;
use crate::trace::lit::object::ObjectId;
use crate::trace::lit::row::LitRow;
use crate::trace::rows::{Fnv, Ident};

/// A reflected ray's identity where it hits nothing.
const REFLECTS_NOTHING: u32 = 0x9e37_79b9;

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
    /// The colour of a primary ray along `d` whose closest hit is `first`: the local
    /// colour, mixed with what the reflected rays see while the surface is a mirror and
    /// the depth allows, rounded to 8 bits once.
    ///
    /// Out of line, for the rows drawn as samples: the row loop inlines the tracer
    /// in several paths, and shading is hundreds of instructions per pixel.
    #[inline(never)]
    pub(super) fn color(&mut self, first: Option<(ObjectId, f32)>, d: Vec3, i: u32) -> Rgb888 {
        self.general(first, d, i)
    }

    /// [`Self::color`], for the colour runs (a `DrawTarget`'s path).
    ///
    /// In a scene type without reflections (`F`), a floor pixel is shaded inline from
    /// the frame's floor constants where it has them ([`Self::floor_color`]), and any
    /// other pixel by the out-of-line [`Self::color`]: the row loop keeps the short
    /// floor path in registers. With reflections (the floor may be a mirror) the general
    /// shading is inlined, so a pixel pays no call and no save of the FP registers it
    /// uses (`vpush d8–d15`; its cost: `docs/firmware.md`, "Lit frames").
    #[inline(always)]
    pub(super) fn shade(&mut self, first: Option<(ObjectId, f32)>, d: Vec3, i: u32) -> Rgb888 {
        if let (true, Some(floor), Some((k, t))) = (F, self.f.floor, first) {
            if k == ObjectId::new(self.f.spheres.len()) {
                return self.floor_color(floor, t, d, i);
            }
        }
        if F {
            self.color(first, d, i)
        } else {
            self.general(first, d, i)
        }
    }

    /// The general shading loop of [`Self::color`].
    #[inline(always)]
    fn general(&mut self, first: Option<(ObjectId, f32)>, d: Vec3, i: u32) -> Rgb888 {
        let f = self.f;
        let mut acc = [0.0f32; 3];
        let mut weight = 1.0f32;
        let (mut origin, mut dir, mut hit) = (Vec3::ZERO, d, first);
        let mut depth = 0u8;
        loop {
            let Some((k, t)) = hit else {
                add(&mut acc, weight, f.bg);
                break;
            };
            let p = origin + dir * t;
            let s = self.surface(k, p, dir, depth == 0);
            // The shadow spans hold for the primary ray only.
            let column = (depth == 0).then_some(i);
            let local = self.local(k, &s, p, dir, column);
            let r = if D == 0 { 0.0 } else { s.material.reflect };
            if !(r > 0.0) {
                add(&mut acc, weight, local);
                break;
            }
            add(&mut acc, weight * (1.0 - r), local);
            weight *= r;
            if depth >= f.max_depth {
                // At the deepest level the background stands in for the reflection.
                add(&mut acc, weight, f.bg);
                break;
            }
            // The mirror direction d − 2(d·n)n (the same for n and −n).
            dir = dir - s.n * (2.0 * dir.dot(s.n));
            origin = O::start(p, dir, f.eps);
            hit = self.closest(origin, dir, k, s.inside);
            depth += 1;
        }
        let round = |x: f32| {
            let v = (x + 0.5) as i32;
            if v > 255 {
                255
            } else {
                v as u8
            }
        };
        Rgb888::new(round(acc[0]), round(acc[1]), round(acc[2]))
    }

    /// [`Self::color`] with the ray's identity (see [`RowTracer::identified`]) mixed
    /// into `id`, for adaptive sampling.
    ///
    /// A copy, so that the one-ray path's code stays as it is. `CULL`: the primary ray
    /// is column `i`'s centre ray, so the row's shadow spans hold for it (a sub-pixel
    /// ray is not culled).
    ///
    /// [`RowTracer::identified`]: crate::trace::scanline::RowTracer::identified
    #[inline(always)]
    fn color_with<I: Ident, const CULL: bool>(
        &mut self,
        first: Option<(ObjectId, f32)>,
        d: Vec3,
        i: u32,
        id: &mut I,
    ) -> Rgb888 {
        let f = self.f;
        let mut acc = [0.0f32; 3];
        let mut weight = 1.0f32;
        let (mut origin, mut dir, mut hit) = (Vec3::ZERO, d, first);
        let mut depth = 0u8;
        loop {
            let Some((k, t)) = hit else {
                if depth > 0 {
                    id.mix(REFLECTS_NOTHING);
                }
                add(&mut acc, weight, f.bg);
                break;
            };
            let p = origin + dir * t;
            let s = self.surface(k, p, dir, depth == 0);
            if I::KEPT && depth == 0 {
                self.fine_checker(k, t, dir, id);
            }
            // The object, and its colour there (a checker cell).
            id.mix(k.index() as u32 + 1);
            id.mix(s.rgb.iter().fold(0, |h, c| h.rotate_left(11) ^ c.to_bits()));
            // The shadow spans hold for the primary ray only.
            let column = (CULL && depth == 0).then_some(i);
            let local = self.local_with(k, &s, p, dir, column, id);
            let r = if D == 0 { 0.0 } else { s.material.reflect };
            if !(r > 0.0) {
                add(&mut acc, weight, local);
                break;
            }
            add(&mut acc, weight * (1.0 - r), local);
            weight *= r;
            if depth >= f.max_depth {
                // At the deepest level the background stands in for the reflection.
                add(&mut acc, weight, f.bg);
                break;
            }
            // The mirror direction d − 2(d·n)n (the same for n and −n).
            dir = dir - s.n * (2.0 * dir.dot(s.n));
            origin = O::start(p, dir, f.eps);
            hit = self.closest(origin, dir, k, s.inside);
            depth += 1;
        }
        let round = |x: f32| {
            let v = (x + 0.5) as i32;
            if v > 255 {
                255
            } else {
                v as u8
            }
        };
        Rgb888::new(round(acc[0]), round(acc[1]), round(acc[2]))
    }

    /// Whether the primary ray `dir` meeting object `k` at `t` sees a checker whose
    /// cells are less than two pixel footprints wide (then `id.fine()`).
    ///
    /// Moving to the next pixel turns the ray by `du` (or `dv`), which moves its hit on
    /// the plane by at most `t·|du|·(1 + |d|/|d·n|)`.
    #[inline(always)]
    fn fine_checker<I: Ident>(&self, k: ObjectId, t: f32, dir: Vec3, id: &mut I) {
        let f = self.f;
        let Some(plane) = k
            .index()
            .checked_sub(f.spheres.len())
            .and_then(|p| f.planes.get(p))
        else {
            return;
        };
        if plane.checker.is_none() {
            return;
        }
        let step = f
            .camera
            .pixel_step()
            .length()
            .max(f.camera.scanline_step().length());
        let dn = dir.dot(plane.n).abs();
        let footprint = t * step * (1.0 + dir.length() / dn);
        // NaN (a ray along the plane) fails the comparison: fine as well.
        if !(footprint * plane.inv_size <= 0.5) {
            id.fine();
        }
    }

    /// [`Self::color_with`] with the identity: out of line, like [`Self::color`].
    #[inline(never)]
    pub(super) fn color_identified<const CULL: bool>(
        &mut self,
        first: Option<(ObjectId, f32)>,
        d: Vec3,
        i: u32,
    ) -> (u32, Rgb888) {
        let mut id = Fnv(0, false);
        let c = self.color_with::<Fnv, CULL>(first, d, i, &mut id);
        (id.get(), c)
    }
}

/// `acc += weight·c`, per channel.
#[inline(always)]
fn add(acc: &mut [f32; 3], weight: f32, c: [f32; 3]) {
    for (a, c) in acc.iter_mut().zip(c) {
        *a += weight * c;
    }
}
