//! Square-root and tangent back ends.
//!
//! The kernel needs three scalar functions: a square root (per pixel where a ray hits,
//! per row and per frame for the span culling and the sphere constants), and [`tan`]
//! (its own, for flash; see there) once per frame for the camera. Two square roots are
//! offered, one per [`Sqrt`](crate::Sqrt) method:
//!
//! | function | source | error bound |
//! |---|---|---|
//! | [`sqrt_exact`] | the FPU's `VSQRT.F32` on hard-float ARM (`target_abi = "eabihf"`, e.g. `thumbv7em-none-eabihf`), `libm::sqrtf` elsewhere | correctly rounded (≤ 0.5 ulp) |
//! | [`sqrt_fast`] | micromath's bit trick `(bits + 0x3f80_0000) >> 1` | `0 ≤ (fast − exact)/exact ≤ 6.07 %` for finite `x ≥ 0`; exact at powers of 4 |
//!
//! Why the instruction: on `thumbv7em-none-eabihf` libm 0.2's `sqrtf` is a software
//! routine (its `arch` feature only has SSE2, AArch64 and wasm back ends; disassembled,
//! `libm::sqrtf` there is a loop of integer shifts and compares, no `vsqrt`), while the
//! Cortex-M4F's FPU computes the same correctly rounded result in one instruction (its
//! timing from the TRM: `docs/firmware.md`, "Cycles, estimated"). Both are
//! IEEE-754 `squareRoot` in round-to-nearest, so the results are bit-identical (checked
//! against `libm::sqrtf` over millions of inputs by this module's tests on the host and
//! by `lab/firmware/examples/qemu_cortex_m4.rs` on the FPU).
//!
//! The two tolerances every error bound of the crate is stated in live here too:
//! [`UNIT_ROUNDOFF`] and [`EDGE_TOLERANCE`].

pub mod limits;
pub mod vec3;
pub(crate) mod wide;

/// The unit roundoff of `f32`, `u = 2⁻²⁴`: one correctly rounded operation changes its
/// exact result by at most `u` relative.
///
/// Every rounding bound in the crate counts in it.
pub const UNIT_ROUNDOFF: f32 = 1.0 / 16_777_216.0;

/// How far, in pixels, a method may move a silhouette edge and still be called exact:
/// 1/16 pixel.
///
/// It sets [`Auto`](crate::SphereTest::Auto)'s choice and the camera's
/// [`MIN_PIXEL_SIZE`](crate::camera::MIN_PIXEL_SIZE) (`UNIT_ROUNDOFF / EDGE_TOLERANCE`).
pub const EDGE_TOLERANCE: f32 = 1.0 / 16.0;

/// Correctly rounded `f32` square root (IEEE-754 `sqrt`, ≤ 0.5 ulp).
///
/// On hard-float ARM (`thumbv7em-none-eabihf`) this is the FPU's `VSQRT.F32`
/// instruction; libm's `sqrtf` there is a loop of integer shifts and compares (libm's
/// `arch` feature has no ARM version). Elsewhere it is `libm::sqrtf`. Both are
/// correctly rounded, so the results are bit-identical on every target (the firmware
/// example checks that in QEMU over millions of inputs).
///
/// ```
/// use embedded_raytracer::math::sqrt_exact;
/// assert_eq!(sqrt_exact(2.0), core::f32::consts::SQRT_2);
/// ```
///
/// The FPU instruction matches libm bit for bit for every
/// input as long as the FPU is in its reset configuration: round to nearest, no
/// flush-to-zero (with `FPSCR.FZ` set, subnormal inputs and results become zero) —
/// and a NaN result may carry a different payload (both are NaN).
#[must_use]
#[inline(always)]
pub fn sqrt_exact(x: f32) -> f32 {
    #[cfg(all(target_arch = "arm", target_abi = "eabihf"))]
    {
        let root: u32;
        // SAFETY: `vsqrt.f32` computes the root in an FPU register and touches no
        // memory. rustc's `sreg` operand class needs the `vfp2` feature, which the
        // single-precision `thumbv7em-none-eabihf` FPU (`vfp4d16sp`) does not count as,
        // so the value travels through core registers and the scratch register s14,
        // declared clobbered (an explicit register needs no operand class): the
        // compiler keeps nothing live in it, so no root pays a save and restore. Every
        // hard-float ARM target (`eabihf`) has a VFP unit
        // (VFPv2 or later, all of which implement VSQRT.F32) and enables it before
        // `main` (cortex-m-rt does so for `thumbv7em-none-eabihf`), so the instruction
        // exists and is enabled. It may set the FPSCR's cumulative exception bits (IXC,
        // IOC), so the block does not claim `preserves_flags`.
        unsafe {
            core::arch::asm!(
                "vmov s14, {x}",
                "vsqrt.f32 s14, s14",
                "vmov {root}, s14",
                x = in(reg) x.to_bits(),
                root = lateout(reg) root,
                out("s14") _,
                options(pure, nomem, nostack)
            );
        }
        f32::from_bits(root)
    }
    #[cfg(not(all(target_arch = "arm", target_abi = "eabihf")))]
    {
        libm::sqrtf(x)
    }
}

/// Fast approximate square root (micromath): one integer add and a shift.
///
/// Error bound: for finite `x ≥ 0` the result is never below the true root and at most
/// 6.07 % above it (the linear interpolation of `√m` over a mantissa octave peaks at
/// `1.5/√2 − 1`); exact at powers of 4. `x = 0` gives `≈ 8.1e-20`, not 0. Negative `x`
/// gives NaN — the kernel only calls it with a non-negative discriminant.
///
/// ```
/// use embedded_raytracer::math::{sqrt_exact, sqrt_fast};
/// assert_eq!(sqrt_fast(16.0), 4.0);
/// let rel = sqrt_fast(2.0) / sqrt_exact(2.0) - 1.0;
/// assert!((0.0..=0.0607).contains(&rel));
/// ```
#[must_use]
#[inline(always)]
pub fn sqrt_fast(x: f32) -> f32 {
    micromath::F32(x).sqrt().0
}

/// `f32::max` inline: the larger of `a` and `b`, the other one where one is NaN.
///
/// The Cortex-M4's FPU has no `VMAXNM`, so `f32::max` is a call to `fmaxf`; per-row
/// code that clamps many values uses this instead.
#[must_use]
#[inline(always)]
pub(crate) fn max(a: f32, b: f32) -> f32 {
    if a < b || a.is_nan() {
        b
    } else {
        a
    }
}

/// `f32::min` inline (as `max`): the smaller, the other one where one is NaN.
#[must_use]
#[inline(always)]
pub(crate) fn min(a: f32, b: f32) -> f32 {
    if b < a || a.is_nan() {
        b
    } else {
        a
    }
}

/// `tan(x)` for the camera's half field of view, `x ∈ [0, π/2)`, once per frame.
///
/// Why not libm's `tanf`: its general argument reduction (`rem_pio2_large`) and the
/// soft-float `f64` it computes in would take most of the render path's flash on a Cortex-M4F
/// (`docs/firmware.md`, "Flash", measures it on `lab/firmware/examples/no_panic.rs`).
/// A field of view needs no reduction: on `[0, π/4]`,
/// `tan x = sin x / cos x` from Taylor polynomials (degree 9 and 10; truncation below
/// 3e-9 relative), and on `(π/4, π/2)`, `tan x = cos y / sin y` with `y = π/2 − x`
/// formed exactly (Sterbenz) from a two-part `π/2`, so the result stays accurate as
/// `x → π/2`.
///
/// Error bound: ≤ 4 ulp (relative 4.8e-7) on `[0, π/2)` against `f64` `tan` (test
/// `tan_error_bound`, a dense sweep up to the largest half field of view, 89.5°).
/// Outside `[0, π/2)` the result is meaningless; the camera never asks for it.
///
/// ```
/// use embedded_raytracer::math::tan;
/// assert!((tan(core::f32::consts::FRAC_PI_4) - 1.0).abs() < 2e-7);
/// ```
#[must_use]
pub fn tan(x: f32) -> f32 {
    // π/2 as hi + lo: hi = fl(π/2), lo = π/2 − hi.
    const PIO2_HI: f32 = core::f32::consts::FRAC_PI_2;
    const PIO2_LO: f32 = -4.371_139e-8;
    if x <= core::f32::consts::FRAC_PI_4 {
        sin_poly(x) / cos_poly(x)
    } else {
        // Exact by Sterbenz for x ∈ [π/4, π/2]; lo restores π/2's rounding.
        let y = (PIO2_HI - x) + PIO2_LO;
        cos_poly(y) / sin_poly(y)
    }
}

/// `sin x` on `[0, π/4]`: Taylor to x⁹ (truncation ≤ x¹¹/11! ≈ 1.7e-9).
#[inline]
fn sin_poly(x: f32) -> f32 {
    let x2 = x * x;
    x * (1.0 + x2 * (-1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5040.0 + x2 * (1.0 / 362_880.0)))))
}

/// `cos x` on `[0, π/4]`: Taylor to x¹⁰ (truncation ≤ x¹²/12! ≈ 1.2e-10).
#[inline]
fn cos_poly(x: f32) -> f32 {
    let x2 = x * x;
    1.0 + x2
        * (-0.5 + x2 * (1.0 / 24.0 + x2 * (-1.0 / 720.0 + x2 * (1.0 / 40_320.0 + x2 * (-1.0 / 3_628_800.0)))))
}

/// A square-root back end chosen once per frame; the render loop is monomorphised
/// over it so the per-pixel code has no branch on the method.
pub(crate) trait SqrtFn {
    /// Correctly rounded: hits and their order are the exact ones' up to rounding.
    const EXACT: bool;
    fn sqrt(x: f32) -> f32;
}

/// [`sqrt_exact`] as a strategy type.
pub(crate) struct ExactSqrt;
/// [`sqrt_fast`] as a strategy type.
pub(crate) struct FastSqrt;

impl SqrtFn for ExactSqrt {
    const EXACT: bool = true;
    #[inline(always)]
    fn sqrt(x: f32) -> f32 {
        sqrt_exact(x)
    }
}

impl SqrtFn for FastSqrt {
    const EXACT: bool = false;
    #[inline(always)]
    fn sqrt(x: f32) -> f32 {
        sqrt_fast(x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stated bound of `sqrt_fast`, checked over a dense sweep of two octaves
    /// (the error is periodic in the exponent pair) and at the extremes.
    #[test]
    fn fast_sqrt_error_bound() {
        let mut worst = 0.0f32;
        let mut x = 1.0f32;
        while x < 4.0 {
            let rel = sqrt_fast(x) / sqrt_exact(x) - 1.0;
            assert!(rel >= 0.0, "fast sqrt below exact at {x}: {rel}");
            worst = worst.max(rel);
            x = f32::from_bits(x.to_bits() + 97);
        }
        assert!(worst <= 0.0607, "worst relative error {worst}");
        // The bound is tight: the peak is just below 2.0.
        assert!(worst > 0.0606, "worst relative error {worst}");
        for x in [1e-30f32, 1e-10, 1e10, 1e30] {
            let rel = sqrt_fast(x) / sqrt_exact(x) - 1.0;
            assert!((0.0..=0.0607).contains(&rel), "{x}: {rel}");
        }
        assert_eq!(sqrt_fast(0.25), 0.5);
        assert!(sqrt_fast(-1.0).is_nan());
    }

    /// `sqrt_exact` is `libm::sqrtf` bit for bit over 2²⁴ + inputs (every 127th bit
    /// pattern from +0 to +∞) and the edge cases: on the host this checks the libm path;
    /// the firmware example runs the same comparison on the FPU instruction.
    #[test]
    fn exact_sqrt_is_bit_identical_to_libm() {
        let same = |x: f32| {
            let (a, b) = (sqrt_exact(x), libm::sqrtf(x));
            a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
        };
        let specials = [
            -0.0,
            f32::from_bits(1),
            f32::from_bits(0x007f_ffff),
            f32::MIN_POSITIVE,
            f32::MAX,
            -1.0,
        ];
        for x in specials {
            assert!(same(x), "{x:e}");
        }
        let mut checked = 0u32;
        for bits in (0..=0x7f80_0000u32).step_by(127) {
            let x = f32::from_bits(bits);
            assert!(same(x), "{x:e}");
            checked += 1;
        }
        assert!(checked > 16_000_000, "{checked}");
    }

    /// The stated bound of `tan`: ≤ 4 ulp over the whole half-field-of-view range,
    /// densely (every 61st f32 from 1e-4 rad up to 89.5°, plus the tiny end).
    #[test]
    fn tan_error_bound() {
        let max = crate::camera::MAX_FOV / 2.0;
        let mut worst_ulps = 0.0f64;
        let mut worst_at = 0.0f32;
        let mut x = 1e-30f32;
        while x <= max {
            let exact = (x as f64).tan();
            let got = tan(x) as f64;
            let ulp = f64::from(f32::from_bits((exact as f32).to_bits() + 1) - exact as f32);
            let ulps = (got - exact).abs() / ulp;
            if ulps > worst_ulps {
                worst_ulps = ulps;
                worst_at = x;
            }
            x = if x < 1e-4 {
                x * 1.5
            } else {
                f32::from_bits(x.to_bits() + 61)
            };
        }
        assert!(worst_ulps <= 4.0, "tan: {worst_ulps} ulp at {worst_at}");
        // The bound is not loose by orders of magnitude: the worst case is over 1 ulp.
        assert!(worst_ulps > 1.0, "tan: worst only {worst_ulps} ulp");
        assert_eq!(tan(0.0), 0.0);
    }

    #[test]
    fn exact_sqrt_is_correctly_rounded() {
        // For a correctly rounded root r of x: r² brackets x within one ulp of r.
        let mut x = 1e-6f32;
        while x < 1e6 {
            let r = sqrt_exact(x);
            let lo = f32::from_bits(r.to_bits() - 1);
            let hi = f32::from_bits(r.to_bits() + 1);
            let (x64, r64) = (x as f64, r as f64);
            assert!(
                (r64 * r64 - x64).abs() <= (lo as f64 * lo as f64 - x64).abs()
                    && (r64 * r64 - x64).abs() <= (hi as f64 * hi as f64 - x64).abs(),
                "sqrt({x}) = {r} is not the nearest"
            );
            x *= 1.013;
        }
    }
}
