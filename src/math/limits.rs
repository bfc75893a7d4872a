//! The numeric limits the constructors enforce (the camera's), in one place that both
//! the validation (`camera/mod.rs`) and the error messages (`error.rs`) read.

use crate::math::{EDGE_TOLERANCE, UNIT_ROUNDOFF};

/// Largest field of view accepted, in radians (179°).
///
/// Beyond it `tan(fov/2)` exceeds 114: the centre pixel of a 320-pixel image would
/// subtend ~40° and the picture is a few smeared pixels around a tiny centre.
pub const MAX_FOV: f32 = 179.0 * core::f32::consts::PI / 180.0;

/// Smallest pixel step on the image plane (2⁻²⁰ ≈ 9.5e-7, with D = 1).
///
/// A ray direction component of magnitude below 1 rounds by at most 2⁻²⁴; at this
/// pixel size that is ≤ 1/16 px per rounding. Narrower fields of view (for the
/// resolution) are refused with [`CameraError::FovTooNarrow`](crate::CameraError::FovTooNarrow). The bound is per
/// rounding: `Stepping::Incremental` accumulates one per pixel along a row, and at this
/// limit, wide and with an oblique camera, drifts by many pixels where `Direct` stays
/// within a fraction of one (`docs/accuracy.md` measures both), so use `Direct` (the
/// default) for narrow views.
pub const MIN_PIXEL_SIZE: f32 = UNIT_ROUNDOFF / EDGE_TOLERANCE;

/// Smallest angle between `up` and the view direction, in radians (as `|ŵ × ûp|`).
///
/// `u = normalize(w × up)` carries an absolute rounding error of ~1e-7 per component
/// of the cross product, so its direction (the roll of the image) is uncertain by about
/// `1.2e-7 / sin(angle)` rad: ≤ 1.2e-4 rad here, under 0.15 px at the edge of a
/// 1920-pixel image. Closer angles are refused with [`CameraError::UpParallelToView`](crate::CameraError::UpParallelToView).
pub const MIN_UP_ANGLE: f32 = 1e-3;

/// Largest width or height, in pixels (the largest the accuracy tests verify).
pub const MAX_RESOLUTION: u32 = 8192;
