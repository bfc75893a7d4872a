//! The integer kernel's per-frame rule and quantisation: the integer picture of the
//! scene ([`IntFrame`], built by [`plan`]), taken only where its bounds hold.
//!
//! ## The integer picture
//!
//! Per frame (in `f64`, once), the scene is expressed in the camera's `u, v, w` basis
//! and quantised, as finely as the integer ranges below allow:
//!
//! - the ray of pixel `(i, j)` is the integer vector `d = (x, y, F)` with
//!   `x = 2ᵏ·(2i + 1 − W)`, `y = 2ᵏ·(H − 1 − 2j)` (half-pixel units times `2ᵏ`: exact)
//!   and `F = round(2ᵏ·2/pw)` the focal length in the same units, `k` the largest with
//!   `|d| ≤ 2²⁶`. Stepping one column is `x += 2ᵏ⁺¹`: **no drift at all**. The rounding
//!   of `F` is the only error: the image of a camera whose focal length differs by at
//!   most `2⁻ᵏ⁻¹` half-pixels, which moves a point at `R` half-pixels from the centre by
//!   at most `R·2⁻ᵏ⁻²/Fz` pixels (`Fz = 2/pw`; ≈ 2⁻¹⁸ pixel at 240×240);
//! - each sphere's eye-relative centre and radius are multiplied by `λ = 2ᵉ` and
//!   rounded: `ℓ = round(λ·L)`, `ρ = round(λ·r)`, `e` the largest with
//!   `λ·max(|L| + r) ≤ 2²⁵` (one `λ` for the frame, so hit distances compare across
//!   spheres without a division). The centre moves by at most `√3/2`, the radius by
//!   `½` (in `λ` units). The silhouette is the cone of half-angle `asin(r/|L|)` about
//!   `L`: its axis turns by `|δL⊥|/|L|`, its half-angle changes by
//!   `(|δL∥|·r/|L| + |δr|)/√c` (`c = |L|² − r²`), together at most
//!   `(√2·√3/2 + ½)/(λ√c) ≤ 1.725/(λ√c)` radians (`√c + r ≤ √2·|L|`), which on the
//!   image is at most `1.725/(λ√c)·(Fz + R²/Fz)/2` pixels.
//!
//! The rule takes the frame only where the two together are within
//! [`EDGE_TOLERANCE`] (1/16 pixel; `docs/accuracy.md`, "The integer kernel", gives them
//! on the standard scenes). Everything after the quantisation is **exact** integer arithmetic on the quantised
//! picture (ranges on [`IntSphere`]), so the coverage has no further error.

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::{Vec, VecView};

use crate::camera::int_cut::IntCut;
use crate::camera::span::{ImageBasis, Margin, Silhouette};
use crate::camera::Camera;
use crate::math::vec3::Vec3;
use crate::math::EDGE_TOLERANCE;
use crate::scene::sphere::Sphere;
use crate::trace::frame::visible;
use crate::trace::options::Options;

/// Largest `|d|` (`2²⁶`): `a = |d|² ≤ 2⁵²`, `x`, `y`, `F` are `i32`.
const MAX_D: f64 = 67_108_864.0;
/// Largest `λ·(|L| + r)` (`2²⁵`): `|ℓ|, ρ ≤ 2²⁵`, so `|b| ≤ 2⁵¹` (`i64`) and `b²`,
/// `a·c`, `A₁·x`, `A₂·x²` and `2A₂s²` are below 2¹⁰⁶ (`i128`).
const MAX_L: f64 = 33_554_432.0;
/// The shade factor's error budget (units of `n·(−w)`): half a level of 255.
const SHADE_BUDGET: f64 = 1.0 / 512.0;

/// One sphere of the integer picture.
///
/// Ranges (guaranteed by the rule): `|ℓ|, ρ ≤ 2²⁵`,
/// `ℓz > ρ ≥ 1`, `c > 0`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct IntSphere {
    /// Index in the scene.
    pub(super) index: usize,
    /// `ℓ = round(λ·L)` in camera coordinates (`u`, `v`, `w`).
    pub(super) lx: i32,
    pub(super) ly: i32,
    pub(super) lz: i32,
    /// `ℓx·s`, the column step of `b`.
    pub(super) lx_s: i64,
    /// `ρ = round(λ·r)`.
    pub(super) rho: i32,
    /// The root's shift `h` (`D ≤ a·ρ² < 2³²⁺²ʰ`) and the shade division's `q`
    /// (`(a >> p)·ρ >> q < 2¹⁵` for every pixel's `a`): fixed per frame, so the pixel
    /// loop counts no leading zeros (the Cortex-M0 has no `CLZ`).
    pub(super) h: u8,
    pub(super) q: u8,
    /// `c = |ℓ|² − ρ²` (> 0).
    pub(super) c: i64,
    /// `2·A₂·s²`, the discriminant's constant second difference (`A₂ = ℓx² − c`, its
    /// `x²` coefficient, is formed per row).
    pub(super) dd: i128,
    /// The object colour's channels.
    pub(super) rgb: [u8; 3],
    /// Where on the image its rays can hit it: the cut of each row ([`IntCut`]) of the
    /// `f32` silhouette enlarged to cover the quantisation's 1/16 pixel, and the rows
    /// `[j0, j1)` outside which the cut has no span ([`Silhouette::int_cut_rows`]); rows
    /// and columns are found without soft float.
    pub(super) rows: (u32, u32),
    pub(super) cut: IntCut,
}

/// The integer kernel's per-frame constants.
///
/// Not generic over the scene's capacity:
/// one copy of the kernel serves every `Scene<N>` of a firmware.
pub(crate) struct IntFrame<'a> {
    pub(super) camera: &'a Camera,
    /// `k` of `x = 2ᵏ·(2i + 1 − W)`.
    pub(super) k: u32,
    /// `F`, the focal length in the pixel units.
    pub(super) f: i32,
    /// The shade's shift `p` (`a >> p < 2³¹`).
    pub(super) p: u32,
    /// `λ = 2ᵉ` as a float (for the trace path's `t` only).
    pub(super) lambda: f32,
    pub(super) spheres: &'a [IntSphere],
    pub(super) background: Rgb888,
    pub(super) i0: u32,
    pub(super) i1: u32,
    pub(super) j0: u32,
    pub(super) j1: u32,
    pub(super) offset: Point,
}

/// Why the rule turned a frame over to `f32`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Refusal {
    /// Nothing visible: no frame to draw either way.
    Invisible,
    /// The integer bounds do not hold for this frame.
    Bounds,
}

/// The rule's frame-wide choices.
struct Plan {
    k: u32,
    f: i32,
    p: u32,
    e: i32,
}

impl Plan {
    fn key(&self) -> Quantisation {
        Quantisation {
            f: self.f,
            e: self.e as i16,
            k: self.k as u8,
            p: self.p as u8,
        }
    }
}

/// The integer kernel's frame-wide quantisation: pixel unit `k`, focal length `F`,
/// shade shift `p` and length unit `e` ([module docs](self)). Two frames with equal
/// quantisations give every sphere the same integer picture from the same inputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Quantisation {
    f: i32,
    // The rule's ranges: 0 ≤ k ≤ 60, 0 ≤ p < 2⁸, −1100 ≤ e ≤ 60.
    e: i16,
    k: u8,
    p: u8,
}

/// The integer kernel's frame-wide quantisation of `scene` seen by `camera`, or `None`
/// where its per-frame rule does not take the frame.
///
/// For each sphere `pick` selects, the rows and the cut its rows are culled with are
/// passed to `f` (the others' silhouettes are not computed). What an incremental frame
/// compares and re-traces, and whether the integer kernel takes a frame; one buffer of
/// `N` spheres, as the render's own.
pub(crate) fn regions<const N: usize>(
    scene: &[Sphere],
    camera: &Camera,
    options: Options,
    pick: impl Fn(usize) -> bool,
    f: impl FnMut((u32, u32), IntCut),
) -> Option<Quantisation> {
    let mut buf: Vec<IntSphere, N> = Vec::new();
    rule_into(buf.as_mut_view(), scene, camera, options, &pick, &pick, f)
}

/// The rule and the integer picture of every sphere into `buf`, as the draw builds
/// them ([`IntFrame::from_picture`] draws it), or `None` where the rule does not take
/// the frame; the rows and cut of each sphere `pick` selects are passed to `f`, as
/// [`regions`] passes them.
pub(crate) fn picture(
    buf: &mut VecView<IntSphere>,
    scene: &[Sphere],
    camera: &Camera,
    options: Options,
    pick: impl Fn(usize) -> bool,
    f: impl FnMut((u32, u32), IntCut),
) -> Option<Quantisation> {
    rule_into(buf, scene, camera, options, &|_| true, &pick, f)
}

/// The rule into `buf`, the silhouettes of the spheres `cull` selects, then the rows
/// and cut of each sphere `pick` selects passed to `f`: [`regions`] and [`picture`].
fn rule_into(
    buf: &mut VecView<IntSphere>,
    scene: &[Sphere],
    camera: &Camera,
    options: Options,
    cull: &dyn Fn(usize) -> bool,
    pick: &impl Fn(usize) -> bool,
    mut f: impl FnMut((u32, u32), IntCut),
) -> Option<Quantisation> {
    let plan = plan(scene, camera, options, buf, cull)?;
    for s in buf.iter() {
        if pick(s.index) {
            f(s.rows, s.cut);
        }
    }
    Some(plan.key())
}

/// The rows and cut of each sphere `pick` selects, as [`regions`] passes them, for a
/// frame whose rule is known to take it: the silhouettes alone, without the rule's
/// quantisation and bounds (a frame's cuts do not depend on them).
pub(crate) fn cuts(
    scene: &[Sphere],
    camera: &Camera,
    options: Options,
    pick: impl Fn(usize) -> bool,
    mut f: impl FnMut((u32, u32), IntCut),
) {
    let basis = ImageBasis::of(camera);
    for (index, s) in scene.iter().enumerate() {
        if pick(index) {
            let (rows, cut) = sphere_cut(s, camera, &basis, options, true);
            f(rows, cut);
        }
    }
}

/// A sphere's rows and cut: its silhouette where it is `culled` and culling is on
/// ([`Silhouette::ALL`] otherwise), enlarged to cover the quantisation's 1/16 pixel;
/// `basis` is the camera's part of every silhouette, worked out once per frame.
fn sphere_cut(
    s: &Sphere,
    camera: &Camera,
    basis: &ImageBasis,
    options: Options,
    culled: bool,
) -> ((u32, u32), IntCut) {
    let silhouette = if options.span_culling && culled {
        // A direction error of pw/16 enlarges the f32 silhouette by ≥ 1/8 pixel: it
        // covers the integer picture's 1/16.
        Silhouette::new_in(
            s.center - camera.eye(),
            s.radius,
            basis,
            Margin::Linear,
            camera.pixel_width() / 16.0,
        )
    } else {
        Silhouette::ALL
    };
    silhouette.int_cut_rows(camera.size().height)
}

impl<'a> IntFrame<'a> {
    /// The per-frame rule and the integer picture: `Err(Bounds)` where the integer
    /// kernel's bounds (this module's docs and [`shade`](super::shade)'s) do not keep every silhouette within 1/16 pixel and
    /// every shade factor within 2⁻⁹, or its magnitudes do not fit.
    #[inline(never)]
    pub(crate) fn new(
        buf: &'a mut VecView<IntSphere>,
        scene: &[Sphere],
        background: Rgb888,
        camera: &'a Camera,
        options: Options,
        clip: Rectangle,
        offset: Point,
    ) -> Result<Self, Refusal> {
        let key = plan(scene, camera, options, buf, &|_| true)
            .ok_or(Refusal::Bounds)?
            .key();
        Self::from_picture(buf, key, background, camera, clip, offset).ok_or(Refusal::Invisible)
    }

    /// The frame of a picture the rule has built ([`picture`], with its quantisation
    /// `key`), or `None` where `clip` shows none of it.
    pub(crate) fn from_picture(
        spheres: &'a [IntSphere],
        key: Quantisation,
        background: Rgb888,
        camera: &'a Camera,
        clip: Rectangle,
        offset: Point,
    ) -> Option<Self> {
        // Clipped as the f32 frame is.
        let (i0, i1, j0, j1) = visible(camera.size(), offset, clip)?;
        Some(Self {
            camera,
            k: u32::from(key.k),
            f: key.f,
            p: u32::from(key.p),
            lambda: libm::ldexpf(1.0, i32::from(key.e)),
            spheres,
            background,
            i0,
            i1,
            j0,
            j1,
            offset,
        })
    }
}

/// `⌈log₂ x⌉` for `x ≥ 1` (0 below; at most 1100): the smallest `e ≥ 0` with
/// `2ᵉ ≥ x`.
///
/// Counted up from `x`'s binary exponent (`2^ilogb(x) ≤ x`, so at most one step, where
/// a count from 0 would take up to a hundred soft-float steps).
fn ceil_log2(x: f64) -> i32 {
    let mut e = if x.is_finite() && x > 1.0 {
        libm::ilogb(x).clamp(0, 1100)
    } else {
        0
    };
    while libm::ldexp(1.0, e) < x && e < 1100 {
        e += 1;
    }
    e
}

/// The largest `e` in `[−1100, 60]` with `2ᵉ·x ≤ limit` (`−1100` if there is none, as
/// for an infinite `x`; 60 for a NaN).
///
/// Counted down from `ilogb(limit) − ilogb(x) + 1`, where
/// `2ᵉ·x ≥ 2^(ilogb(limit) + 1) > limit` already fails (at most two steps); from 60
/// where either is not positive and finite.
fn fit_exponent(x: f64, limit: f64) -> i32 {
    let mut e = if x.is_finite() && x > 0.0 && limit.is_finite() && limit > 0.0 {
        (libm::ilogb(limit) - libm::ilogb(x) + 1).clamp(-1100, 60)
    } else {
        60
    };
    while libm::ldexp(x, e) > limit && e > -1100 {
        e -= 1;
    }
    e
}

/// The rule and the integer picture (this module's docs), or `None`.
///
/// Only the spheres `cull` selects get their silhouette's rows and cut (the others
/// cull nothing, [`Silhouette::ALL`]): the rule's decision and quantisation do not
/// depend on them, and a caller that needs only those skips the silhouettes' soft
/// `f64`.
fn plan(
    scene: &[Sphere],
    camera: &Camera,
    options: Options,
    spheres: &mut VecView<IntSphere>,
    // Not generic: one copy of the rule's soft float for every caller.
    cull: &dyn Fn(usize) -> bool,
) -> Option<Plan> {
    let (pw, ph) = (camera.pixel_width(), camera.pixel_height());
    // Square pixels only: x and y share one unit.
    if pw != ph {
        return None;
    }
    let size = camera.size();
    let (wf, hf) = (f64::from(size.width), f64::from(size.height));
    let fz = 2.0 / f64::from(pw);
    // R: the largest distance of a pixel centre from the image centre, half-pixels.
    let r_img = libm::sqrt(wf * wf + hf * hf);
    // The finest pixel unit 2⁻ᵏ that keeps |d| ≤ 2²⁶.
    let k = fit_exponent(r_img + fz + 1.0, MAX_D);
    let f = libm::round(libm::ldexp(fz, k));
    let d_max = libm::ldexp(r_img, k) + f;
    let focal_edge = r_img * libm::ldexp(0.25, -k) / fz;
    if !(k >= 0 && f >= 1.0 && d_max <= MAX_D && focal_edge <= f64::from(EDGE_TOLERANCE) / 8.0) {
        return None;
    }
    // The shade's shift p: a ≤ d_max² becomes < 2³¹, and T ≤ b ≤ |ℓ|·|d| ≤ 2²⁵·d_max
    // must become < 2³² (true whenever d_max > 2²⁴, as the finest k makes it).
    let p = (ceil_log2(d_max * d_max) - 31).max(0);
    if !(libm::ldexp(MAX_L * d_max, -p) < 4_294_967_296.0) {
        return None;
    }
    // Radians to pixels at the image's edge: (Fz + R²/Fz)/2.
    let px_per_rad = (fz + r_img * r_img / fz) / 2.0;
    let (u, v, w) = (camera.u(), camera.v(), camera.w());
    let eye = camera.eye();
    let dot = Vec3::dot_f64;
    // λ: the finest unit that keeps every |ℓ| + ρ ≤ 2²⁵.
    let mut l_max = 0.0f64;
    for s in scene {
        let lv = s.center - eye;
        let l2 = dot(lv, lv);
        if !(l2.is_finite() && s.radius.is_finite()) {
            return None;
        }
        l_max = l_max.max(libm::sqrt(l2) + f64::from(s.radius.abs()));
    }
    let e = if l_max > 0.0 {
        fit_exponent(l_max, MAX_L - 2.0)
    } else {
        0
    };
    let lambda = libm::ldexp(1.0, e);
    spheres.clear();
    let basis = ImageBasis::of(camera);
    let s_col = libm::ldexp(2.0, k) as i64; // the column step s = 2ᵏ⁺¹
    for (index, s) in scene.iter().enumerate() {
        let lv = s.center - eye;
        let exact = [dot(lv, u), dot(lv, v), dot(lv, w), f64::from(s.radius)].map(|x| x * lambda);
        let [lx, ly, lz, rho] = exact.map(libm::round);
        // How far the quantisation moved this sphere (λ units): its centre by `|ℓ − λL|`
        // (≤ √3/2), its radius by `|ρ − λr|` (≤ ½); the f64 products and sums above err
        // by far less than the 2⁻³⁰·(|ℓ| + ρ) added.
        let sq = |x: f64| x * x;
        let moved = libm::sqrt(sq(lx - exact[0]) + sq(ly - exact[1]) + sq(lz - exact[2]))
            + (rho - exact[3]).abs()
            + libm::ldexp(lx.abs() + ly.abs() + lz.abs() + rho, -30);
        // Wholly in front of the eye (every hit has t > 0, the eye is outside).
        if !(rho >= 1.0 && lz > rho) {
            return None;
        }
        let (lxi, lyi, lzi, rhoi) = (lx as i64, ly as i64, lz as i64, rho as i64);
        // Exact: |ℓ|² ≤ 3·2⁵⁰.
        let c = lxi * lxi + lyi * lyi + lzi * lzi - rhoi * rhoi;
        if c <= 0 {
            return None;
        }
        // The silhouette's bound (f64 from the exact c).
        let edge = 1.725 * px_per_rad / libm::sqrt(c as f64) + focal_edge;
        // The root's shift h (D ≤ a·ρ² ≤ (d_max·ρ)² < 2³²⁺²ʰ) and the division's q
        // ((d_max² >> p)·ρ >> q < 2¹⁵).
        let h = ((ceil_log2(d_max * d_max * rho * rho) - 32).max(0) + 1) / 2;
        let den_max = libm::ldexp(d_max * d_max, -p) * rho;
        let q = (ceil_log2(den_max + 1.0) - 15).max(0);
        // The smallest divisor (a ≥ F²) after the shift, ≥ 1.
        let den_min = libm::floor(libm::floor(libm::ldexp(f * f, -p)) * rho / libm::ldexp(1.0, q));
        // The shade factor's bound: root (F·2ʰ⁺¹/(a·ρ), a ≥ F²), T's shift, the
        // division (2/den_min + 2⁻¹⁶) and the sphere's quantisation.
        let shade_err = libm::ldexp(2.0, h) / (f * rho)
            + libm::ldexp(1.0, p) / (f * rho)
            + (lz + rho) * libm::ldexp(1.0, p) / (f * f * rho)
            + 2.0 / den_min
            + 1.0 / 65536.0
            + moved / rho;
        // The grazing ring: where the hit lies less than `g = moved/budget` (λ units)
        // below the silhouette's rim, the quantisation can turn the normal by up to
        // moved/g or more; the ring is `g²/(2ρ)` wide, and together with the edge's own
        // bound it must stay within the edge tolerance (there the image is that of the
        // sphere moved by less than 1/16 pixel).
        let graze = moved / (SHADE_BUDGET - shade_err);
        let ring = px_per_rad / libm::sqrt(c as f64) * graze * graze / (2.0 * rho);
        if !(shade_err < SHADE_BUDGET && graze < rho && edge + ring <= f64::from(EDGE_TOLERANCE)) {
            return None;
        }
        let a2 = lxi * lxi - c;
        let (rows, cut) = sphere_cut(s, camera, &basis, options, cull(index));
        let _ = spheres.push(IntSphere {
            index,
            lx: lx as i32,
            ly: ly as i32,
            lz: lz as i32,
            lx_s: lxi * s_col,
            rho: rho as i32,
            h: h as u8,
            q: q as u8,
            c,
            dd: 2 * i128::from(a2) * i128::from(s_col * s_col),
            rgb: [s.color.r(), s.color.g(), s.color.b()],
            rows,
            cut,
        });
    }
    Some(Plan {
        k: k as u32,
        f: f as i32,
        p: p as u32,
        e,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The exponent searches equal plain counts (up from 0, down from 60) on values of
    /// every magnitude, at and beside powers of two, and on the edge cases.
    #[test]
    fn exponents_equal_the_plain_counts() {
        let ceil_count = |x: f64| {
            let mut e = 0;
            while libm::ldexp(1.0, e) < x && e < 1100 {
                e += 1;
            }
            e
        };
        let fit_count = |x: f64, limit: f64| {
            let mut e = 60;
            while libm::ldexp(x, e) > limit && e > -1100 {
                e -= 1;
            }
            e
        };
        let mut xs = std::vec![
            0.0,
            -1.0,
            0.5,
            1.0,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::INFINITY,
            f64::NAN
        ];
        for b in -1074..1024 {
            let p = libm::ldexp(1.0, b);
            xs.extend([
                p,
                p * (1.0 + f64::EPSILON),
                p * (1.0 - f64::EPSILON / 2.0),
                p * 1.5,
            ]);
        }
        for &x in &xs {
            assert_eq!(ceil_log2(x), ceil_count(x), "ceil_log2({x:e})");
            for limit in [MAX_D, MAX_L - 2.0, 1.0, 3.0, 1e300, f64::MIN_POSITIVE, 5e-324] {
                assert_eq!(
                    fit_exponent(x, limit),
                    fit_count(x, limit),
                    "fit_exponent({x:e}, {limit})"
                );
            }
        }
    }
}
