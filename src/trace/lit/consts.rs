//! The per-frame constants of the features path's spheres, planes and lights.
//!
//! Each sphere's shading constants ([`LitSphere`], beside the geometry
//! `trace/frame.rs` builds for every path), each plane's ([`FramePlane`]) and each
//! light's ([`FrameLight`]), and the floor's as its pixels' shading reads them
//! ([`Floor`]), all in the frame's eye-relative, scaled units ([`Scale`]).

use crate::math::vec3::Vec3;
use crate::method::intersect::{Scale, SphereGeom};
use crate::scene::light::Light;
use crate::scene::material::Material;
use crate::scene::plane::Plane;
use crate::scene::sphere::Sphere;
use crate::trace::shade::{channels, Shader};

/// The per-sphere shading constants of the scene-features path.
pub(crate) struct LitSphere;

/// [`LitSphere`]'s constants.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LitObject {
    /// The colour's channels as `f32`.
    pub(super) rgb: [f32; 3],
    /// `1/r` in scaled units.
    pub(super) inv_r: f32,
    pub(super) material: Material,
}

impl Shader for LitSphere {
    type Object = LitObject;

    #[inline(always)]
    fn object(sphere: &Sphere, _g: &SphereGeom, scale: Scale, _w: Vec3) -> LitObject {
        LitObject {
            rgb: channels(sphere.color),
            inv_r: 1.0 / (sphere.radius * scale.0),
            material: sphere.material,
        }
    }
}

/// A plane as the frame sees it.
#[derive(Clone, Copy, Debug)]
pub(super) struct FramePlane {
    /// The plane's anchor relative to the eye ([`Plane::anchor`]), scaled.
    pub(super) q: Vec3,
    /// The unit normal, as given (not turned).
    pub(super) n: Vec3,
    /// `q·n`: the eye's signed distance, negated; a ray hits where `d·n` has its sign.
    pub(super) s: f32,
    rgb: [f32; 3],
    /// The odd cells' colour; `None`: not checkered.
    pub(super) checker: Option<[f32; 3]>,
    /// The checker basis `e₁`, `e₂` and `1/size` (scaled).
    e1: Vec3,
    e2: Vec3,
    pub(super) inv_size: f32,
    pub(super) material: Material,
}

impl FramePlane {
    /// A plane no ray meets (`s = 0` and a zero normal: every `t` it gives is NaN or
    /// not positive).
    ///
    /// What an unusable plane of an unchecked scene becomes, so the other planes keep
    /// their object numbers.
    pub(super) const NEVER: FramePlane = FramePlane {
        q: Vec3::ZERO,
        n: Vec3::ZERO,
        s: 0.0,
        rgb: [0.0; 3],
        checker: None,
        e1: Vec3::ZERO,
        e2: Vec3::ZERO,
        inv_size: 0.0,
        material: Material::DEFAULT,
    };

    /// The plane's constants; `None` for a zero or non-finite normal.
    pub(super) fn new(plane: &Plane, eye: Vec3, scale: Scale) -> Option<Self> {
        let (n, e1, e2) = plane.basis()?;
        let q = plane.anchor(eye) * scale.0;
        Some(Self {
            q,
            n,
            s: q.dot(n),
            rgb: channels(plane.color),
            checker: plane.checker.map(channels),
            e1,
            e2,
            inv_size: 1.0 / (plane.checker_size * scale.0),
            material: plane.material,
        })
    }

    /// The ray parameter where `o + t·dir` meets the plane (NaN or ±∞ where the ray is
    /// parallel to it, which every `t > 0 && t < t_max` test rejects).
    #[inline(always)]
    pub(super) fn t_from(&self, o: Vec3, dir: Vec3) -> f32 {
        (self.q - o).dot(self.n) / dir.dot(self.n)
    }

    /// Whether the open segment from `o` to the lamp at `at` crosses the plane: its
    /// equation `h(x) = (x − q)·n` has strictly opposite signs at the two ends.
    ///
    /// A sign decision, no intersection parameter: nothing is divided, and no `t` near
    /// the segment's length is compared with it, so an end however far (a point 10²³
    /// away and a lamp a few units from the plane) is decided as well as a near one.
    /// **Bound:** each `h` is one rounded subtraction per coordinate and a three-term
    /// dot product, within `γ₄·Σ|xᵢ − qᵢ|·|nᵢ| ≤ 4√3·u·|x − q|` of its exact value for
    /// the `f32` end `x` (`u` = [`UNIT_ROUNDOFF`], to first order): the answer is the
    /// exact one for the `f32` ends unless an end lies within that distance of the
    /// plane, where the reference's band leaves the shadow undecided too. An end on the
    /// plane (`h = 0`) does not cross: the segment is open.
    ///
    /// [`UNIT_ROUNDOFF`]: crate::math::UNIT_ROUNDOFF
    #[inline(always)]
    pub(super) fn separates(&self, o: Vec3, at: Vec3) -> bool {
        let (h, side) = (self.height(o), self.height(at));
        (h < 0.0 && side > 0.0) || (h > 0.0 && side < 0.0)
    }

    /// The plane's equation at `x` (eye-relative, scaled): `(x − q)·n`, whose sign says
    /// the side (positive along the normal), with [`Self::separates`]' rounding.
    #[inline(always)]
    pub(super) fn height(&self, x: Vec3) -> f32 {
        (x - self.q).dot(self.n)
    }

    /// The colour at `p` (eye-relative, scaled): the checker cell's.
    #[inline(always)]
    pub(super) fn color_at(&self, p: Vec3) -> [f32; 3] {
        match self.checker {
            None => self.rgb,
            Some(odd) => {
                let x = p - self.q;
                let cell =
                    floor(x.dot(self.e1) * self.inv_size).wrapping_add(floor(x.dot(self.e2) * self.inv_size));
                if cell & 1 == 0 {
                    self.rgb
                } else {
                    odd
                }
            }
        }
    }
}

/// `floor(x)` as an `i32` (saturating at `±2³¹`, NaN → 0): only its parity is used.
///
/// `i32`, not `i64`: on a Cortex-M the `f32 → i32` conversion is one instruction and
/// the `i64` one a library call. Beyond `2³¹` cells from the plane's point every cell
/// is far smaller than a pixel (the checker is aliasing noise there, for the reference
/// too), so the saturated parity costs nothing visible.
#[inline(always)]
fn floor(x: f32) -> i32 {
    let t = x as i32;
    if (t as f32) > x {
        t.wrapping_sub(1)
    } else {
        t
    }
}

/// A light as the frame sees it.
#[derive(Clone, Copy, Debug)]
pub(super) enum FrameLight {
    /// Unit vector toward the light.
    Directional { l: Vec3, intensity: f32 },
    /// Eye-relative, scaled position; `far`: the shadow segment's length beyond which
    /// it is tested from the lamp ([`FAR_FACTOR`] times `|p|`, at most the larger of
    /// [`RADII_FACTOR`] times the smallest radius and `2·|p|`).
    Point { p: Vec3, intensity: f32, far: f32 },
}

/// How many times the lamp's distance from the eye a shadow segment must exceed before
/// it is tested from the lamp's end: `2¹⁰` (a point light's `far`).
///
/// A segment longer than `2¹⁰·|P|` (`P` the lamp, eye-relative) starts at a surface
/// point `o` more than `2¹⁰ − 1` times farther from the eye than the lamp. Its tests
/// then run on the same open segment from the lamp's end (`LitRow::occluded_exact`):
/// a sphere from `P` toward `o`, where `C − o` would be rounded to `u·|o|` and can
/// lose every sphere near the lamp; a plane by the signs of its equation at the two
/// ends ([`FramePlane::separates`]), where the intersection parameter and the length
/// it is compared with differ below `f32`'s resolution. **Bound:** from the lamp the
/// line is known at a sphere to a few `u·(|P| + |C|)` plus `|C − P|` times the
/// direction's error (a few `u` plus `o`'s own error over the segment's length), never
/// more than a few times the test from `o`'s few `u·(|o| + |C|)` plus `|C − o|` times
/// the same direction error, and `2¹⁰` times less for a sphere near the lamp. Below the
/// limit a segment keeps the tests from `o` and their bits. A directional light has no
/// lamp end and keeps the tests from `o`.
pub(super) const FAR_FACTOR: f32 = 1024.0;

/// How many times the frame's smallest sphere radius a shadow segment must exceed before
/// it is tested from the lamp's end, whatever the lamp's distance from the eye: `2¹⁶`.
///
/// With the eye far from the scene the lamp is far too, and [`FAR_FACTOR`]`·|P|` may
/// exceed every segment: a surface `2⁹·|P|` away would be tested from its own points,
/// whose rounding `u·|o|` exceeds the radii of the spheres near the lamp (false
/// shadows over the whole surface). A segment longer than both `2¹⁶·r` and `2·|P|`
/// starts at a point farther from the eye than the lamp (`|o| ≥ dist − |P| > |P|`),
/// whose rounding is at least `2⁻⁹·r`; from the lamp the line is known to the same
/// bound as above, never more than a few times `o`'s. (Without `2·|P|`, a lamp far
/// from a near scene would be taken as the end, and its own rounding exceeds the
/// radii.) A scene whose lamp lies within `2⁶` smallest radii of the eye keeps
/// [`FAR_FACTOR`]'s limit and its bits.
pub(super) const RADII_FACTOR: f32 = 65_536.0;

impl FrameLight {
    /// The light's constants; `None` for a directional light without a direction.
    /// `smallest`: the frame's smallest sphere radius, scaled (`∞` without spheres),
    /// for the far limit ([`RADII_FACTOR`]).
    pub(super) fn new(light: &Light, eye: Vec3, scale: Scale, smallest: f32) -> Option<Self> {
        Some(match *light {
            Light::Directional { direction, intensity } => FrameLight::Directional {
                l: -direction.try_normalize()?,
                intensity,
            },
            Light::Point { position, intensity } => {
                let p = (position - eye) * scale.0;
                FrameLight::Point {
                    p,
                    intensity,
                    far: {
                        let lamp = p.length();
                        (FAR_FACTOR * lamp).min((RADII_FACTOR * smallest).max(2.0 * lamp))
                    },
                }
            }
        })
    }

    /// The lamp's position (a point light's), for the exact shadow path.
    #[inline(always)]
    pub(super) fn at(&self) -> Vec3 {
        match *self {
            FrameLight::Point { p, .. } => p,
            FrameLight::Directional { .. } => Vec3::ZERO,
        }
    }
}

#[cfg(test)]
mod tests {
    use embedded_graphics::pixelcolor::{Rgb888, RgbColor};

    use super::{FrameLight, FramePlane};
    use crate::math::sqrt_exact;
    use crate::math::vec3::Vec3;
    use crate::method::intersect::Scale;
    use crate::scene::light::Light;
    use crate::scene::plane::Plane;

    /// A floor `y = 0`, a lamp 4.5 above it and surface points 10²²…10²³ away above the
    /// lamp, in a frame scaled by `2⁻²⁹` (as a frame holding them is): the signs never
    /// let the floor block, where the intersection parameter `t = (q − o)·n/(l·n)`
    /// against the segment's length `t < dist` — two numbers whose difference is `4.5/y`
    /// of them, far below `f32`'s resolution — blocks about one in seven.
    #[test]
    fn a_far_point_above_a_near_lamp_is_not_shadowed_by_the_floor() {
        let s = 1.0 / 536_870_912.0; // 2⁻²⁹
        let (eye, scale) = (Vec3::ZERO, Scale(s));
        let plane = Plane::new(Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), Rgb888::WHITE);
        let floor = FramePlane::new(&plane, eye, scale).unwrap();
        let lamp = FrameLight::new(
            &Light::point(Vec3::new(3.0, 4.5, 3.5), 1.0),
            eye,
            scale,
            f32::INFINITY,
        )
        .unwrap();
        let mut by_t = 0;
        for k in 0..1000 {
            let f = k as f32 / 1000.0;
            let o = Vec3::new(1e22 * (f - 0.5), 1e22 + 9e22 * f, -4e23 - 1e23 * f) * s;
            assert!(!floor.separates(o, lamp.at()), "{o:?}");
            let to = lamp.at() - o;
            let dist = sqrt_exact(to.dot(to));
            let t = floor.t_from(o, to * (1.0 / dist));
            by_t += usize::from(t > 0.0 && t < dist);
        }
        assert!(by_t > 50, "{by_t}");
    }

    /// The signs do block where the segment crosses: a point below the floor under the
    /// lamp, near and far.
    #[test]
    fn a_point_below_the_floor_is_shadowed_by_it() {
        let plane = Plane::new(Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), Rgb888::WHITE);
        let floor = FramePlane::new(&plane, Vec3::ZERO, Scale(1.0)).unwrap();
        let at = Vec3::new(3.0, 4.5, 3.5);
        for o in [Vec3::new(0.0, -1.0, 0.0), Vec3::new(1e20, -1e19, -1e20)] {
            assert!(floor.separates(o, at), "{o:?}");
        }
        // An end on the plane does not cross: the segment is open.
        assert!(!floor.separates(Vec3::new(5.0, 0.0, 1.0), at));
    }
}

/// A light as a floor pixel's shading reads it.
#[derive(Clone, Copy, Debug)]
pub(super) enum FloorLight {
    /// A directional light the floor's turned normal faces away from (`n·l ≤ 0` or
    /// NaN): it lights no floor pixel and casts no shadow ray from one.
    Dark,
    /// A directional light in front of the floor: its unit vector `l` and its diffuse
    /// term `intensity·(n·l)`, the product every lit floor pixel adds; `exact`: its
    /// shadow rays need the frame's ties ([`Ties::exact_mask`]).
    ///
    /// [`Ties::exact_mask`]: crate::trace::lit::ties::Ties::exact_mask
    Sun { l: Vec3, term: f32, exact: bool },
    /// A point light, as [`FrameLight::Point`]; `exact` as for a sun.
    Lamp {
        p: Vec3,
        intensity: f32,
        far: f32,
        exact: bool,
    },
}

/// The floor's per-frame shading constants: its normal turned toward the eye, and its
/// lights.
///
/// Built only in a scene type without reflections, for a floor whose pixels the
/// general shading colours by their local colour alone (no highlight: `specular` not
/// above 0), in a frame with lights.
pub(super) struct Floor<const L: usize> {
    /// The normal turned toward the eye, as the general shading turns it for a primary
    /// ray: by the sign of the plane's `s = (q − eye)·n`.
    pub(super) n: Vec3,
    /// The frame's lights in the scene's order, then [`FloorLight::Dark`] up to the
    /// capacity: a loop of a constant length, which the compiler unrolls.
    pub(super) lights: [FloorLight; L],
}

impl<const L: usize> Floor<L> {
    /// The floor's constants, or `None` where its pixels need the general shading (a
    /// highlight, no light); `exact_mask`: the frame's
    /// [`Ties::exact_mask`].
    ///
    /// [`Ties::exact_mask`]: crate::trace::lit::ties::Ties::exact_mask
    pub(super) fn new(plane: &FramePlane, lights: &[FrameLight], exact_mask: u32) -> Option<Self> {
        let m = plane.material;
        if lights.is_empty() || m.specular > 0.0 {
            return None;
        }
        // The primary ray's turned normal (`LitRow::surface`, `primary`).
        let n = if plane.s > 0.0 { -plane.n } else { plane.n };
        let mut out = [FloorLight::Dark; L];
        for ((k, light), slot) in lights.iter().enumerate().zip(&mut out) {
            let exact = exact_mask & (1 << k.min(31)) != 0;
            let fl = match *light {
                FrameLight::Directional { l, intensity } => {
                    let nl = n.dot(l);
                    if nl > 0.0 {
                        FloorLight::Sun {
                            l,
                            term: intensity * nl,
                            exact,
                        }
                    } else {
                        FloorLight::Dark
                    }
                }
                FrameLight::Point { p, intensity, far } => FloorLight::Lamp {
                    p,
                    intensity,
                    far,
                    exact,
                },
            };
            *slot = fl;
        }
        Some(Self { n, lights: out })
    }
}
