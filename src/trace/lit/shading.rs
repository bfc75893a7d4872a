//! The row tracer's shading of a surface point: the surface met ([`Surface`]) and its
//! local colour.
//!
//! Lab #1 without lights; with lights, Phong (ambient, diffuse and a specular
//! highlight, [`phong_power`]) with a shadow ray per light.

use crate::math::sqrt_exact;
use crate::math::vec3::Vec3;
use crate::math::SqrtFn;
use crate::method::intersect::TestStrategy;
use crate::scene::material::Material;
use crate::trace::lit::consts::FrameLight;
use crate::trace::lit::exit::Exit;
use crate::trace::lit::object::ObjectId;
use crate::trace::lit::row::LitRow;
use crate::trace::lit::shadow::ShadowRay;
use crate::trace::rows::Ident;
use crate::trace::shade::lab1_factor;

/// A surface point: its normal turned toward the ray's origin, colour and material.
pub(super) struct Surface {
    pub(super) n: Vec3,
    pub(super) rgb: [f32; 3],
    pub(super) material: Material,
    /// The ray met a sphere's inner surface (it can meet it again).
    pub(super) inside: bool,
}

impl Surface {
    /// Lab #1's colour: the colour times [`lab1_factor`] of `n_z = n·(−w)` with a
    /// sphere's outward normal (`n` turned back where the ray is inside: `(−n)·w` and
    /// `−(n·w)` differ at most in the sign of a zero or a NaN, which the factor does not
    /// see) or a plane's turned one. Formed only in a frame without lights, the one that
    /// reads it.
    #[inline(always)]
    fn lab1(&self, w: Vec3) -> [f32; 3] {
        let nw = self.n.dot(w);
        let kz = lab1_factor(if self.inside { nw } else { -nw });
        self.rgb.map(|c| c * kz)
    }
}

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
    /// The surface at `p` of object `k`, met by a ray along `dir`; `primary`: the ray is
    /// the pixel's own, whose hit the row's primary test found.
    ///
    /// A plane's normal is turned toward the ray's origin by the sign of `dir·n`. For a
    /// primary ray that sign is the frame's: the hit had `0 < t = s/(dir·n) < t_max ≤ ∞`
    /// with this very `dir·n` (a quotient's sign is the product of its operands' signs,
    /// and `dir·n = ±0` gives `t = ±∞` or NaN, never below `t_max`), so it has the sign
    /// of `s`, and the normal is chosen by `s` without the product (the same normal, bit
    /// for bit).
    #[inline(always)]
    pub(super) fn surface(&self, k: ObjectId, p: Vec3, dir: Vec3, primary: bool) -> Surface {
        let f = self.f;
        if let Some(s) = f.spheres.get(k.index()) {
            let n_out = (p - s.geom.l) * s.shade.inv_r;
            let inside = dir.dot(n_out) > 0.0;
            Surface {
                n: if inside { -n_out } else { n_out },
                rgb: s.shade.rgb,
                material: s.shade.material,
                inside,
            }
        } else if let Some(plane) = k
            .index()
            .checked_sub(f.spheres.len())
            .and_then(|i| f.planes.get(i))
        {
            let away = if primary {
                plane.s > 0.0
            } else {
                dir.dot(plane.n) > 0.0
            };
            Surface {
                n: if away { -plane.n } else { plane.n },
                rgb: plane.color_at(p),
                material: plane.material,
                inside: false,
            }
        } else {
            // Unreachable (`k` comes from a hit); shade as the background.
            Surface {
                n: f.w,
                rgb: f.bg,
                material: Material::DEFAULT,
                inside: false,
            }
        }
    }

    /// The local colour at `p` (not rounded): Lab #1 without lights, otherwise
    /// ambient + diffuse + specular with a shadow ray per light.
    #[inline(always)]
    pub(super) fn local(
        &mut self,
        k: ObjectId,
        s: &Surface,
        p: Vec3,
        dir: Vec3,
        column: Option<u32>,
    ) -> [f32; 3] {
        if L == 0 || self.f.lights.is_empty() {
            return s.lab1(self.f.w);
        }
        let f = self.f;
        // v, the unit vector back along the ray, only where a highlight needs it.
        let v = if s.material.specular > 0.0 {
            dir * (-1.0 / sqrt_exact(dir.dot(dir)))
        } else {
            Vec3::ZERO
        };
        let (mut diffuse, mut spec) = (0.0f32, 0.0f32);
        for (index, light) in f.lights.iter().enumerate() {
            let (l, dist, intensity, far) = match *light {
                FrameLight::Directional { l, intensity } => (l, f32::INFINITY, intensity, f32::INFINITY),
                FrameLight::Point {
                    p: at,
                    intensity,
                    far,
                } => {
                    let to = at - p;
                    let dist = sqrt_exact(to.dot(to));
                    (to * (1.0 / dist), dist, intensity, far)
                }
            };
            let nl = s.n.dot(l);
            // Only a light in front of the surface lights it (and needs a shadow ray).
            if !(nl > 0.0) {
                continue;
            }
            if f.shadows {
                let o = O::start(p, l, f.eps);
                let dist = if O::TESTS_SELF { dist - f.eps } else { dist };
                let ray = || ShadowRay {
                    o,
                    l,
                    dist,
                    from: k,
                    inside: s.inside,
                };
                // Beyond the far limit the segment is tested from the lamp's end.
                let blocked = self.shadowed(index, ray, dist > far, column);
                if blocked {
                    continue;
                }
            }
            diffuse += intensity * nl;
            if s.material.specular > 0.0 {
                // n·h with h = (l + v)/|l + v|: one root and one division, no vector
                // scaling (|l + v| ≤ 2: no overflow). No highlight where l + v = 0.
                let half = l + v;
                let h2 = half.dot(half);
                if h2 > 0.0 {
                    let nh = s.n.dot(half) / sqrt_exact(h2);
                    if nh > 0.0 {
                        spec += intensity * s.material.specular * phong_power(nh, s.material.shininess);
                    }
                }
            }
        }
        let light = f.ambient + diffuse;
        let spec = 255.0 * spec;
        s.rgb.map(|c| {
            let x = c * light + spec;
            if x > 255.0 {
                255.0
            } else {
                x
            }
        })
    }

    /// [`Self::local`] with the ray's identity (which lights reach the point) mixed
    /// into `id`: the copy adaptive sampling's rays use, so that the one-ray path's
    /// code stays as it is.
    ///
    /// The local colour at `p` (not rounded): Lab #1 without lights, otherwise
    /// ambient + diffuse + specular with a shadow ray per light.
    #[inline(always)]
    pub(super) fn local_with<I: Ident>(
        &mut self,
        k: ObjectId,
        s: &Surface,
        p: Vec3,
        dir: Vec3,
        column: Option<u32>,
        id: &mut I,
    ) -> [f32; 3] {
        if L == 0 || self.f.lights.is_empty() {
            return s.lab1(self.f.w);
        }
        let f = self.f;
        // v, the unit vector back along the ray, only where a highlight needs it.
        let v = if s.material.specular > 0.0 {
            dir * (-1.0 / sqrt_exact(dir.dot(dir)))
        } else {
            Vec3::ZERO
        };
        let (mut diffuse, mut spec) = (0.0f32, 0.0f32);
        for (index, light) in f.lights.iter().enumerate() {
            let (l, dist, intensity, far) = match *light {
                FrameLight::Directional { l, intensity } => (l, f32::INFINITY, intensity, f32::INFINITY),
                FrameLight::Point {
                    p: at,
                    intensity,
                    far,
                } => {
                    let to = at - p;
                    let dist = sqrt_exact(to.dot(to));
                    (to * (1.0 / dist), dist, intensity, far)
                }
            };
            let nl = s.n.dot(l);
            // Only a light in front of the surface lights it (and needs a shadow ray).
            if !(nl > 0.0) {
                continue;
            }
            if f.shadows {
                let o = O::start(p, l, f.eps);
                let dist = if O::TESTS_SELF { dist - f.eps } else { dist };
                let ray = || ShadowRay {
                    o,
                    l,
                    dist,
                    from: k,
                    inside: s.inside,
                };
                // Beyond the far limit the segment is tested from the lamp's end.
                let blocked = self.shadowed(index, ray, dist > far, column);
                // Which lights reach the surface: a shadow boundary is an edge.
                id.mix(2 * index as u32 + 1 + u32::from(blocked));
                if blocked {
                    continue;
                }
            }
            diffuse += intensity * nl;
            if s.material.specular > 0.0 {
                // n·h with h = (l + v)/|l + v|: one root and one division, no vector
                // scaling (|l + v| ≤ 2: no overflow). No highlight where l + v = 0.
                let half = l + v;
                let h2 = half.dot(half);
                if h2 > 0.0 {
                    let nh = s.n.dot(half) / sqrt_exact(h2);
                    if nh > 0.0 {
                        spec += intensity * s.material.specular * phong_power(nh, s.material.shininess);
                    }
                }
            }
        }
        let light = f.ambient + diffuse;
        let spec = 255.0 * spec;
        s.rgb.map(|c| {
            let x = c * light + spec;
            if x > 255.0 {
                255.0
            } else {
                x
            }
        })
    }
}

/// `x^shininess` for `x ∈ (0, 1]`, by repeated squaring when the exponent is a whole
/// number up to 1024, by `libm::powf` otherwise.
///
/// Whole exponents up to 1024 are the usual Phong exponents: a handful of
/// multiplications instead of `powf`'s logarithm and exponential.
///
/// **Error bound.** Each multiplication rounds by at most `u = 2⁻²⁴` relative, and a
/// squaring doubles the relative error it is given, so the error of `x^s` is the sum
/// over the exponent's bits: at most `(s − 1)·u` to first order, `< s·u` (`< 6.2·10⁻⁵`
/// for `s = 1024`; `powf` is within 1 ulp). The highlight term `255·x^s ≤ 255` so
/// moves by less than `0.016` of a level at `s = 1024`, `5·10⁻⁴` at the default 32
/// (tested against `f64::powf`).
#[inline(always)]
fn phong_power(x: f32, shininess: f32) -> f32 {
    let whole = shininess as u32;
    if whole as f32 == shininess && whole <= 1024 {
        let (mut base, mut e, mut acc) = (x, whole, 1.0f32);
        while e > 0 {
            if e & 1 == 1 {
                acc *= base;
            }
            base *= base;
            e >>= 1;
        }
        acc
    } else {
        libm::powf(x, shininess)
    }
}

#[cfg(test)]
mod tests {
    use super::phong_power;

    /// Repeated squaring against `f64::powf`, within its stated bound, for whole
    /// exponents 1…1024 and bases across (0, 1]; fractional exponents go to `powf`.
    #[test]
    fn phong_power_within_its_bound() {
        let mut worst = 0.0f64;
        for s in (1..=1024).step_by(7).chain([2, 32, 64, 1000, 1024]) {
            let bound = f64::from(s) * f64::from(crate::math::UNIT_ROUNDOFF);
            for k in 1..=200 {
                let x = k as f32 / 200.0;
                let exact = f64::from(x).powf(f64::from(s));
                if exact < 1e-30 {
                    continue; // below f32's normal range: a contribution of nothing
                }
                let got = f64::from(phong_power(x, s as f32));
                let rel = (got - exact).abs() / exact;
                worst = worst.max(rel / bound);
                assert!(rel <= bound, "x = {x}, s = {s}: {got} vs {exact} ({rel:e})");
            }
        }
        // The bound is not loose by orders of magnitude: some case uses a tenth of it.
        assert!(worst > 0.1, "worst case {worst} of the bound");
        let frac = phong_power(0.5, 2.5);
        assert_eq!(frac, libm::powf(0.5, 2.5));
    }
}
