//! Shading: the colour of a hit, behind the `Shader` strategy type.
//!
//! This module's model is the lecture notes' Lab #1 (`Lab1`, zero-sized); the features
//! path's (lights, shadow rays, mirrors) is another `Shader` (`lit/consts.rs`'s
//! `LitSphere`), chosen at compile time by the scene's type, so a scene without lights
//! keeps this one's loop.

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};

use crate::math::vec3::Vec3;
use crate::method::intersect::{Scale, SphereGeom};
use crate::scene::sphere::Sphere;

/// A shading model as a strategy type: its per-sphere constants, built by the frame
/// with the geometry.
///
/// The scanline loop is monomorphised over it. How a hit is shaded is the row tracer's
/// (`scanline.rs`'s `Lab1Row`, `lit/row.rs`'s `LitRow`).
pub(crate) trait Shader {
    /// Per-frame, per-object constants (built once per frame with the geometry).
    type Object: Copy;
    /// The constants of `sphere`, whose eye-relative geometry is `g` (lengths scaled by
    /// `scale`); `w` is the camera's view direction.
    fn object(sphere: &Sphere, g: &SphereGeom, scale: Scale, w: Vec3) -> Self::Object;
}

/// The lecture notes' Lab #1 shading ([`lab1`]) as a [`Shader`].
pub(crate) struct Lab1;

/// [`Lab1`]'s per-sphere constants.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Lab1Object {
    /// `L·w`, for the view-space normal.
    lw: f32,
    /// `1/r`.
    inv_r: f32,
    /// The object colour's channels as `f32`.
    rgb: [f32; 3],
}

impl Shader for Lab1 {
    type Object = Lab1Object;

    #[inline(always)]
    fn object(sphere: &Sphere, g: &SphereGeom, scale: Scale, w: Vec3) -> Lab1Object {
        Lab1Object {
            lw: g.l.dot(w),
            inv_r: 1.0 / (sphere.radius * scale.0),
            rgb: channels(sphere.color),
        }
    }
}

impl Lab1 {
    /// The colour of the hit at `t` along the primary ray `eye + t·d`.
    #[inline(always)]
    pub(crate) fn shade(o: &Lab1Object, w: Vec3, d: Vec3, t: f32) -> Rgb888 {
        // The view-space normal n·(−w) = ((L − t·d)·w)/r, camera-relative so |eye|
        // does not cost precision.
        let n_z = (o.lw - t * d.dot(w)) * o.inv_r;
        lab1_channels(o.rgb, n_z)
    }
}

/// Lowest shading factor: surfaces facing away are never darker than 30 %.
pub const AMBIENT: f32 = 0.3;

/// Lab #1 shading: `object_colour × clamp(n_z, 0.3, 1.0)`, each 8-bit channel scaled
/// and rounded to nearest (halves round up).
///
/// `n_z` is the view-space z of the unit outward normal, `n·(−w)`. A NaN factor (a
/// degenerate sphere) shades at the 0.3 floor rather than producing garbage.
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb888;
/// use embedded_raytracer::shade::lab1;
///
/// let c = Rgb888::new(255, 100, 10);
/// assert_eq!(lab1(c, 1.0), c);                      // facing the eye
/// assert_eq!(lab1(c, 0.5), Rgb888::new(128, 50, 5)); // 127.5 → 128, 5.0 → 5
/// assert_eq!(lab1(c, -1.0), lab1(c, 0.3));           // clamped at 0.3
/// ```
#[must_use]
#[inline]
pub fn lab1(color: Rgb888, n_z: f32) -> Rgb888 {
    lab1_channels(channels(color), n_z)
}

/// An object colour's channels as `f32` (exact), converted once per frame so the pixel
/// loop does not convert them per hit.
#[must_use]
#[inline]
pub(crate) fn channels(color: Rgb888) -> [f32; 3] {
    [f32::from(color.r()), f32::from(color.g()), f32::from(color.b())]
}

/// [`lab1`] on pre-converted channels: bit-identical (the u8 → f32 conversion is exact).
#[inline(always)]
fn lab1_channels(c: [f32; 3], n_z: f32) -> Rgb888 {
    let k = lab1_factor(n_z);
    let [r, g, b] = c;
    Rgb888::new(scale(r, k), scale(g, k), scale(b, k))
}

/// Lab #1's factor `clamp(n_z, 0.3, 1)`, shared by the Lab #1 loop and the
/// scene-features path's unlit scenes.
///
/// Clamped with comparisons, not `max`/`min` (on a Cortex-M4 those are calls to libm's
/// `fmaxf`/`fminf`) nor `clamp` (NaN would propagate):
/// a NaN fails both tests and takes the 0.3 floor, exactly as `n_z.max(0.3).min(1.0)`
/// does (tested below).
#[inline(always)]
pub(crate) fn lab1_factor(n_z: f32) -> f32 {
    if n_z > 1.0 {
        1.0
    } else if n_z >= AMBIENT {
        n_z
    } else {
        AMBIENT
    }
}

/// `round(channel × k)` for `k ∈ [0.3, 1]` and a channel in `0 … 255`.
///
/// The sum is in `[0, 255.5]` before the truncating cast, so truncation through `i32`
/// (one instruction) equals the saturating `as u8` and cannot overflow.
#[inline(always)]
fn scale(channel: f32, k: f32) -> u8 {
    (channel * k + 0.5) as i32 as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamps_at_both_ends_and_rounds() {
        let white = Rgb888::new(255, 255, 255);
        assert_eq!(lab1(white, 2.0), white);
        assert_eq!(lab1(white, 1.0), white);
        // 255 × 0.3 = 76.5 → 77 (round half up)
        assert_eq!(lab1(white, 0.3), Rgb888::new(77, 77, 77));
        assert_eq!(lab1(white, 0.0), Rgb888::new(77, 77, 77));
        assert_eq!(lab1(white, -0.7), Rgb888::new(77, 77, 77));
        assert_eq!(lab1(white, f32::NAN), Rgb888::new(77, 77, 77));
        // 10 × 0.45 = 4.5 → 5; 10 × 0.44 = 4.4 → 4
        assert_eq!(lab1(Rgb888::new(10, 0, 1), 0.45), Rgb888::new(5, 0, 0));
        assert_eq!(lab1(Rgb888::new(10, 0, 1), 0.44), Rgb888::new(4, 0, 0));
        // 200 × 0.75 = 150 exactly
        assert_eq!(lab1(Rgb888::new(200, 0, 0), 0.75), Rgb888::new(150, 0, 0));
    }

    /// The comparison clamp is bit-for-bit `n_z.max(0.3).min(1.0)` for every `f32` in
    /// a sweep across its whole range, both zeros, the infinities and NaN.
    #[test]
    fn comparison_clamp_equals_max_min() {
        let c = Rgb888::new(255, 128, 7);
        let check = |n: f32| {
            // The textbook clamp as the oracle (NaN → 0.3 through max/min, unlike clamp).
            #[allow(clippy::manual_clamp)]
            let k = n.max(AMBIENT).min(1.0);
            let expected = Rgb888::new(scale(255.0, k), scale(128.0, k), scale(7.0, k));
            assert_eq!(lab1(c, n), expected, "n_z = {n:e}");
        };
        for special in [
            0.0,
            -0.0,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            AMBIENT,
            1.0,
        ] {
            check(special);
        }
        let mut bits = 0u32;
        while let Some(next) = bits.checked_add(65_537) {
            check(f32::from_bits(bits));
            bits = next;
        }
    }
}
