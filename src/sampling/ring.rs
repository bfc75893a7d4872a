//! Once per frame, each sphere's rings for the silhouette-decided `Adaptive`
//! ([`SpanAdaptiveRows`](super::span::SpanAdaptiveRows)): where an edge can cross a
//! pixel, and where the centre's Lab #1 shade is no fair stand-in for the pixel's mean.

use heapless::Vec;

use crate::math::vec3::Vec3;
use crate::method::intersect::TestStrategy;
use crate::method::stepping::Stepper;
use crate::trace::frame::Frame;
use crate::trace::shade::Shader;

/// A ring on the image between two ellipses: `outer` contains it, `inner` (`None`:
/// empty) is cut out of it.
#[derive(Clone, Copy)]
pub(super) struct Ring {
    outer: crate::camera::span::Silhouette,
    inner: Option<crate::camera::span::Silhouette>,
    /// The outer ellipse's [`Silhouette::reach_consts`](crate::camera::span::Silhouette::reach_consts).
    reach: (f32, f32),
}

impl Ring {
    fn new(outer: crate::camera::span::Silhouette, inner: Option<crate::camera::span::Silhouette>) -> Self {
        Self {
            outer,
            inner,
            reach: outer.reach_consts(),
        }
    }

    /// Row `j`'s columns `i` whose segment `[i − h, i + h] × [j − h, j + h]` meets the
    /// outer ellipse (`lo..hi`) and, within them, those whose segment lies inside the
    /// inner one (`in_lo..in_hi`, empty as `hi..hi`).
    ///
    /// Clamped to `f0..f1`; `None` if the outer one is out of reach.
    #[inline(always)]
    pub(super) fn columns(&self, j: u32, h: f32, (f0, f1): (f32, f32)) -> Option<[u32; 4]> {
        // The columns `⌈a⌉ ..= ⌊b⌋` of the frame, `None` if none: an interval that
        // ends left of the frame or starts right of it is empty (clamping it first
        // would make it the border column). Clamped, then rounded by conversion (the
        // bounds are integers, so the two commute; the values are in [0, 2¹³]).
        let columns = |a: f32, b: f32| -> Option<(u32, u32)> {
            if !(b >= f0 && a < f1 && a <= b) {
                return None;
            }
            let a = crate::math::max(a, f0);
            let t = a as u32;
            let lo = t + u32::from((t as f32) < a);
            let hi = (crate::math::min(b, f1) as u32 + 1).min(f1 as u32);
            (lo < hi).then_some((lo, hi))
        };
        let (x0, x1) = self.outer.band_reach(j, h, self.reach)?;
        // [i − h, i + h] meets [x0, x1]: i in [x0 − h, x1 + h].
        let (lo, hi) = columns(x0 - h, x1 + h)?;
        // [i − h, i + h] inside [x0, x1]: i in [x0 + h, x1 − h].
        let (in_lo, in_hi) = self
            .inner
            .and_then(|s| s.band_inside(j, h))
            .and_then(|(x0, x1)| columns(x0 + h, x1 - h))
            .map(|(a, z)| (a.max(lo), z.min(hi)))
            .filter(|(a, z)| a < z)
            .unwrap_or((hi, hi));
        Some([lo, hi, in_lo, in_hi])
    }
}

/// Per frame, per sphere: the ring between where sub-pixel and centre rays can hit it
/// and where they all do (the silhouette's edge), and the ring where the centre's
/// Lab #1 shade may be more than [`SHADE_TOLERANCE`] from the pixel's mean.
pub(super) struct SpanBands {
    /// `None`: a sphere wholly behind the eye, which no ray hits.
    pub(super) silhouette: Option<Ring>,
    pub(super) shade: Option<Ring>,
}

/// How far (8-bit levels) the Lab #1 shade at a pixel's centre may be from the mean
/// of its sub-samples before the pixel is an edge pixel (the error model is in the
/// source, at `shade_ring`).
pub const SHADE_TOLERANCE: f32 = 1.5;

/// Every sphere's [`SpanBands`] for the frame: silhouettes enlarged and shrunk by the
/// test's margin and the larger of the stepping's and the sub-pixel rays' direction
/// error (`Stepping::Direct`'s bound covers the latter:
/// [`SubSteps`](super::average::SubSteps)).
///
/// A sphere wholly behind the eye ([`behind_the_eye`]) has no ring: no ray hits it.
///
/// `None` when the silhouettes alone cannot find the edges: a silhouette that is not
/// a bounded ellipse (a sphere reaching the eye's plane), or two spheres (neither
/// behind the eye) closer than the sum of their radii plus
/// `g = 2⁻¹⁰·(|L₁| + |L₂|)` (where both can be hit, the one in front can change inside
/// a pixel). Between two other spheres a separating plane keeps the same one in front
/// along every ray through both (the eye is on one side of it), with a gap no `t`'s
/// rounding (`≲ 2⁻²⁰·|L|`) can close; and the eye's powers `|L|² − r²` (f32, error
/// `≲ 2⁻²³·|L|²`) order them wherever a ray can hit both (the eye is then at least
/// `g/2` from their radical plane, where the powers differ by at least `g²`).
#[inline(never)]
pub(super) fn span_bands<const N: usize, S: Stepper, T: TestStrategy, Sh: Shader>(
    frame: &Frame<'_, T, Sh>,
) -> Option<Vec<SpanBands, N>> {
    use crate::camera::span::Silhouette;
    let camera = frame.camera;
    let step_err = S::error_bound(camera);
    let err = step_err.max(<crate::method::stepping::DirectStep as Stepper>::error_bound(
        camera,
    ));
    let mut out: Vec<SpanBands, N> = Vec::new();
    let w = camera.w();
    for (k, fs) in frame.spheres.iter().enumerate() {
        let g = &fs.geom;
        let r = crate::math::sqrt_exact(g.r2);
        if behind_the_eye(g, w) {
            // Never fails: one per sphere.
            let _ = out.push(SpanBands {
                silhouette: None,
                shade: None,
            });
            continue;
        }
        // Each pair once. The f32 distance's rounding (≲ 2⁻²²·(|L₁| + |L₂|)) is far
        // inside the gap asked for; NaN counts as touching.
        let touching = frame
            .spheres
            .iter()
            .skip(k + 1)
            .filter(|o| !behind_the_eye(&o.geom, w))
            .any(|other| {
                let o = &other.geom;
                let gap =
                    crate::math::sqrt_exact((g.l - o.l).dot(g.l - o.l)) - r - crate::math::sqrt_exact(o.r2);
                !(gap > (crate::math::sqrt_exact(g.l2) + crate::math::sqrt_exact(o.l2)) * (1.0 / 1024.0))
            });
        // The culling ellipse where it was built for the same error (the direct
        // stepping), saving its f64 work.
        let outer = if !fs.silhouette.is_all() && step_err >= err {
            fs.silhouette
        } else {
            Silhouette::new(g.l, r, camera, T::MARGIN, err)
        };
        if touching || outer.is_all() {
            return None;
        }
        // Never fails: one per sphere.
        let _ = out.push(SpanBands {
            silhouette: Some(Ring::new(
                outer,
                Silhouette::inner(g.l, r, camera, T::MARGIN, err),
            )),
            shade: shade_ring(g.l, r, camera, outer),
        });
    }
    Some(out)
}

/// Whether the sphere `g` lies wholly behind the eye, its nearest point at least
/// `2⁻⁸·(|L| + r)` behind the plane through the eye parallel to the image (`w` the
/// view direction).
///
/// The test is `L·w + r ≤ −2⁻⁸·(|L| + r)`, in f32 (`f32` rounding of `L·w`, `|L|` and
/// `r` is below `2⁻²⁰·(|L| + r)`, so a sphere passes only if it is behind by more than
/// `2⁻⁹·(|L| + r)`; NaN fails).
///
/// No ray of the frame hits it, in any test with the exact square root (the only
/// root this rule runs with: a fast root's 6 % can lift the slides' algebraic `√disc`
/// above `|b|`, and frames with it fall back): every primary and sub-pixel direction
/// has `d·w` equal to the focal distance (`du`, `dv` ⟂ `w`; the stepping's error is
/// far smaller), so a point at `t > 0` is in front of that plane and the exact roots
/// are negative. The computed ones keep their sign. With `m = 2⁻⁹·(|L| + r)`, the
/// eye's power is `c = |L|² − r² ≥ m·(|L| + r)` (`|L| ≥ r + m`) and, where the ray's
/// line meets the sphere, the roots' mean `b/a` (`b = L·d`, `a = d·d`) is behind by
/// `m/(d·w)`, so `−b ≥ m·|d|`: each is `2¹³` or more times its `f32` rounding (a
/// forward-differenced `b`, `2⁻²⁰` relative after 16 steps, too). With `b < 0` and
/// `c > 0` every test's roots are negative: `q/a` and `c/q` with `q = b − √disc < 0`
/// (robust, forward differences), `(b ± √disc)/a` with `√disc` below `|b|` by a
/// relative `c/(2|L|²) ≥ 2⁻¹⁰` (the slides' algebraic form), and the geometric test
/// stops at `L·d < 0`. The premise that the directions keep `d·w > 0` is the
/// stepping's error bound (below 10⁻² for any silhouette to be built at all). The
/// tests in `lab/tests/lab/sampling.rs` place spheres just past the margin, and one crossing
/// the eye's plane (not left out).
#[inline]
fn behind_the_eye(g: &crate::method::intersect::SphereGeom, w: crate::math::vec3::Vec3) -> bool {
    let r = crate::math::sqrt_exact(g.r2);
    let l = crate::math::sqrt_exact(g.l2);
    g.l.dot(w) + r <= -(l + r) * (1.0 / 256.0)
}

/// Where the centre's Lab #1 shade may be more than [`SHADE_TOLERANCE`] levels from
/// the mean of a pixel's sub-samples.
///
/// Those are the hits whose `f = n·(−w)` lies in `[f_lo, f_hi]`, taken as the ring of
/// centres between the sphere of the points with `f ≥ f_lo` and the one of the points
/// with `f ≥ f_hi`.
///
/// The points of the sphere (centre `L`, radius `r`) with `n·(−w) ≥ f` lie in the
/// sphere of centre `L − r·f·w` and radius `r·√(1 − f²)` (their distance² to it is
/// `r²·(1 − 2f·n·(−w) + f²) ≤ r²·(1 − f²)`), so a centre ray outside its silhouette
/// hits at `f < f_lo`; a centre ray inside the silhouette of the `f_hi` one hits, for
/// all but the perspective's slight bulge, at `f ≥ f_hi` (a heuristic: the box
/// filter's error is not an edge, and the tables measure it).
///
/// The error model, for a silhouette of radius `R` pixels (its semi-minor axis) and a
/// channel of 255: the mean of the `n × n` samples (offset variance `5/64` px² for
/// `n` = 4) minus the centre is about `(5/128)·∇²c` plus the linear-light average's
/// `0.6·|∇c|²·(5/64)/c`, together `≲ 22/(f³·R²)` levels, below the tolerance where
/// `f³ ≥ 22/(tol·R²)`; the `f = 0.3` floor of Lab #1 is a kink whose slope
/// `s ≈ 255·3.2/R` levels per pixel moves the mean by up to `s/8` levels, more than the
/// tolerance within `¼ − 2·tol/s` pixels of it.
fn shade_ring(
    l: Vec3,
    r: f32,
    camera: &crate::camera::Camera,
    outer: crate::camera::span::Silhouette,
) -> Option<Ring> {
    use crate::camera::span::{Margin, Silhouette};
    let radius = outer.bounds()?.1.max(0.5);
    let tol = SHADE_TOLERANCE;
    let slope = 255.0 * 3.2 / radius;
    let kink = (0.25 - 2.0 * tol / slope).max(0.0) * 3.2 / radius;
    let smooth = libm::cbrtf(22.0 / (tol * radius * radius));
    let f_lo = if kink > 0.0 {
        crate::trace::shade::AMBIENT - kink
    } else {
        crate::trace::shade::AMBIENT
    };
    let f_hi = smooth.max(crate::trace::shade::AMBIENT + kink);
    if !(f_hi > f_lo) {
        return None;
    }
    let w = camera.w();
    let cap = |f: f32, side_outer: bool| {
        let f = f.clamp(0.0, 1.0);
        let (c, rho) = (l - w * (r * f), r * crate::math::sqrt_exact(1.0 - f * f));
        if side_outer {
            Some(Silhouette::new(c, rho, camera, Margin::Linear, 0.0))
        } else if f < 1.0 {
            Silhouette::inner(c, rho, camera, Margin::Linear, 0.0)
        } else {
            None
        }
    };
    Some(Ring::new(cap(f_lo, true)?, cap(f_hi, false)))
}
