//! The cone of the image's primary rays ([`ViewCone`]): a sphere outside it is met by
//! no ray of the frame.

use crate::camera::Camera;
use crate::math::vec3::Vec3;

/// The cone around the camera's axis `w` that holds every primary ray through a pixel
/// centre.
///
/// Its half-angle `β` is the angle to the farthest pixel centre: a sphere whose
/// enlarged angular radius `α` plus `β` is less than the angle `θ` between its centre
/// and the centre ray is met by no primary ray. Built once per frame, and only for a
/// frame that leaves spheres out for its scale (`trace/frame.rs`).
///
/// In `f32`, with every bound loose enough for its rounding: `sin α` is taken as
/// `(r/|l|)·(1 + 2⁻¹⁰) + 2⁻⁸ + 2.002·step_err` (above either test margin's enlargement
/// and the stepping's, see [`Silhouette::new`](super::span::Silhouette::new)), and the
/// cosines compared with a slack of `10⁻⁵` (`α + β < π`, where the cosine decreases:
/// `θ > α + β ⇔ cos θ < cos α·cos β − sin α·sin β`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct ViewCone {
    /// The camera's unit axis `w`.
    axis: Vec3,
    cos_b: f32,
    sin_b: f32,
    /// The angular enlargement `2⁻⁸ + 2.002·step_err`.
    widen: f32,
}

impl ViewCone {
    /// The camera's cone: around `w`, through the pixel centre farthest from it, at
    /// `((W − 1)/2, (H − 1)/2)` pixels on the image plane at distance `F·w` (`F` the
    /// first pixel's direction).
    ///
    /// `None` where that is not a positive distance.
    pub(crate) fn new(camera: &Camera, step_err: f32) -> Option<Self> {
        let size = camera.size();
        let axis = camera.w();
        let d = camera.first_direction().dot(axis);
        let x = (size.width.max(1) - 1) as f32 * 0.5 * camera.pixel_width();
        let y = (size.height.max(1) - 1) as f32 * 0.5 * camera.pixel_height();
        let tan_b = crate::math::sqrt_exact(x * x + y * y) / d;
        if !(d > 0.0 && tan_b.is_finite()) {
            return None;
        }
        let cos_b = 1.0 / crate::math::sqrt_exact(1.0 + tan_b * tan_b);
        Some(Self {
            axis,
            cos_b,
            sin_b: tan_b * cos_b,
            widen: 1.0 / 256.0 + 2.002 * step_err,
        })
    }

    /// Whether no primary ray meets the sphere `l = centre − eye`, radius `radius`.
    pub(crate) fn misses(&self, l: Vec3, radius: f32) -> bool {
        // Scaled to its largest coordinate first: no square overflows at 10³⁸.
        let m = l.max_abs();
        if !(m > 0.0 && m.is_finite()) {
            return false;
        }
        let Some(dir) = (l * (1.0 / m)).try_normalize() else {
            return false;
        };
        let len = (l * (1.0 / m)).dot(l * (1.0 / m));
        let sin_a = radius / m / crate::math::sqrt_exact(len) * (1.0 + 1.0 / 1024.0) + self.widen;
        if !(sin_a < 1.0) {
            return false;
        }
        let cos_a = crate::math::sqrt_exact(1.0 - sin_a * sin_a);
        self.axis.dot(dir) < cos_a * self.cos_b - sin_a * self.sin_b - 1e-5
    }
}
