//! TOML scene files (feature `std`, host only): the format of `scenes/*.toml`.
//!
//! ```toml
//! background = [0, 0, 0]        # optional, default black
//!
//! [camera]
//! eye = [0.0, 0.0, 5.0]
//! look_at = [0.0, 0.0, 0.0]
//! up = [0.0, 1.0, 0.0]          # optional, default +y
//! fov_y_deg = 60.0
//! # fov_x_deg = 80.0            # optional: non-square pixels
//! width = 320
//! height = 240
//!
//! [[sphere]]
//! center = [0.0, 0.0, 0.0]
//! radius = 1.0
//! color = [255, 64, 64]         # 8-bit sRGB
//! ```
//!
//! Lights, planes and mirrors are optional keys; a file without them is spheres under
//! the Lab #1 headlight, whatever the scene type it is loaded into:
//!
//! ```toml
//! ambient = 0.1                 # optional, 0 … 1
//! max_depth = 2                 # optional, 0 … 8 (and at most the scene type's D)
//! shadows = true                # optional
//!
//! [[light]]
//! type = "directional"          # or "point"
//! direction = [-1.0, -2.0, -1.0]  # directional only: the way the light travels
//! # position = [2.0, 5.0, 3.0]   # point only
//! intensity = 0.8               # optional, default 1, ≥ 0
//!
//! [[sphere]]                    # as above, plus optionally:
//! specular = 0.5                # 0 … 1, default 0
//! shininess = 32                # ≥ 1, default 32
//! reflect = 0.3                 # 0 … 1, default 0 (needs D ≥ 1)
//!
//! [[plane]]
//! point = [0.0, -1.0, 0.0]
//! normal = [0.0, 1.0, 0.0]      # not zero
//! color = [220, 220, 220]
//! checker = [40, 40, 40]        # optional second colour
//! checker_size = 1.0            # optional, default 1, > 0 (only with `checker`)
//! # specular, shininess and reflect as for spheres
//! ```
//!
//! A scene may move ([`motion`](crate::motion)): each `[[motion]]` table moves one
//! sphere or the camera, in file order, and `[animation]` says how it is played:
//!
//! ```toml
//! [animation]                   # optional
//! fps = 25                      # optional, default 25, > 0
//! frames = 50                   # optional, default one loop of the longest period
//!
//! [[motion]]
//! kind = "circle"               # sphere[0] circles `center` in its horizontal plane
//! sphere = 0                    # the sphere's index, from 0 in file order
//! center = [0.0, 0.5, 0.0]
//! radius = 1.5
//! period = 4.0                  # seconds a turn, > 0
//! phase = 0.25                  # optional, turns along at t = 0, default 0
//!
//! [[motion]]
//! kind = "bounce"               # up `height` and back every `period` seconds
//! sphere = 1
//! height = 1.2
//! period = 1.0
//!
//! [[motion]]
//! kind = "orbit"                # the camera orbits its look_at about `up`
//! period = 10.0
//! ```
//!
//! At most [`MAX_MOTIONS`] motions; a field another kind takes is refused rather than
//! ignored (`motion[1].center: a bounce has no center`).
//!
//! The scene type's capacities are the loader's limits: [`parse`]`::<N, L, P, D>` reads
//! at most `N` spheres, `L` lights and `P` planes (each counted while parsing, so a huge
//! file is refused at entry `N + 1`) and accepts `reflect > 0` only if `D ≥ 1`.
//!
//! Every fixed-length array must have exactly its length, every number must fit its
//! type (an `f32` field refuses `1e39` rather than reading it as infinity), and [`load`]
//! reads only a regular file of at most [`MAX_FILE_SIZE`] bytes.
//!
//! Every error names the field (`camera.fov_y_deg`, `sphere[2].radius`,
//! `light[1].direction`, `plane[0].normal`, with `sphere[k]` counting from 0 in file
//! order), the line where the parser knows it, and the reason:
//!
//! ```
//! use embedded_raytracer::scene_file::parse;
//!
//! let text = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov_y_deg = 60\nwidth = 4\nheight = 3\n\
//!             [[sphere]]\ncenter = [0, 0, 0]\nradius = 0\ncolor = [255, 0, 0]\n";
//! let err = parse::<4, 0, 0, 0>(text).unwrap_err();
//! assert_eq!(err.field.as_deref(), Some("sphere[0].radius"));
//! assert_eq!(err.to_string(), "sphere[0].radius: radius must be greater than 0");
//!
//! let lit = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov_y_deg = 60\nwidth = 4\nheight = 3\n\
//!            [[light]]\ntype = \"point\"\ndirection = [0, -1, 0]\n";
//! let err = parse::<4, 2, 1, 2>(lit).unwrap_err();
//! assert_eq!(err.to_string(), "light[0].direction: a point light has no direction (give `position`)");
//! ```

use std::fmt;
use std::io::Read;
use std::marker::PhantomData;
use std::path::{Path, PathBuf};
use std::string::{String, ToString};
use std::vec::Vec;
use std::{format, fs};

use embedded_graphics::{geometry::Size, pixelcolor::Rgb888};
use serde::de::{self, Deserializer, IgnoredAny, MapAccess, SeqAccess, Unexpected, Visitor};
use serde::Deserialize;

use crate::camera::{Camera, CameraParams};
use crate::error::{CameraError, LightError, PlaneError, SceneError, SphereError};
use crate::math::vec3::Vec3;
use crate::motion::{Animation, Bounce, Circle, Motion, Orbit, DEFAULT_FPS};
use crate::scene::light::Light;
use crate::scene::material::Material;
use crate::scene::plane::Plane;
use crate::scene::sphere::Sphere;
use crate::scene::{Scene, Settings};

/// The largest scene file [`load`] reads, in bytes (1 MiB; `scenes/crowd.toml`, 64
/// spheres, is 5,351 bytes).
pub const MAX_FILE_SIZE: u64 = 1 << 20;

/// The most `[[motion]]` tables a scene file may have: the capacity of
/// [`SceneFile::animation`].
pub const MAX_MOTIONS: usize = 8;

/// A loaded scene file: the scene (with capacities `N` spheres, `L` lights, `P`
/// planes, reflection depth `D`) and its camera.
#[derive(Clone, Debug)]
pub struct SceneFile<const N: usize, const L: usize = 0, const P: usize = 0, const D: usize = 0> {
    /// The objects, lights, background and settings.
    pub scene: Scene<N, L, P, D>,
    /// The validated camera.
    pub camera: Camera,
    /// The file's motions (none if it has no `[[motion]]`), frame rate and frames,
    /// checked against the scene: every sphere a motion names is in it.
    pub animation: Animation<MAX_MOTIONS>,
}

impl<const N: usize, const L: usize, const P: usize, const D: usize> SceneFile<N, L, P, D> {
    /// Whether the scene has a light, a plane or a mirror (`reflect > 0`): anything
    /// the spheres-only type `Scene<N>` cannot draw.
    #[must_use]
    pub fn has_features(&self) -> bool {
        !self.scene.lights().is_empty()
            || !self.scene.planes().is_empty()
            || self.scene.spheres().iter().any(|s| s.material.reflect > 0.0)
    }

    /// The same file as the spheres-only type `SceneFile<N>` when it has no light,
    /// plane or mirror ([`has_features`](Self::has_features) is false): rendered
    /// through `Scene<N>`, it draws with the Lab #1 loop, the pixels of a file without
    /// the new keys. Without lights the settings and the spheres' highlights change no
    /// pixel, so nothing the picture depends on is dropped. `None` when it has features.
    #[must_use]
    pub fn spheres_only(&self) -> Option<SceneFile<N>> {
        if self.has_features() {
            return None;
        }
        let mut scene = Scene::new(self.scene.background());
        for sphere in self.scene.spheres() {
            // Cannot fail: the same capacity, spheres already checked, no mirror.
            scene.push(*sphere).ok()?;
        }
        Some(SceneFile {
            scene,
            camera: self.camera,
            animation: self.animation.clone(),
        })
    }
}

/// Why a scene file was rejected: the file, the field, the line and the reason.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneFileError {
    /// The file, when the error came from [`load`].
    pub path: Option<PathBuf>,
    /// The field, e.g. `camera.width` or `sphere[2].radius`, when one is to blame.
    pub field: Option<String>,
    /// 1-based line number, when the parser knows it.
    pub line: Option<usize>,
    /// What is wrong.
    pub reason: String,
}

impl fmt::Display for SceneFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(path) = &self.path {
            write!(f, "{}: ", path.display())?;
        }
        if let Some(line) = self.line {
            write!(f, "line {line}: ")?;
        }
        if let Some(field) = &self.field {
            write!(f, "{field}: ")?;
        }
        f.write_str(&self.reason)
    }
}

impl std::error::Error for SceneFileError {}

impl SceneFileError {
    fn field(field: impl Into<String>, reason: impl ToString) -> Self {
        Self {
            path: None,
            field: Some(field.into()),
            line: None,
            reason: reason.to_string(),
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene<const N: usize, const L: usize, const P: usize> {
    background: Option<Exact<Int<u8>, 3>>,
    ambient: Option<F32>,
    max_depth: Option<Depth>,
    shadows: Option<bool>,
    camera: RawCamera,
    #[serde(default, deserialize_with = "capped::<_, RawSphere, N>")]
    sphere: Vec<RawSphere>,
    #[serde(default, deserialize_with = "capped::<_, RawLight, L>")]
    light: Vec<RawLight>,
    #[serde(default, deserialize_with = "capped::<_, RawPlane, P>")]
    plane: Vec<RawPlane>,
    #[serde(default, deserialize_with = "capped::<_, RawMotion, MAX_MOTIONS>")]
    motion: Vec<RawMotion>,
    animation: Option<RawAnimation>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAnimation {
    fps: Option<F32>,
    frames: Option<Int<u32>>,
}

/// A motion's `kind`: `"circle"`, `"bounce"` or `"orbit"`.
#[derive(Clone, Copy)]
enum MotionKind {
    Circle,
    Bounce,
    Orbit,
}

impl MotionKind {
    const fn name(self) -> &'static str {
        match self {
            MotionKind::Circle => "circle",
            MotionKind::Bounce => "bounce",
            MotionKind::Orbit => "orbit",
        }
    }
}

impl<'de> Deserialize<'de> for MotionKind {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct KindVisitor;
        impl Visitor<'_> for KindVisitor {
            type Value = MotionKind;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("\"circle\", \"bounce\" or \"orbit\"")
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<MotionKind, E> {
                match v {
                    "circle" => Ok(MotionKind::Circle),
                    "bounce" => Ok(MotionKind::Bounce),
                    "orbit" => Ok(MotionKind::Orbit),
                    _ => Err(E::invalid_value(Unexpected::Str(v), &self)),
                }
            }
        }
        d.deserialize_any(KindVisitor)
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMotion {
    kind: MotionKind,
    sphere: Option<Int<u32>>,
    center: Option<Exact<F32, 3>>,
    radius: Option<F32>,
    period: F32,
    phase: Option<F32>,
    height: Option<F32>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCamera {
    eye: Exact<F32, 3>,
    look_at: Exact<F32, 3>,
    up: Option<Exact<F32, 3>>,
    fov_y_deg: F32,
    fov_x_deg: Option<F32>,
    width: Int<u32>,
    height: Int<u32>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSphere {
    center: Exact<F32, 3>,
    radius: F32,
    color: Exact<Int<u8>, 3>,
    specular: Option<F32>,
    shininess: Option<F32>,
    reflect: Option<F32>,
}

/// A sphere's or plane's material from its optional keys, each missing one at its
/// default (unchecked). The keys are written out in both structs rather than
/// flattened: serde's `flatten` drops `deny_unknown_fields` and the error's line.
fn material(specular: &Option<F32>, shininess: &Option<F32>, reflect: &Option<F32>) -> Material {
    let or = |v: &Option<F32>, default: f32| v.as_ref().map_or(default, |v| v.0);
    let d = Material::DEFAULT;
    Material::new(
        or(specular, d.specular),
        or(shininess, d.shininess),
        or(reflect, d.reflect),
    )
}

/// A light's `type`: `"directional"` or `"point"`.
#[derive(Clone, Copy)]
enum LightKind {
    Directional,
    Point,
}

impl<'de> Deserialize<'de> for LightKind {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct KindVisitor;
        impl Visitor<'_> for KindVisitor {
            type Value = LightKind;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("\"directional\" or \"point\"")
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<LightKind, E> {
                match v {
                    "directional" => Ok(LightKind::Directional),
                    "point" => Ok(LightKind::Point),
                    _ => Err(E::invalid_value(Unexpected::Str(v), &self)),
                }
            }
        }
        // Any other type (a number, a table, …) is answered by the visitor's
        // `expecting`: "invalid type: integer `5`, expected "directional" or "point"".
        d.deserialize_any(KindVisitor)
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLight {
    #[serde(rename = "type")]
    kind: LightKind,
    direction: Option<Exact<F32, 3>>,
    position: Option<Exact<F32, 3>>,
    intensity: Option<F32>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPlane {
    point: Exact<F32, 3>,
    normal: Exact<F32, 3>,
    color: Exact<Int<u8>, 3>,
    checker: Option<Exact<Int<u8>, 3>>,
    checker_size: Option<F32>,
    specular: Option<F32>,
    shininess: Option<F32>,
    reflect: Option<F32>,
}

/// The noun an array of tables is counted in, for the too-many message.
trait Noun {
    const NOUN: &'static str;
}

impl Noun for RawSphere {
    const NOUN: &'static str = "sphere";
}

impl Noun for RawLight {
    const NOUN: &'static str = "light";
}

impl Noun for RawPlane {
    const NOUN: &'static str = "plane";
}

impl Noun for RawMotion {
    const NOUN: &'static str = "motion";
}

fn vec3(v: &Exact<F32, 3>) -> Vec3 {
    let [x, y, z] = &v.0;
    Vec3::new(x.0, y.0, z.0)
}

fn rgb(c: &Exact<Int<u8>, 3>) -> Rgb888 {
    let [r, g, b] = &c.0;
    Rgb888::new(r.0, g.0, b.0)
}

/// Degrees to radians, keeping a positive angle positive: a field of view that
/// underflows to 0 rad is then refused as too narrow, not as "not greater than 0°".
fn radians(degrees: f32) -> f32 {
    let r = degrees.to_radians();
    if degrees > 0.0 && r == 0.0 {
        f32::from_bits(1)
    } else {
        r
    }
}

/// `count` and the noun, singular for 1.
fn count_of(count: usize, noun: &str) -> String {
    if count == 1 {
        format!("1 {noun}")
    } else {
        format!("{count} {noun}s")
    }
}

/// An array of tables (`[[sphere]]`, `[[light]]`, `[[plane]]`), refused as soon as it
/// has more than `N` entries: entry `N + 1` is skipped unread, nothing after it is
/// looked at.
fn capped<'de, D: Deserializer<'de>, T: Deserialize<'de> + Noun, const N: usize>(
    d: D,
) -> Result<Vec<T>, D::Error> {
    struct Capped<T, const N: usize>(PhantomData<T>);
    impl<'de, T: Deserialize<'de> + Noun, const N: usize> Visitor<'de> for Capped<T, N> {
        type Value = Vec<T>;
        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            write!(f, "an array of [[{}]] tables", T::NOUN)
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
            let mut entries = Vec::new();
            while entries.len() < N {
                match seq.next_element()? {
                    Some(entry) => entries.push(entry),
                    None => return Ok(entries),
                }
            }
            if seq.next_element::<IgnoredAny>()?.is_some() {
                let verb = if N == 1 { "is" } else { "are" };
                return Err(de::Error::custom(format_args!(
                    "more than {}: at most {N} {verb} supported",
                    count_of(N, T::NOUN)
                )));
            }
            Ok(entries)
        }
    }
    d.deserialize_seq(Capped::<T, N>(PhantomData))
}

/// A TOML date-time where `what` was expected: toml hands it to a visitor as a map,
/// which serde would report as "invalid type: map".
fn date_or_map<'de, A: MapAccess<'de>>(map: A, what: &dyn de::Expected) -> A::Error {
    match toml::value::Datetime::deserialize(de::value::MapAccessDeserializer::new(map)) {
        Ok(date) => de::Error::custom(format_args!("invalid type: date-time {date}, expected {what}")),
        Err(_) => de::Error::invalid_type(Unexpected::Map, what),
    }
}

/// An array of exactly `N` values: more or fewer is an error naming both counts.
struct Exact<T, const N: usize>([T; N]);

impl<'de, T: Deserialize<'de>, const N: usize> Deserialize<'de> for Exact<T, N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct ExactVisitor<T, const N: usize>(PhantomData<T>);
        impl<'de, T: Deserialize<'de>, const N: usize> Visitor<'de> for ExactVisitor<T, N> {
            type Value = Exact<T, N>;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "an array of {N} values")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
                let mut values = Vec::with_capacity(N);
                while values.len() < N {
                    match seq.next_element()? {
                        Some(value) => values.push(value),
                        None => break,
                    }
                }
                // Count what is beyond the N-th value without reading it as a T.
                let mut found = values.len();
                while seq.next_element::<IgnoredAny>()?.is_some() {
                    found += 1;
                }
                match <[T; N]>::try_from(values) {
                    Ok(array) if found == N => Ok(Exact(array)),
                    _ => Err(de::Error::custom(format_args!(
                        "expected {N} values, found {found}"
                    ))),
                }
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Self::Value, A::Error> {
                Err(date_or_map(map, &self))
            }
        }
        d.deserialize_any(ExactVisitor(PhantomData))
    }
}

/// A number that `f32` holds: an integer, or a float whose magnitude is neither above
/// `f32::MAX` nor so small that it would round to 0 (`nan` and `inf` pass through, for
/// the camera and sphere checks to report as not finite).
struct F32(f32);

impl<'de> Deserialize<'de> for F32 {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct F32Visitor;
        impl<'de> Visitor<'de> for F32Visitor {
            type Value = F32;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a number")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<F32, E> {
                let single = v as f32;
                if v.is_finite() && single.is_infinite() {
                    return Err(E::custom(format_args!(
                        "{v:e} is outside the f32 range (largest magnitude {:e})",
                        f32::MAX
                    )));
                }
                if v != 0.0 && single == 0.0 {
                    return Err(E::custom(format_args!(
                        "{v:e} is outside the f32 range (it rounds to 0; smallest magnitude {:e})",
                        f32::from_bits(1)
                    )));
                }
                Ok(F32(single))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<F32, E> {
                Ok(F32(v as f32))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<F32, E> {
                Ok(F32(v as f32))
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<F32, A::Error> {
                Err(date_or_map(map, &self))
            }
        }
        d.deserialize_any(F32Visitor)
    }
}

/// An unsigned integer field (`u8` colour channel, `u32` size).
struct Int<T>(T);

impl<'de, T: TryFrom<u64> + Bounded> Deserialize<'de> for Int<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct IntVisitor<T>(PhantomData<T>);
        impl<'de, T: TryFrom<u64> + Bounded> Visitor<'de> for IntVisitor<T> {
            type Value = Int<T>;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "an integer from 0 to {}", T::MAX)
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Int<T>, E> {
                T::try_from(v)
                    .map(Int)
                    .map_err(|_| E::invalid_value(Unexpected::Unsigned(v), &self))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Int<T>, E> {
                match u64::try_from(v) {
                    Ok(v) => self.visit_u64(v),
                    Err(_) => Err(E::invalid_value(Unexpected::Signed(v), &self)),
                }
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Int<T>, A::Error> {
                Err(date_or_map(map, &self))
            }
        }
        d.deserialize_any(IntVisitor(PhantomData))
    }
}

/// The largest value of an [`Int`] field, for its messages.
trait Bounded {
    const MAX: u64;
}

impl Bounded for u8 {
    const MAX: u64 = u8::MAX as u64;
}

impl Bounded for u32 {
    const MAX: u64 = u32::MAX as u64;
}

/// `max_depth`: any integer `≥ 0`, held saturated at 255 so that every value above
/// [`MAX_DEPTH`](crate::MAX_DEPTH) gets the settings check's "at most" message.
struct Depth(u8);

impl<'de> Deserialize<'de> for Depth {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct DepthVisitor;
        impl<'de> Visitor<'de> for DepthVisitor {
            type Value = Depth;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "an integer from 0 to {}", crate::MAX_DEPTH)
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Depth, E> {
                Ok(Depth(u8::try_from(v).unwrap_or(u8::MAX)))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Depth, E> {
                match u64::try_from(v) {
                    Ok(v) => self.visit_u64(v),
                    Err(_) => Err(E::invalid_value(Unexpected::Signed(v), &self)),
                }
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Depth, A::Error> {
                Err(date_or_map(map, &self))
            }
        }
        d.deserialize_any(DepthVisitor)
    }
}

/// Parses a scene file's text into a scene with capacities `N` spheres, `L` lights,
/// `P` planes and reflection depth `D`, and its camera.
pub fn parse<const N: usize, const L: usize, const P: usize, const D: usize>(
    text: &str,
) -> Result<SceneFile<N, L, P, D>, SceneFileError> {
    let raw: RawScene<N, L, P> = deserialize(text)?;

    let c = &raw.camera;
    let up = c.up.as_ref().map_or(Vec3::new(0.0, 1.0, 0.0), vec3);
    let size = Size::new(c.width.0, c.height.0);
    let mut params = CameraParams::new(vec3(&c.eye), vec3(&c.look_at), up, radians(c.fov_y_deg.0), size);
    if let Some(fov_x) = &c.fov_x_deg {
        params = params.with_fov_x(radians(fov_x.0));
    }
    let camera = params
        .build()
        .map_err(|e| SceneFileError::field(camera_field(e, size), e))?;

    let background = raw.background.as_ref().map_or(Rgb888::new(0, 0, 0), rgb);
    let mut scene = Scene::new(background);
    // Settings only when the file names one: otherwise the scene type's defaults stand.
    if raw.ambient.is_some() || raw.max_depth.is_some() || raw.shadows.is_some() {
        let d = scene.settings();
        let settings = Settings {
            ambient: raw.ambient.as_ref().map_or(d.ambient, |a| a.0),
            max_depth: raw.max_depth.as_ref().map_or(d.max_depth, |m| m.0),
            shadows: raw.shadows.unwrap_or(d.shadows),
        };
        scene.set_settings(settings).map_err(|e| {
            let key = match e {
                SceneError::Settings(s) => s.file_key(),
                // `set_settings` refuses nothing but settings; the depth is what the
                // scene type limits.
                _ => "max_depth",
            };
            SceneFileError::field(key, e)
        })?;
    }
    for (k, s) in raw.sphere.iter().enumerate() {
        let center = vec3(&s.center);
        let sphere = Sphere::new(center, s.radius.0, rgb(&s.color))
            .with_material(material(&s.specular, &s.shininess, &s.reflect))
            .check()
            .map_err(|e| {
                let key = match e {
                    SphereError::NotFinite if !center.is_finite() => "center",
                    SphereError::NotFinite | SphereError::RadiusNotPositive => "radius",
                    SphereError::Material(m) => m.file_key(),
                };
                SceneFileError::field(format!("sphere[{k}].{key}"), e)
            })?;
        scene
            .push(sphere)
            .map_err(|e| refused(format!("sphere[{k}]"), e))?;
    }
    for (k, l) in raw.light.iter().enumerate() {
        let light =
            light(l).map_err(|(key, reason)| SceneFileError::field(format!("light[{k}].{key}"), reason))?;
        scene
            .push_light(light)
            .map_err(|e| refused(format!("light[{k}]"), e))?;
    }
    for (k, p) in raw.plane.iter().enumerate() {
        let plane =
            plane(p).map_err(|(key, reason)| SceneFileError::field(format!("plane[{k}].{key}"), reason))?;
        scene
            .push_plane(plane)
            .map_err(|e| refused(format!("plane[{k}]"), e))?;
    }
    let animation = animation(&raw, scene.spheres().len())?;
    Ok(SceneFile {
        scene,
        camera,
        animation,
    })
}

/// The checked animation of a file with `spheres` spheres: its motions in file order,
/// the frame rate (default [`DEFAULT_FPS`]) and the frames (default one loop of the
/// longest period, [`Animation::frames_for`]).
fn animation<const N: usize, const L: usize, const P: usize>(
    raw: &RawScene<N, L, P>,
    spheres: usize,
) -> Result<Animation<MAX_MOTIONS>, SceneFileError> {
    let mut animation = Animation::new();
    let mut longest = 0.0f32;
    for (k, m) in raw.motion.iter().enumerate() {
        let field = |key: &str, reason: &dyn ToString| {
            SceneFileError::field(format!("motion[{k}].{key}"), reason.to_string())
        };
        let m = motion(m, spheres).map_err(|(key, reason)| field(key, &reason))?;
        animation.push(m).map_err(|e| field(e.file_key(), &e))?;
        longest = longest.max(m.period());
    }
    let timing = raw.animation.as_ref();
    let fps = timing.and_then(|a| a.fps.as_ref()).map_or(DEFAULT_FPS, |f| f.0);
    let frames = timing
        .and_then(|a| a.frames.as_ref())
        .map_or_else(|| Animation::<MAX_MOTIONS>::frames_for(longest, fps), |f| f.0);
    let animation = animation.with_fps(fps).with_frames(frames);
    animation
        .check()
        .map_err(|e| SceneFileError::field(format!("animation.{}", e.file_key()), e))?;
    Ok(animation)
}

/// A motion from its table, or the key to blame and why. The `kind` decides which keys
/// it takes; a key of another kind is refused rather than ignored.
fn motion(m: &RawMotion, spheres: usize) -> Result<Motion, (&'static str, String)> {
    let kind = m.kind.name();
    let takes: &[&str] = match m.kind {
        MotionKind::Circle => &["sphere", "center", "radius", "phase"],
        MotionKind::Bounce => &["sphere", "height"],
        MotionKind::Orbit => &[],
    };
    let given = [
        ("sphere", m.sphere.is_some()),
        ("center", m.center.is_some()),
        ("radius", m.radius.is_some()),
        ("phase", m.phase.is_some()),
        ("height", m.height.is_some()),
    ];
    for (key, present) in given {
        if present && !takes.contains(&key) {
            let a = if kind == "orbit" { "an" } else { "a" };
            return Err((key, format!("{a} {kind} has no {key}")));
        }
        if !present && takes.contains(&key) && key != "phase" {
            return Err((key, format!("a {kind} needs a `{key}`")));
        }
    }
    let sphere = match &m.sphere {
        Some(s) => {
            let k = s.0 as usize;
            if k >= spheres {
                return Err((
                    "sphere",
                    format!(
                        "the scene has no sphere[{k}] (it has {})",
                        count_of(spheres, "sphere")
                    ),
                ));
            }
            k
        }
        None => 0,
    };
    let number = |v: &Option<F32>| v.as_ref().map_or(0.0, |v| v.0);
    let motion = match m.kind {
        MotionKind::Circle => Motion::Circle(Circle::new(
            sphere,
            m.center.as_ref().map_or(Vec3::ZERO, vec3),
            number(&m.radius),
            m.period.0,
            number(&m.phase),
        )),
        MotionKind::Bounce => Motion::Bounce(Bounce::new(sphere, number(&m.height), m.period.0)),
        MotionKind::Orbit => Motion::Orbit(Orbit::new(m.period.0)),
    };
    motion.check(0).map_err(|e| (e.file_key(), e.to_string()))
}

/// A checked light from its table, or the key to blame and why. The `type` decides
/// which of `direction` and `position` it takes; the other one is refused rather than
/// ignored (a point light with a `direction` is most likely a directional light whose
/// `type` was mistyped).
fn light(l: &RawLight) -> Result<Light, (&'static str, String)> {
    let (kind, own, other, value, stray) = match l.kind {
        LightKind::Directional => ("directional", "direction", "position", &l.direction, &l.position),
        LightKind::Point => ("point", "position", "direction", &l.position, &l.direction),
    };
    if stray.is_some() {
        return Err((other, format!("a {kind} light has no {other} (give `{own}`)")));
    }
    let Some(value) = value else {
        return Err((own, format!("a {kind} light needs a `{own}`")));
    };
    let intensity = l.intensity.as_ref().map_or(1.0, |i| i.0);
    let light = match l.kind {
        LightKind::Directional => Light::directional(vec3(value), intensity),
        LightKind::Point => Light::point(vec3(value), intensity),
    };
    light.check().map_err(|e| {
        let key = match e {
            LightError::NotFinite => own,
            LightError::ZeroDirection | LightError::Intensity => e.file_key(),
        };
        (key, e.to_string())
    })
}

/// A checked plane from its table, or the key to blame and why.
fn plane(p: &RawPlane) -> Result<Plane, (&'static str, String)> {
    let point = vec3(&p.point);
    let mut plane = Plane::new(point, vec3(&p.normal), rgb(&p.color)).with_material(material(
        &p.specular,
        &p.shininess,
        &p.reflect,
    ));
    match (&p.checker, &p.checker_size) {
        (Some(second), size) => plane = plane.with_checker(rgb(second), size.as_ref().map_or(1.0, |s| s.0)),
        // A size alone would be silently unused: most likely `checker` was forgotten.
        (None, Some(_)) => {
            return Err((
                "checker_size",
                "checker_size needs a second colour `checker`".to_string(),
            ))
        }
        (None, None) => {}
    }
    plane.check().map_err(|e| {
        let key = match e {
            PlaneError::NotFinite if !point.is_finite() => "point",
            PlaneError::NotFinite => "normal",
            _ => e.file_key(),
        };
        (key, e.to_string())
    })
}

/// A checked object the scene refused: a mirror in a type without reflection depth
/// blames `reflect`; anything else (a full scene, which the capped arrays already
/// prevent) blames the object.
fn refused(object: String, e: SceneError) -> SceneFileError {
    match e {
        SceneError::MirrorWithoutDepth => SceneFileError::field(format!("{object}.reflect"), e),
        _ => SceneFileError::field(object, e),
    }
}

/// Reads and parses a scene file; errors carry the path.
///
/// Only a regular file is read (a FIFO would block, a device like `/dev/zero` never
/// ends), and at most [`MAX_FILE_SIZE`] bytes of it.
pub fn load<const N: usize, const L: usize, const P: usize, const D: usize>(
    path: impl AsRef<Path>,
) -> Result<SceneFile<N, L, P, D>, SceneFileError> {
    let path = path.as_ref();
    let with_path = |mut e: SceneFileError| {
        e.path = Some(path.to_path_buf());
        e
    };
    let text = read_capped(path).map_err(|reason| {
        with_path(SceneFileError {
            path: None,
            field: None,
            line: None,
            reason,
        })
    })?;
    parse(&text).map_err(with_path)
}

/// The text of a regular file of at most [`MAX_FILE_SIZE`] bytes.
fn read_capped(path: &Path) -> Result<String, String> {
    let too_large =
        || format!("the file is larger than {MAX_FILE_SIZE} bytes (1 MiB), the limit for a scene file");
    // Look before opening: opening a FIFO would already block.
    let meta = fs::metadata(path).map_err(|e| format!("cannot read the file: {e}"))?;
    if !meta.is_file() {
        let kind = if meta.is_dir() {
            "a directory"
        } else {
            "a device, FIFO or socket"
        };
        return Err(format!(
            "not a regular file ({kind}): a scene must be a regular file"
        ));
    }
    if meta.len() > MAX_FILE_SIZE {
        return Err(too_large());
    }
    // The file may have grown since: read at most one byte past the limit.
    let mut bytes = Vec::new();
    fs::File::open(path)
        .and_then(|file| file.take(MAX_FILE_SIZE + 1).read_to_end(&mut bytes))
        .map_err(|e| format!("cannot read the file: {e}"))?;
    if bytes.len() as u64 > MAX_FILE_SIZE {
        return Err(too_large());
    }
    String::from_utf8(bytes).map_err(|e| {
        format!(
            "not UTF-8 text (invalid byte at offset {})",
            e.utf8_error().valid_up_to()
        )
    })
}

/// The scene-file key of a camera error, as `camera.<key>`; a resolution error names
/// the dimension that is out of range.
fn camera_field(e: CameraError, size: Size) -> String {
    let key = match e {
        CameraError::ZeroResolution if size.width == 0 => "width",
        CameraError::ResolutionTooLarge if size.width > crate::camera::MAX_RESOLUTION => "width",
        CameraError::ZeroResolution | CameraError::ResolutionTooLarge => "height",
        _ => e.file_key(),
    };
    format!("camera.{key}")
}

/// The deepest nesting of arrays and inline tables a scene file has a use for: an
/// inline array of tables whose values are arrays (`sphere = [{ center = [0, 0, 0] }]`).
const MAX_NESTING: usize = 3;

/// Twice what a scene of `n` spheres, `l` lights, `p` planes and [`MAX_MOTIONS`] motions can hold, counted as
/// the pre-check counts: keys (`=`) and separators (`,`), and table headers. A plane,
/// the largest object, has 8 keys and 4 arrays of 3 (8 separators, a trailing comma
/// each: 4 more), 20 in all; the camera 7 keys and 3 arrays, the top level 4 keys and 1
/// array. Twice, plus a margin: a file a little over a capacity still reaches the
/// parser, whose error names the count ("more than 2 spheres"); one far over it, which
/// could only be hostile, is refused without being parsed.
fn scene_bounds(n: usize, l: usize, p: usize) -> (usize, usize) {
    // Motions count as objects: a motion table is smaller than a plane's.
    let objects = n.saturating_add(l).saturating_add(p).saturating_add(MAX_MOTIONS);
    let entries = objects.saturating_mul(40).saturating_add(256);
    // One header per object and `[camera]`, twice, and a margin.
    let headers = objects.saturating_mul(2).saturating_add(16);
    (entries, headers)
}

/// Rejects, before the TOML parser builds anything, a text that cannot be a scene of
/// these capacities: nesting deeper than [`MAX_NESTING`], or more keys, values or
/// table headers than [`scene_bounds`] allows. So the parser's memory is bounded by
/// that many small values whatever the file (1 MiB of `[[`, of `{`, or one array of half
/// a million numbers is refused here, at a scan's cost). The scan skips strings and
/// comments as TOML defines them; it need not be exact elsewhere, only never refuse a
/// valid scene: every count it makes is at least what the parser would see.
fn precheck(text: &str, n: usize, l: usize, p: usize) -> Result<(), SceneFileError> {
    let (max_entries, max_headers) = scene_bounds(n, l, p);
    let (mut depth, mut entries, mut headers, mut line) = (0usize, 0usize, 0usize, 1usize);
    let mut line_start = true;
    let mut chars = text.chars().peekable();
    let too_many = |what: &str, line: usize| SceneFileError {
        path: None,
        field: None,
        line: Some(line),
        reason: format!(
            "more {what} than a scene of {n} spheres, {l} lights and {p} planes can hold \
             (checked before parsing, at most {})",
            if what == "table headers" {
                max_headers
            } else {
                max_entries
            }
        ),
    };
    while let Some(c) = chars.next() {
        match c {
            '\n' => {
                line += 1;
                line_start = true;
                continue;
            }
            ' ' | '\t' | '\r' => continue,
            '#' => {
                // A comment runs to the end of the line.
                while chars.peek().is_some_and(|&c| c != '\n') {
                    chars.next();
                }
                continue;
            }
            '"' | '\'' => {
                // A string: basic ones have escapes; either kind may be multi-line
                // (three quotes), which only the closing three quotes end.
                let triple = chars.peek() == Some(&c) && {
                    let mut ahead = chars.clone();
                    ahead.next();
                    ahead.peek() == Some(&c)
                };
                if triple {
                    chars.next();
                    chars.next();
                }
                let mut run = 0;
                while let Some(d) = chars.next() {
                    if d == '\n' {
                        line += 1;
                    }
                    if d == '\\' && c == '"' {
                        chars.next();
                        run = 0;
                        continue;
                    }
                    if d == c {
                        run += 1;
                        if !triple || run == 3 {
                            break;
                        }
                    } else {
                        run = 0;
                        if !triple && d == '\n' {
                            break;
                        }
                    }
                }
            }
            '[' if line_start && depth == 0 => {
                // A table header, `[name]` or `[[name]]`: one more table.
                headers += 1;
                if headers > max_headers {
                    return Err(too_many("table headers", line));
                }
                while chars.peek().is_some_and(|&c| c != '\n') {
                    chars.next();
                }
            }
            '[' | '{' => {
                depth += 1;
                if depth > MAX_NESTING {
                    return Err(SceneFileError {
                        path: None,
                        field: None,
                        line: Some(line),
                        reason: format!(
                            "arrays and inline tables nested {depth} deep: no scene field nests deeper than {MAX_NESTING}"
                        ),
                    });
                }
            }
            ']' | '}' => depth = depth.saturating_sub(1),
            '=' | ',' => {
                entries += 1;
                if entries > max_entries {
                    return Err(too_many("keys and values", line));
                }
            }
            _ => {}
        }
        line_start = false;
    }
    Ok(())
}

/// The table a byte offset of the text lies in, as the error paths name it: `""` at
/// the top level, `camera`, or `light[1]` for the second `[[light]]`.
fn table_at(text: &str, offset: usize) -> String {
    let mut current = String::new();
    let mut counts: Vec<(String, usize)> = Vec::new();
    for line in text.get(..offset).unwrap_or(text).lines() {
        let line = line.trim();
        if let Some(name) = line.strip_prefix("[[").and_then(|r| r.split("]]").next()) {
            let name = name.trim().to_string();
            let k = match counts.iter_mut().find(|(n, _)| *n == name) {
                Some((_, k)) => {
                    *k += 1;
                    *k
                }
                None => {
                    counts.push((name.clone(), 0));
                    0
                }
            };
            current = format!("{name}[{k}]");
        } else if let Some(name) = line.strip_prefix('[').and_then(|r| r.split(']').next()) {
            current = name.trim().to_string();
        }
    }
    current
}

/// TOML → raw structs, with the failing field's path and line.
fn deserialize<const N: usize, const L: usize, const P: usize>(
    text: &str,
) -> Result<RawScene<N, L, P>, SceneFileError> {
    precheck(text, N, L, P)?;
    let line_of = |e: &toml::de::Error| {
        e.span()
            .map(|s| text.get(..s.start).unwrap_or(text).matches('\n').count() + 1)
    };
    let de = toml::Deserializer::parse(text).map_err(|e| {
        let reason = e.message().trim();
        // The parser names neither the key nor its table for a duplicate: both are
        // at its span (the second occurrence's key).
        let field = e
            .span()
            .filter(|_| reason.contains("duplicate key"))
            .and_then(|span| {
                let key = text
                    .get(span.clone())?
                    .trim()
                    .trim_matches(|c| c == '"' || c == '\'');
                let table = table_at(text, span.start);
                Some(if table.is_empty() {
                    key.to_string()
                } else {
                    format!("{table}.{key}")
                })
            });
        let reason = match &field {
            Some(_) => "not valid TOML: duplicate key (given twice in its table)".to_string(),
            None => format!("not valid TOML: {reason}"),
        };
        SceneFileError {
            path: None,
            field,
            line: line_of(&e),
            reason,
        }
    })?;
    serde_path_to_error::deserialize(de).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.inner();
        SceneFileError {
            path: None,
            field: (path != ".").then_some(path),
            line: line_of(inner),
            reason: inner.message().trim().to_string(),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"
background = [10, 20, 30]
[camera]
eye = [0.0, 0.0, 5.0]
look_at = [0.0, 0.0, 0.0]
fov_y_deg = 60.0
width = 32
height = 24
[[sphere]]
center = [0.0, 0.0, 0.0]
radius = 1.0
color = [255, 64, 64]
"#;

    fn err(text: &str) -> SceneFileError {
        match parse::<4, 0, 0, 0>(text) {
            Ok(_) => panic!("accepted:\n{text}"),
            Err(e) => e,
        }
    }

    #[test]
    fn parses_the_documented_format() {
        let f = parse::<4, 0, 0, 0>(GOOD).unwrap();
        assert_eq!(f.scene.spheres().len(), 1);
        assert_eq!(f.scene.background(), Rgb888::new(10, 20, 30));
        assert_eq!(f.camera.size(), Size::new(32, 24));
        assert_eq!(f.camera.params().up, Vec3::new(0.0, 1.0, 0.0));
    }

    #[test]
    fn a_duplicate_key_names_the_key_and_its_table() {
        let text = format!(
            "{GOOD}[[light]]\ntype = \"point\"\nposition = [0.0, 1.0, 0.0]\n\
             [[light]]\ntype = \"point\"\nposition = [0.0, 1.0, 0.0]\nintensity = 1.0\nintensity = 2.0\n"
        );
        let e = match parse::<4, 2, 0, 0>(&text) {
            Ok(_) => panic!("accepted"),
            Err(e) => e,
        };
        assert_eq!(e.field.as_deref(), Some("light[1].intensity"), "{e}");
        assert!(e.reason.contains("duplicate key"), "{e}");
        assert_eq!(e.line, Some(GOOD.lines().count() + 8), "{e}");
        // At the top level and in a plain table, too.
        let e = err(&GOOD.replace("width = 32", "width = 32\nwidth = 33"));
        assert_eq!(e.field.as_deref(), Some("camera.width"), "{e}");
        let e = err(&format!("background = [0, 0, 0]\n{GOOD}"));
        assert_eq!(e.field.as_deref(), Some("background"), "{e}");
    }

    #[test]
    fn a_light_type_of_another_type_names_the_choices() {
        let text = format!("{GOOD}[[light]]\ntype = 5\ndirection = [0.0, -1.0, 0.0]\n");
        let e = match parse::<4, 1, 0, 0>(&text) {
            Ok(_) => panic!("accepted"),
            Err(e) => e,
        };
        assert_eq!(e.field.as_deref(), Some("light[0].type"), "{e}");
        assert!(
            e.reason.contains("integer `5`") && e.reason.contains("\"directional\" or \"point\""),
            "{e}"
        );
        let text = format!("{GOOD}[[light]]\ntype = \"spot\"\ndirection = [0.0, -1.0, 0.0]\n");
        let e = match parse::<4, 1, 0, 0>(&text) {
            Ok(_) => panic!("accepted"),
            Err(e) => e,
        };
        assert_eq!(e.field.as_deref(), Some("light[0].type"), "{e}");
        assert!(
            e.reason.contains("\"spot\"") && e.reason.contains("\"directional\" or \"point\""),
            "{e}"
        );
    }

    /// A megabyte of one array, of nested brackets or of table headers is refused by
    /// the pre-check, before the parser allocates a value for it.
    #[test]
    fn hostile_files_are_refused_before_parsing() {
        let numbers = format!("{GOOD}x = [{}]\n", "1, ".repeat(523_901));
        let e = match parse::<256, 8, 8, 8>(&numbers) {
            Ok(_) => panic!("accepted"),
            Err(e) => e,
        };
        assert!(
            e.reason
                .contains("more keys and values than a scene of 256 spheres"),
            "{e}"
        );

        let nested = format!("{GOOD}y = {}{}\n", "[".repeat(200_000), "]".repeat(200_000));
        let e = match parse::<256, 8, 8, 8>(&nested) {
            Ok(_) => panic!("accepted"),
            Err(e) => e,
        };
        assert!(e.reason.contains("nested 4 deep"), "{e}");
        assert_eq!(e.line, Some(GOOD.lines().count() + 1), "{e}");

        let tables = format!("{GOOD}{}", "[[z]]\n".repeat(170_000));
        let e = match parse::<256, 8, 8, 8>(&tables) {
            Ok(_) => panic!("accepted"),
            Err(e) => e,
        };
        assert!(e.reason.contains("more table headers"), "{e}");
    }

    /// The pre-check never refuses a scene the parser accepts: the fullest scene of
    /// each capacity (every object at its capacity with every key, trailing commas,
    /// comments and strings holding what the scan counts, the inline-table form)
    /// passes it and parses.
    #[test]
    fn the_precheck_takes_the_fullest_scenes() {
        let sphere = "[[sphere]] # a [[comment]], = , {\ncenter = [0.0, 0.0, -5.0,]\nradius = 0.5\n\
                      color = [1, 2, 3,]\nspecular = 0.5\nshininess = 8.0\nreflect = 0.5\n";
        let light = "[[light]]\ntype = \"point\"\nposition = [0.0, 5.0, 0.0,]\nintensity = 0.5\n";
        let plane = "[[plane]]\npoint = [0.0, -1.0, 0.0,]\nnormal = [0.0, 1.0, 0.0,]\ncolor = [9, 9, 9,]\n\
                     checker = [1, 1, 1,]\nchecker_size = 1.0\nspecular = 0.1\nshininess = 4.0\nreflect = 0.2\n";
        let top = "background = [0, 0, 0,]\nambient = 0.1\nmax_depth = 8\nshadows = true\n\
                   [camera]\neye = [0.0, 0.0, 5.0,]\nlook_at = [0.0, 0.0, 0.0,]\nup = [0.0, 1.0, 0.0,]\n\
                   fov_y_deg = 60.0\nfov_x_deg = 70.0\nwidth = 32\nheight = 24\n";
        let text = format!(
            "{top}{}{}{}",
            sphere.repeat(256),
            light.repeat(8),
            plane.repeat(8)
        );
        let file = parse::<256, 8, 8, 8>(&text).unwrap_or_else(|e| panic!("{e}"));
        let counts = (
            file.scene.spheres().len(),
            file.scene.lights().len(),
            file.scene.planes().len(),
        );
        assert_eq!(counts, (256, 8, 8));
        assert!(parse::<1, 1, 1, 8>(&format!("{top}{sphere}{light}{plane}")).is_ok());

        // Inline tables, one line per sphere, beside comments that hold brackets,
        // commas, equals signs and quotes.
        let top_keys = "background = [0, 0, 0,] # \"[{,=\" '''[[x]]'''\nambient = 0.1\nmax_depth = 8\n";
        let camera = "[camera]\neye = [0.0, 0.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_y_deg = 60.0\nwidth = 32\nheight = 24\n";
        let inline = "{ center = [0.0, 0.0, -5.0,], radius = 0.5, color = [1, 2, 3,], specular = 0.5, shininess = 8.0, reflect = 0.5 }";
        let text = format!(
            "{top_keys}sphere = [\n{},\n]\n{camera}{}{}",
            [inline; 256].join(",\n"),
            light.repeat(8),
            plane.repeat(8)
        );
        let file = parse::<256, 8, 8, 8>(&text).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(file.scene.spheres().len(), 256);
    }

    #[test]
    fn errors_name_field_and_line() {
        let e = err(&GOOD.replace("width = 32", "width = 32\nzoom = 2"));
        assert_eq!(e.field.as_deref(), Some("camera.zoom"));
        assert!(e.reason.contains("unknown field `zoom`"), "{e}");
        assert_eq!(e.line, Some(8));

        let e = err(&GOOD.replace("width = 32", "width = \"wide\""));
        assert_eq!(e.field.as_deref(), Some("camera.width"), "{e}");
        assert_eq!(e.line, Some(7));

        let e = err(&GOOD.replace("eye = [0.0, 0.0, 5.0]\n", ""));
        assert!(e.reason.contains("missing field `eye`"), "{e}");

        let e = err(&GOOD.replace("radius = 1.0", "radius = 0.0"));
        assert_eq!(e.to_string(), "sphere[0].radius: radius must be greater than 0");

        let e = err(&GOOD.replace("[255, 64, 64]", "[256, 64, 64]"));
        assert_eq!(e.field.as_deref(), Some("sphere[0].color[0]"), "{e}");

        let e = err(&GOOD.replace("fov_y_deg = 60.0", "fov_y_deg = 180.0"));
        assert_eq!(e.field.as_deref(), Some("camera.fov_y_deg"));

        let e = err(&GOOD.replace("look_at = [0.0, 0.0, 0.0]", "look_at = [0.0, 0.0, 5.0]"));
        assert_eq!(e.field.as_deref(), Some("camera.look_at"));

        let e = err(&GOOD.replace("fov_y_deg", "up = [0.0, 0.0, 2.0]\nfov_y_deg"));
        assert_eq!(e.field.as_deref(), Some("camera.up"));

        let e = err(&GOOD.replace("height = 24", "height = 0"));
        assert_eq!(e.field.as_deref(), Some("camera.height"));
        let e = err(&GOOD.replace("width = 32", "width = 9000"));
        assert_eq!(e.field.as_deref(), Some("camera.width"));

        let e = err("this is [not toml");
        assert!(e.reason.starts_with("not valid TOML"), "{e}");
        assert_eq!(e.line, Some(1));

        let e = err(&GOOD.replace("center = [0.0, 0.0, 0.0]", "center = [nan, 0.0, 0.0]"));
        assert_eq!(e.field.as_deref(), Some("sphere[0].center"));
    }

    #[test]
    fn too_many_spheres() {
        let sphere = GOOD.split_once("[[sphere]]").unwrap().1;
        let text = format!("{GOOD}[[sphere]]{sphere}[[sphere]]{sphere}");
        assert_eq!(parse::<3, 0, 0, 0>(&text).unwrap().scene.spheres().len(), 3);
        let e = parse::<2, 0, 0, 0>(&text).unwrap_err();
        assert_eq!(e.field.as_deref(), Some("sphere"));
        assert_eq!(e.reason, "more than 2 spheres: at most 2 are supported");
        assert_eq!(
            parse::<1, 0, 0, 0>(&text).unwrap_err().reason,
            "more than 1 sphere: at most 1 is supported"
        );
    }

    /// The count is checked while the array is read: a bad sphere after the N-th is
    /// never looked at, so the error is the count, not that sphere's field.
    #[test]
    fn sphere_count_is_checked_while_parsing() {
        let sphere = GOOD.split_once("[[sphere]]").unwrap().1;
        let bad = sphere.replace("radius = 1.0", "radius = \"big\"");
        let text = format!("{GOOD}[[sphere]]{sphere}[[sphere]]{bad}");
        assert_eq!(
            parse::<2, 0, 0, 0>(&text).unwrap_err().field.as_deref(),
            Some("sphere")
        );
        assert_eq!(
            parse::<3, 0, 0, 0>(&text).unwrap_err().field.as_deref(),
            Some("sphere[2].radius")
        );
    }

    #[test]
    fn every_fixed_length_array_has_exactly_its_length() {
        for (from, to, field, found) in [
            (
                "color = [255, 64, 64]",
                "color = [255, 64, 64, 1]",
                "sphere[0].color",
                4,
            ),
            (
                "eye = [0.0, 0.0, 5.0]",
                "eye = [0.0, 0.0, 5.0, 1.0]",
                "camera.eye",
                4,
            ),
            (
                "center = [0.0, 0.0, 0.0]",
                "center = [0, 0, 0, \"junk\"]",
                "sphere[0].center",
                4,
            ),
            (
                "background = [10, 20, 30]",
                "background = [10, 20, 30, 40]",
                "background",
                4,
            ),
            (
                "look_at = [0.0, 0.0, 0.0]",
                "look_at = [0.0, 0.0]",
                "camera.look_at",
                2,
            ),
            ("fov_y_deg", "up = []\nfov_y_deg", "camera.up", 0),
        ] {
            let e = err(&GOOD.replace(from, to));
            assert_eq!(e.field.as_deref(), Some(field), "{to}: {e}");
            assert_eq!(e.reason, format!("expected 3 values, found {found}"), "{to}");
        }
    }

    #[test]
    fn errors_blame_the_right_field_and_reason() {
        // Both sizes bad: each message names the dimension it is about.
        let both = GOOD.replace("width = 32", "width = 9000");
        let e = err(&both.replace("height = 24", "height = 0"));
        assert_eq!(
            e.to_string(),
            "camera.height: width and height must be at least 1"
        );
        let e = err(&GOOD
            .replace("width = 32", "width = 0")
            .replace("height = 24", "height = 9000"));
        assert_eq!(e.to_string(), "camera.width: width and height must be at least 1");
        let e = err(&GOOD.replace("height = 24", "height = 9000"));
        assert_eq!(e.field.as_deref(), Some("camera.height"));

        // Beyond f32: out of range, not "not finite"; the element is named.
        let e = err(&GOOD.replace("eye = [0.0, 0.0, 5.0]", "eye = [0.0, 0.0, 1e39]"));
        assert_eq!(e.field.as_deref(), Some("camera.eye[2]"));
        assert!(e.reason.contains("outside the f32 range"), "{e}");
        let e = err(&GOOD.replace("radius = 1.0", "radius = 1e-50"));
        assert!(e.reason.contains("outside the f32 range"), "{e}");
        // `inf` and `nan` are TOML floats: reported as not finite by the checks.
        let e = err(&GOOD.replace("radius = 1.0", "radius = inf"));
        assert_eq!(e.field.as_deref(), Some("sphere[0].radius"));

        // A field of view that underflows to 0 rad is too narrow, not "not > 0°".
        let e = err(&GOOD.replace("fov_y_deg = 60.0", "fov_y_deg = 1e-45"));
        assert_eq!(e.field.as_deref(), Some("camera.fov_y_deg"));
        assert!(e.reason.contains("too narrow"), "{e}");
        let e = err(&GOOD.replace("fov_y_deg = 60.0", "fov_y_deg = 0.0"));
        assert!(e.reason.contains("greater than 0"), "{e}");

        // A date where a number or array belongs is called a date.
        for (from, to, field) in [
            ("fov_y_deg = 60.0", "fov_y_deg = 1979-05-27", "camera.fov_y_deg"),
            ("width = 32", "width = 1979-05-27T07:32:00Z", "camera.width"),
            ("eye = [0.0, 0.0, 5.0]", "eye = 07:32:00", "camera.eye"),
            (
                "color = [255, 64, 64]",
                "color = [255, 1979-05-27, 64]",
                "sphere[0].color[1]",
            ),
        ] {
            let e = err(&GOOD.replace(from, to));
            assert_eq!(e.field.as_deref(), Some(field), "{to}: {e}");
            assert!(e.reason.starts_with("invalid type: date-time "), "{to}: {e}");
        }
        // An inline table is still called a map.
        let e = err(&GOOD.replace("radius = 1.0", "radius = { r = 1 }"));
        assert!(e.reason.contains("invalid type: map"), "{e}");

        // Far-away points and huge vectors are valid cameras, not "same point" or
        // "parallel".
        parse::<4, 0, 0, 0>(&GOOD.replace("eye = [0.0, 0.0, 5.0]", "eye = [0.0, 0.0, 1e20]")).unwrap();
        parse::<4, 0, 0, 0>(&GOOD.replace("fov_y_deg", "up = [0, 3e38, 3e38]\nfov_y_deg")).unwrap();
    }

    /// Every new key at a non-default value: two lights, a material, a checkered
    /// mirror floor and the settings.
    const LIT: &str = r#"
ambient = 0.2
max_depth = 3
shadows = false
[camera]
eye = [0.0, 0.0, 5.0]
look_at = [0.0, 0.0, 0.0]
fov_y_deg = 60.0
width = 32
height = 24
[[light]]
type = "directional"
direction = [-1.0, -2.0, -1.0]
intensity = 0.8
[[light]]
type = "point"
position = [2.0, 5.0, 3.0]
intensity = 0.5
[[sphere]]
center = [0.0, 0.0, 0.0]
radius = 1.0
color = [255, 64, 64]
specular = 0.5
shininess = 16
reflect = 0.3
[[plane]]
point = [0.0, -1.0, 0.0]
normal = [0.0, 2.0, 0.0]
color = [220, 220, 220]
checker = [40, 40, 40]
checker_size = 2.0
specular = 0.25
shininess = 8
reflect = 0.1
"#;

    /// The capacities the host tools load with, shrunk to the test files.
    type Full = SceneFile<4, 2, 2, 8>;

    fn full(text: &str) -> Result<Full, SceneFileError> {
        parse(text)
    }

    fn full_err(text: &str) -> SceneFileError {
        match full(text) {
            Ok(_) => panic!("accepted:\n{text}"),
            Err(e) => e,
        }
    }

    #[test]
    fn parses_lights_planes_materials_and_settings() {
        let f = full(LIT).unwrap();
        let scene = &f.scene;
        assert_eq!(
            scene.settings(),
            Settings {
                ambient: 0.2,
                max_depth: 3,
                shadows: false
            }
        );
        assert_eq!(scene.max_depth(), 3);
        assert_eq!(
            scene.lights(),
            [
                Light::directional(Vec3::new(-1.0, -2.0, -1.0), 0.8),
                Light::point(Vec3::new(2.0, 5.0, 3.0), 0.5)
            ]
        );
        assert_eq!(scene.spheres()[0].material, Material::new(0.5, 16.0, 0.3));
        let plane = Plane::new(
            Vec3::new(0.0, -1.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
            Rgb888::new(220, 220, 220),
        )
        .with_checker(Rgb888::new(40, 40, 40), 2.0)
        .with_material(Material::new(0.25, 8.0, 0.1));
        assert_eq!(scene.planes(), [plane]);
        assert!(f.has_features());
        assert!(f.spheres_only().is_none());
    }

    #[test]
    fn missing_new_keys_take_their_defaults() {
        let light = "[[light]]\ntype = \"point\"\nposition = [0.0, 4.0, 0.0]\n";
        let plane = "[[plane]]\npoint = [0.0, -1.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\ncolor = [1, 2, 3]\n";
        let f = full(&format!("{GOOD}{light}{plane}")).unwrap();
        assert_eq!(f.scene.lights()[0].intensity(), 1.0);
        assert_eq!(f.scene.spheres()[0].material, Material::DEFAULT);
        let p = f.scene.planes()[0];
        assert_eq!(
            (p.checker, p.checker_size, p.material),
            (None, 1.0, Material::DEFAULT)
        );
        assert_eq!(f.scene.settings(), Settings::DEFAULT);

        // A checker without a size: cells of side 1.
        let checkered = plane.replace("color = [1, 2, 3]", "color = [1, 2, 3]\nchecker = [9, 9, 9]");
        let p = full(&format!("{GOOD}{checkered}")).unwrap().scene.planes()[0];
        assert_eq!((p.checker, p.checker_size), (Some(Rgb888::new(9, 9, 9)), 1.0));

        // One setting given: the others keep their defaults.
        let f = full(&format!("shadows = false\n{GOOD}")).unwrap();
        assert_eq!(
            f.scene.settings(),
            Settings {
                shadows: false,
                ..Settings::DEFAULT
            }
        );
        let f = full(&format!("ambient = 0\nmax_depth = 8\n{GOOD}")).unwrap();
        assert_eq!((f.scene.settings().ambient, f.scene.max_depth()), (0.0, 8));

        // Without settings, a type with a shallower depth keeps its own default, also
        // when another setting is given.
        let f = parse::<4, 1, 1, 1>(GOOD).unwrap();
        assert_eq!(f.scene.settings().max_depth, 1);
        let f = parse::<4, 0, 0, 0>(&format!("ambient = 0.3\n{GOOD}")).unwrap();
        assert_eq!(
            (f.scene.settings().ambient, f.scene.settings().max_depth),
            (0.3, 0)
        );
    }

    /// A file without the new keys is the same scene and the same errors whatever the
    /// capacities it is loaded with, and converts back to the spheres-only type.
    #[test]
    fn files_without_new_keys_mean_what_they_meant() {
        let old = parse::<4, 0, 0, 0>(GOOD).unwrap();
        let new = full(GOOD).unwrap();
        assert_eq!(new.scene.spheres(), old.scene.spheres());
        assert_eq!(new.scene.background(), old.scene.background());
        assert!(new.scene.lights().is_empty() && new.scene.planes().is_empty());
        assert!(!new.has_features());
        let back = new.spheres_only().unwrap();
        assert_eq!(back.scene.spheres(), old.scene.spheres());
        assert_eq!(back.scene.background(), old.scene.background());
        assert_eq!(back.camera.params(), old.camera.params());

        // Highlights and settings without a light, plane or mirror change no pixel:
        // still the spheres-only scene.
        let shiny = format!(
            "ambient = 0.5\n{}",
            GOOD.replace("radius = 1.0", "radius = 1.0\nspecular = 1")
        );
        assert!(full(&shiny).unwrap().spheres_only().is_some());
        // A mirror alone is a feature (even at depth 0 it mixes in the background).
        let mirror = GOOD.replace("radius = 1.0", "radius = 1.0\nreflect = 0.5");
        assert!(full(&mirror).unwrap().spheres_only().is_none());

        for (from, to) in [
            ("width = 32", "width = 32\nzoom = 2"),
            ("width = 32", "width = \"wide\""),
            ("radius = 1.0", "radius = 0.0"),
            ("[255, 64, 64]", "[256, 64, 64]"),
            ("background = [10, 20, 30]", "background = [10, 20, 30]\nfog = 1"),
            ("fov_y_deg = 60.0", "fov_y_deg = 180.0"),
            ("center = [0.0, 0.0, 0.0]", "center = [nan, 0.0, 0.0]"),
        ] {
            let text = GOOD.replace(from, to);
            assert_eq!(full_err(&text), err(&text), "{to}");
        }
    }

    #[test]
    fn every_new_field_has_its_error() {
        for (from, to, field, reason) in [
            // Settings.
            (
                "ambient = 0.2",
                "ambient = 1.5",
                "ambient",
                "ambient must be between 0 and 1",
            ),
            (
                "ambient = 0.2",
                "ambient = -0.1",
                "ambient",
                "ambient must be between 0 and 1",
            ),
            (
                "ambient = 0.2",
                "ambient = nan",
                "ambient",
                "ambient must be between 0 and 1",
            ),
            (
                "max_depth = 3",
                "max_depth = 9",
                "max_depth",
                "max_depth must be at most 8",
            ),
            (
                "max_depth = 3",
                "max_depth = 1000",
                "max_depth",
                "max_depth must be at most 8",
            ),
            (
                "max_depth = 3",
                "max_depth = -1",
                "max_depth",
                "expected an integer from 0 to 8",
            ),
            (
                "max_depth = 3",
                "max_depth = 2.5",
                "max_depth",
                "invalid type: floating point",
            ),
            (
                "shadows = false",
                "shadows = 1",
                "shadows",
                "invalid type: integer",
            ),
            // Lights.
            (
                "direction = [-1.0, -2.0, -1.0]",
                "direction = [0.0, 0.0, 0.0]",
                "light[0].direction",
                "a directional light's direction must not be zero",
            ),
            (
                "direction = [-1.0, -2.0, -1.0]",
                "direction = [-1.0, inf, -1.0]",
                "light[0].direction",
                "must be finite",
            ),
            (
                "position = [2.0, 5.0, 3.0]",
                "position = [2.0, nan, 3.0]",
                "light[1].position",
                "must be finite",
            ),
            (
                "intensity = 0.8",
                "intensity = -0.5",
                "light[0].intensity",
                "intensity must be a finite number of at least 0",
            ),
            (
                "intensity = 0.5",
                "intensity = inf",
                "light[1].intensity",
                "at least 0",
            ),
            (
                "type = \"directional\"",
                "type = \"spot\"",
                "light[0].type",
                "invalid value: string \"spot\", expected \"directional\" or \"point\"",
            ),
            ("type = \"directional\"\n", "", "light[0]", "missing field `type`"),
            (
                "position = [2.0, 5.0, 3.0]",
                "direction = [2.0, 5.0, 3.0]",
                "light[1].direction",
                "a point light has no direction (give `position`)",
            ),
            (
                "position = [2.0, 5.0, 3.0]\n",
                "",
                "light[1].position",
                "a point light needs a `position`",
            ),
            (
                "direction = [-1.0, -2.0, -1.0]",
                "position = [-1.0, -2.0, -1.0]",
                "light[0].position",
                "a directional light has no position (give `direction`)",
            ),
            (
                "direction = [-1.0, -2.0, -1.0]\n",
                "",
                "light[0].direction",
                "a directional light needs a `direction`",
            ),
            (
                "direction = [-1.0, -2.0, -1.0]",
                "direction = [-1.0, -2.0]",
                "light[0].direction",
                "expected 3 values, found 2",
            ),
            (
                "intensity = 0.8",
                "color = [1, 2, 3]",
                "light[0].color",
                "unknown field `color`",
            ),
            // Sphere materials.
            (
                "specular = 0.5",
                "specular = 1.5",
                "sphere[0].specular",
                "specular must be between 0 and 1",
            ),
            (
                "shininess = 16",
                "shininess = 0.5",
                "sphere[0].shininess",
                "shininess must be a finite number of at least 1",
            ),
            (
                "reflect = 0.3",
                "reflect = -0.3",
                "sphere[0].reflect",
                "reflect must be between 0 and 1",
            ),
            // Planes.
            (
                "normal = [0.0, 2.0, 0.0]",
                "normal = [0.0, 0.0, 0.0]",
                "plane[0].normal",
                "the plane's normal must not be zero",
            ),
            (
                "normal = [0.0, 2.0, 0.0]",
                "normal = [0.0, nan, 0.0]",
                "plane[0].normal",
                "must be finite",
            ),
            (
                "point = [0.0, -1.0, 0.0]",
                "point = [0.0, -inf, 0.0]",
                "plane[0].point",
                "must be finite",
            ),
            (
                "checker_size = 2.0",
                "checker_size = 0.0",
                "plane[0].checker_size",
                "checker_size must be a finite number greater than 0",
            ),
            (
                "checker = [40, 40, 40]\n",
                "",
                "plane[0].checker_size",
                "checker_size needs a second colour `checker`",
            ),
            (
                "checker = [40, 40, 40]",
                "checker = [40, 40, 40, 40]",
                "plane[0].checker",
                "expected 3 values, found 4",
            ),
            (
                "checker = [40, 40, 40]",
                "checker = [40, 256, 40]",
                "plane[0].checker[1]",
                "invalid value",
            ),
            (
                "specular = 0.25",
                "specular = 2",
                "plane[0].specular",
                "specular must be between 0 and 1",
            ),
            (
                "shininess = 8",
                "shininess = 0",
                "plane[0].shininess",
                "shininess must be a finite number of at least 1",
            ),
            (
                "reflect = 0.1",
                "reflect = 1.01",
                "plane[0].reflect",
                "reflect must be between 0 and 1",
            ),
            (
                "normal = [0.0, 2.0, 0.0]\n",
                "",
                "plane[0]",
                "missing field `normal`",
            ),
            (
                "checker_size = 2.0",
                "size = 2.0",
                "plane[0].size",
                "unknown field `size`",
            ),
        ] {
            assert_eq!(LIT.matches(from).count(), 1, "{from}");
            let e = full_err(&LIT.replace(from, to));
            assert_eq!(e.field.as_deref(), Some(field), "{to}: {e}");
            assert!(e.reason.contains(reason), "{to}: {e}");
        }
        // The parser's own errors also give the line.
        let e = full_err(&LIT.replace("\"directional\"", "\"spot\""));
        assert_eq!(
            e.line,
            Some(
                LIT.lines()
                    .position(|l| l.contains("directional"))
                    .map(|l| l + 1)
                    .unwrap()
            )
        );
    }

    /// The capacities are the limits: too many lights or planes, a mirror or a depth
    /// the type cannot trace.
    #[test]
    fn the_scene_type_limits_lights_planes_and_mirrors() {
        let e = parse::<4, 1, 2, 8>(LIT).unwrap_err();
        assert_eq!(e.field.as_deref(), Some("light"));
        assert_eq!(e.reason, "more than 1 light: at most 1 is supported");
        let e = parse::<4, 0, 2, 8>(LIT).unwrap_err();
        assert_eq!(e.reason, "more than 0 lights: at most 0 are supported");

        let second = LIT.split_once("[[plane]]").unwrap().1;
        let e = parse::<4, 2, 1, 8>(&format!("{LIT}[[plane]]{second}")).unwrap_err();
        assert_eq!(e.field.as_deref(), Some("plane"));
        assert_eq!(e.reason, "more than 1 plane: at most 1 is supported");
        assert_eq!(
            parse::<4, 2, 2, 8>(&format!("{LIT}[[plane]]{second}"))
                .unwrap()
                .scene
                .planes()
                .len(),
            2
        );

        // A depth the type cannot trace.
        let e = parse::<4, 2, 2, 2>(LIT).unwrap_err();
        assert_eq!(e.to_string(), "max_depth: max_depth must be at most 2");

        // A mirror in a type without reflection depth: the sphere's, then the plane's.
        let shallow = LIT.replace("max_depth = 3\n", "");
        let e = parse::<4, 2, 2, 0>(&shallow).unwrap_err();
        assert_eq!(e.field.as_deref(), Some("sphere[0].reflect"));
        assert!(e.reason.contains("reflection depth"), "{e}");
        let e = parse::<4, 2, 2, 0>(&shallow.replace("reflect = 0.3\n", "")).unwrap_err();
        assert_eq!(e.field.as_deref(), Some("plane[0].reflect"));
        // reflect = 0 is no mirror.
        parse::<4, 2, 2, 0>(
            &shallow
                .replace("reflect = 0.3", "reflect = 0")
                .replace("reflect = 0.1", "reflect = 0"),
        )
        .unwrap();
    }

    /// Two spheres, one circling and one bouncing, and the camera orbiting.
    const MOVING: &str = r#"
[camera]
eye = [0.0, 2.0, 8.0]
look_at = [0.0, 0.0, 0.0]
fov_y_deg = 40.0
width = 32
height = 24
[animation]
fps = 30
frames = 90
[[sphere]]
center = [0.0, 1.0, 0.0]
radius = 1.0
color = [255, 64, 64]
[[sphere]]
center = [2.0, 0.5, 0.0]
radius = 0.5
color = [64, 64, 255]
[[motion]]
kind = "circle"
sphere = 1
center = [0.0, 0.5, 0.0]
radius = 2.0
period = 3.0
phase = 0.25
[[motion]]
kind = "bounce"
sphere = 0
height = 1.5
period = 1.0
[[motion]]
kind = "orbit"
period = 10.0
"#;

    #[test]
    fn parses_motions_and_timing() {
        let f = parse::<2, 0, 0, 0>(MOVING).unwrap();
        let want: Animation<3> = Animation::from_array([
            Motion::Circle(Circle::new(1, Vec3::new(0.0, 0.5, 0.0), 2.0, 3.0, 0.25)),
            Motion::Bounce(Bounce::new(0, 1.5, 1.0)),
            Motion::Orbit(Orbit::new(10.0)),
        ]);
        assert_eq!(f.animation.motions(), want.motions());
        assert_eq!((f.animation.fps(), f.animation.frames()), (30.0, 90));
        // Defaults: 25 frames a second, one loop of the longest period (10 s).
        let f = parse::<2, 0, 0, 0>(&MOVING.replace("fps = 30\nframes = 90\n", "")).unwrap();
        assert_eq!((f.animation.fps(), f.animation.frames()), (25.0, 250));
        // A file without motion: still, one frame.
        let f = parse::<4, 0, 0, 0>(GOOD).unwrap();
        assert!(f.animation.is_still());
        assert_eq!(f.animation.frames(), 1);
        assert_eq!(f.spheres_only().unwrap().animation, f.animation);
    }

    #[test]
    fn every_motion_field_has_its_error() {
        for (from, to, field, reason) in [
            (
                "period = 3.0",
                "period = 0",
                "motion[0].period",
                "period must be a finite number greater than 0",
            ),
            (
                "period = 1.0",
                "period = -1.0",
                "motion[1].period",
                "greater than 0",
            ),
            (
                "period = 10.0",
                "period = nan",
                "motion[2].period",
                "greater than 0",
            ),
            ("period = 10.0\n", "", "motion[2]", "missing field `period`"),
            (
                "sphere = 1",
                "sphere = 2",
                "motion[0].sphere",
                "the scene has no sphere[2] (it has 2 spheres)",
            ),
            (
                "sphere = 0",
                "sphere = -1",
                "motion[1].sphere",
                "expected an integer",
            ),
            (
                "sphere = 1\n",
                "",
                "motion[0].sphere",
                "a circle needs a `sphere`",
            ),
            (
                "radius = 2.0\n",
                "",
                "motion[0].radius",
                "a circle needs a `radius`",
            ),
            (
                "radius = 2.0",
                "radius = inf",
                "motion[0].radius",
                "radius must be a finite number",
            ),
            (
                "center = [0.0, 0.5, 0.0]",
                "center = [0.0, 0.5]",
                "motion[0].center",
                "expected 3 values, found 2",
            ),
            (
                "center = [0.0, 0.5, 0.0]",
                "center = [0.0, nan, 0.0]",
                "motion[0].center",
                "finite",
            ),
            ("phase = 0.25", "phase = inf", "motion[0].phase", "finite"),
            (
                "height = 1.5",
                "height = 1.5\nradius = 1",
                "motion[1].radius",
                "a bounce has no radius",
            ),
            (
                "height = 1.5\n",
                "",
                "motion[1].height",
                "a bounce needs a `height`",
            ),
            (
                "period = 10.0",
                "period = 10.0\nsphere = 0",
                "motion[2].sphere",
                "an orbit has no sphere",
            ),
            (
                "kind = \"orbit\"",
                "kind = \"spin\"",
                "motion[2].kind",
                "expected \"circle\", \"bounce\" or \"orbit\"",
            ),
            (
                "period = 10.0",
                "period = 10.0\nspeed = 2",
                "motion[2].speed",
                "unknown field `speed`",
            ),
            (
                "fps = 30",
                "fps = 0",
                "animation.fps",
                "fps must be a finite number greater than 0",
            ),
            (
                "frames = 90",
                "frames = 0",
                "animation.frames",
                "frames must be at least 1",
            ),
            ("frames = 90", "frames = 1.5", "animation.frames", "invalid type"),
            (
                "frames = 90",
                "loop = true",
                "animation.loop",
                "unknown field `loop`",
            ),
        ] {
            assert_eq!(MOVING.matches(from).count(), 1, "{from}");
            let e = match parse::<2, 0, 0, 0>(&MOVING.replace(from, to)) {
                Ok(_) => panic!("accepted: {to}"),
                Err(e) => e,
            };
            assert_eq!(e.field.as_deref(), Some(field), "{to}: {e}");
            assert!(e.reason.contains(reason), "{to}: {e}");
        }
        // More than MAX_MOTIONS motions.
        let orbit = "[[motion]]\nkind = \"orbit\"\nperiod = 1.0\n";
        let e = parse::<4, 0, 0, 0>(&format!("{GOOD}{}", orbit.repeat(MAX_MOTIONS + 1))).unwrap_err();
        assert_eq!(e.field.as_deref(), Some("motion"));
        assert_eq!(e.reason, "more than 8 motions: at most 8 are supported");
        parse::<4, 0, 0, 0>(&format!("{GOOD}{}", orbit.repeat(MAX_MOTIONS))).unwrap();
    }

    /// The light count is checked while the array is read, like the spheres'.
    #[test]
    fn light_count_is_checked_while_parsing() {
        let text = LIT.replace("intensity = 0.5", "intensity = \"bright\"");
        assert_eq!(
            parse::<4, 1, 2, 8>(&text).unwrap_err().field.as_deref(),
            Some("light")
        );
        assert_eq!(
            parse::<4, 2, 2, 8>(&text).unwrap_err().field.as_deref(),
            Some("light[1].intensity")
        );
    }
}
