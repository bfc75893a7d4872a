//! Lights: directional (the sun) or point.
//!
//! A scene holds up to `L` of them (`Scene<N, L, …>`); with none, shading is the
//! lecture notes' Lab #1 headlight.

use crate::error::LightError;
use crate::math::vec3::Vec3;

/// A light source.
///
/// ```
/// use embedded_raytracer::{Light, Vec3};
///
/// // The sun, shining down and away from the viewer.
/// static SUN: Light = match Light::directional(Vec3::new(-1.0, -2.0, -1.0), 0.8).check() {
///     Ok(l) => l,
///     Err(_) => panic!("invalid light"),
/// };
/// let lamp = Light::point(Vec3::new(2.0, 5.0, 3.0), 1.0).check()?;
/// assert!(Light::directional(Vec3::ZERO, 1.0).check().is_err()); // no direction
/// # Ok::<(), embedded_raytracer::LightError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// Parallel light travelling along `direction` (non-zero; need not be unit length).
    Directional {
        /// The way the light travels.
        direction: Vec3,
        /// Intensity, `≥ 0` (1 is full strength).
        intensity: f32,
    },
    /// Light from a point, without fall-off.
    Point {
        /// Where the light is.
        position: Vec3,
        /// Intensity, `≥ 0`.
        intensity: f32,
    },
}

impl Light {
    /// A directional light, unchecked (see [`Light::check`]).
    #[must_use]
    pub const fn directional(direction: Vec3, intensity: f32) -> Self {
        Light::Directional { direction, intensity }
    }

    /// A point light, unchecked (see [`Light::check`]).
    #[must_use]
    pub const fn point(position: Vec3, intensity: f32) -> Self {
        Light::Point { position, intensity }
    }

    /// The light's intensity.
    #[must_use]
    pub const fn intensity(&self) -> f32 {
        match *self {
            Light::Directional { intensity, .. } | Light::Point { intensity, .. } => intensity,
        }
    }

    /// The light if its numbers are usable: finite, intensity `≥ 0`, a directional
    /// light's direction not zero (any non-zero length normalises: see
    /// [`Vec3::try_normalize`]).
    pub const fn check(self) -> Result<Self, LightError> {
        let intensity = self.intensity();
        if !(intensity >= 0.0 && intensity <= f32::MAX) {
            return Err(LightError::Intensity);
        }
        match self {
            Light::Directional { direction, .. } => {
                if !direction.is_finite() {
                    return Err(LightError::NotFinite);
                }
                let d = direction;
                if d.x == 0.0 && d.y == 0.0 && d.z == 0.0 {
                    return Err(LightError::ZeroDirection);
                }
            }
            Light::Point { position, .. } => {
                if !position.is_finite() {
                    return Err(LightError::NotFinite);
                }
            }
        }
        Ok(self)
    }
}
