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
//! Every fixed-length array must have exactly its length, every number must fit its
//! type (an `f32` field refuses `1e39` rather than reading it as infinity), at most `N`
//! spheres are read (counted while parsing, so a huge file is refused at sphere
//! `N + 1`), and [`load`] reads only a regular file of at most [`MAX_FILE_SIZE`] bytes.
//!
//! Every error names the field (`camera.fov_y_deg`, `sphere[2].radius`, with
//! `sphere[k]` counting from 0 in file order), the line where the parser knows it,
//! and the reason:
//!
//! ```
//! use embedded_raytracer::scene_file::parse;
//!
//! let text = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov_y_deg = 60\nwidth = 4\nheight = 3\n\
//!             [[sphere]]\ncenter = [0, 0, 0]\nradius = 0\ncolor = [255, 0, 0]\n";
//! let err = parse::<4>(text).unwrap_err();
//! assert_eq!(err.field.as_deref(), Some("sphere[0].radius"));
//! assert_eq!(err.to_string(), "sphere[0].radius: radius must be greater than 0");
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
use crate::error::CameraError;
use crate::scene::Scene;
use crate::sphere::Sphere;
use crate::vec3::Vec3;

/// The largest scene file [`load`] reads, in bytes (1 MiB; `scenes/crowd.toml`, 64
/// spheres, is 5,351 bytes).
pub const MAX_FILE_SIZE: u64 = 1 << 20;

/// A loaded scene file: the scene and its camera.
#[derive(Clone, Debug)]
pub struct SceneFile<const N: usize> {
    /// The spheres and background.
    pub scene: Scene<N>,
    /// The validated camera.
    pub camera: Camera,
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
struct RawScene<const N: usize> {
    background: Option<Exact<Int<u8>, 3>>,
    camera: RawCamera,
    #[serde(default, deserialize_with = "spheres::<_, N>")]
    sphere: Vec<RawSphere>,
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

/// The `[[sphere]]` array, refused as soon as it has more than `N` entries: sphere
/// `N + 1` is skipped unread, nothing after it is looked at.
fn spheres<'de, D: Deserializer<'de>, const N: usize>(d: D) -> Result<Vec<RawSphere>, D::Error> {
    struct Spheres<const N: usize>;
    impl<'de, const N: usize> Visitor<'de> for Spheres<N> {
        type Value = Vec<RawSphere>;
        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            f.write_str("an array of [[sphere]] tables")
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
            let mut spheres = Vec::new();
            while spheres.len() < N {
                match seq.next_element()? {
                    Some(sphere) => spheres.push(sphere),
                    None => return Ok(spheres),
                }
            }
            if seq.next_element::<IgnoredAny>()?.is_some() {
                let verb = if N == 1 { "is" } else { "are" };
                return Err(de::Error::custom(format_args!(
                    "more than {}: at most {N} {verb} supported",
                    count_of(N, "sphere")
                )));
            }
            Ok(spheres)
        }
    }
    d.deserialize_seq(Spheres::<N>)
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

/// Parses a scene file's text into a scene of capacity `N` and its camera.
pub fn parse<const N: usize>(text: &str) -> Result<SceneFile<N>, SceneFileError> {
    let raw: RawScene<N> = deserialize(text)?;

    let c = &raw.camera;
    let up = c.up.as_ref().map_or(Vec3::new(0.0, 1.0, 0.0), vec3);
    let size = Size::new(c.width.0, c.height.0);
    let mut params = CameraParams::new(vec3(&c.eye), vec3(&c.look_at), up, radians(c.fov_y_deg.0), size);
    if let Some(fov_x) = &c.fov_x_deg {
        params = params.with_fov_x(radians(fov_x.0));
    }
    let camera = Camera::from_params(params).map_err(|e| SceneFileError::field(camera_field(e, size), e))?;

    let background = raw.background.as_ref().map_or(Rgb888::new(0, 0, 0), rgb);
    let mut scene = Scene::new(background);
    for (k, s) in raw.sphere.iter().enumerate() {
        let center = vec3(&s.center);
        let sphere = Sphere::try_new(center, s.radius.0, rgb(&s.color)).map_err(|e| {
            let key = match e {
                crate::SphereError::NotFinite if !center.is_finite() => "center",
                _ => "radius",
            };
            SceneFileError::field(format!("sphere[{k}].{key}"), e)
        })?;
        scene
            .push(sphere)
            .map_err(|e| SceneFileError::field(format!("sphere[{k}]"), e))?;
    }
    Ok(SceneFile { scene, camera })
}

/// Reads and parses a scene file; errors carry the path.
///
/// Only a regular file is read (a FIFO would block, a device like `/dev/zero` never
/// ends), and at most [`MAX_FILE_SIZE`] bytes of it.
pub fn load<const N: usize>(path: impl AsRef<Path>) -> Result<SceneFile<N>, SceneFileError> {
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

/// TOML → raw structs, with the failing field's path and line.
fn deserialize<const N: usize>(text: &str) -> Result<RawScene<N>, SceneFileError> {
    let line_of = |e: &toml::de::Error| {
        e.span()
            .map(|s| text.get(..s.start).unwrap_or(text).matches('\n').count() + 1)
    };
    let de = toml::Deserializer::parse(text).map_err(|e| SceneFileError {
        path: None,
        field: None,
        line: line_of(&e),
        reason: format!("not valid TOML: {}", e.message().trim()),
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
        match parse::<4>(text) {
            Ok(_) => panic!("accepted:\n{text}"),
            Err(e) => e,
        }
    }

    #[test]
    fn parses_the_documented_format() {
        let f = parse::<4>(GOOD).unwrap();
        assert_eq!(f.scene.spheres().len(), 1);
        assert_eq!(f.scene.background(), Rgb888::new(10, 20, 30));
        assert_eq!(f.camera.size(), Size::new(32, 24));
        assert_eq!(f.camera.params().up, Vec3::new(0.0, 1.0, 0.0));
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
        assert_eq!(parse::<3>(&text).unwrap().scene.spheres().len(), 3);
        let e = parse::<2>(&text).unwrap_err();
        assert_eq!(e.field.as_deref(), Some("sphere"));
        assert_eq!(e.reason, "more than 2 spheres: at most 2 are supported");
        assert_eq!(
            parse::<1>(&text).unwrap_err().reason,
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
        assert_eq!(parse::<2>(&text).unwrap_err().field.as_deref(), Some("sphere"));
        assert_eq!(
            parse::<3>(&text).unwrap_err().field.as_deref(),
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
        parse::<4>(&GOOD.replace("eye = [0.0, 0.0, 5.0]", "eye = [0.0, 0.0, 1e20]")).unwrap();
        parse::<4>(&GOOD.replace("fov_y_deg", "up = [0, 3e38, 3e38]\nfov_y_deg")).unwrap();
    }
}
