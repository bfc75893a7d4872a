//! The typed errors every constructor that takes run-time values returns, instead of
//! panicking or letting a NaN through.

use core::fmt;

/// A camera parameter, as named by [`CameraError`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
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
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
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
    /// [`MIN_PIXEL_SIZE`](crate::camera::MIN_PIXEL_SIZE) on the image plane.
    ///
    /// Below that step `f32` can no longer tell neighbouring pixels' rays apart reliably.
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
        use crate::math::limits::{MAX_RESOLUTION, MIN_PIXEL_SIZE, MIN_UP_ANGLE};
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
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum SphereError {
    /// The centre or radius is NaN or infinite.
    NotFinite,
    /// The radius is zero or negative.
    RadiusNotPositive,
    /// Its material is invalid.
    Material(MaterialError),
}

impl fmt::Display for SphereError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            SphereError::NotFinite => "centre and radius must be finite numbers",
            SphereError::RadiusNotPositive => "radius must be greater than 0",
            SphereError::Material(e) => return fmt::Display::fmt(e, f),
        })
    }
}

/// Why a [`Material`](crate::Material) is invalid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum MaterialError {
    /// `specular` is not in `[0, 1]`.
    Specular,
    /// `shininess` is not a finite number `≥ 1`.
    Shininess,
    /// `reflect` is not in `[0, 1]`.
    Reflect,
}

impl MaterialError {
    /// The scene-file key the error is about.
    #[must_use]
    pub const fn file_key(self) -> &'static str {
        match self {
            MaterialError::Specular => "specular",
            MaterialError::Shininess => "shininess",
            MaterialError::Reflect => "reflect",
        }
    }
}

impl fmt::Display for MaterialError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            MaterialError::Specular => "specular must be between 0 and 1",
            MaterialError::Shininess => "shininess must be a finite number of at least 1",
            MaterialError::Reflect => "reflect must be between 0 and 1",
        })
    }
}

impl core::error::Error for MaterialError {}

/// Why a [`Light`](crate::Light) is invalid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum LightError {
    /// The direction or position is NaN or infinite.
    NotFinite,
    /// A directional light's direction is zero.
    ZeroDirection,
    /// The intensity is negative, NaN or infinite.
    Intensity,
}

impl LightError {
    /// The scene-file key the error is about.
    #[must_use]
    pub const fn file_key(self) -> &'static str {
        match self {
            LightError::NotFinite => "direction/position",
            LightError::ZeroDirection => "direction",
            LightError::Intensity => "intensity",
        }
    }
}

impl fmt::Display for LightError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            LightError::NotFinite => "the light's direction or position must be finite numbers",
            LightError::ZeroDirection => "a directional light's direction must not be zero",
            LightError::Intensity => "intensity must be a finite number of at least 0",
        })
    }
}

impl core::error::Error for LightError {}

/// Why a [`Plane`](crate::Plane) is invalid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum PlaneError {
    /// The point or normal is NaN or infinite.
    NotFinite,
    /// The normal is zero.
    ZeroNormal,
    /// `checker_size` is not a finite number `> 0`.
    CheckerSize,
    /// Its material is invalid.
    Material(MaterialError),
}

impl PlaneError {
    /// The scene-file key the error is about.
    #[must_use]
    pub const fn file_key(self) -> &'static str {
        match self {
            PlaneError::NotFinite => "point/normal",
            PlaneError::ZeroNormal => "normal",
            PlaneError::CheckerSize => "checker_size",
            PlaneError::Material(e) => e.file_key(),
        }
    }
}

impl fmt::Display for PlaneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            PlaneError::NotFinite => "the plane's point and normal must be finite numbers",
            PlaneError::ZeroNormal => "the plane's normal must not be zero",
            PlaneError::CheckerSize => "checker_size must be a finite number greater than 0",
            PlaneError::Material(e) => return fmt::Display::fmt(e, f),
        })
    }
}

impl core::error::Error for PlaneError {}

/// Why a scene's [`Settings`](crate::Settings) are invalid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum SettingsError {
    /// `ambient` is not in `[0, 1]`.
    Ambient,
    /// `max_depth` exceeds what the scene type can trace (its `D`).
    MaxDepth {
        /// The largest depth allowed.
        max: u8,
    },
}

impl SettingsError {
    /// The scene-file key the error is about.
    #[must_use]
    pub const fn file_key(self) -> &'static str {
        match self {
            SettingsError::Ambient => "ambient",
            SettingsError::MaxDepth { .. } => "max_depth",
        }
    }
}

impl fmt::Display for SettingsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SettingsError::Ambient => f.write_str("ambient must be between 0 and 1"),
            SettingsError::MaxDepth { max } => write!(f, "max_depth must be at most {max}"),
        }
    }
}

impl core::error::Error for SettingsError {}

impl core::error::Error for SphereError {}

/// Why an object or setting could not be added to a [`Scene`](crate::Scene).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum SceneError {
    /// The scene already holds its capacity `N` of spheres.
    Full {
        /// The capacity.
        capacity: usize,
    },
    /// The scene already holds its capacity `L` of lights.
    TooManyLights {
        /// The capacity.
        capacity: usize,
    },
    /// The scene already holds its capacity `P` of planes.
    TooManyPlanes {
        /// The capacity.
        capacity: usize,
    },
    /// A mirror (`reflect > 0`) in a scene type without reflection depth (`D = 0`).
    MirrorWithoutDepth,
    /// The sphere itself is invalid.
    Sphere(SphereError),
    /// The light itself is invalid.
    Light(LightError),
    /// The plane itself is invalid.
    Plane(PlaneError),
    /// The settings are invalid.
    Settings(SettingsError),
    /// No such object to replace: the index is not below the count of its kind.
    NoSuchObject(ObjectRef),
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneError::Full { capacity } => {
                write!(f, "too many spheres: the scene holds at most {capacity}")
            }
            SceneError::TooManyLights { capacity } => {
                write!(f, "too many lights: the scene holds at most {capacity}")
            }
            SceneError::TooManyPlanes { capacity } => {
                write!(f, "too many planes: the scene holds at most {capacity}")
            }
            SceneError::MirrorWithoutDepth => f.write_str(
                "reflect > 0 needs a scene type with a reflection depth (Scene<N, L, P, D> with D ≥ 1)",
            ),
            SceneError::Sphere(e) => fmt::Display::fmt(e, f),
            SceneError::Light(e) => fmt::Display::fmt(e, f),
            SceneError::Plane(e) => fmt::Display::fmt(e, f),
            SceneError::Settings(e) => fmt::Display::fmt(e, f),
            SceneError::NoSuchObject(object) => write!(f, "the scene has no {object}"),
        }
    }
}

impl core::error::Error for SceneError {}

/// An object of a scene, as a [`FrameError`] names it: its index among the scene's
/// spheres, planes or lights.
///
/// The index is the order they were pushed, the order of a scene file's `[[sphere]]`,
/// `[[plane]]` and `[[light]]` tables.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum ObjectRef {
    /// `scene.spheres()[i]`.
    Sphere(usize),
    /// `scene.planes()[i]`.
    Plane(usize),
    /// `scene.lights()[i]`.
    Light(usize),
}

impl fmt::Display for ObjectRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            ObjectRef::Sphere(i) => write!(f, "sphere {i}"),
            ObjectRef::Plane(i) => write!(f, "plane {i}"),
            ObjectRef::Light(i) => write!(f, "light {i}"),
        }
    }
}

/// Why a frame cannot be drawn exactly in `f32`.
///
/// [`Render::check`](crate::Render::check) returns it, and
/// [`Render::draw_band`](crate::Render::draw_band) as [`BandError::Frame`]. Such a frame
/// is not drawn: [`Drawable::draw`](embedded_graphics::Drawable::draw) leaves the
/// target as it was, rather than draw a wrong picture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum FrameError {
    /// No one power of two brings both objects' sizes into the range a frame computes
    /// exactly in, `[2⁻⁴⁰, 2⁵⁰)`.
    ///
    /// An object's size is its largest coordinate relative to the eye or its radius:
    /// `far` is more than about 2⁹⁰ (10²⁷) times `near`, or beyond `f32` (its
    /// coordinates ±10³⁸ from the eye's). An object the frame can prove no ray meets does
    /// not count (a sphere outside the view of a scene without lights, planes or mirrors,
    /// with one ray a pixel).
    Magnitudes {
        /// The object of the largest size.
        far: ObjectRef,
        /// The object of the smallest size.
        near: ObjectRef,
    },
}

impl fmt::Display for FrameError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            FrameError::Magnitudes { far, near } => write!(
                f,
                "{far} is more than 2^90 times farther from the eye (or larger) than {near}: \
                 f32 cannot draw both exactly in one frame; move {far} nearer or leave it out"
            ),
        }
    }
}

impl core::error::Error for FrameError {}

/// Why [`Render::draw_band`](crate::Render::draw_band) refused a band.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
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
    /// The frame cannot be drawn exactly ([`FrameError`]); the buffer keeps what it held.
    Frame(FrameError),
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
            BandError::Frame(e) => fmt::Display::fmt(&e, f),
        }
    }
}

impl core::error::Error for BandError {}

/// Why [`Render::draw_integer`](crate::Render::draw_integer) did not draw the frame, or
/// [`Render::draw_band_integer`](crate::Render::draw_band_integer) the band.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum IntegerError<E> {
    /// The integer kernel does not take this frame, and nothing was drawn.
    ///
    /// Its per-frame rule (see [`Arithmetic::Integer`](crate::Arithmetic::Integer)) does
    /// not hold for the scene and camera, the scene has lights, planes or mirrors, or the
    /// sampling is not [`Sampling::Center`](crate::Sampling::Center).
    Refused,
    /// The draw target's own error; for a band, why the band cannot be drawn
    /// ([`BandError`]).
    Target(E),
}

impl<E: fmt::Display> fmt::Display for IntegerError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            IntegerError::Refused => f.write_str(
                "the integer kernel does not take this frame (its bounds do not hold for the scene and camera, \
                 the scene has lights, planes or mirrors, or the sampling is not center)",
            ),
            IntegerError::Target(e) => write!(f, "draw target: {e}"),
        }
    }
}

impl<E: fmt::Debug + fmt::Display> core::error::Error for IntegerError<E> {}

impl From<SphereError> for SceneError {
    fn from(e: SphereError) -> Self {
        SceneError::Sphere(e)
    }
}

impl From<LightError> for SceneError {
    fn from(e: LightError) -> Self {
        SceneError::Light(e)
    }
}

impl From<PlaneError> for SceneError {
    fn from(e: PlaneError) -> Self {
        SceneError::Plane(e)
    }
}

impl From<SettingsError> for SceneError {
    fn from(e: SettingsError) -> Self {
        SceneError::Settings(e)
    }
}

/// A method name (`--stepping`, `--sphere-test`, `--sqrt`) that is not one of the choices.
///
/// ```
/// use embedded_raytracer::{ParseMethodError, Sqrt};
/// let e = "slow".parse::<Sqrt>().unwrap_err();
/// assert_eq!((e.what, e.expected), ("sqrt", Sqrt::NAMES));
/// assert_eq!(e.to_string(), "unknown sqrt: expected one of exact, fast");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub struct ParseMethodError {
    /// What was being parsed (`stepping`, `sphere test`, `sqrt`).
    pub what: &'static str,
    /// The accepted names, in the axis' order; `Display` joins them with `, `.
    pub expected: &'static [&'static str],
}

impl fmt::Display for ParseMethodError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "unknown {}: expected one of ", self.what)?;
        for (k, name) in self.expected.iter().enumerate() {
            if k > 0 {
                f.write_str(", ")?;
            }
            f.write_str(name)?;
        }
        Ok(())
    }
}

impl core::error::Error for ParseMethodError {}
