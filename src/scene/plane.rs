//! The infinite plane primitive, optionally checkered: a floor for spheres to stand
//! on and cast shadows onto.
//!
//! A scene holds up to `P` of them (`Scene<N, L, P>`).

use embedded_graphics::pixelcolor::Rgb888;

use crate::error::PlaneError;
use crate::math::vec3::Vec3;
use crate::scene::material::Material;

/// An infinite plane through `point` with normal `normal` (non-zero, any length).
///
/// Any point of the plane will do, however far from the eye: a frame anchors the plane at
/// its point nearest the eye (the checker moved by whole pairs of cells), so only the
/// plane's distance from the eye enters the frame's range of sizes.
///
/// With a checker colour the plane is tiled in squares of side `checker_size`: in plane
/// coordinates `x₁ = (p − point)·e₁`, `x₂ = (p − point)·e₂` (with `n` the unit normal,
/// `a` the world axis along which `n` has its smallest absolute component — ties x
/// before y before z —, `e₁ = normalize(n × a)`, `e₂ = n × e₁`) a cell shows `color`
/// where `floor(x₁/size) + floor(x₂/size)` is even and the checker colour elsewhere.
///
/// A checker finer than `f32` resolves is not filtered: where `x/size` is beyond `±2³¹`
/// (say `checker_size = 1e-30`, or a cell of 1 far out on the plane) both cell indices
/// saturate to the same odd number (`i32::MAX`: a positive `x/size` converts to it, a
/// negative one to `i32::MIN`, and `floor` steps that down, wrapping to `i32::MAX`), so
/// their sum is even and the plane shows its `color` alone — one solid colour, not
/// noise; only on an axis, where an index is exactly 0, is the sum odd. Tested by
/// `tests/api/lit.rs`, `a_checker_finer_than_f32_resolves_draws_the_planes_colour`.
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb888;
/// use embedded_raytracer::{Plane, Vec3};
///
/// static FLOOR: Plane = match Plane::new(Vec3::new(0.0, -1.0, 0.0), Vec3::new(0.0, 1.0, 0.0), Rgb888::new(220, 220, 220))
///     .with_checker(Rgb888::new(40, 40, 40), 1.0)
///     .check()
/// {
///     Ok(p) => p,
///     Err(_) => panic!("invalid plane"),
/// };
/// assert!(Plane::new(Vec3::ZERO, Vec3::ZERO, Rgb888::new(0, 0, 0)).check().is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// A point on the plane.
    pub point: Vec3,
    /// The normal (non-zero; its length does not matter).
    pub normal: Vec3,
    /// The colour (of the even checker cells, if checkered).
    pub color: Rgb888,
    /// The odd cells' colour, if checkered.
    pub checker: Option<Rgb888>,
    /// The side of a checker cell, `> 0` (default 1).
    pub checker_size: f32,
    /// Highlight and mirror response.
    pub material: Material,
}

impl Plane {
    /// A plain plane, unchecked (see [`Plane::check`]).
    #[must_use]
    pub const fn new(point: Vec3, normal: Vec3, color: Rgb888) -> Self {
        Self {
            point,
            normal,
            color,
            checker: None,
            checker_size: 1.0,
            material: Material::DEFAULT,
        }
    }

    /// The same plane checkered with `second` in cells of side `size`.
    #[must_use]
    pub const fn with_checker(mut self, second: Rgb888, size: f32) -> Self {
        self.checker = Some(second);
        self.checker_size = size;
        self
    }

    /// The same plane with another material.
    #[must_use]
    pub const fn with_material(mut self, material: Material) -> Self {
        self.material = material;
        self
    }

    /// The unit normal `n` and the checker basis `e₁`, `e₂` (see [`Plane`]); `None`
    /// for a zero or non-finite normal.
    pub(crate) fn basis(&self) -> Option<(Vec3, Vec3, Vec3)> {
        let n = self.normal.try_normalize()?;
        // The world axis along which n is smallest (ties x, y, z).
        let (ax, ay, az) = (n.x.abs(), n.y.abs(), n.z.abs());
        let axis = if ax <= ay && ax <= az {
            Vec3::new(1.0, 0.0, 0.0)
        } else if ay <= az {
            Vec3::new(0.0, 1.0, 0.0)
        } else {
            Vec3::new(0.0, 0.0, 1.0)
        };
        let e1 = n.cross(axis).try_normalize()?;
        Some((n, e1, n.cross(e1)))
    }

    /// The plane's point as a frame anchors it, relative to `eye`.
    ///
    /// That is `point − eye`, or, where that is more than 2¹⁰ times the plane's distance
    /// from the eye plus two checker cells, the plane's point nearest the eye moved along
    /// `e₁` and `e₂` by the given point's offsets modulo two cells. The same plane and
    /// the same cells (a shift by whole pairs of cells keeps every cell's parity), but no
    /// product of the frame's plane test cancels: with the point far along the plane, `(q − o)·n` in
    /// `f32` would lose the plane's position to rounding of `|q|` (a point 10⁸ away on
    /// a tilted plane misplaces it by units). Once per frame, in `f64`, where each
    /// product of two `f32` values is exact.
    pub(crate) fn anchor(&self, eye: Vec3) -> Vec3 {
        let q = self.point - eye;
        let Some((n, e1, e2)) = self.basis() else {
            return q;
        };
        let v = |a: Vec3| [f64::from(a.x), f64::from(a.y), f64::from(a.z)];
        let dot = |[a0, a1, a2]: [f64; 3], [b0, b1, b2]: [f64; 3]| a0 * b0 + a1 * b1 + a2 * b2;
        let ([p0, p1, p2], [x0, x1, x2]) = (v(self.point), v(eye));
        let q64 = [p0 - x0, p1 - x1, p2 - x2];
        let s = dot(q64, v(n));
        let period = 2.0 * f64::from(self.checker_size);
        let reach = s.abs() + if self.checker.is_some() { period } else { 0.0 };
        if !(f64::from(q.max_abs()) > 1024.0 * reach) {
            return q;
        }
        // The offsets less whole periods: `a − period·⌊a/period⌋` (libm's `fmod` has
        // panicking branches, which `no_std` firmware must not link); off from the
        // exact remainder by the `f64` rounding of `a`, far inside a cell wherever
        // `|a|` is less than 2⁴⁰ cells.
        let reduce = |a: f64| {
            if self.checker.is_some() {
                a - period * libm::floor(a / period)
            } else {
                0.0
            }
        };
        let (r1, r2) = (reduce(dot(q64, v(e1))), reduce(dot(q64, v(e2))));
        let at =
            |n: f32, e1: f32, e2: f32| (f64::from(n) * s + f64::from(e1) * r1 + f64::from(e2) * r2) as f32;
        let anchored = Vec3::new(at(n.x, e1.x, e2.x), at(n.y, e1.y, e2.y), at(n.z, e1.z, e2.z));
        if anchored.is_finite() {
            anchored
        } else {
            q
        }
    }

    /// The plane if its numbers are usable: finite point and normal, a normal that is
    /// not zero (any non-zero length normalises: see [`Vec3::try_normalize`]), `checker_size > 0` and finite, and a
    /// valid [`Material`].
    pub const fn check(self) -> Result<Self, PlaneError> {
        if !(self.point.is_finite() && self.normal.is_finite()) {
            return Err(PlaneError::NotFinite);
        }
        let n = self.normal;
        if n.x == 0.0 && n.y == 0.0 && n.z == 0.0 {
            return Err(PlaneError::ZeroNormal);
        }
        if !(self.checker_size > 0.0 && self.checker_size <= f32::MAX) {
            return Err(PlaneError::CheckerSize);
        }
        match self.material.check() {
            Ok(_) => Ok(self),
            Err(e) => Err(PlaneError::Material(e)),
        }
    }
}
