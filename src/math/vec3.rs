//! A minimal `f32` 3-vector: exactly the operations the kernel uses, nothing more.

use core::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

/// A 3-vector of `f32` (a point or a direction in world space; right-handed).
///
/// Plain `Copy` data with `const fn` constructors, so scenes can live in flash.
/// Arithmetic is IEEE-754 single precision with no fused multiply-add, so the same
/// inputs give bit-identical results on the host and on a Cortex-M4F.
///
/// ```
/// use embedded_raytracer::Vec3;
/// let x = Vec3::new(1.0, 0.0, 0.0);
/// let y = Vec3::new(0.0, 1.0, 0.0);
/// assert_eq!(x.cross(y), Vec3::new(0.0, 0.0, 1.0)); // right-handed
/// assert_eq!((x + y).dot(x), 1.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Vec3 {
    /// x component.
    pub x: f32,
    /// y component.
    pub y: f32,
    /// z component.
    pub z: f32,
}

impl Vec3 {
    /// The zero vector.
    pub const ZERO: Vec3 = Vec3::new(0.0, 0.0, 0.0);

    /// A vector from its components.
    #[must_use]
    pub const fn new(x: f32, y: f32, z: f32) -> Self {
        Self { x, y, z }
    }

    /// Dot product.
    #[must_use]
    #[inline(always)]
    pub fn dot(self, o: Vec3) -> f32 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// Dot product in `f64`: each product exact ([`mul_f32_exact`]), summed left to
    /// right — the bits of `f64::from(x)·f64::from(o.x) + …`, cheaper where `f64` is
    /// software.
    ///
    /// [`mul_f32_exact`]: crate::math::wide::mul_f32_exact
    #[inline(always)]
    pub(crate) fn dot_f64(self, o: Vec3) -> f64 {
        use crate::math::wide::mul_f32_exact;
        mul_f32_exact(self.x, o.x) + mul_f32_exact(self.y, o.y) + mul_f32_exact(self.z, o.z)
    }

    /// Cross product (right-handed: `x × y = z`).
    #[must_use]
    #[inline(always)]
    pub fn cross(self, o: Vec3) -> Vec3 {
        Vec3::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }

    /// `self · self`.
    #[must_use]
    #[inline(always)]
    pub fn length_squared(self) -> f32 {
        self.dot(self)
    }

    /// Euclidean length, with the correctly rounded square root.
    #[must_use]
    pub fn length(self) -> f32 {
        crate::math::sqrt_exact(self.length_squared())
    }

    /// `true` if every component is finite (not NaN, not ±∞).
    #[must_use]
    pub const fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.z.is_finite()
    }

    /// The unit vector in the direction of `self`, or `None` when `self` is zero or not
    /// finite (so no NaN or ∞ can come out).
    ///
    /// The vector is first scaled by a power of two that brings its largest component
    /// near 1, so no magnitude `f32` holds, subnormal ones included, makes its squared
    /// length overflow or go subnormal. Scaling by a power of two is exact, so the
    /// result is bit for bit what `self / |self|` gives wherever that is representable.
    ///
    /// Not inlined: a camera calls it four times, once per frame at most; one copy
    /// keeps firmware flash small.
    #[must_use]
    #[inline(never)]
    pub fn try_normalize(self) -> Option<Vec3> {
        let m = self.max_abs();
        if !(m.is_finite() && m > 0.0 && self.is_finite()) {
            return None;
        }
        // m = 2^e · 1.f with e in −126 … 127 (−127: subnormal, m ≥ 2⁻¹⁴⁹): scale by
        // 2^−e, which is a normal f32 but for e = 127 (then 2^−126 · ½).
        let e = ((m.to_bits() >> 23) & 0xff) as i32 - 127;
        let v = self * f32::from_bits(((127 - e.min(126)) as u32) << 23);
        let v = if e > 126 { v * 0.5 } else { v };
        let len = v.length();
        (len.is_finite() && len > 0.0).then(|| v * (1.0 / len))
    }

    /// The largest absolute component; NaN components are passed over (comparisons,
    /// not `f32::max`, which is a libm call on a Cortex-M4).
    #[inline]
    pub(crate) fn max_abs(self) -> f32 {
        let mut m = self.x.abs();
        for c in [self.y.abs(), self.z.abs()] {
            if c > m {
                m = c;
            }
        }
        m
    }
}

impl Add for Vec3 {
    type Output = Vec3;
    #[inline(always)]
    fn add(self, o: Vec3) -> Vec3 {
        Vec3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl AddAssign for Vec3 {
    #[inline(always)]
    fn add_assign(&mut self, o: Vec3) {
        *self = *self + o;
    }
}

impl Sub for Vec3 {
    type Output = Vec3;
    #[inline(always)]
    fn sub(self, o: Vec3) -> Vec3 {
        Vec3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl SubAssign for Vec3 {
    #[inline(always)]
    fn sub_assign(&mut self, o: Vec3) {
        *self = *self - o;
    }
}

impl Mul<f32> for Vec3 {
    type Output = Vec3;
    #[inline(always)]
    fn mul(self, s: f32) -> Vec3 {
        Vec3::new(self.x * s, self.y * s, self.z * s)
    }
}

impl Neg for Vec3 {
    type Output = Vec3;
    #[inline(always)]
    fn neg(self) -> Vec3 {
        Vec3::new(-self.x, -self.y, -self.z)
    }
}
