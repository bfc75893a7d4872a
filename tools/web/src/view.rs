//! What the page's pickers choose: everything that decides a frame's pixels besides the
//! scene, and the orbit of the file's camera.
//!
//! The page sends it as one line of
//! `key=value` pairs joined by `&` (the share link's view part, too).

use embedded_graphics::geometry::Size;
use embedded_raytracer::dither::Bayer;
use embedded_raytracer::{CameraParams, Method, Sampling, SecondaryOrigin, Vec3};

use embedded_raytracer_display::{bayer, Model, Theme};

/// The secondary-ray origins the page offers (the preview's `E` key): the default, the
/// textbook epsilon, one below the hit points' rounding error at the standard scenes'
/// coordinates (shadow acne), one large for them (light leaks under resting spheres).
pub const SECONDARY: [SecondaryOrigin; 4] = [
    SecondaryOrigin::Convex,
    SecondaryOrigin::TEXTBOOK,
    SecondaryOrigin::Epsilon(1e-6),
    SecondaryOrigin::Epsilon(1e-1),
];

/// Elevation stays within ±89° of the plane normal to `up`, well clear of the camera's
/// up-parallel-to-view limit (the preview's limit).
pub const MAX_ELEVATION: f32 = 89.0 * core::f32::consts::PI / 180.0;

/// Distance factor per zoom step (the preview's).
const ZOOM: f32 = 1.1;

/// The most zoom steps either way: 1.1⁴⁰ ≈ 45 times nearer or farther.
const MAX_ZOOM_STEPS: i32 = 40;

/// Everything besides the scene that decides the pixels shown.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    pub model: Model,
    /// The matrix of the dithered models.
    pub bayer: Bayer,
    /// The window colours of the 1-bit models.
    pub theme: Theme,
    pub method: Method,
    pub sampling: Sampling,
    /// Where shadow and reflection rays start (scenes with lights or mirrors).
    pub secondary: SecondaryOrigin,
    /// The display's resolution; `None`: the scene file's.
    pub size: Option<Size>,
    pub orbit: Orbit,
    /// The difference view: pixels that differ from the `direct/robust/exact` render
    /// (convex origin), through the same model, in magenta.
    pub diff: bool,
}

impl Default for View {
    /// The render CLI's frame: the file's size and camera, `Rgb888`, the target's
    /// default method (`f32` in WebAssembly: it has hardware floating point).
    fn default() -> Self {
        Self {
            model: Model::Rgb888,
            bayer: Bayer::Eight,
            theme: Theme::OledBlue,
            method: Method::default(),
            sampling: Sampling::Center,
            secondary: SecondaryOrigin::Convex,
            size: None,
            orbit: Orbit::default(),
            diff: false,
        }
    }
}

impl View {
    /// This view with the pairs of `spec` (`display=rgb565&size=240x240&…`) applied;
    /// keys not given keep their value.
    ///
    /// Keys: `display`, `bayer` (4, 8), `theme`,
    /// `method` (`[integer/]stepping/sphere-test/sqrt`), `sampling`, `secondary`
    /// (`convex`, `epsilon:E`), `size` (`WxH`, or `file`), `azimuth` and `elevation`
    /// (radians from the file's camera), `zoom` (steps of 1.1, negative nearer), `diff`
    /// (0, 1).
    pub fn with(mut self, spec: &str) -> Result<View, String> {
        for pair in spec.split('&').filter(|p| !p.is_empty()) {
            let (key, value) = pair
                .split_once('=')
                .ok_or_else(|| format!("`{pair}`: expected key=value"))?;
            let bad = |what: &str| format!("{key}: `{value}` is not {what}");
            match key {
                "display" => self.model = Model::from_name(value).ok_or_else(|| bad("a display model"))?,
                "bayer" => self.bayer = bayer::from_name(value).ok_or_else(|| bad("4 or 8"))?,
                "theme" => {
                    self.theme = Theme::from_name(value).ok_or_else(|| bad("oled-blue or oled-white"))?
                }
                "method" => self.method = value.parse().map_err(|e| format!("{key}: {e}"))?,
                "sampling" => self.sampling = value.parse().map_err(|e| format!("{key}: {e}"))?,
                "secondary" => self.secondary = parse_secondary(value).ok_or_else(|| bad("an origin"))?,
                "size" => self.size = parse_size(value).ok_or_else(|| bad("WxH or file"))?,
                "azimuth" => self.orbit.azimuth = finite(value).ok_or_else(|| bad("an angle"))?,
                "elevation" => self.orbit.elevation = finite(value).ok_or_else(|| bad("an angle"))?,
                "zoom" => {
                    let steps: i32 = value.parse().map_err(|_| bad("a whole number"))?;
                    self.orbit.zoom_steps = steps.clamp(-MAX_ZOOM_STEPS, MAX_ZOOM_STEPS);
                }
                "diff" => self.diff = value == "1",
                _ => return Err(format!("unknown view key `{key}`")),
            }
        }
        Ok(self)
    }
}

/// `convex` or `epsilon:E` (the render CLI's names, `SecondaryOrigin`'s `Display`).
fn parse_secondary(value: &str) -> Option<SecondaryOrigin> {
    if value == "convex" {
        return Some(SecondaryOrigin::Convex);
    }
    let eps = finite(value.strip_prefix("epsilon:")?)?;
    (eps > 0.0).then_some(SecondaryOrigin::Epsilon(eps))
}

/// `WxH` (`Some(size)`) or `file` (`None`: the scene file's size).
fn parse_size(value: &str) -> Option<Option<Size>> {
    if value == "file" {
        return Some(None);
    }
    let (w, h) = value.split_once('x')?;
    Some(Some(Size::new(w.parse().ok()?, h.parse().ok()?)))
}

fn finite(value: &str) -> Option<f32> {
    value.parse::<f32>().ok().filter(|v| v.is_finite())
}

/// The user's orbit relative to the scene file's camera (the preview's): all zero is
/// the file's camera, bit for bit.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Orbit {
    /// Radians about `up`.
    pub azimuth: f32,
    /// Radians added to the file eye's elevation (the total is kept within
    /// ±[`MAX_ELEVATION`]).
    pub elevation: f32,
    /// Steps of 1.1 in distance, negative nearer.
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
        let k = base.up.try_normalize()?;
        let along = offset.dot(k);
        let horizontal = offset - k * along;
        // Looking straight along `up` cannot happen (the camera refuses it), but pick a
        // perpendicular anyway rather than fail.
        let e1 = horizontal
            .try_normalize()
            .or_else(|| k.cross(Vec3::new(1.0, 0.0, 0.0)).try_normalize())
            .or_else(|| k.cross(Vec3::new(0.0, 0.0, 1.0)).try_normalize())?;
        Some(Self {
            k,
            e1,
            e2: k.cross(e1),
            elevation: along.atan2(horizontal.length()),
            distance: offset.length(),
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

    /// The range of [`Orbit::elevation`] that keeps the total within
    /// ±[`MAX_ELEVATION`] for `base`'s eye.
    pub fn elevation_range(base: &CameraParams) -> (f32, f32) {
        let el0 = OrbitFrame::new(base).map_or(0.0, |f| f.elevation);
        (-MAX_ELEVATION - el0, MAX_ELEVATION - el0)
    }
}
