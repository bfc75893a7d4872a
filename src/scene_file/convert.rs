//! The raw tables through the kernel's checked constructors: the camera, the settings,
//! each sphere, light and plane, and the animation, each refusal a field-level error
//! naming the key to blame.

use std::format;
use std::string::{String, ToString};

use embedded_graphics::{geometry::Size, pixelcolor::Rgb888};

use crate::camera::CameraParams;
use crate::error::{CameraError, LightError, PlaneError, SceneError, SphereError};
use crate::math::vec3::Vec3;
use crate::motion::{Animation, Bounce, Circle, Motion, Orbit, DEFAULT_FPS};
use crate::scene::light::Light;
use crate::scene::material::Material;
use crate::scene::plane::Plane;
use crate::scene::sphere::Sphere;
use crate::scene::{Scene, Settings};
use crate::scene_file::schema::{LightKind, MotionKind, RawLight, RawMotion, RawPlane, RawScene};
use crate::scene_file::values::{count_of, Exact, Int, F32};
use crate::scene_file::{SceneFile, SceneFileError, MAX_MOTIONS};

/// The scene with capacities `N` spheres, `L` lights, `P` planes and reflection depth
/// `D`, its camera and its animation, from a file's tables, checked in file order.
pub(super) fn scene_file<const N: usize, const L: usize, const P: usize, const D: usize>(
    raw: &RawScene<N, L, P>,
) -> Result<SceneFile<N, L, P, D>, SceneFileError> {
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
    let animation = animation(raw, scene.spheres().len())?;
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

/// A motion from its table, or the key to blame and why.
///
/// The `kind` decides which keys it takes; a key of another kind is refused rather
/// than ignored.
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

/// A checked light from its table, or the key to blame and why.
///
/// The `type` decides which of `direction` and `position` it takes; the other one is
/// refused rather than ignored (a point light with a `direction` is most likely a
/// directional light whose `type` is mistyped).
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
        // A size alone would be silently unused: most likely `checker` is missing.
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

/// A sphere's or plane's material from its optional keys, each missing one at its
/// default (unchecked).
///
/// The keys are written out in both structs rather than flattened: serde's `flatten`
/// drops `deny_unknown_fields` and the error's line.
fn material(specular: &Option<F32>, shininess: &Option<F32>, reflect: &Option<F32>) -> Material {
    let or = |v: &Option<F32>, default: f32| v.as_ref().map_or(default, |v| v.0);
    let d = Material::DEFAULT;
    Material::new(
        or(specular, d.specular),
        or(shininess, d.shininess),
        or(reflect, d.reflect),
    )
}

/// A point or vector from its array of three numbers.
fn vec3(v: &Exact<F32, 3>) -> Vec3 {
    let [x, y, z] = &v.0;
    Vec3::new(x.0, y.0, z.0)
}

/// An 8-bit sRGB colour from its array of three channels.
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
