//! Surface materials: how a sphere or plane answers light (specular highlight) and
//! mirrors (reflection).
//!
//! Only scenes with lights read `specular` and `shininess`; only
//! scene types with a reflection depth (`Scene<N, L, P, D>`, `D ≥ 1`) read `reflect`.

use crate::error::MaterialError;

/// A surface's response to lights and mirrors.
///
/// ```
/// use embedded_raytracer::Material;
///
/// static CHROME: Material = match Material::new(0.8, 64.0, 0.6).check() {
///     Ok(m) => m,
///     Err(_) => panic!("invalid material"),
/// };
/// assert_eq!(Material::DEFAULT.shininess, 32.0);
/// assert!(Material::new(1.5, 32.0, 0.0).check().is_err()); // specular > 1
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// Weight of the specular highlight, `0 … 1` (default 0: matte).
    pub specular: f32,
    /// Phong exponent of the highlight (`max(0, n·h)^shininess`), `≥ 1` (default 32).
    pub shininess: f32,
    /// Mirror weight, `0 … 1` (default 0): the final colour is
    /// `(1 − reflect)·local + reflect·(what the reflected ray sees)`.
    pub reflect: f32,
}

impl Material {
    /// Matte, not a mirror: specular 0, shininess 32, reflect 0.
    pub const DEFAULT: Material = Material::new(0.0, 32.0, 0.0);

    /// A material, unchecked (see [`Material::check`]).
    #[must_use]
    pub const fn new(specular: f32, shininess: f32, reflect: f32) -> Self {
        Self {
            specular,
            shininess,
            reflect,
        }
    }

    /// The material if every field is in range: `specular` and `reflect` in `[0, 1]`,
    /// `shininess` finite and `≥ 1`.
    ///
    /// NaN is out of every range.
    pub const fn check(self) -> Result<Self, MaterialError> {
        if !(self.specular >= 0.0 && self.specular <= 1.0) {
            return Err(MaterialError::Specular);
        }
        if !(self.shininess >= 1.0 && self.shininess <= f32::MAX) {
            return Err(MaterialError::Shininess);
        }
        if !(self.reflect >= 0.0 && self.reflect <= 1.0) {
            return Err(MaterialError::Reflect);
        }
        Ok(self)
    }
}

impl Default for Material {
    fn default() -> Self {
        Material::DEFAULT
    }
}
