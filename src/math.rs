//! Square-root and tangent back ends.
//!
//! The kernel needs three scalar functions: a square root in the per-pixel loop (only
//! where a ray hits), and `tan` and an exact square root once per frame (camera
//! setup). Two square roots are offered, one per [`Sqrt`](crate::Sqrt) method:
//!
//! | function | source | error bound |
//! |---|---|---|
//! | [`sqrt_exact`] | the FPU's `VSQRT.F32` on hard-float ARM (Cortex-M4F/M7), `libm::sqrtf` elsewhere | correctly rounded (≤ 0.5 ulp): both back ends give the same bits |
//! | [`sqrt_fast`] | micromath's bit trick `(bits + 0x3f80_0000) >> 1` | `0 ≤ (fast − exact)/exact ≤ 6.07 %` for finite `x ≥ 0`; exact at powers of 4 |

/// Correctly rounded `f32` square root (IEEE-754 `sqrt`, ≤ 0.5 ulp).
///
/// On hard-float ARM (`thumbv7em-none-eabihf`) this is the FPU's `VSQRT.F32`
/// instruction; libm's `sqrtf` there is a ~55-instruction integer routine (libm's
/// `arch` feature has no ARM version). Elsewhere it is `libm::sqrtf`. Both are
/// correctly rounded, so the results are bit-identical on every target (the firmware
/// example checks that in QEMU over millions of inputs).
///
/// ```
/// use embedded_raytracer::math::sqrt_exact;
/// assert_eq!(sqrt_exact(2.0), core::f32::consts::SQRT_2);
/// ```
#[must_use]
#[inline(always)]
pub fn sqrt_exact(x: f32) -> f32 {
    #[cfg(all(target_arch = "arm", target_abi = "eabihf"))]
    {
        // SAFETY: `embedded_raytracer_vsqrtf` (below) follows the AAPCS-VFP calling
        // convention of `extern "C"` on this target: its argument arrives in s0 and its
        // result leaves in s0; it touches no other register and no memory.
        unsafe { embedded_raytracer_vsqrtf(x) }
    }
    #[cfg(not(all(target_arch = "arm", target_abi = "eabihf")))]
    {
        libm::sqrtf(x)
    }
}

/// `libm::sqrtf`, for checking [`sqrt_exact`]'s hardware back end against it.
#[must_use]
pub fn sqrt_libm(x: f32) -> f32 {
    libm::sqrtf(x)
}

// The one `unsafe` asm block of the crate: `VSQRT.F32 s0, s0; BX LR` as a function.
// Hard-float ARM only. Stable Rust sets no `vfp2` target feature cfg for these
// targets, so `asm!` cannot name s-registers; a `global_asm!` function with `.fpu`
// declared is the stable way to reach the instruction.
#[cfg(all(target_arch = "arm", target_abi = "eabihf"))]
core::arch::global_asm!(
    ".fpu fpv4-sp-d16",
    ".section .text.embedded_raytracer_vsqrtf,\"ax\",%progbits",
    ".global embedded_raytracer_vsqrtf",
    ".type embedded_raytracer_vsqrtf,%function",
    ".thumb_func",
    "embedded_raytracer_vsqrtf:",
    "vsqrt.f32 s0, s0",
    "bx lr",
    ".size embedded_raytracer_vsqrtf, . - embedded_raytracer_vsqrtf",
);

#[cfg(all(target_arch = "arm", target_abi = "eabihf"))]
extern "C" {
    fn embedded_raytracer_vsqrtf(x: f32) -> f32;
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

/// `tan(x)` for the camera's field of view (libm `tanf`, < 1 ulp), once per frame.
#[must_use]
pub fn tan(x: f32) -> f32 {
    libm::tanf(x)
}

/// A square-root back end chosen once per frame; the render loop is monomorphised
/// over it so the per-pixel code has no branch on the method.
pub(crate) trait SqrtFn {
    fn sqrt(x: f32) -> f32;
}

/// [`sqrt_exact`] as a strategy type.
pub(crate) struct ExactSqrt;
/// [`sqrt_fast`] as a strategy type.
pub(crate) struct FastSqrt;

impl SqrtFn for ExactSqrt {
    #[inline(always)]
    fn sqrt(x: f32) -> f32 {
        sqrt_exact(x)
    }
}

impl SqrtFn for FastSqrt {
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
