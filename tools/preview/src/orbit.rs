//! Orbiting the scene file's camera: the user's azimuth, elevation and zoom around the
//! look-at point, turned into camera parameters.

use embedded_graphics::prelude::Size;
use embedded_raytracer::{CameraParams, Vec3};

/// Orbit step per arrow key press.
pub const ORBIT_STEP: f32 = 5.0 * core::f32::consts::PI / 180.0;
/// Elevation stays within ±89° of the plane normal to `up`, well clear of the
/// camera's up-parallel-to-view limit.
const MAX_ELEVATION: f32 = 89.0 * core::f32::consts::PI / 180.0;
/// Distance factor per zoom step.
const ZOOM: f32 = 1.1;

/// The user's orbit relative to the scene file's camera. All zero = the file's camera,
/// bit for bit.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Orbit {
    pub azimuth: f32,
    pub elevation: f32,
    pub zoom_steps: i32,
}

/// The orbit's frame around the look-at point: `k` = up, `e1` toward the file's eye
/// in the plane normal to `k`, `e2 = k × e1`; the file eye's elevation and distance.
struct OrbitFrame {
    k: Vec3,
    e1: Vec3,
    e2: Vec3,
    elevation: f32,
    distance: f32,
}

impl OrbitFrame {
    fn new(base: &CameraParams) -> Option<Self> {
        let offset = base.eye - base.look_at;
        let distance = offset.length();
        let k = base.up.try_normalize()?;
        let along = offset.dot(k);
        let horizontal = offset - k * along;
        // Looking straight along `up` cannot happen (the camera refuses it), but pick a
        // perpendicular anyway rather than fail.
        let e1 = horizontal
            .try_normalize()
            .or_else(|| k.cross(Vec3::new(1.0, 0.0, 0.0)).try_normalize())
            .or_else(|| k.cross(Vec3::new(0.0, 0.0, 1.0)).try_normalize())?;
        let e2 = k.cross(e1);
        Some(Self {
            k,
            e1,
            e2,
            elevation: along.atan2(horizontal.length()),
            distance,
        })
    }
}

impl Orbit {
    /// The camera parameters for this orbit of `base`, at the display's `size`.
    pub fn params(&self, base: &CameraParams, size: Size) -> CameraParams {
        let mut params = CameraParams { size, ..*base };
        if *self == Orbit::default() {
            return params; // the file's camera exactly: comparable with the render CLI
        }
        let Some(f) = OrbitFrame::new(base) else {
            return params;
        };
        let el = (f.elevation + self.elevation).clamp(-MAX_ELEVATION, MAX_ELEVATION);
        let dist = f.distance * ZOOM.powi(self.zoom_steps);
        let (sa, ca) = self.azimuth.sin_cos();
        let (se, ce) = el.sin_cos();
        params.eye = base.look_at + (f.e1 * ca + f.e2 * sa) * (dist * ce) + f.k * (dist * se);
        params
    }

    /// Adds `delta` to the elevation, keeping the total within ±`MAX_ELEVATION`.
    pub fn tilt(&mut self, base: &CameraParams, delta: f32) {
        let el0 = OrbitFrame::new(base).map_or(0.0, |f| f.elevation);
        self.elevation = (el0 + self.elevation + delta).clamp(-MAX_ELEVATION, MAX_ELEVATION) - el0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_orbit_is_the_files_camera_and_a_full_turn_comes_back() {
        let base = CameraParams::new(
            Vec3::new(0.0, 1.0, 5.0),
            Vec3::ZERO,
            Vec3::new(0.0, 1.0, 0.0),
            1.0,
            Size::new(32, 24),
        );
        assert_eq!(Orbit::default().params(&base, base.size), base);
        let turned = Orbit {
            azimuth: 2.0 * core::f32::consts::PI,
            ..Orbit::default()
        }
        .params(&base, base.size);
        assert!((turned.eye - base.eye).length() < 1e-5);
        // A quarter turn keeps the distance and the height above the look-at plane.
        let q = Orbit {
            azimuth: core::f32::consts::FRAC_PI_2,
            ..Orbit::default()
        }
        .params(&base, base.size);
        assert!(((q.eye - q.look_at).length() - (base.eye - base.look_at).length()).abs() < 1e-5);
        assert!((q.eye.y - base.eye.y).abs() < 1e-5);
        assert!(q.eye.z.abs() < 1e-5);
    }

    #[test]
    fn tilt_is_clamped_short_of_up() {
        let base = CameraParams::new(
            Vec3::new(0.0, 0.0, 5.0),
            Vec3::ZERO,
            Vec3::new(0.0, 1.0, 0.0),
            1.0,
            Size::new(32, 24),
        );
        let mut o = Orbit::default();
        o.tilt(&base, 10.0);
        assert!((o.elevation - MAX_ELEVATION).abs() < 1e-6);
        assert!(o.params(&base, base.size).build().is_ok());
    }
}
