//! The frame's exact ties between objects ([`Ties`]): a point light lying on a surface,
//! and coincident objects, decided once per frame.

use crate::math::vec3::Vec3;
use crate::scene::light::Light;
use crate::scene::Scene;
use crate::trace::lit::object::ObjectId;

/// How close to a surface a lamp counts as lying on it, relative to the frame's
/// lengths: `2⁻¹⁶` (see [`Ties`]).
const ON_SURFACE: f64 = 1.0 / 65_536.0;

/// Where a point light lies against a surface ([`Ties`]): beyond the bound (`Off`), or
/// within it, on the side the `f64` sign of its offset says — inside the sphere or
/// below the plane (`Neg`, against the plane's normal), exactly on it (`On`), outside
/// or above (`Pos`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Near {
    Off,
    Neg,
    On,
    Pos,
}

impl Near {
    /// Within the bound of `bound` at the signed offset `h` (its sign decides the side).
    fn of(h: f64, bound: f64) -> Self {
        if !(h.abs() <= bound) {
            Near::Off
        } else if h < 0.0 {
            Near::Neg
        } else if h > 0.0 {
            Near::Pos
        } else {
            Near::On
        }
    }
}

/// The frame's exact ties between objects, decided once per frame.
///
/// They are decided in `f64` from the scene's own `f32` values (not from the rounded
/// eye-relative ones), so that every target decides them alike:
///
/// - **A lamp on a surface.** A point light `P` lies on sphere `(C, r)` when
///   `| |P − C| − r | ≤ 2⁻¹⁶·(|P − E| + |C − E| + r)`, on a plane through `Q` with
///   unit normal `n` when `|(P − Q)·n| ≤ 2⁻¹⁶·(|P − E| + |Q − E|)` (`E` the eye). A
///   shadow segment toward such a lamp ends on that surface, where the test's root at
///   `t ≈ dist` is compared with `dist`: both carry the rounding of the test, about
///   `8u·(|C − o| + r + |P − o|)` (`u = 2⁻²⁴`) across the surface, so the comparison is
///   a coin toss (speckles). For origins `o` within `S = |P − E| + |C − E| + r` of the
///   eye that rounding is at most `24u·S`, under a tenth of the bound `2⁻¹⁶·S =
///   256u·S`: a lamp farther from the surface than the bound is decided by the roots,
///   clear of the coin toss (origins farther out carry a rounding that grows with
///   their distance, as the reference's shadow band does). Within the bound the
///   segment is decided by the side it reaches the lamp from and by the side of the
///   surface the lamp is on ([`Near`]: the sign of its offset in `f64`, wrong only
///   for a lamp within the `f64` rounding of the surface), with no root near `dist`:
///   - a plane blocks iff the lamp lies off it and the segment's origin on the other
///     side (the signs at the two ends; the origin's in the frame's `f32`, exact
///     unless it lies within rounding of the plane); a plane through the lamp never
///     blocks (the segment meets it only at its open end);
///   - a sphere through the lamp (its `f64` offset exactly 0): the line meets it at
///     the lamp and at `2σ` before it, `σ = (P − C)·l` (`l` the unit direction toward
///     the lamp); the segment is inside the sphere just before the lamp iff `σ > 0`,
///     and then blocked iff the other root lies on it, `0 < 2σ < dist`;
///   - a lamp inside the sphere: blocked iff the segment's origin is outside it (the
///     sign of `|o − C|² − r²` in the frame's `f32`, exact unless `o` lies within
///     rounding of the sphere, e.g. on it: the surface the ray leaves never blocks);
///   - a lamp outside it: the line, walked back from the lamp, meets the sphere at
///     `s = σ ± √(σ² − g)` with `g = |P − C|² − r² > 0` kept from `f64` (its `f32`
///     rounding moves the near root by at most `2⁻²³` of itself), and the segment is
///     blocked iff it reaches the near root, `σ > 0`, `σ² ≥ g` and
///     `g/(σ + √(σ² − g)) < dist` (no cancellation: `g` is never formed from the
///     frame's rounded ends, whose error exceeds it);
///
///   a lamp farther than the bound from a sphere is decided by the roots, as any
///   occluder.
/// - **Coincident objects.** A sphere with the same centre and radius bits as a
///   lower-numbered one (a plane with the same point and normal bits) is the same
///   surface: every test computes the same bits for both, so a primary ray shows the
///   lower number (the strict `t < t_max`), and a secondary ray leaving either treats
///   the other as the surface it leaves (the convex exit): no ray sees one twin from
///   the other at `t ≈ 0`.
///
/// A frame without either tie draws the pixels it would without this rule: its shadow
/// rays take the plain test (a branch on [`Ties::exact_mask`] in
/// [`LitRow::shadowed`]) and its reflected rays test one flag.
///
/// [`LitRow::shadowed`]: crate::trace::lit::row::LitRow::shadowed
#[derive(PartialEq)]
pub(super) struct Ties<const N: usize, const L: usize, const P: usize> {
    /// Per light (the frame's numbering) and sphere: whether, and on which side, the
    /// lamp lies on it.
    pub(super) on_sphere: [[Near; N]; L],
    /// Per light and sphere, for a lamp within the bound outside it ([`Near::Pos`]):
    /// `g = |P − C|² − r²` in the frame's scaled units, from `f64` (0 otherwise).
    pub(super) sphere_g: [[f32; N]; L],
    /// Per light and plane: the same.
    pub(super) on_plane: [[Near; P]; L],
    /// Per sphere: the lowest-numbered sphere identical to it (itself if none).
    pub(super) sphere_twin: [ObjectId; N],
    /// Per plane: the object number of the lowest-numbered identical plane.
    pub(super) plane_twin: [ObjectId; P],
    /// Some object has a lower-numbered twin.
    pub(super) twins: bool,
    /// Per light: its shadow rays need the ties (see [`Ties::exact`]).
    exact: [bool; L],
    /// Some light's do: one test per shadow ray for a frame without ties.
    any: bool,
}

impl<const N: usize, const L: usize, const P: usize> Ties<N, L, P> {
    /// The ties of `scene` seen from `eye` at the frame's `scale`, and each light's
    /// `exact` flag (the frame's lights: the scene's in order, less the unusable ones).
    ///
    /// Once per frame, out of line.
    #[cold]
    #[inline(never)]
    pub(super) fn new<const D: usize>(scene: &Scene<N, L, P, D>, eye: Vec3, scale: f32) -> Self {
        let v = |a: Vec3| [f64::from(a.x), f64::from(a.y), f64::from(a.z)];
        let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let len = |a: [f64; 3]| libm::sqrt(dot(a, a));
        let e = v(eye);
        let spheres = scene.spheres();
        let planes = scene.planes();
        let n_spheres = spheres.len();
        let bits = |a: Vec3| (a.x.to_bits(), a.y.to_bits(), a.z.to_bits());
        let mut sphere_twin: [ObjectId; N] = core::array::from_fn(ObjectId::new);
        let mut plane_twin: [ObjectId; P] = core::array::from_fn(|k| ObjectId::new(n_spheres + k));
        let mut twins = false;
        for (k, s) in spheres.iter().enumerate() {
            let key = (bits(s.center), s.radius.to_bits());
            if let (Some(j), Some(slot)) = (
                spheres
                    .iter()
                    .position(|t| (bits(t.center), t.radius.to_bits()) == key),
                sphere_twin.get_mut(k),
            ) {
                *slot = ObjectId::new(j);
                twins |= j != k;
            }
        }
        for (k, p) in planes.iter().enumerate() {
            let key = (bits(p.point), bits(p.normal));
            if let (Some(j), Some(slot)) = (
                planes.iter().position(|q| (bits(q.point), bits(q.normal)) == key),
                plane_twin.get_mut(k),
            ) {
                *slot = ObjectId::new(n_spheres + j);
                twins |= j != k;
            }
        }
        let mut on_sphere = [[Near::Off; N]; L];
        let mut on_plane = [[Near::Off; P]; L];
        let mut sphere_g = [[0.0; N]; L];
        let scale = f64::from(scale);
        let usable = scene.lights().iter().filter(|l| match **l {
            Light::Directional { direction, .. } => direction.try_normalize().is_some(),
            Light::Point { .. } => true,
        });
        let mut exact = [false; L];
        let mut any = false;
        let lights = usable
            .zip(&mut exact)
            .zip(&mut on_sphere)
            .zip(&mut sphere_g)
            .zip(&mut on_plane);
        for ((((light, exact), row), grow), prow) in lights {
            let mut on = false;
            if let Light::Point { position, .. } = *light {
                let at = v(position);
                let pe = len(sub(at, e));
                for ((flag, g), sphere) in row.iter_mut().zip(grow.iter_mut()).zip(spheres) {
                    let (c, r) = (v(sphere.center), f64::from(sphere.radius));
                    let gap = len(sub(at, c)) - r;
                    *flag = Near::of(gap, ON_SURFACE * (pe + len(sub(c, e)) + r));
                    if *flag == Near::Pos {
                        // |P − C|² − r², scaled: exact powers of two, rounded once.
                        *g = ((gap * scale) * ((gap + 2.0 * r) * scale)) as f32;
                    }
                    on |= *flag != Near::Off;
                }
                for (flag, p) in prow.iter_mut().zip(planes) {
                    let Some(n) = p.normal.try_normalize() else {
                        continue;
                    };
                    let q = v(p.point);
                    let h = dot(sub(at, q), v(n));
                    *flag = Near::of(h, ON_SURFACE * (pe + len(sub(q, e))));
                    on |= *flag != Near::Off;
                }
            }
            *exact = on || twins;
            any |= *exact;
        }
        Self {
            on_sphere,
            sphere_g,
            on_plane,
            sphere_twin,
            plane_twin,
            twins,
            exact,
            any,
        }
    }

    /// Which lights' shadow rays take [`LitRow::occluded_exact`] (their lamp lies on
    /// some object, or the frame has coincident objects), as a mask for the pixel loop.
    ///
    /// Bit `k` for light `k`, bit 31 for every light from 31 on.
    ///
    /// [`LitRow::occluded_exact`]: crate::trace::lit::row::LitRow::occluded_exact
    pub(super) fn exact_mask(&self) -> u32 {
        if !self.any {
            return 0;
        }
        let mut mask = 0;
        for (k, &e) in self.exact.iter().enumerate() {
            if e {
                mask |= 1 << k.min(31);
            }
        }
        mask
    }
}

/// Whether two scenes seen from `eye` at the frame's `scale` have the same [`Ties`],
/// the frame-wide part of a features frame that a moved sphere can change besides its
/// own pixels (a moved sphere near a lamp changes its `g`: the whole frame is drawn).
///
/// The ties (a lamp lying on a surface, coincident objects) choose every row's shadow
/// test: where they are equal, every row takes the same path in both scenes.
pub(crate) fn same_ties<const N: usize, const L: usize, const P: usize, const D: usize>(
    a: &Scene<N, L, P, D>,
    b: &Scene<N, L, P, D>,
    eye: Vec3,
    scale: f32,
) -> bool {
    Ties::new(a, eye, scale) == Ties::new(b, eye, scale)
}
