//! The animation: the scene camera's eye turned about +y around its look-at point, 5°
//! a frame. Compiled by this firmware and by the lab's host test
//! (`lab/tests/lab/board_examples.rs`), which checks that the frames of this orbit, drawn
//! as the firmware draws them, are the library's whole render.

use embedded_graphics::geometry::Size;
use embedded_raytracer::{Camera, CameraError, CameraParams, Vec3};

/// The orbit's step per frame (5°).
pub const STEP: f32 = 5.0 * (core::f32::consts::PI / 180.0);

/// The camera of `params` with its eye turned by `angle` (radians) about +y around the
/// look-at point, at `size` (the panel's).
pub fn orbit(params: &CameraParams, angle: f32, size: Size) -> Result<Camera, CameraError> {
    let offset = params.eye - params.look_at;
    let (s, c) = (libm::sinf(angle), libm::cosf(angle));
    let turned = Vec3::new(c * offset.x + s * offset.z, offset.y, c * offset.z - s * offset.x);
    Camera::new(
        params.look_at + turned,
        params.look_at,
        params.up,
        params.fov_y,
        size,
    )
}

/// The next frame's angle, from 0 around the circle and back.
pub fn next_angle(angle: f32) -> f32 {
    (angle + STEP) % (2.0 * core::f32::consts::PI)
}
