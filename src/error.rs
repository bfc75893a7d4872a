//! Error types. Every constructor that takes run-time values returns one of these
//! instead of panicking or letting a NaN through.

use core::fmt;

pub use crate::method::ParseMethodError;

/// A camera parameter, as named by [`CameraError`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CameraParam {
    /// The eye (camera position).
    Eye,
    /// The look-at point.
    LookAt,
    /// The up vector.
    Up,
    /// The vertical field of view.
    FovY,
    /// The horizontal field of view.
    FovX,
}

impl CameraParam {
    /// The parameter's name as written in scene files (`eye`, `look_at`, `up`,
    /// `fov_y_deg`, `fov_x_deg`).
    #[must_use]
    pub const fn file_key(self) -> &'static str {
        match self {
            CameraParam::Eye => "eye",
            CameraParam::LookAt => "look_at",
            CameraParam::Up => "up",
            CameraParam::FovY => "fov_y_deg",
            CameraParam::FovX => "fov_x_deg",
        }
    }
}

/// Why a [`Camera`](crate::Camera) could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CameraError {
    /// A parameter is NaN or infinite.
    NotFinite(CameraParam),
    /// The eye and the look-at point coincide, so there is no view direction.
    EyeAtLookAt,
    /// `up` is zero or within [`MIN_UP_ANGLE`](crate::camera::MIN_UP_ANGLE) of the
    /// view direction, so `u = w × up` has no reliable direction.
    UpParallelToView,
    /// A field of view is not in `(0, MAX_FOV]` (see [`MAX_FOV`](crate::camera::MAX_FOV)).
    FovOutOfRange(CameraParam),
    /// A field of view is so narrow that a pixel step is smaller than
    /// [`MIN_PIXEL_SIZE`](crate::camera::MIN_PIXEL_SIZE) on the image plane, where f32 can
    /// no longer tell neighbouring pixels' rays apart reliably.
    FovTooNarrow(CameraParam),
    /// Width or height is zero.
    ZeroResolution,
    /// Width or height exceeds [`MAX_RESOLUTION`](crate::camera::MAX_RESOLUTION).
    ResolutionTooLarge,
}

impl CameraError {
    /// The scene-file key the error is about (`up`, `fov_y_deg`, `width`, …).
    #[must_use]
    pub const fn file_key(self) -> &'static str {
        match self {
            CameraError::NotFinite(p) | CameraError::FovOutOfRange(p) | CameraError::FovTooNarrow(p) => {
                p.file_key()
            }
            CameraError::EyeAtLookAt => "look_at",
            CameraError::UpParallelToView => "up",
            CameraError::ZeroResolution | CameraError::ResolutionTooLarge => "width/height",
        }
    }
}

impl fmt::Display for CameraError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use crate::limits::{MAX_RESOLUTION, MIN_PIXEL_SIZE, MIN_UP_ANGLE};
        match self {
            CameraError::NotFinite(p) => write!(f, "`{}` is not a finite number", p.file_key()),
            CameraError::EyeAtLookAt => {
                f.write_str("eye and look_at are the same point: there is no view direction")
            }
            CameraError::UpParallelToView => write!(
                f,
                "up is zero or (nearly) parallel to the view direction (less than {MIN_UP_ANGLE} rad apart)"
            ),
            CameraError::FovOutOfRange(p) => write!(
                f,
                "`{}` must be greater than 0° and at most 179°",
                p.file_key()
            ),
            CameraError::FovTooNarrow(p) => write!(
                f,
                "`{}` is too narrow for the resolution: a pixel would be smaller than {MIN_PIXEL_SIZE:e} on the image plane",
                p.file_key()
            ),
            CameraError::ZeroResolution => f.write_str("width and height must be at least 1"),
            CameraError::ResolutionTooLarge => {
                write!(f, "width and height must be at most {MAX_RESOLUTION}")
            }
        }
    }
}

impl core::error::Error for CameraError {}

/// Why a [`Sphere`](crate::Sphere) is invalid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SphereError {
    /// The centre or radius is NaN or infinite.
    NotFinite,
    /// The radius is zero or negative.
    RadiusNotPositive,
}

impl fmt::Display for SphereError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            SphereError::NotFinite => "centre and radius must be finite numbers",
            SphereError::RadiusNotPositive => "radius must be greater than 0",
        })
    }
}

impl core::error::Error for SphereError {}

/// Why a sphere could not be added to a [`Scene`](crate::Scene).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SceneError {
    /// The scene already holds its capacity `N` of spheres.
    Full {
        /// The capacity.
        capacity: usize,
    },
    /// The sphere itself is invalid.
    Sphere(SphereError),
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneError::Full { capacity } => {
                write!(f, "too many spheres: the scene holds at most {capacity}")
            }
            SceneError::Sphere(e) => fmt::Display::fmt(e, f),
        }
    }
}

impl core::error::Error for SceneError {}

/// Why [`Render::draw_band`](crate::Render::draw_band) refused a band.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BandError {
    /// The rows are empty or reach past the image.
    Rows {
        /// First row asked for.
        start: u32,
        /// One past the last row asked for.
        end: u32,
        /// The image's height.
        height: u32,
    },
    /// The buffer does not hold exactly `width × rows` pixels.
    BufferSize {
        /// `width × rows`.
        expected: usize,
        /// The buffer's length.
        found: usize,
    },
}

impl fmt::Display for BandError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            BandError::Rows { start, end, height } => write!(
                f,
                "rows {start}..{end} are not a non-empty range of the image's {height} rows"
            ),
            BandError::BufferSize { expected, found } => write!(
                f,
                "the band buffer holds {found} pixels; the rows need exactly {expected}"
            ),
        }
    }
}

impl core::error::Error for BandError {}

impl From<SphereError> for SceneError {
    fn from(e: SphereError) -> Self {
        SceneError::Sphere(e)
    }
}
