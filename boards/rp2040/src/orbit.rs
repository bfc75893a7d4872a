//! The RP2040 firmware's camera: the lab camera's eye orbiting the look-at point about
//! +y, one step a frame, every frame traced by the integer kernel alone
//! (`Render::draw_band_integer`).
//!
//! Shared with `#[path]` by the firmware (`boards/rp2040/src/main.rs`) and the host test
//! `lab/tests/lab/rp2040_split.rs`, which checks that the kernel's per-frame rule takes every
//! frame of the orbit, the whole cycle of `f32` angles from 0 back to 0 (so no band of
//! it is refused and left black).

use embedded_graphics::geometry::Size;
use embedded_raytracer::{Camera, Vec3};

use crate::scenes;

/// The orbit's step per frame (5°).
pub const STEP: f32 = 5.0 * (core::f32::consts::PI / 180.0);

/// The camera of the frame at orbit angle `angle` (radians) at `size`: the lab camera's
/// eye turned about +y around the look-at point. `None` if the kernel rejects it.
pub fn camera_at(angle: f32, size: Size) -> Option<Camera> {
    let lab = scenes::LAB_CAMERA;
    let offset = lab.eye - lab.look_at;
    let (s, c) = (libm::sinf(angle), libm::cosf(angle));
    let eye = lab.look_at + Vec3::new(c * offset.x + s * offset.z, offset.y, c * offset.z - s * offset.x);
    Camera::new(eye, lab.look_at, lab.up, lab.fov_y, size).ok()
}

/// The next frame's orbit angle; both cores step it with this function from 0.
pub fn next_angle(angle: f32) -> f32 {
    (angle + STEP) % (2.0 * core::f32::consts::PI)
}
