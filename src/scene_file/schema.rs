//! The format as serde structs, one per table (`RawScene`, `RawCamera`, `RawSphere`,
//! …), written in the strict value types, and TOML into them with the failing field's
//! path and line.

use std::fmt;
use std::format;
use std::string::{String, ToString};
use std::vec::Vec;

use serde::de::{self, Deserializer, Unexpected, Visitor};
use serde::Deserialize;

use crate::scene_file::precheck::precheck;
use crate::scene_file::values::{capped, Depth, Exact, Int, Noun, F32};
use crate::scene_file::{SceneFileError, MAX_MOTIONS};

/// A scene file's top level: the settings, the camera, the arrays of tables (each
/// capped at its capacity while it is read) and the animation's timing.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawScene<const N: usize, const L: usize, const P: usize> {
    pub(super) background: Option<Exact<Int<u8>, 3>>,
    pub(super) ambient: Option<F32>,
    pub(super) max_depth: Option<Depth>,
    pub(super) shadows: Option<bool>,
    pub(super) camera: RawCamera,
    #[serde(default, deserialize_with = "capped::<_, RawSphere, N>")]
    pub(super) sphere: Vec<RawSphere>,
    #[serde(default, deserialize_with = "capped::<_, RawLight, L>")]
    pub(super) light: Vec<RawLight>,
    #[serde(default, deserialize_with = "capped::<_, RawPlane, P>")]
    pub(super) plane: Vec<RawPlane>,
    #[serde(default, deserialize_with = "capped::<_, RawMotion, MAX_MOTIONS>")]
    pub(super) motion: Vec<RawMotion>,
    pub(super) animation: Option<RawAnimation>,
}

/// `[animation]`: the frame rate and the number of frames, each optional.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawAnimation {
    pub(super) fps: Option<F32>,
    pub(super) frames: Option<Int<u32>>,
}

/// A motion's `kind`: `"circle"`, `"bounce"` or `"orbit"`.
#[derive(Clone, Copy)]
pub(super) enum MotionKind {
    Circle,
    Bounce,
    Orbit,
}

impl MotionKind {
    pub(super) const fn name(self) -> &'static str {
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

/// A `[[motion]]` table: its `kind` decides which of the optional keys it takes.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMotion {
    pub(super) kind: MotionKind,
    pub(super) sphere: Option<Int<u32>>,
    pub(super) center: Option<Exact<F32, 3>>,
    pub(super) radius: Option<F32>,
    pub(super) period: F32,
    pub(super) phase: Option<F32>,
    pub(super) height: Option<F32>,
}

/// `[camera]`: the eye, the point looked at, the field of view and the size.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawCamera {
    pub(super) eye: Exact<F32, 3>,
    pub(super) look_at: Exact<F32, 3>,
    pub(super) up: Option<Exact<F32, 3>>,
    pub(super) fov_y_deg: F32,
    pub(super) fov_x_deg: Option<F32>,
    pub(super) width: Int<u32>,
    pub(super) height: Int<u32>,
}

/// A `[[sphere]]` table with its optional material keys.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSphere {
    pub(super) center: Exact<F32, 3>,
    pub(super) radius: F32,
    pub(super) color: Exact<Int<u8>, 3>,
    pub(super) specular: Option<F32>,
    pub(super) shininess: Option<F32>,
    pub(super) reflect: Option<F32>,
}

/// A light's `type`: `"directional"` or `"point"`.
#[derive(Clone, Copy)]
pub(super) enum LightKind {
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

/// A `[[light]]` table: its `type` decides which of `direction` and `position` it takes.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawLight {
    #[serde(rename = "type")]
    pub(super) kind: LightKind,
    pub(super) direction: Option<Exact<F32, 3>>,
    pub(super) position: Option<Exact<F32, 3>>,
    pub(super) intensity: Option<F32>,
}

/// A `[[plane]]` table with its optional checkerboard and material keys.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawPlane {
    pub(super) point: Exact<F32, 3>,
    pub(super) normal: Exact<F32, 3>,
    pub(super) color: Exact<Int<u8>, 3>,
    pub(super) checker: Option<Exact<Int<u8>, 3>>,
    pub(super) checker_size: Option<F32>,
    pub(super) specular: Option<F32>,
    pub(super) shininess: Option<F32>,
    pub(super) reflect: Option<F32>,
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
pub(super) fn deserialize<const N: usize, const L: usize, const P: usize>(
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
