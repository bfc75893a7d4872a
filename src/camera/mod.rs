//! The lecture notes' pin-hole camera: the u/v/w basis, pixel size from the field of view, the
//! upper-left pixel centre and the per-pixel and per-scanline steps.
//!
//! Conventions: right-handed world, angles in radians, image plane one unit in front
//! of the eye (D = 1). Column `i` runs left to right, row `j` top to bottom, both from 0:
//!
//! ```text
//! p(i,j) − eye = w + ((i + ½) − W/2)·pw·u + (H/2 − (j + ½))·ph·v
//! ```

pub(crate) mod cone;
pub(crate) mod int_cut;
pub(crate) mod span;

use embedded_graphics::geometry::Size;

use crate::error::{CameraError, CameraParam};
use crate::math;
use crate::math::vec3::Vec3;

pub use crate::math::limits::{MAX_FOV, MAX_RESOLUTION, MIN_PIXEL_SIZE, MIN_UP_ANGLE};

/// What a camera is built from: plain data, `const`-constructible.
///
/// ```
/// use embedded_graphics::geometry::Size;
/// use embedded_raytracer::{CameraParams, Vec3};
///
/// const PARAMS: CameraParams = CameraParams::new(
///     Vec3::new(0.0, 0.0, 5.0),
///     Vec3::new(0.0, 0.0, 0.0),
///     Vec3::new(0.0, 1.0, 0.0),
///     core::f32::consts::FRAC_PI_3, // 60° vertical field of view
///     Size::new(320, 240),
/// );
/// let camera = PARAMS.build().unwrap();
/// assert_eq!(camera.size(), Size::new(320, 240));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraParams {
    /// Eye (camera) position.
    pub eye: Vec3,
    /// The point looked at (centre of interest).
    pub look_at: Vec3,
    /// Which way is up; need not be perpendicular to the view direction.
    pub up: Vec3,
    /// Vertical field of view, radians.
    pub fov_y: f32,
    /// Horizontal field of view, radians; `None` for square pixels.
    pub fov_x: Option<f32>,
    /// Resolution in pixels.
    pub size: Size,
}

impl CameraParams {
    /// Parameters with square pixels (`fov_x` follows from `fov_y` and the aspect ratio).
    #[must_use]
    pub const fn new(eye: Vec3, look_at: Vec3, up: Vec3, fov_y: f32, size: Size) -> Self {
        Self {
            eye,
            look_at,
            up,
            fov_y,
            fov_x: None,
            size,
        }
    }

    /// The same parameters with an explicit horizontal field of view (non-square
    /// pixels: aspect ratio `pixel_width / pixel_height`).
    #[must_use]
    pub const fn with_fov_x(mut self, fov_x: f32) -> Self {
        self.fov_x = Some(fov_x);
        self
    }

    /// The same parameters at another resolution (the field of view kept).
    #[must_use]
    pub const fn with_size(mut self, size: Size) -> Self {
        self.size = size;
        self
    }

    /// The same parameters with the eye moved to `eye`, still looking at `look_at`: a
    /// dolly, a crane or a walk around the scene.
    #[must_use]
    pub const fn with_eye(mut self, eye: Vec3) -> Self {
        self.eye = eye;
        self
    }

    /// The same parameters with the eye turned by `angle` radians about the line
    /// through `look_at` along `up` (counter-clockwise seen from above).
    ///
    /// The camera orbits the point it looks at, keeping its height and distance. Two
    /// sines and a handful of products (`libm`, so every target computes the same bits); cheap
    /// enough for every frame on a chip without an FPU. A non-finite angle, or an `up`
    /// that is zero, makes a non-finite eye, which [`build`](Self::build) refuses.
    ///
    /// ```
    /// use embedded_graphics::geometry::Size;
    /// use embedded_raytracer::{CameraParams, Vec3};
    ///
    /// let params = CameraParams::new(
    ///     Vec3::new(0.0, 1.0, 5.0), Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), 1.0, Size::new(64, 64),
    /// );
    /// // A quarter turn: the eye goes from +z to +x, at the same height.
    /// let eye = params.orbited(core::f32::consts::FRAC_PI_2).eye;
    /// assert!((eye.x - 5.0).abs() < 1e-5 && eye.y == 1.0 && eye.z.abs() < 1e-5);
    /// ```
    #[must_use]
    pub fn orbited(self, angle: f32) -> Self {
        // Rodrigues' rotation of r = eye − look_at about the unit axis k:
        // r·cos + (k×r)·sin + k(k·r)(1 − cos).
        let k = self.up * (1.0 / math::sqrt_exact(self.up.dot(self.up)));
        let r = self.eye - self.look_at;
        let (s, c) = (libm::sinf(angle), libm::cosf(angle));
        let along = k * k.dot(r);
        let across = r - along;
        let rotated = along + across * c + k.cross(r) * s;
        self.with_eye(self.look_at + rotated)
    }

    /// Validates the parameters and computes the lecture notes' camera set-up: the one way a
    /// [`Camera`] is made ([`Camera::new`] is this with square pixels).
    ///
    /// Errors: any non-finite number ([`CameraError::NotFinite`]); eye = look-at;
    /// `up` zero or within [`MIN_UP_ANGLE`] of the view direction; a field of view
    /// outside `(0, MAX_FOV]` or so narrow that a pixel is below [`MIN_PIXEL_SIZE`];
    /// a zero width or height, or one above [`MAX_RESOLUTION`]. On success every
    /// stored number is finite.
    pub fn build(self) -> Result<Camera, CameraError> {
        Camera::validate(self)
    }
}

/// A validated pin-hole camera with its per-frame constants precomputed.
///
/// Everything here is computed once per frame; the render loop only adds the steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    params: CameraParams,
    u: Vec3,
    v: Vec3,
    w: Vec3,
    pixel_width: f32,
    pixel_height: f32,
    /// `pw·u`: one pixel to the right.
    du: Vec3,
    /// `−ph·v`: one scanline down.
    dv: Vec3,
    /// `p(0,0) − eye`, the camera-relative direction to the upper-left pixel centre.
    first: Vec3,
    /// The lecture notes' world-space upper-left pixel centre, evaluated as the slides
    /// write it.
    upper_left_world: Vec3,
}

impl Camera {
    /// A camera with square pixels: eye, look-at point, up vector, vertical field of
    /// view in radians, resolution.
    ///
    /// ```
    /// use embedded_graphics::geometry::Size;
    /// use embedded_raytracer::{Camera, CameraError, Vec3};
    ///
    /// let eye = Vec3::new(0.0, 0.0, 5.0);
    /// let up = Vec3::new(0.0, 1.0, 0.0);
    /// let cam = Camera::new(eye, Vec3::ZERO, up, 1.0, Size::new(64, 48)).unwrap();
    /// assert_eq!(cam.w(), Vec3::new(0.0, 0.0, -1.0));
    ///
    /// // Looking straight along `up` leaves the image's roll undefined:
    /// let err = Camera::new(eye, Vec3::ZERO, Vec3::new(0.0, 0.0, 1.0), 1.0, Size::new(64, 48));
    /// assert_eq!(err, Err(CameraError::UpParallelToView));
    /// ```
    pub fn new(eye: Vec3, look_at: Vec3, up: Vec3, fov_y: f32, size: Size) -> Result<Self, CameraError> {
        CameraParams::new(eye, look_at, up, fov_y, size).build()
    }

    /// [`CameraParams::build`].
    fn validate(params: CameraParams) -> Result<Self, CameraError> {
        let CameraParams {
            eye,
            look_at,
            up,
            fov_y,
            fov_x,
            size,
        } = params;
        for (value, param) in [
            (eye, CameraParam::Eye),
            (look_at, CameraParam::LookAt),
            (up, CameraParam::Up),
        ] {
            if !value.is_finite() {
                return Err(CameraError::NotFinite(param));
            }
        }
        if size.width == 0 || size.height == 0 {
            return Err(CameraError::ZeroResolution);
        }
        if size.width > MAX_RESOLUTION || size.height > MAX_RESOLUTION {
            return Err(CameraError::ResolutionTooLarge);
        }

        // Build the view basis: w toward the look-at point, u = w × up, v = u × w.
        let w = unit_direction(eye, look_at).ok_or(CameraError::EyeAtLookAt)?;
        let up = up.try_normalize().ok_or(CameraError::UpParallelToView)?;
        let w_cross_up = w.cross(up);
        // |ŵ × ûp| = sin(angle between them).
        if !(w_cross_up.length() >= MIN_UP_ANGLE) {
            return Err(CameraError::UpParallelToView);
        }
        let u = w_cross_up.try_normalize().ok_or(CameraError::UpParallelToView)?;
        let v = u.cross(w);

        // Pixel size from the field of view, image plane at D = 1.
        let (width, height) = (size.width as f32, size.height as f32);
        let pixel_height = pixel_size(fov_y, height, CameraParam::FovY)?;
        let pixel_width = match fov_x {
            Some(fov_x) => pixel_size(fov_x, width, CameraParam::FovX)?,
            None => {
                // Square pixels; the implied horizontal extent must stay finite.
                if !(pixel_height * width).is_finite() {
                    return Err(CameraError::FovOutOfRange(CameraParam::FovY));
                }
                pixel_height
            }
        };

        // Per-pixel and per-scanline steps.
        let du = u * pixel_width;
        let dv = v * -pixel_height;
        // Upper-left pixel centre, camera-relative: one rounding per coefficient.
        let first = w + u * ((0.5 - width / 2.0) * pixel_width) + v * ((height / 2.0 - 0.5) * pixel_height);
        // The slides' world-space formula, term by term, for the `WorldSpace` method:
        // Eye + w − (xres/2)·pw·u + (yres/2)·ph·v + (pw/2)·u − (ph/2)·v.
        let upper_left_world = eye + w - u * (width / 2.0 * pixel_width)
            + v * (height / 2.0 * pixel_height)
            + u * (pixel_width / 2.0)
            - v * (pixel_height / 2.0);
        if !(first.is_finite() && upper_left_world.is_finite()) {
            // Unreachable for finite inputs below the limits, but no NaN may escape.
            return Err(CameraError::NotFinite(CameraParam::Eye));
        }

        Ok(Self {
            params,
            u,
            v,
            w,
            pixel_width,
            pixel_height,
            du,
            dv,
            first,
            upper_left_world,
        })
    }

    /// The parameters the camera was built from.
    #[must_use]
    pub const fn params(&self) -> &CameraParams {
        &self.params
    }

    /// Eye position.
    #[must_use]
    pub const fn eye(&self) -> Vec3 {
        self.params.eye
    }

    /// Resolution in pixels.
    #[must_use]
    pub const fn size(&self) -> Size {
        self.params.size
    }

    /// `u`: unit vector to the right on the image.
    #[must_use]
    pub const fn u(&self) -> Vec3 {
        self.u
    }

    /// `v`: unit vector up on the image.
    #[must_use]
    pub const fn v(&self) -> Vec3 {
        self.v
    }

    /// `w`: unit view direction.
    #[must_use]
    pub const fn w(&self) -> Vec3 {
        self.w
    }

    /// Pixel width on the image plane (D = 1): `2·tan(fov_x/2)/W`.
    #[must_use]
    pub const fn pixel_width(&self) -> f32 {
        self.pixel_width
    }

    /// Pixel height on the image plane (D = 1): `2·tan(fov_y/2)/H`.
    #[must_use]
    pub const fn pixel_height(&self) -> f32 {
        self.pixel_height
    }

    /// The step to the next pixel to the right, `pw·u`.
    #[must_use]
    pub const fn pixel_step(&self) -> Vec3 {
        self.du
    }

    /// The step to the next scanline down, `−ph·v`.
    #[must_use]
    pub const fn scanline_step(&self) -> Vec3 {
        self.dv
    }

    /// `p(0,0) − eye`: the direction through the upper-left pixel centre.
    #[must_use]
    pub const fn first_direction(&self) -> Vec3 {
        self.first
    }

    /// The lecture notes' world-space upper-left pixel centre, as the slides compute it.
    #[must_use]
    pub const fn upper_left_world(&self) -> Vec3 {
        self.upper_left_world
    }

    /// `p(i,j) − eye` by the lecture notes' direct formula (no stepping):
    /// `w + ((i + ½) − W/2)·pw·u + (H/2 − (j + ½))·ph·v`.
    #[must_use]
    pub fn direction(&self, i: u32, j: u32) -> Vec3 {
        let (width, height) = (self.params.size.width as f32, self.params.size.height as f32);
        let x = ((i as f32 + 0.5) - width / 2.0) * self.pixel_width;
        let y = (height / 2.0 - (j as f32 + 0.5)) * self.pixel_height;
        self.w + self.u * x + self.v * y
    }
}

/// The unit vector from `from` towards `to`; `None` only when they are the same point.
///
/// When `to − from` overflows (points ±3e38 apart), its halves do not.
/// ([`Vec3::try_normalize`] itself handles any finite magnitude.)
fn unit_direction(from: Vec3, to: Vec3) -> Option<Vec3> {
    let d = to - from;
    if d.is_finite() {
        d.try_normalize()
    } else {
        (to * 0.5 - from * 0.5).try_normalize()
    }
}

/// `2·tan(fov/2)/pixels`, validated.
fn pixel_size(fov: f32, pixels: f32, param: CameraParam) -> Result<f32, CameraError> {
    if !fov.is_finite() {
        return Err(CameraError::NotFinite(param));
    }
    if !(fov > 0.0 && fov <= MAX_FOV) {
        return Err(CameraError::FovOutOfRange(param));
    }
    let size = 2.0 * math::tan(fov / 2.0) / pixels;
    if !(size >= MIN_PIXEL_SIZE) {
        return Err(CameraError::FovTooNarrow(param));
    }
    Ok(size)
}
