//! The per-frame constants of the features path's spheres, planes and lights.
//!
//! Each sphere's shading constants ([`LitSphere`], beside the geometry
//! `trace/frame.rs` builds for every path), each plane's ([`FramePlane`]) and each
//! light's ([`FrameLight`]), all in the frame's eye-relative, scaled units
//! ([`Scale`]).

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
    /// Eye-relative, scaled position.
    Point { p: Vec3, intensity: f32 },
}

impl FrameLight {
    /// The light's constants; `None` for a directional light without a direction.
    pub(super) fn new(light: &Light, eye: Vec3, scale: Scale) -> Option<Self> {
        Some(match *light {
            Light::Directional { direction, intensity } => FrameLight::Directional {
                l: -direction.try_normalize()?,
                intensity,
            },
            Light::Point { position, intensity } => FrameLight::Point {
                p: (position - eye) * scale.0,
                intensity,
            },
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
