//! The shading of a primary ray's hit on the first plane, the floor
//! ([`LitRow::floor_color`]): the general shading's arithmetic in its order, with what
//! is constant over the frame formed once (`Floor`, `consts.rs`).
//!
//! Most pixels of a lit scene are floor pixels, and the general shading
//! (`shading.rs`, `color.rs`) works out per pixel what a floor's pixels share: which
//! surface was met and its normal turned toward the eye, the material's highlight and
//! mirror, a directional light's `n·l` and its diffuse term. In a scene type without
//! reflections (`Scene<N, L, P>`, `D = 0`) and for a floor without a highlight, a frame
//! forms those once, and a floor pixel reads its checker cell, its lamps and its
//! shadow rays alone; the frame's other pixels take the general shading out of line
//! (a call a pixel), so that the row loop keeps the floor's path in registers. Every
//! value is the general path's, bit for bit: the same operations on the same operands
//! in the same order.
//!
//! **Cost where it does not apply**: a frame of such a scene type whose floor has a
//! highlight (or that has no lights) shades every pixel through the out-of-line call:
//! `mirrors` drawn through such a loop took 1,719.9 estimated cycles a pixel on the
//! Cortex-M4F against 1,652.4 with the general shading inlined, as a scene type with
//! reflections keeps it.

use embedded_graphics::pixelcolor::Rgb888;

use crate::math::sqrt_exact;
use crate::math::vec3::Vec3;
use crate::math::SqrtFn;
use crate::method::intersect::TestStrategy;
use crate::trace::lit::consts::{Floor, FloorLight};
use crate::trace::lit::exit::Exit;
use crate::trace::lit::object::ObjectId;
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
    /// The colour of column `i`'s primary ray along `d`, whose closest hit is the floor
    /// at `t`.
    ///
    /// The general shading's steps for such a hit, each value the same bits: the hit
    /// point `0 + d·t`, the checker cell, per light (in the scene's order) the lamp's
    /// distance and direction and `n·l`, the shadow ray as [`LitRow::shadowed`] tests
    /// it, the diffuse sum, then `c·(ambient + diffuse) + 0` clamped to 255 and
    /// rounded. The general path then adds that local colour, weighted by 1,
    /// to a zero sum: `0 + 1·x = x` for every `x` it can be (not below `+0`: `c·light
    /// + 0` is never `−0`; or NaN), so the sum is left out.
    #[inline(always)]
    pub(super) fn floor_color(&mut self, floor: &Floor<L>, t: f32, d: Vec3, i: u32) -> Rgb888 {
        let f = self.f;
        let k = ObjectId::new(f.spheres.len());
        let p = Vec3::ZERO + d * t;
        let rgb = f.planes.first().map_or(f.bg, |plane| plane.color_at(p));
        let mut diffuse = 0.0f32;
        for (index, light) in floor.lights.iter().enumerate() {
            let (l, dist, far, term, exact) = match *light {
                FloorLight::Dark => continue,
                FloorLight::Sun { l, term, exact } => (l, f32::INFINITY, f32::INFINITY, term, exact),
                FloorLight::Lamp {
                    p: at,
                    intensity,
                    far,
                    exact,
                } => {
                    let to = at - p;
                    let dist = sqrt_exact(to.dot(to));
                    let l = to * (1.0 / dist);
                    let nl = floor.n.dot(l);
                    if !(nl > 0.0) {
                        continue;
                    }
                    (l, dist, far, intensity * nl, exact)
                }
            };
            if f.shadows {
                let o = O::start(p, l, f.eps);
                let dist = if O::TESTS_SELF { dist - f.eps } else { dist };
                // Built in each branch (see `LitRow::shadowed`).
                let ray = || ShadowRay {
                    o,
                    l,
                    dist,
                    from: k,
                    inside: false,
                };
                // `LitRow::shadowed`'s choice, its mask bit read once per frame.
                let far = dist > far;
                let blocked = if far || exact {
                    self.occluded_exact(index, ray(), far)
                } else {
                    self.occluded(index, ray(), Some(i))
                };
                if blocked {
                    continue;
                }
            }
            diffuse += term;
        }
        let light = f.ambient + diffuse;
        let ch = |c: f32| {
            let x = c * light + 0.0;
            let x = if x > 255.0 { 255.0 } else { x };
            let v = (x + 0.5) as i32;
            if v > 255 {
                255
            } else {
                v as u8
            }
        };
        Rgb888::new(ch(rgb[0]), ch(rgb[1]), ch(rgb[2]))
    }
}
