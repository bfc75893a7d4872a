//! The integer kernel ([`Arithmetic::Integer`](crate::method::Arithmetic::Integer)):
//! Lab #1 on spheres in integer arithmetic only, for chips without an FPU (a
//! Cortex-M0's soft float costs ≈ 80–320 instructions per `f32` operation).
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
//! [`EDGE_TOLERANCE`] (1/16 pixel); on the standard scenes they are below 10⁻⁴ pixel.
//! Everything after the quantisation is **exact** integer arithmetic on the quantised
//! picture (ranges on [`IntSphere`]), so the coverage has no further error.
//!
//! ## The test (exact forward differences)
//!
//! With `b = ℓ·d`, `a = |d|²` and `c = |ℓ|² − ρ²`, the discriminant `D = b² − a·c`
//! (exactly the robust `a·ρ² − |ℓ × d|²`: the identity holds in integers) is along a
//! row a quadratic in `x`: `D = A₂x² + A₁x + A₀` with `A₂ = ℓx² − c`. It is stepped by
//! `D += Δ; Δ += 2·A₂·s²` (`s = 2ᵏ⁺¹`), exactly in `i128`, and `b += ℓx·s` in `i64`:
//! per sphere and pixel five 32-bit add-with-carry chains, no multiply. `D` and `Δ` are
//! evaluated directly at each span's first visible column, as `b² − a·c` and
//! `ℓx·s·(2b + ℓx·s) − c·(2xs + s²)` (so a pixel never depends on the clip). A hit is
//! `D ≥ 0`; the rule admits only spheres wholly in front of the eye, so every hit has
//! `t > 0`.
//!
//! ## Depth and shade
//!
//! Where `D ≥ 0` the hit distance's numerator `T = b − √D` (`t = T/a`, the same `a` for
//! every sphere of the pixel) orders the spheres; [`isqrt`] has error `< 2^(h+1)` with
//! the sphere's per-frame shift `h = ⌈(bits(d_max²·ρ²) − 32)/2⌉` (`D ≤ a·ρ²`: about
//! `4·|d|·ρ·2⁻¹⁶`). Lab #1 needs `n·(−w) = (ℓz − t·F)/ρ = (ℓz·a − F·T)/(a·ρ)`: formed
//! from `a` and `T` shifted right by the frame's `p` (so `a >> p < 2³¹` and
//! `T >> p < 2³²`: 32×32-bit products; the `ℓz/ρ` part is unchanged by it), then
//! divided once in 32 bits after a per-frame shift `q` ([`nz_q16`]). The shade factor's
//! error against the quantised sphere is `≤ 2ʰ⁺¹/(F·ρ)` (root, `a ≥ F²`) `+ 2ᵖ/(F·ρ)`
//! (shift) `+ 2/((F² >> p)·ρ >> q) + 2⁻¹⁶` (division, smallest divisor at the image's
//! centre), `+ (ℓz + ρ)·2ᵖ/(F²·ρ)` (the shift of `a` in `T/a`); the quantisation moves
//! the sphere by `m ≤ √3/2 + ½` (its centre's and radius's rounding, measured per
//! sphere and frame), which turns the normal by at most `m/ρ` where the hit's
//! half-chord `h` is large and by `≈ m/h` near the rim: with the rest of the budget
//! `β`, the hits with `h < g = m/β` form a ring `g²/(2ρ)` wide (λ units) along the
//! silhouette, where the shade moves with the edge. The rule takes the frame only where
//! the sum is < 2⁻⁹ (under one level of 255, with room for the `f32` result's own
//! rounding) and that ring, added to the edge bound, is within 1/16 pixel: there the
//! image is that of the sphere moved by less than 1/16 pixel. Colours are
//! `(c·k + 2¹⁵) >> 16` with `k = max(n·(−w), 0.3)` in Q16.
//!
//! Where the rule does not hold (non-square pixels, an eye inside or beside a sphere,
//! a sphere too small or too close for the bounds at the scene's extent, a scene with
//! lights, planes or mirrors) the frame is drawn by the `f32` method instead.

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::{Vec, VecView};

use crate::camera::int_cut::IntCut;
use crate::camera::span::{Margin, Silhouette};
use crate::camera::Camera;
use crate::math::vec3::Vec3;
use crate::math::wide::{div_q16, isqrt, mul_i32_wide, mul_i64_wide, mul_wide, shr_u64_low, ARMV6M};
use crate::math::{SqrtFn, EDGE_TOLERANCE};
use crate::method::intersect::TestStrategy;
use crate::method::stepping::Stepper;
use crate::scene::sphere::Sphere;
use crate::scene::{Hit, Scene};
use crate::trace::frame::{hull, visible};
use crate::trace::options::{Options, Sample};
use crate::trace::scanline::RowSink;
use crate::trace::scanline::{ColorRuns, PixelRow};

/// Largest `|d|` (`2²⁶`): `a = |d|² ≤ 2⁵²`, `x`, `y`, `F` are `i32`.
const MAX_D: f64 = 67_108_864.0;
/// Largest `λ·(|L| + r)` (`2²⁵`): `|ℓ|, ρ ≤ 2²⁵`, so `|b| ≤ 2⁵¹` (`i64`) and `b²`,
/// `a·c`, `A₁·x`, `A₂·x²` and `2A₂s²` are below 2¹⁰⁶ (`i128`).
const MAX_L: f64 = 33_554_432.0;
/// The shade factor's error budget (units of `n·(−w)`): half a level of 255.
const SHADE_BUDGET: f64 = 1.0 / 512.0;

/// One sphere of the integer picture. Ranges (guaranteed by the rule): `|ℓ|, ρ ≤ 2²⁵`,
/// `ℓz > ρ ≥ 1`, `c > 0`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct IntSphere {
    /// Index in the scene.
    index: usize,
    /// `ℓ = round(λ·L)` in camera coordinates (`u`, `v`, `w`).
    lx: i32,
    ly: i32,
    lz: i32,
    /// `ℓx·s`, the column step of `b`.
    lx_s: i64,
    /// `ρ = round(λ·r)`.
    rho: i32,
    /// The root's shift `h` (`D ≤ a·ρ² < 2³²⁺²ʰ`) and the shade division's `q`
    /// (`(a >> p)·ρ >> q < 2¹⁵` for every pixel's `a`): fixed per frame, so the pixel
    /// loop counts no leading zeros (the Cortex-M0 has no `CLZ`).
    h: u8,
    q: u8,
    /// `c = |ℓ|² − ρ²` (> 0).
    c: i64,
    /// `2·A₂·s²`, the discriminant's constant second difference (`A₂ = ℓx² − c`, its
    /// `x²` coefficient, is formed per row).
    dd: i128,
    /// The object colour's channels.
    rgb: [u8; 3],
    /// Where on the image its rays can hit it: the rows `[j0, j1)` outside which it has
    /// no span ([`Silhouette::rows`]) and the cut of each row ([`IntCut`]), both of the
    /// `f32` silhouette enlarged to cover the quantisation's 1/16 pixel; a row finds
    /// its columns without soft float.
    rows: (u32, u32),
    cut: IntCut,
}

/// The integer kernel's per-frame constants. Not generic over the scene's capacity:
/// one copy of the kernel serves every `Scene<N>` of a firmware.
pub(crate) struct IntFrame<'a> {
    camera: &'a Camera,
    /// `k` of `x = 2ᵏ·(2i + 1 − W)`.
    k: u32,
    /// `F`, the focal length in the pixel units.
    f: i32,
    /// The shade's shift `p` (`a >> p < 2³¹`).
    p: u32,
    /// `λ = 2ᵉ` as a float (for the trace path's `t` only).
    lambda: f32,
    spheres: &'a [IntSphere],
    background: Rgb888,
    i0: u32,
    i1: u32,
    j0: u32,
    j1: u32,
    offset: Point,
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

/// Draws a frame of a scene without lights, planes or mirrors with the integer kernel
/// where its rule takes the frame, else with the f32 method `S`, `T`, `Q`.
///
/// Out of line, and so are both paths: the f32 path's per-sphere constants and the
/// integer kernel's are never on the stack together (a `Scene<64>` would not fit a
/// 16 KiB Cortex-M0 otherwise).
#[allow(clippy::too_many_arguments)]
#[inline(never)]
pub(crate) fn render_or_f32<
    const N: usize,
    const L: usize,
    const P: usize,
    const D: usize,
    K: RowSink,
    S: Stepper,
    T: TestStrategy,
    Q: SqrtFn,
    I: Iterator<Item = Rectangle> + Clone,
>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    options: Options,
    clips: I,
    offset: Point,
    sink: &mut K,
) -> Result<(), K::Error> {
    let (spheres, background) = (scene.spheres(), scene.background());
    if let Some(done) = render::<N, K, I>(spheres, background, camera, options, clips.clone(), offset, sink) {
        return done;
    }
    f32_frame::<N, L, P, D, K, S, T, Q, I>(scene, camera, options, clips, offset, sink)
}

/// The f32 method's frame, out of line (see [`render_or_f32`]).
#[inline(never)]
fn f32_frame<
    const N: usize,
    const L: usize,
    const P: usize,
    const D: usize,
    K: RowSink,
    S: Stepper,
    T: TestStrategy,
    Q: SqrtFn,
    I: Iterator<Item = Rectangle> + Clone,
>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    options: Options,
    clips: I,
    offset: Point,
    sink: &mut K,
) -> Result<(), K::Error> {
    crate::trace::lab1::render::<N, L, P, D, K, S, T, Q, crate::trace::rows::CenterRows, I>(
        scene,
        camera,
        options,
        (clips, crate::trace::rows::CenterRows),
        offset,
        sink,
    )
}

/// Draws the part of a frame each of `clips` shows (a scene without lights, planes or
/// mirrors) with the integer kernel, its per-frame rule and quantisation once for all of
/// them, or returns `None` (nothing drawn) where its rule does not take the frame.
///
/// Out of line: its per-sphere buffers live in its own stack frame, never beside the
/// `f32` path's (which runs only after this has returned).
#[inline(never)]
pub(crate) fn render<const N: usize, K: RowSink, I: Iterator<Item = Rectangle> + Clone>(
    spheres: &[Sphere],
    background: Rgb888,
    camera: &Camera,
    options: Options,
    clips: I,
    offset: Point,
    sink: &mut K,
) -> Option<Result<(), K::Error>> {
    let mut int_spheres: Vec<IntSphere, N> = Vec::new();
    let mut active: Vec<Active<'_>, N> = Vec::new();
    let Some(bound) = clips.clone().reduce(hull) else {
        return Some(Ok(()));
    };
    match IntFrame::new(
        int_spheres.as_mut_view(),
        spheres,
        background,
        camera,
        options,
        bound,
        offset,
    ) {
        Ok(mut frame) => {
            for clip in clips {
                let Some((i0, i1, j0, j1)) = visible(camera.size(), offset, clip) else {
                    continue;
                };
                (frame.i0, frame.i1, frame.j0, frame.j1) = (i0, i1, j0, j1);
                if let Err(e) = draw_rows(&frame, active.as_mut_view(), sink) {
                    return Some(Err(e));
                }
            }
            Some(Ok(()))
        }
        Err(Refusal::Invisible) => Some(Ok(())),
        Err(Refusal::Bounds) => None,
    }
}

/// The integer kernel's frame-wide quantisation of `scene` seen by `camera` — the pixel
/// unit, focal length, shade shift and length unit — or `None` where its per-frame rule
/// does not take the frame; and, for each sphere `pick` selects, the rows and the cut
/// its rows are culled with, passed to `f`. What an incremental frame compares and
/// re-traces; one buffer of `N` spheres, as the render's own.
pub(crate) fn regions<const N: usize>(
    scene: &[Sphere],
    camera: &Camera,
    options: Options,
    pick: impl Fn(usize) -> bool,
    mut f: impl FnMut((u32, u32), IntCut),
) -> Option<[i32; 4]> {
    let mut buf: Vec<IntSphere, N> = Vec::new();
    let plan = plan(scene, camera, options, buf.as_mut_view())?;
    for s in &buf {
        if pick(s.index) {
            f(s.rows, s.cut);
        }
    }
    Some([plan.k as i32, plan.f, plan.p as i32, plan.e])
}

impl<'a> IntFrame<'a> {
    /// The per-frame rule and the integer picture: `Err(Bounds)` where the integer
    /// kernel's bounds (module docs) do not keep every silhouette within 1/16 pixel and
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
        let plan = plan(scene, camera, options, buf).ok_or(Refusal::Bounds)?;
        // Clipped as the f32 frame is.
        let (i0, i1, j0, j1) = visible(camera.size(), offset, clip).ok_or(Refusal::Invisible)?;
        Ok(Self {
            camera,
            k: plan.k,
            f: plan.f,
            p: plan.p,
            lambda: libm::ldexpf(1.0, plan.e),
            spheres: buf,
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
/// `2ᵉ ≥ x`, counted up from `x`'s binary exponent (`2^ilogb(x) ≤ x`, so at most one
/// step, where a count from 0 would take up to a hundred soft-float steps).
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
/// for an infinite `x`; 60 for a NaN), counted down from `ilogb(limit) − ilogb(x) + 1`,
/// where `2ᵉ·x ≥ 2^(ilogb(limit) + 1) > limit` already fails (at most two steps); from 60
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

/// The rule and the integer picture (module docs), or `None`.
fn plan(
    scene: &[Sphere],
    camera: &Camera,
    options: Options,
    spheres: &mut VecView<IntSphere>,
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
    let dot = |a: Vec3, b: Vec3| {
        f64::from(a.x) * f64::from(b.x) + f64::from(a.y) * f64::from(b.y) + f64::from(a.z) * f64::from(b.z)
    };
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
        let silhouette = if options.span_culling {
            // A direction error of pw/16 enlarges the f32 silhouette by ≥ 1/8 pixel:
            // it covers the integer picture's 1/16.
            Silhouette::new(lv, s.radius, camera, Margin::Linear, pw / 16.0)
        } else {
            Silhouette::ALL
        };
        let rows = silhouette.rows(camera.size().height);
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
            cut: silhouette.int_cut(rows),
        });
    }
    Some(Plan {
        k: k as u32,
        f: f as i32,
        p: p as u32,
        e,
    })
}

/// `n·(−w)` in Q16 from `num = ℓz·a − F·T` and `den = a·ρ > 0` (`|num|, den < 2⁶³`),
/// clamped to `[0, 2¹⁶]`: both shifted right by `q` (`den >> q < 2¹⁵`), then one
/// 32-bit division. Error bound: `≤ 2/(den >> q) + 2⁻¹⁶` (the truncations and the
/// quotient's floor).
#[inline(always)]
pub(crate) fn nz_q16(num: i64, den: u64, q: u32) -> u32 {
    if num <= 0 {
        return 0;
    }
    // num > 0 from here.
    if num as u64 >= den {
        return 1 << 16;
    }
    let (n, d) = (shr_u64_low(num as u64, q), shr_u64_low(den, q));
    if d == 0 {
        return 0;
    }
    // n ≤ d < 2¹⁵: n·2¹⁶ < 2³¹.
    if ARMV6M {
        div_q16(n, d)
    } else {
        (n << 16) / d
    }
}

/// Lab #1's `clamp(n_z, 0.3, 1)` in Q16 (`0.3·2¹⁶ = 19660.8`, taken as 19661) and the
/// channels `round(c·k)`.
#[inline(always)]
fn shade(rgb: [u8; 3], nz: u32) -> Rgb888 {
    const AMBIENT_Q16: u32 = 19_661;
    let k = nz.max(AMBIENT_Q16);
    let ch = |c: u8| ((u32::from(c) * k + (1 << 15)) >> 16) as u8;
    Rgb888::new(ch(rgb[0]), ch(rgb[1]), ch(rgb[2]))
}

/// A sphere whose span meets the current row, with its forward differences.
pub(crate) struct Active<'s> {
    lo: u32,
    len: u32,
    /// The discriminant at the next column of the span and its first difference.
    disc: i128,
    delta: i128,
    /// `b = ℓ·d` at the next column (`|b| ≤ 2⁵¹`).
    b: i64,
    sphere: &'s IntSphere,
}

/// Draws the frame's visible rows into the sink.
#[inline(never)]
fn draw_rows<'s, K: RowSink>(
    frame: &IntFrame<'s>,
    active: &mut VecView<Active<'s>>,
    sink: &mut K,
) -> Result<(), K::Error> {
    let size = frame.camera.size();
    let (w, h) = (size.width as i32, size.height as i32);
    let s = 2i32 << frame.k;
    let width = frame.i1 - frame.i0;
    let f = i64::from(frame.f);
    for j in frame.j0..frame.j1 {
        let y = (h - 1 - 2 * j as i32) << frame.k;
        // α = y² + F² ≤ |d|² ≤ 2⁵².
        let alpha = i64::from(y) * i64::from(y) + f * f;
        let x0 = (2 * frame.i0 as i32 + 1 - w) << frame.k;
        let (lo_all, hi_all) = activate(frame, j, y, alpha, active);
        let area = Rectangle::new(
            Point::new(
                frame.offset.x.wrapping_add(frame.i0 as i32),
                frame.offset.y.wrapping_add(j as i32),
            ),
            Size::new(width, 1),
        );
        // a = x² + α and its first difference 2xs + s² at the first column.
        let (xw, sw) = (i64::from(x0), i64::from(s));
        let row = IntRow {
            frame,
            active,
            lo_all,
            hi_all,
            i: frame.i0,
            end: frame.i1,
            j,
            x: x0,
            s,
            a: xw * xw + alpha,
            da: 2 * xw * sw + sw * sw,
            dda: 2 * sw * sw,
            alpha,
        };
        sink.row(area, row)?;
    }
    Ok(())
}

/// Row `j`'s active spheres, each with `D`, `Δ` and `b` evaluated directly at its
/// first visible column (exact), and the union of their spans.
#[inline(never)]
fn activate<'s>(
    frame: &IntFrame<'s>,
    j: u32,
    y: i32,
    alpha: i64,
    active: &mut VecView<Active<'s>>,
) -> (u32, u32) {
    active.clear();
    let width = frame.camera.size().width;
    let (mut lo_all, mut hi_all) = (frame.i1, frame.i0);
    let s = 2i32 << frame.k;
    for sp in frame.spheres.iter() {
        if j < sp.rows.0 || j >= sp.rows.1 {
            continue;
        }
        let Some((lo, hi)) = sp.cut.row_span(j, width) else {
            continue;
        };
        let (lo, hi) = (lo.max(frame.i0), hi.min(frame.i1));
        if lo >= hi {
            continue;
        }
        lo_all = lo_all.min(lo);
        hi_all = hi_all.max(hi);
        let x = (2 * lo as i32 + 1 - width as i32) << frame.k;
        // b = ℓ·d = ℓx·x + β with β = ℓy·y + ℓz·F (|b|, |β| ≤ 2⁵¹) and a = x² + α.
        let beta = mul_i32_wide(sp.ly, y) + mul_i32_wide(sp.lz, frame.f);
        let b = mul_i32_wide(sp.lx, x) + beta;
        let a = mul_i32_wide(x, x) + alpha;
        // D = b² − a·c, and Δ = D(x + s) − D(x) = ℓx·s·(2b + ℓx·s) − c·(2xs + s²):
        // exact, the same integers as the quadratic in x the row steps.
        let disc = mul_i64_wide(b, b) - mul_i64_wide(a, sp.c);
        let delta = mul_i64_wide(sp.lx_s, 2 * b + sp.lx_s)
            - mul_i64_wide(sp.c, 2 * mul_i32_wide(x, s) + mul_i32_wide(s, s));
        let _ = active.push(Active {
            lo,
            len: hi - lo,
            disc,
            delta,
            b,
            sphere: sp,
        });
    }
    (lo_all, hi_all)
}

/// One row of the integer kernel as a sink takes it.
struct IntRow<'r, 's, 'c> {
    frame: &'s IntFrame<'c>,
    active: &'r mut [Active<'c>],
    lo_all: u32,
    hi_all: u32,
    i: u32,
    end: u32,
    j: u32,
    /// The current column's `x` and its step `s`; `a = |d|²` (`≤ 2⁵²`) at the current
    /// column, stepped exactly like the discriminant (`a += Δa; Δa += 2s²`).
    x: i32,
    s: i32,
    a: i64,
    da: i64,
    dda: i64,
    /// The row's `α = y² + F²`.
    alpha: i64,
}

impl<'c> IntRow<'_, '_, 'c> {
    /// One column to the right: `x`, and `a` by its exact differences.
    #[inline(always)]
    fn step(&mut self) {
        self.i += 1;
        self.x += self.s;
        self.a += self.da;
        self.da += self.dda;
    }

    /// `n` columns to the right (the background before the spans), `a` and its
    /// difference evaluated directly at the new column.
    fn skip(&mut self, n: u32) {
        self.i += n;
        self.x += n as i32 * self.s;
        let (x, s) = (i64::from(self.x), i64::from(self.s));
        self.a = x * x + self.alpha;
        self.da = 2 * x * s + s * s;
    }

    /// Column `i` (at `self.x`): the closest sphere hit (sphere, `T`) and its colour.
    /// Advances every active sphere that holds `i` by one column.
    #[inline(always)]
    fn trace(&mut self, i: u32) -> (Option<(&'c IntSphere, i64)>, Rgb888) {
        let mut best: Option<(&'c IntSphere, i64)> = None;
        for act in self.active.iter_mut() {
            if i.wrapping_sub(act.lo) < act.len {
                let sp = act.sphere;
                // The test at this column, then the step to the next (in place: no
                // copy of D and b stays live across the root).
                if act.disc >= 0 {
                    let t = act.b - isqrt(act.disc as u128, u32::from(sp.h)) as i64;
                    if best.is_none_or(|(_, bt)| t < bt) {
                        best = Some((sp, t));
                    }
                }
                act.disc += act.delta;
                act.delta += sp.dd;
                act.b += sp.lx_s;
            }
        }
        let color = match best {
            Some((sp, t)) => {
                let p = self.frame.p;
                // a and T (both > 0) shifted by p: a >> p < 2³¹, T >> p < 2³² (the
                // rule's ranges); the products are below 2⁵⁸, their difference an i64.
                let a = shr_u64_low(self.a as u64, p);
                let t = shr_u64_low(t as u64, p);
                let num = mul_wide(a, sp.lz as u32) as i64 - mul_wide(t, self.frame.f as u32) as i64;
                shade(sp.rgb, nz_q16(num, mul_wide(a, sp.rho as u32), u32::from(sp.q)))
            }
            None => self.frame.background,
        };
        (best, color)
    }
}

impl PixelRow for IntRow<'_, '_, '_> {
    fn samples(self) -> impl Iterator<Item = Sample> {
        IntSamples(self)
    }

    #[inline(always)]
    fn color_runs(mut self) -> ColorRuns<impl Iterator<Item = Rgb888>> {
        let (lo, hi) = if self.lo_all < self.hi_all {
            (self.lo_all, self.hi_all)
        } else {
            (self.end, self.end)
        };
        let before = lo - self.i;
        let after = self.end - hi;
        self.skip(before);
        self.end = hi;
        ColorRuns {
            background: self.frame.background,
            before,
            traced_len: hi - lo,
            traced: IntColors(self),
            after,
        }
    }
}

/// A row's traced colours.
struct IntColors<'r, 's, 'c>(IntRow<'r, 's, 'c>);

impl Iterator for IntColors<'_, '_, '_> {
    type Item = Rgb888;

    #[inline(always)]
    fn next(&mut self) -> Option<Rgb888> {
        let row = &mut self.0;
        let i = row.i;
        if i >= row.end {
            return None;
        }
        let (_, color) = row.trace(i);
        row.step();
        Some(color)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = (self.0.end - self.0.i) as usize;
        (n, Some(n))
    }
}

/// A row's samples (the trace path, [`Render::trace`](crate::Render::trace)): the
/// colour and hit of the integer kernel, the direction and `t` converted to `f32` for
/// the caller (off the drawing path).
struct IntSamples<'r, 's, 'c>(IntRow<'r, 's, 'c>);

impl Iterator for IntSamples<'_, '_, '_> {
    type Item = Sample;

    fn next(&mut self) -> Option<Sample> {
        let row = &mut self.0;
        let i = row.i;
        if i >= row.end {
            return None;
        }
        let (best, color) = if i >= row.lo_all && i < row.hi_all {
            row.trace(i)
        } else {
            (None, row.frame.background)
        };
        let camera = row.frame.camera;
        let direction = camera.direction(i, row.j);
        let hit = best.map(|(sp, t)| {
            // The integer ray's t (λ units, integer d) as the caller's: the hit's
            // distance T/a·|d_int|/λ along the f32 direction.
            let a = row.a as f64;
            let dist = (t as f64 / libm::sqrt(a) / f64::from(row.frame.lambda)) as f32;
            Hit {
                index: sp.index,
                t: dist / direction.length(),
            }
        });
        row.step();
        Some(Sample {
            pixel: Point::new(i as i32, row.j as i32),
            direction,
            hit,
            color,
            rays: 1,
        })
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = (self.0.end - self.0.i) as usize;
        (n, Some(n))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::wide::*;

    /// One step of the xorshift64 generator the random tests draw from.
    fn xorshift(x: &mut u64) {
        *x ^= *x << 13;
        *x ^= *x >> 7;
        *x ^= *x << 17;
    }

    /// `div_q16(n, d) = ⌊n·2¹⁶/d⌋` for every divisor, the numerators at the ends and
    /// spread over the range, every numerator for divisors at the normalisation's and
    /// the table's boundaries; and outside the range (it divides there).
    #[test]
    fn div_q16_is_exact() {
        let check = |n: u32, d: u32| assert_eq!(div_q16(n, d), (n << 16) / d, "{n}/{d}");
        for d in 1..1u32 << 15 {
            for n in [0, 1, d / 3, d / 2, d.saturating_sub(2), d - 1, d] {
                check(n, d);
            }
            for k in 1..16 {
                check(d * k / 16, d);
            }
        }
        for d in [
            1, 2, 3, 63, 64, 65, 127, 128, 16_383, 16_384, 16_385, 16_447, 16_448, 32_703, 32_704, 32_767,
        ] {
            for n in 0..=d {
                check(n, d);
            }
        }
        assert_eq!(div_q16(5, 0), 0);
        assert_eq!(div_q16(40_000, 40_000), 1 << 16);
        assert_eq!(div_q16(3, 1 << 15), (3 << 16) >> 15);
    }

    /// Every `(n, d)` of [`div_q16`]'s range: 2²⁹ pairs, seconds in release mode
    /// (`cargo test --release --lib -- --ignored _is_exact_everywhere`, run by `.ci/run`).
    #[test]
    #[ignore = "exhaustive: run in release mode"]
    fn div_q16_is_exact_everywhere() {
        for d in 1..1u32 << 15 {
            for n in 0..=d {
                assert_eq!(div_q16(n, d), (n << 16) / d, "{n}/{d}");
            }
        }
    }

    /// `mul_wide_halves` equals the `u64` product for every size of `x` and `y`: the
    /// halves' extremes, the carries out of the cross products and out of the low
    /// word, and random values of every width.
    #[test]
    fn mul_wide_equals_the_product() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut values = std::vec![0u32, 1, 0xffff, 0x1_0000, 0x1_ffff, 0x8000_0000, 0x7fff_ffff];
        values.extend([u32::MAX, u32::MAX - 1, 0xffff_0000, 0x0001_ffff, 0xfffe_0001]);
        for _ in 0..2_000 {
            xorshift(&mut x);
            values.push((x as u32) >> (x % 32));
        }
        for &a in &values {
            for &b in &values {
                assert_eq!(mul_wide_halves(a, b), u64::from(a) * u64::from(b), "{a}·{b}");
            }
        }
    }

    /// The signed wide products from halves (the ARMv6-M code) equal the operators for
    /// operands of every sign and size: zero, ±1, the extremes (`MIN`, whose magnitude
    /// is not an `i32`/`i64`), the halves' boundaries and random values of every width.
    #[test]
    fn signed_wide_products_equal_the_operators() {
        let mut x = 0x5851_f42d_4c95_7f2du64;
        let mut values = std::vec![0i64, 1, -1, 0xffff_ffff, -0xffff_ffff, 1 << 32, -(1 << 32)];
        values.extend([
            i64::MAX,
            i64::MIN,
            i64::MIN + 1,
            i64::from(i32::MAX),
            i64::from(i32::MIN),
        ]);
        for _ in 0..1_000 {
            xorshift(&mut x);
            values.push((x as i64) >> (x % 64));
        }
        for &a in &values {
            for &b in &values {
                assert_eq!(
                    mul_i64_wide_halves(a, b),
                    i128::from(a) * i128::from(b),
                    "{a}·{b}"
                );
                let (a32, b32) = (a as i32, b as i32);
                assert_eq!(
                    mul_i32_wide_halves(a32, b32),
                    i64::from(a32) * i64::from(b32),
                    "{a32}·{b32}"
                );
            }
        }
    }

    /// The word-wise shifts equal the operators, at every distance, on values with
    /// every bit pattern class (zero, all ones, sign bit, random).
    #[test]
    fn word_shifts_equal_the_operators() {
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut values = std::vec![
            0u64,
            1,
            u64::MAX,
            1 << 63,
            (1 << 63) - 1,
            0x8000_0001,
            0xffff_ffff
        ];
        for _ in 0..200 {
            xorshift(&mut x);
            values.push(x);
        }
        for &v in &values {
            for s in 0..64 {
                assert_eq!(shr_u64_low_words(v, s), (v >> s) as u32, "{v:#x} >> {s}");
                assert_eq!(
                    shl_u64_words(v as u32, s),
                    u64::from(v as u32) << s,
                    "{v:#x} << {s}"
                );
            }
            for &w in &values {
                let wide = (u128::from(v) << 64) | u128::from(w);
                for s in 0..128 {
                    assert_eq!(
                        shr_u128_low_words(wide, s),
                        (wide >> s) as u32,
                        "{wide:#x} >> {s}"
                    );
                }
            }
        }
    }

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

    /// `r = ⌊√v⌋`: `r² ≤ v < (r + 1)²`.
    fn check_isqrt32(v: u32) {
        let r = u64::from(isqrt32(v));
        assert!(
            r * r <= u64::from(v) && (r + 1) * (r + 1) > u64::from(v),
            "√{v}: {r}"
        );
    }

    /// [`isqrt32`] on the first million, next to every square (where `⌊√v⌋` steps), at
    /// the normalisation's and the table's boundaries, and at the top of the range.
    #[test]
    fn isqrt32_is_exact() {
        for v in 0..1_000_000u32 {
            check_isqrt32(v);
        }
        for r in 0..=0xffffu32 {
            let sq = r * r;
            for v in [sq.wrapping_sub(1), sq, sq + 1, sq + r, sq + 2 * r] {
                check_isqrt32(v);
            }
        }
        for b in 0..32 {
            let p = 1u32 << b;
            for v in [p - 1, p, p + 1, p | (p >> 1), p | (p - 1)] {
                check_isqrt32(v);
            }
        }
        for k in 64..256u32 {
            let n = k << 24;
            for v in [n.wrapping_sub(1), n, n | 0xff_ffff] {
                check_isqrt32(v);
            }
        }
    }

    /// Every `u32`: 2³² roots, about a minute in release mode
    /// (`cargo test --release --lib -- --ignored _is_exact_everywhere`, run by `.ci/run`).
    #[test]
    #[ignore = "exhaustive: run in release mode"]
    fn isqrt32_is_exact_everywhere() {
        for v in 0..=u32::MAX {
            check_isqrt32(v);
        }
    }

    /// `0 ≤ √v − isqrt(v) < 2^(h+1)`, at the bound's worst places (just below powers of
    /// four, where the truncated bits are all ones) and on random values of every size.
    #[test]
    fn isqrt_bound() {
        let mut vs = std::vec::Vec::new();
        // The kernel's discriminants are below 2¹⁰⁶ (roots below 2⁵³: no u64 overflow).
        for b in 0..106u32 {
            let p = 1u128 << b;
            vs.extend([p, p - 1, p + 1, p | (p >> 1), (p << 1) - 1]);
        }
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..100_000 {
            xorshift(&mut x);
            let y = x.rotate_left(17) ^ 0x5555;
            vs.push(((u128::from(x) << 64) | u128::from(y)) >> (22 + x % 106));
        }
        for v in vs {
            let bits = 128 - v.leading_zeros();
            // The smallest admissible h, and larger ones (a frame's h fits its largest D).
            let h0 = (bits.max(32) - 32).div_ceil(2);
            for h in [h0, h0 + 1, h0 + 7] {
                let got = isqrt(v, h);
                // Exact check in integers: got² ≤ v < (got + 2^(h+1))².
                assert!(u128::from(got) * u128::from(got) <= v, "{v}: {got} too large");
                let hi = u128::from(got) + (1u128 << (h + 1));
                assert!(hi * hi > v, "{v}: {got} below √v by 2^(h+1) or more, h {h}");
            }
        }
    }

    /// `nz_q16` within `2/(den >> q) + 2⁻¹⁶` of the exact quotient, over the divisor's
    /// whole range and shifts that leave it 15 down to 6 bits.
    #[test]
    fn nz_bound() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..200_000 {
            xorshift(&mut x);
            let den = ((x >> 3) >> (x % 50)).max(1) as i64;
            let frac = (x % 10_007) as f64 / 10_007.0;
            let num = (den as f64 * frac) as i64;
            let bits = 64 - den.leading_zeros();
            for keep in [15, 11, 6] {
                let q = bits.saturating_sub(keep);
                let d = (den >> q) as f64;
                let got = f64::from(nz_q16(num, den as u64, q)) / 65536.0;
                let exact = num as f64 / den as f64;
                let bound = 2.0 / d + 1.0 / 65536.0;
                assert!(
                    (got - exact).abs() <= bound,
                    "{num}/{den} q {q}: {got} vs {exact}"
                );
            }
        }
        assert_eq!(nz_q16(-5, 10, 0), 0);
        assert_eq!(nz_q16(i64::MIN, 10, 0), 0);
        assert_eq!(nz_q16(11, 10, 0), 1 << 16);
        assert_eq!(nz_q16(10, 10, 0), 1 << 16);
    }
}
