//! Lights, planes, checker floors and mirrors in the `f64` reference, traced from the
//! feature's specification alone (no kernel arithmetic: the kernel's scene types are
//! read for their `f32` data only).
//!
//! Per pixel: the primary ray's closest hit over spheres (Haines et al.'s robust test,
//! [`intersect`]) and planes (`t = (q − o)·n / (d·n)`), numbered spheres first, then
//! planes; the local colour under Lab #1 (no light in the scene) or Phong (lights, hard
//! shadows); mirrors as a loop to [`Scene::max_depth`], the background standing in at
//! that depth; the sum rounded to 8 bits once, halves up.
//!
//! # What a correct `f32` implementation may decide either way
//!
//! The reference also marks, per pixel, the decisions a correct `f32` implementation may
//! take either way ([`RefPixel::why`]). The argument, with `u = 2⁻²⁴` (`f32`'s unit
//! roundoff, [`UNIT_ROUNDOFF_F32`]):
//!
//! - **The ray's line.** A primary direction is within `DIR_ULPS·u·E` of the exact
//!   one, `E` the image-plane extent ([`DIR_ULPS`], [`direction_error`]: the direct
//!   stepping's four roundings of `F + dv·j + du·i`, each counted twice). Forming
//!   `c − o` (or `q − o`), the test's discriminant and root, and `o + t·d` are each a
//!   handful of roundings of numbers no larger than `S = |o| + s + |c| + r` (sphere) or
//!   `|o| + s + |q|` (plane), `s` the hit distance: at most `POINT_ULPS·u·S`
//!   ([`POINT_ULPS`] = 16: eight roundings, doubled for the step from components to
//!   Euclidean norms). So the ray is known to within
//!   `e_line = e_o + s·e_dir + POINT_ULPS·u·S` across it, `e_o` the origin's own error
//!   (0 for the eye).
//! - **The hit point** slides along the surface by `e_line/|cos θ|` (`θ` between the
//!   ray and the normal), for a sphere at most the sagitta `√(2r·e + e²)`:
//!   `e_p = e_line + min(e_line/|cos θ|, √(2r·e_line + e_line²))` (a plane has no cap:
//!   near its horizon the point is legitimately unknown).
//! - **Decisions at the point**: a checker edge where `x₁` or `x₂` is within
//!   `e_p + POINT_ULPS·u·(|p| + |q|)` of a multiple of the cell size; the `n·l > 0` gate
//!   within `e_n + e_l + POINT_ULPS·u`, with the normal's error `e_n = (e_p +
//!   POINT_ULPS·u·(|p| + |c|))/r + POINT_ULPS·u` (a plane's: `POINT_ULPS·u`) and the
//!   light direction's `e_l = (e_p + POINT_ULPS·u·(|light| + |p|))/dist` (directional:
//!   `POINT_ULPS·u`); `l + v` within `e_l + e_dir + POINT_ULPS·u` of zero.
//! - **A shadow ray** `p + s·l` is known to within `δ = e_p + s·e_l + POINT_ULPS·u·(|p| +
//!   |c| + r + |light|)` at the occluder (`s` up to its far side): its decision is
//!   undecidable when the occluder grown or shrunk by `δ` decides otherwise (grazing
//!   rays, a point near the occluder's surface, a point light near it). A plane
//!   occluder: `p`'s or the light's signed distance within rounding of 0, or (directional)
//!   `l·n` within `e_l + POINT_ULPS·u` of 0. The surface `p` lies on is treated exactly:
//!   a plane cannot block a ray leaving it; a sphere blocks it only if the ray goes into
//!   it, at the chord `s = 2·(c − p)·l̂`, known to `2·(e_p + POINT_ULPS·u·(|c| + |p|) +
//!   r·e_l)`. A point light on or near a surface ([`ON_SURFACE`]) is decided without
//!   a root near the light: a plane through it never blocks; a sphere through it
//!   blocks iff `0 < 2σ < dist` (`σ = (light − c)·l`, the line's other root `2σ` before
//!   the light), a sphere around it iff `p` is outside it, a sphere it lies outside
//!   iff the segment reaches the root nearest the light, `σ − √(σ² − g)` (`g` from the
//!   light's gap); each undecidable when `σ` and `dist` moved by `e_σ = e_p +
//!   POINT_ULPS·u·(|c| + |p| + r + |light|) + r·e_l` decide otherwise (the sphere
//!   around it: when `p` is within rounding of it). An object with a lower-numbered twin (the
//!   same centre and radius, or point and normal) is never met: coincident objects are
//!   one surface, the lower index's.
//! - **A reflected ray** starts at `p` (error `e_p`) with direction error
//!   `e_dir + 2·e_n + POINT_ULPS·u`; its line passes `p` at the incoming line's offset
//!   `e_line` (the slide along the surface lies in the plane of incidence at angle θ to
//!   the normal, so it moves the reflected line across itself by `e_line` only). A chord inside a sphere that ends on the same
//!   sphere uses what reflection inside a sphere keeps: the line's distance `b` from the
//!   centre (its error `δb` gains only the new rounding per bounce) while the direction
//!   turns by `π − 2α` (`sin α = b/r`), so the direction's error grows by
//!   `2·δb/(r·cos α)` per bounce and the point's is `r·δψ` plus the slide of `δb`:
//!   linear along the chain, where per-bounce worst cases would compound (with the eye
//!   inside a mirror sphere at depth 8, they would mark most of the image). Which
//!   object a reflected ray shows is undecidable when, for the lines within that error,
//!   another object's hit distance interval reaches below the shown one's
//!   (silhouettes, horizons, depth ties, a self-hit at a grazing chord).
//!   Primary rays use the same rule for every decision that involves a plane; a primary
//!   ray's sphere silhouettes and sphere–sphere ties keep the reference's own band
//!   ([`BAND_ULPS`](super::BAND_ULPS)), as for Lab #1 scenes.
//!
//! A decision counts only if flipping it can move the unrounded colour by more than
//! [`LEVEL`]: the local colour enters the pixel with weight `Π rₖ·(1 − r)` along the
//! mirror chain, the light's term (diffuse plus highlight) bounds a shadow's or the
//! gate's jump, the two cell colours' difference times the lighting bounds a checker
//! edge's, and `255·Π rₖ` bounds a reflected ray's choice of object. Every band is a
//! few `f32` ulps of the quantities that decide it: it is narrow wherever the geometry
//! is well conditioned and widens only where the decision is genuinely ill conditioned
//! (grazing hits, the horizon).

use std::vec::Vec;

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};

use super::{has_twin, intersect, sphere_doubt, why, RayHit, RefCamera, RefPixel, D3, HIDDEN};
use embedded_raytracer::Light;
use embedded_raytracer::Scene;

/// `f32`'s unit roundoff, `2⁻²⁴`.
pub const UNIT_ROUNDOFF_F32: f64 = 1.0 / 16_777_216.0;

/// A correct primary direction's absolute error, in units of [`UNIT_ROUNDOFF_F32`] times
/// the image-plane extent `E = |d(0, 0)| + H·ph + W·pw` (see [`direction_error`]):
/// direct stepping forms `F + dv·j + du·i` in four roundings of numbers no larger than
/// `E`, each counted twice.
pub const DIR_ULPS: f64 = 16.0;

/// The relative error of a correct `f32` primary direction `d`: `DIR_ULPS·u·E/|d|`, `E`
/// the image-plane extent the direct stepping adds up (the first pixel's direction and
/// the image's height and width in steps).
#[must_use]
pub fn direction_error(camera: &RefCamera, d: D3) -> f64 {
    let extent = camera.direction(0, 0).length()
        + f64::from(camera.height) * camera.pixel_height
        + f64::from(camera.width) * camera.pixel_width;
    DIR_ULPS * UNIT_ROUNDOFF_F32 * extent / d.length()
}

/// The constant of the hit point's error `POINT_ULPS·u·(|o| + s + size)`: eight
/// roundings (forming `c − o`, the discriminant's terms, the root, `o + t·d`), doubled
/// for the step from per-component to Euclidean bounds.
pub const POINT_ULPS: f64 = 16.0;

/// A decision counts as undecidable only if flipping it can move the unrounded colour
/// by more than this many 8-bit levels (so a flip that cannot is at most 2 levels off
/// after rounding, inside the tables' tolerance).
pub const LEVEL: f64 = 1.0;

const ROUND: f64 = POINT_ULPS * UNIT_ROUNDOFF_F32;

/// A colour in `f64` channels, 0 … 255.
pub type Rgb = [f64; 3];

fn rgb(c: Rgb888) -> Rgb {
    [f64::from(c.r()), f64::from(c.g()), f64::from(c.b())]
}

fn max_channel(c: Rgb) -> f64 {
    c[0].max(c[1]).max(c[2])
}

/// A surface's material in `f64`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefMaterial {
    /// Weight of the highlight.
    pub specular: f64,
    /// Phong exponent.
    pub shininess: f64,
    /// Mirror weight (0 in a scene type without reflection depth).
    pub reflect: f64,
}

/// A sphere as the lit reference sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefLitSphere {
    /// Centre.
    pub center: D3,
    /// Radius.
    pub radius: f64,
    /// Colour.
    pub color: Rgb,
    /// Material.
    pub material: RefMaterial,
}

/// A plane as the lit reference sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefPlane {
    /// A point on the plane.
    pub point: D3,
    /// Unit normal as given and its checker basis `(n, e₁, e₂)`; `None` for a zero
    /// normal (such a plane is never hit).
    pub frame: Option<(D3, D3, D3)>,
    /// Colour of the even cells (of the whole plane without a checker).
    pub color: Rgb,
    /// Colour of the odd cells.
    pub checker: Option<Rgb>,
    /// Cell side.
    pub size: f64,
    /// Material.
    pub material: RefMaterial,
}

/// A light as the lit reference sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RefLight {
    /// Parallel light: `toward` is the unit vector toward the light (`−direction`).
    Directional {
        /// Unit vector toward the light.
        toward: D3,
        /// Intensity.
        intensity: f64,
    },
    /// A point light.
    Point {
        /// Position.
        position: D3,
        /// Intensity.
        intensity: f64,
    },
}

/// A scene in `f64`: what the lit reference traces.
#[derive(Clone, Debug, PartialEq)]
pub struct RefScene {
    /// Spheres (object indices `0 … spheres.len()`).
    pub spheres: Vec<RefLitSphere>,
    /// Planes (object index `spheres.len() + k`).
    pub planes: Vec<RefPlane>,
    /// Lights (a directional light with a zero direction is left out).
    pub lights: Vec<RefLight>,
    /// Ambient term.
    pub ambient: f64,
    /// Whether lights cast shadows.
    pub shadows: bool,
    /// Reflection depth traced ([`Scene::max_depth`]).
    pub max_depth: u8,
    /// Whether the scene type has reflection depth (`D ≥ 1`): without it mirrors are
    /// matte.
    pub mirrors: bool,
    /// Background colour.
    pub background: Rgb888,
    /// Per object (spheres, then planes): it has a lower-numbered twin — the same
    /// centre and radius, or the same point and normal, bit for bit. Coincident objects
    /// are one surface, shown in the lower index's colour: the twin is never met.
    pub hidden: Vec<bool>,
    /// Whether a point light within [`ON_SURFACE`] of a surface is decided by the
    /// on-surface rule (`true`, what [`RefScene::of`] sets: the kernel's contract).
    /// `false` sends every pair through the general segment test — the plain `f64`
    /// geometry with its own error band, no tie: the independent check of the rule.
    pub lamp_ties: bool,
}

/// A point light lies on a surface within `2⁻¹⁶` of the frame's lengths: on sphere
/// `(C, r)` when `| |P − C| − r | ≤ 2⁻¹⁶·(|P − E| + |C − E| + r)`, on a plane through
/// `Q` with unit normal `n` when `|(P − Q)·n| ≤ 2⁻¹⁶·(|P − E| + |Q − E|)` (`E` the
/// eye). Such a pair is decided without a root near the lamp, whose rounding in the
/// kernel exceeds the gap: a plane exactly through the lamp (in `f64`) never blocks
/// the segment (open at the lamp), one the lamp lies off blocks it iff the segment's
/// ends are on opposite sides; a sphere exactly through the lamp blocks it iff `0 < 2σ
/// < dist` with `σ = (P − C)·l` (the line meets the sphere at the lamp and `2σ` before
/// it); a sphere around the lamp blocks it iff the segment starts outside the sphere;
/// a sphere the lamp lies outside blocks it iff the segment reaches the line's root
/// nearest the lamp, `σ − √(σ² − g)` with `g = |P − C|² − r²` taken from the lamp's
/// gap. The kernel decides these pairs by the same geometry.
pub const ON_SURFACE: f64 = 1.0 / 65_536.0;

/// Whether lamp `p` lies on sphere `(c, r)` seen from `eye` ([`ON_SURFACE`]).
#[must_use]
pub fn lamp_on_sphere(p: D3, eye: D3, c: D3, r: f64) -> bool {
    ((p - c).length() - r).abs() <= ON_SURFACE * ((p - eye).length() + (c - eye).length() + r)
}

/// Whether lamp `p` lies on the plane through `q` with unit normal `n` seen from `eye`
/// ([`ON_SURFACE`]).
#[must_use]
pub fn lamp_on_plane(p: D3, eye: D3, q: D3, n: D3) -> bool {
    (p - q).dot(n).abs() <= ON_SURFACE * ((p - eye).length() + (q - eye).length())
}

/// The checker basis of a plane with unit normal `n`: `a` the world axis along which `n`
/// has its smallest absolute component (ties: x before y before z), `e₁ = normalize(n ×
/// a)`, `e₂ = n × e₁`. `None` if `n` is not a usable unit vector.
#[must_use]
pub fn plane_basis(n: D3) -> Option<(D3, D3)> {
    let (ax, ay, az) = (n.x.abs(), n.y.abs(), n.z.abs());
    let a = if ax <= ay && ax <= az {
        D3::new(1.0, 0.0, 0.0)
    } else if ay <= az {
        D3::new(0.0, 1.0, 0.0)
    } else {
        D3::new(0.0, 0.0, 1.0)
    };
    let e1 = n.cross(a).normalize()?;
    Some((e1, n.cross(e1)))
}

fn material(m: &embedded_raytracer::Material, mirrors: bool) -> RefMaterial {
    RefMaterial {
        specular: f64::from(m.specular),
        shininess: f64::from(m.shininess),
        reflect: if mirrors { f64::from(m.reflect) } else { 0.0 },
    }
}

impl RefScene {
    /// The scene's `f32` data in `f64`.
    #[must_use]
    pub fn of<const N: usize, const L: usize, const P: usize, const D: usize>(
        scene: &Scene<N, L, P, D>,
    ) -> Self {
        let mirrors = D > 0;
        let spheres = scene
            .spheres()
            .iter()
            .map(|s| RefLitSphere {
                center: D3::of(s.center),
                radius: f64::from(s.radius),
                color: rgb(s.color),
                material: material(&s.material, mirrors),
            })
            .collect();
        let planes = scene
            .planes()
            .iter()
            .map(|p| RefPlane {
                point: D3::of(p.point),
                frame: D3::of(p.normal)
                    .normalize()
                    .and_then(|n| plane_basis(n).map(|(e1, e2)| (n, e1, e2))),
                color: rgb(p.color),
                checker: p.checker.map(rgb),
                size: f64::from(p.checker_size),
                material: material(&p.material, mirrors),
            })
            .collect();
        let lights = scene
            .lights()
            .iter()
            .filter_map(|l| match *l {
                Light::Directional { direction, intensity } => (D3::default() - D3::of(direction))
                    .normalize()
                    .map(|toward| RefLight::Directional {
                        toward,
                        intensity: f64::from(intensity),
                    }),
                Light::Point { position, intensity } => Some(RefLight::Point {
                    position: D3::of(position),
                    intensity: f64::from(intensity),
                }),
            })
            .collect();
        let settings = scene.settings();
        let geometry: Vec<(D3, f64)> = scene
            .spheres()
            .iter()
            .map(|s| (D3::of(s.center), f64::from(s.radius)))
            .collect();
        let bits = |v: embedded_raytracer::Vec3| (v.x.to_bits(), v.y.to_bits(), v.z.to_bits());
        let plane_key = |p: &embedded_raytracer::Plane| (bits(p.point), bits(p.normal));
        let hidden = (0..geometry.len())
            .map(|k| has_twin(&geometry, k))
            .chain(scene.planes().iter().enumerate().map(|(k, p)| {
                scene
                    .planes()
                    .iter()
                    .take(k)
                    .any(|q| plane_key(q) == plane_key(p))
            }))
            .collect();
        Self {
            hidden,
            lamp_ties: true,
            spheres,
            planes,
            lights,
            ambient: f64::from(settings.ambient),
            shadows: settings.shadows,
            max_depth: scene.max_depth(),
            mirrors,
            background: scene.background(),
        }
    }

    /// Whether the scene is spheres under Lab #1 only (no light, no plane, no mirror that
    /// shows): then the reference traces it exactly as a Lab #1 scene.
    #[must_use]
    pub fn is_lab1(&self) -> bool {
        self.lights.is_empty()
            && self.planes.is_empty()
            && self.spheres.iter().all(|s| !(s.material.reflect > 0.0))
    }
}

/// One ray of a mirror chain: origin, direction (the primary's is the camera's, not
/// unit), the `f32` errors a correct implementation carries on them, and the surface
/// it leaves.
#[derive(Clone, Copy, Debug)]
struct Ray {
    o: D3,
    d: D3,
    len: f64,
    /// Absolute error of the origin.
    e_o: f64,
    /// Error of the line across itself at the origin (`≤ e_o`: a point that slid along
    /// the surface it was found on moves the reflected line only by the incoming
    /// line's offset).
    e_off: f64,
    /// Relative (angular) error of the direction.
    e_dir: f64,
    /// The object the ray leaves (its index), if any.
    from: Option<usize>,
    /// A chord of sphere `k` from inside: `(k, δb)`, the error of the line's distance
    /// from the centre (reflection inside a sphere keeps that distance, see
    /// [`surface`]).
    chord: Option<(usize, f64)>,
}

/// One object along a ray: its exact hit parameter, and the interval of parameters a
/// correct `f32` implementation may find (`∞`: it may see no hit).
#[derive(Clone, Copy, Debug)]
struct Cand {
    index: usize,
    t: Option<f64>,
    tmin: f64,
    tmax: f64,
    /// The largest parameter it may be hit at, given that it is hit.
    hit_hi: f64,
}

const NONE: (f64, f64) = (f64::INFINITY, f64::INFINITY);

/// Smallest and largest of the optional hit parameters (`None` counts as `∞`), and the
/// largest of those present.
fn span(ts: &[Option<f64>]) -> (f64, f64, f64) {
    let lo = ts.iter().flatten().fold(f64::INFINITY, |a, &t| a.min(t));
    let hit_hi = ts.iter().flatten().fold(0.0, |a: f64, &t| a.max(t));
    let hi = if ts.iter().all(Option::is_some) {
        hit_hi
    } else {
        f64::INFINITY
    };
    (lo, hi, hit_hi)
}

fn sphere_cand(ray: &Ray, index: usize, s: &RefLitSphere, hit: Option<&RayHit>) -> Cand {
    let (c, r) = (s.center, s.radius);
    let d_hat = ray.d * (1.0 / ray.len);
    if ray.from == Some(index) {
        // Leaving its own surface: hit again only going into it, at the chord.
        let chord = 2.0 * (c - ray.o).dot(d_hat);
        let err = 2.0 * (ray.e_o + ROUND * (c.length() + ray.o.length()) + r * ray.e_dir);
        let (lo, hi) = if chord > err {
            (chord - err, chord + err)
        } else if chord > -err {
            (0.0, f64::INFINITY)
        } else {
            NONE
        };
        return Cand {
            index,
            t: (chord > 0.0).then(|| chord / ray.len),
            tmin: lo / ray.len,
            tmax: hi / ray.len,
            hit_hi: (chord + err) / ray.len,
        };
    }
    let h = hit.copied().unwrap_or_else(|| intersect(ray.o, ray.d, c, r));
    let reach = h.t_closest.max(0.0) * ray.len + r;
    let rounding = ROUND * (ray.o.length() + c.length() + r);
    let delta = ray.e_off + reach * ray.e_dir + rounding;
    let (tmin, tmax, hit_hi) = if ((c - ray.o).length() - r).abs() <= ray.e_o + rounding {
        // The origin may be on either side of the surface.
        (0.0, f64::INFINITY, f64::INFINITY)
    } else {
        let grown = intersect(ray.o, ray.d, c, r + delta).t;
        let shrunk = (r > delta)
            .then(|| intersect(ray.o, ray.d, c, r - delta).t)
            .flatten();
        let (lo, hi, hit_hi) = span(&[h.t, grown, shrunk]);
        let pad = delta / ray.len;
        ((lo - pad).max(0.0), hi + pad, hit_hi + pad)
    };
    Cand {
        index,
        t: h.t,
        tmin,
        tmax,
        hit_hi,
    }
}

fn plane_cand(ray: &Ray, index: usize, p: &RefPlane) -> Cand {
    let miss = Cand {
        index,
        t: None,
        tmin: f64::INFINITY,
        tmax: f64::INFINITY,
        hit_hi: f64::INFINITY,
    };
    let Some((n, _, _)) = p.frame else {
        return miss;
    };
    if ray.from == Some(index) {
        // A plane cannot be hit again by a ray leaving it.
        return miss;
    }
    // Signed distance of the origin and the direction's slope toward the plane: a hit
    // iff they have strictly opposite signs, at t = −h/(d·n).
    let h = (ray.o - p.point).dot(n);
    let dn_raw = ray.d.dot(n);
    let dn = dn_raw / ray.len;
    let t = (h * dn < 0.0).then(|| -h / dn_raw);
    let e_h = ray.e_o + ROUND * (ray.o.length() + p.point.length());
    let e_dn = ray.e_dir + ROUND;
    let (h_lo, h_hi, d_lo, d_hi) = (h - e_h, h + e_h, dn - e_dn, dn + e_dn);
    let possible = (h_lo < 0.0 && d_hi > 0.0) || (h_hi > 0.0 && d_lo < 0.0);
    let certain = (h_hi < 0.0 && d_lo > 0.0) || (h_lo > 0.0 && d_hi < 0.0);
    let tmin = if possible {
        (h.abs() - e_h).max(0.0) / (dn.abs() + e_dn) / ray.len
    } else {
        f64::INFINITY
    };
    let tmax = if certain {
        (h.abs() + e_h) / (dn.abs() - e_dn) / ray.len
    } else {
        f64::INFINITY
    };
    Cand {
        index,
        t,
        tmin,
        tmax,
        hit_hi: tmax,
    }
}

/// Every object along `ray`, spheres first, then planes.
fn candidates(scene: &RefScene, ray: &Ray, sphere_hits: &[RayHit]) -> Vec<Cand> {
    let spheres = scene
        .spheres
        .iter()
        .enumerate()
        .map(|(k, s)| sphere_cand(ray, k, s, sphere_hits.get(k)))
        .map(|c| hide(scene, c));
    let n = scene.spheres.len();
    let planes = scene
        .planes
        .iter()
        .enumerate()
        .map(|(k, p)| plane_cand(ray, n + k, p))
        .map(|c| hide(scene, c));
    spheres.chain(planes).collect()
}

/// A coincident object's candidate is never met (its lower-numbered twin is).
fn hide(scene: &RefScene, c: Cand) -> Cand {
    if scene.hidden.get(c.index).copied().unwrap_or(false) {
        Cand {
            index: c.index,
            t: None,
            tmin: f64::INFINITY,
            tmax: f64::INFINITY,
            hit_hi: f64::INFINITY,
        }
    } else {
        c
    }
}

/// The closest hit, first index on exact ties (the kernel's strict `t < t_max`).
fn closest(cands: &[Cand]) -> Option<Cand> {
    let mut best: Option<Cand> = None;
    for c in cands {
        if let Some(t) = c.t {
            if best.is_none_or(|b| b.t.is_none_or(|bt| t < bt)) {
                best = Some(*c);
            }
        }
    }
    best
}

/// Whether `f32` may show another object than `best` (a reflected ray): `best`'s presence
/// is in doubt, or another object's hit interval reaches below `best`'s.
fn object_doubt(cands: &[Cand], best: Option<Cand>) -> bool {
    let bi = best.map(|b| b.index);
    let tmax = best.map_or(f64::INFINITY, |b| b.tmax);
    best.is_some_and(|b| b.tmax.is_infinite())
        || cands
            .iter()
            .any(|c| Some(c.index) != bi && c.tmin.is_finite() && c.tmin <= tmax)
}

/// Whether `f32` may show another object than `best` on a primary ray by a decision that
/// involves a plane: the shown plane's presence (its horizon), or a plane and another
/// object whose hit intervals overlap. A sphere's own silhouette is the reference band's
/// ([`sphere_doubt`]): here a sphere counts only where it is hit, the shown one with
/// its depth range given a hit.
fn plane_doubt(cands: &[Cand], best: Option<Cand>, n_spheres: usize) -> bool {
    let plane = |i: usize| i >= n_spheres;
    let (bi, hi) = match best {
        Some(b) if plane(b.index) => {
            if b.tmax.is_infinite() {
                return true;
            }
            (Some(b.index), b.tmax)
        }
        Some(b) => (Some(b.index), b.hit_hi),
        None => (None, f64::INFINITY),
    };
    cands.iter().any(|c| {
        Some(c.index) != bi
            && (plane(c.index) || bi.is_some_and(plane))
            && (plane(c.index) || c.t.is_some())
            && c.tmin.is_finite()
            && c.tmin <= hi
    })
}

/// The surface seen at a hit, as shading needs it.
struct Surface {
    p: D3,
    /// Unit normal turned to face the ray's origin.
    n: D3,
    /// Lab #1's `n·(−w)`: a sphere's outward normal, a plane's turned one.
    n_view: f64,
    color: Rgb,
    /// The other cell colour's largest channel difference, if the cell is in doubt.
    checker_doubt: Option<f64>,
    material: RefMaterial,
    /// Absolute error of the point.
    e_p: f64,
    /// Error of the unit normal (the gate's input).
    e_n: f64,
    /// Direction error of the reflected ray.
    e_dir_next: f64,
    /// Line offset error of the reflected ray at `p`.
    e_off_next: f64,
    /// The reflected ray is a chord of this sphere from inside: `(index, δb)`.
    chord: Option<(usize, f64)>,
}

fn surface(scene: &RefScene, ray: &Ray, hit: &Cand, w: D3) -> Option<Surface> {
    let t = hit.t?;
    let p = ray.o + ray.d * t;
    let s = t * ray.len;
    let d_hat = ray.d * (1.0 / ray.len);
    let n_spheres = scene.spheres.len();
    if let Some(sp) = scene.spheres.get(hit.index) {
        let (c, r) = (sp.center, sp.radius);
        let outward = (p - c) * (1.0 / r);
        let cos = d_hat.dot(outward).abs();
        let rounding = ROUND * (ray.o.length() + s + c.length() + r);
        // Along the surface, a line offset `x` moves the point by x/|cos θ|, at most the
        // sagitta.
        let slide = |x: f64| (x / cos).min((2.0 * r * x + x * x).sqrt());
        let (e_p, e_dir_next, e_off_next, chord) = match ray.chord {
            Some((k, db)) if k == hit.index && ray.from == Some(k) => {
                // A chord of this sphere from inside ends on it again. Reflection inside
                // a sphere keeps the line's distance b from the centre and turns its
                // direction by π − 2α (sin α = b/r): the line is known to δb across and
                // its direction to the ray's error, which grows by 2δb/(r·cos α) per
                // bounce (linearly, not compounding). The point is off by r·δψ from the
                // turn plus the slide of δb.
                let x = db + rounding;
                let e_p = r * ray.e_dir + x + slide(x);
                let e_dir_next = ray.e_dir + 2.0 * slide(x) / r + 3.0 * ROUND;
                (e_p, e_dir_next, x + r * ray.e_dir, Some((k, x)))
            }
            _ => {
                let e_line = ray.e_off + s * ray.e_dir + rounding;
                let e_p = e_line + slide(e_line);
                let e_n = (e_p + ROUND * (p.length() + c.length())) / r + ROUND;
                // Seen from inside, the reflected ray is a chord of this sphere.
                let chord = (outward.dot(ray.d) > 0.0).then_some((hit.index, e_line));
                // The reflected line passes the slid point at the incoming line's offset.
                (e_p, ray.e_dir + 2.0 * e_n + ROUND, e_line, chord)
            }
        };
        let e_n = (e_p + ROUND * (p.length() + c.length())) / r + ROUND;
        // Lab #1's view-space normal, camera-relative: ((c − o)·w − t·(d·w))/r.
        let n_view = ((c - ray.o).dot(w) - t * ray.d.dot(w)) / r;
        let n = if outward.dot(ray.d) > 0.0 {
            D3::default() - outward
        } else {
            outward
        };
        return Some(Surface {
            p,
            n,
            n_view,
            color: sp.color,
            checker_doubt: None,
            material: sp.material,
            e_p,
            e_n,
            e_dir_next,
            e_off_next,
            chord,
        });
    }
    let pl = scene.planes.get(hit.index.checked_sub(n_spheres)?)?;
    let (n0, e1, e2) = pl.frame?;
    let e_line = ray.e_off + s * ray.e_dir + ROUND * (ray.o.length() + s + pl.point.length());
    let e_p = e_line + e_line / d_hat.dot(n0).abs();
    let n = if n0.dot(ray.d) > 0.0 {
        D3::default() - n0
    } else {
        n0
    };
    let (color, checker_doubt) = match pl.checker {
        None => (pl.color, None),
        Some(second) => {
            // Cell parity from the plane coordinates x₁, x₂ (normal as given, not turned).
            let rel = p - pl.point;
            let (y1, y2) = (rel.dot(e1) / pl.size, rel.dot(e2) / pl.size);
            let parity = (y1.floor() + y2.floor()).rem_euclid(2.0);
            let color = if parity == 0.0 { pl.color } else { second };
            let e_x = (e_p + ROUND * (p.length() + pl.point.length())) / pl.size;
            let near = |y: f64| (y - y.round()).abs() <= e_x;
            let jump = (0..3).fold(0.0, |m: f64, k| {
                let a = pl.color.get(k).copied().unwrap_or(0.0);
                let b = second.get(k).copied().unwrap_or(0.0);
                m.max((a - b).abs())
            });
            (color, (near(y1) || near(y2)).then_some(jump))
        }
    };
    Some(Surface {
        p,
        n,
        n_view: n.dot(D3::default() - w),
        color,
        checker_doubt,
        material: pl.material,
        e_p,
        e_n: ROUND,
        e_dir_next: ray.e_dir + 3.0 * ROUND,
        e_off_next: e_line,
        chord: None,
    })
}

/// Does sphere `(c, r)` cross the segment `p + s·l`, `0 < s < dist` (unit `l`)?
fn crosses(p: D3, l: D3, dist: f64, c: D3, r: f64) -> bool {
    if !(r > 0.0) {
        return false;
    }
    let lc = c - p;
    let b = lc.dot(l);
    let perp = lc - l * b;
    let disc = r * r - perp.dot(perp);
    if disc < 0.0 {
        return false;
    }
    // Stable roots: q = b ± √disc by b's sign, the other c₀/q.
    let c0 = lc.dot(lc) - r * r;
    let root = disc.sqrt();
    let q = if b >= 0.0 { b + root } else { b - root };
    let other = if q == 0.0 { 0.0 } else { c0 / q };
    let inside = |s: f64| s > 0.0 && s < dist;
    inside(q) || inside(other)
}

/// The shadow ray from `p` (on object `from`) toward a light (`lamp`: a point light's
/// position, with the `eye` that decides whether it lies on a surface,
/// [`ON_SURFACE`]): `(blocked, doubt)`, any-hit (the first certain occluder ends the
/// test).
#[allow(clippy::too_many_arguments)]
fn shadow(
    scene: &RefScene,
    from: usize,
    p: D3,
    l: D3,
    dist: f64,
    light_size: f64,
    e_p: f64,
    e_l: f64,
    lamp: Option<D3>,
    eye: D3,
) -> (bool, bool) {
    let (mut blocked, mut doubt) = (false, false);
    let hidden = |k: usize| scene.hidden.get(k).copied().unwrap_or(false);
    for (k, s) in scene.spheres.iter().enumerate() {
        let (c, r) = (s.center, s.radius);
        if hidden(k) {
            continue;
        }
        let on = lamp.filter(|&at| scene.lamp_ties && lamp_on_sphere(at, eye, c, r));
        let (b, d) = if let Some(at) = on {
            if k == from {
                // A chord of its own sphere ends at the lamp on it: open there.
                (false, false)
            } else {
                let lamp_gap = (at - c).length() - r;
                let sigma = (at - c).dot(l);
                let err = e_p + ROUND * (c.length() + p.length() + r + light_size) + r * e_l;
                if lamp_gap < 0.0 {
                    // A lamp inside: the segment crosses the sphere iff it starts
                    // outside it.
                    let gap = (p - c).length() - r;
                    (
                        gap > 0.0,
                        gap.abs() <= e_p + ROUND * (c.length() + p.length() + r),
                    )
                } else if lamp_gap > 0.0 {
                    // A lamp outside: the segment reaches the line's root nearest the
                    // lamp, s₋ = σ − √(σ² − g) with g = |P − C|² − r² (from the gap:
                    // no cancellation); blocked grows with σ and with dist, so the
                    // decision is in doubt iff the ends of their error intervals
                    // decide otherwise.
                    let g = lamp_gap * (lamp_gap + 2.0 * r);
                    let reaches = |sigma: f64, dist: f64| {
                        let disc = sigma * sigma - g;
                        sigma > 0.0 && disc >= 0.0 && g < dist * (sigma + disc.sqrt())
                    };
                    let lo = reaches(sigma - err, dist - err);
                    (reaches(sigma, dist), lo != reaches(sigma + err, dist + err))
                } else {
                    // Through the lamp: the line meets the sphere at the lamp and 2σ
                    // before it.
                    let two_sigma = 2.0 * sigma;
                    let doubt = two_sigma.abs() <= 2.0 * err || (two_sigma - dist).abs() <= 2.0 * err;
                    (two_sigma > 0.0 && two_sigma < dist, doubt)
                }
            }
        } else if k == from {
            // Its own surface: only going into it, out at the chord.
            let chord = 2.0 * (c - p).dot(l);
            let err = 2.0 * (e_p + ROUND * (c.length() + p.length()) + r * e_l);
            (
                chord > 0.0 && chord < dist,
                chord.abs() <= err || (chord - dist).abs() <= err,
            )
        } else {
            let reach = ((c - p).dot(l) + r).clamp(0.0, dist);
            let delta = e_p + reach * e_l + ROUND * (p.length() + c.length() + r + light_size);
            let b = crosses(p, l, dist, c, r);
            let d = crosses(p, l, dist, c, r - delta) != b || crosses(p, l, dist, c, r + delta) != b;
            (b, d)
        };
        if b && !d {
            return (true, false);
        }
        blocked |= b;
        doubt |= d;
    }
    let n_spheres = scene.spheres.len();
    for (k, pl) in scene.planes.iter().enumerate() {
        let Some((n, _, _)) = pl.frame else {
            continue;
        };
        if n_spheres + k == from || hidden(n_spheres + k) {
            continue;
        }
        if lamp.is_some_and(|at| {
            scene.lamp_ties && lamp_on_plane(at, eye, pl.point, n) && (at - pl.point).dot(n) == 0.0
        }) {
            // Through the lamp: met only at the segment's open end. A lamp on it but
            // off it in f64 is decided below, by the signs at the two ends.
            continue;
        }
        let h = (p - pl.point).dot(n);
        let e_h = e_p + ROUND * (p.length() + pl.point.length());
        let (b, d) = if dist.is_finite() {
            // A point light: blocked iff the point and the light are strictly on opposite
            // sides. The light's own position, not `p + l·dist`: from a point far from
            // the plane that sum carries `p`'s rounding, which can exceed the lamp's
            // height above the plane.
            let light = lamp.unwrap_or(p + l * dist);
            let hl = (light - pl.point).dot(n);
            let e_hl = ROUND * (light_size + pl.point.length());
            (h * hl < 0.0, h.abs() <= e_h || hl.abs() <= e_hl)
        } else {
            // Directional: the ray heads into the plane from the side `p` is on.
            let ln = l.dot(n);
            (h * ln < 0.0, h.abs() <= e_h || ln.abs() <= e_l + ROUND)
        };
        if b && !d {
            return (true, false);
        }
        blocked |= b;
        doubt |= d;
    }
    (blocked, doubt)
}

/// The local colour under the scene's lights (Phong with hard shadows), and the
/// decisions in doubt that can move it by more than [`LEVEL`] at weight `weight`.
fn phong(scene: &RefScene, ray: &Ray, from: usize, sf: &Surface, weight: f64, why: &mut u8, eye: D3) -> Rgb {
    let v = D3::default() - ray.d * (1.0 / ray.len);
    let m = sf.material;
    let (mut diffuse, mut spec, mut diffuse_bound) = (0.0, 0.0, 0.0);
    for light in &scene.lights {
        let (l, dist, size, intensity) = match *light {
            RefLight::Directional { toward, intensity } => (toward, f64::INFINITY, 0.0, intensity),
            RefLight::Point { position, intensity } => {
                let to = position - sf.p;
                let Some(l) = to.normalize() else {
                    continue;
                };
                (l, to.length(), position.length(), intensity)
            }
        };
        let e_l = if dist.is_finite() {
            (sf.e_p + ROUND * (size + sf.p.length())) / dist
        } else {
            ROUND
        };
        let ndl = sf.n.dot(l);
        let e_gate = sf.e_n + e_l + ROUND;
        let spec_open = (l + v).normalize().map_or(0.0, |h| {
            intensity * m.specular * sf.n.dot(h).max(0.0).powf(m.shininess)
        });
        let reach = ndl > -e_gate;
        let (blocked, doubt) = if scene.shadows && reach {
            let lamp = match *light {
                RefLight::Point { position, .. } => Some(position),
                RefLight::Directional { .. } => None,
            };
            shadow(scene, from, sf.p, l, dist, size, sf.e_p, e_l, lamp, eye)
        } else {
            (false, false)
        };
        // Doubts matter only where the light can reach: not certainly blocked.
        if reach && (doubt || !blocked) {
            let lit = max_channel(sf.color) * intensity * ndl.max(0.0) + 255.0 * spec_open;
            if doubt && weight * lit > LEVEL {
                *why |= why::SHADOW;
            }
            if ndl.abs() <= e_gate && weight * 255.0 * spec_open > LEVEL {
                *why |= why::GATE;
            }
            let e_lv = e_l + ray.e_dir + ROUND;
            if (l + v).length() <= e_lv && weight * 255.0 * intensity * m.specular > LEVEL {
                *why |= why::GATE;
            }
        }
        diffuse_bound += intensity * ndl.max(0.0);
        if !blocked {
            diffuse += intensity * ndl.max(0.0);
            if ndl > 0.0 {
                spec += spec_open;
            }
        }
    }
    if let Some(jump) = sf.checker_doubt {
        if weight * jump * (scene.ambient + diffuse_bound) > LEVEL {
            *why |= why::CHECKER;
        }
    }
    let k = scene.ambient + diffuse;
    sf.color.map(|c| (c * k + 255.0 * spec).min(255.0))
}

/// Lab #1's local colour `colour × clamp(n·(−w), 0.3, 1)`, and its checker doubt.
fn lab1_local(sf: &Surface, weight: f64, why: &mut u8) -> Rgb {
    let k = sf.n_view.clamp(0.3, 1.0);
    if let Some(jump) = sf.checker_doubt {
        if weight * jump * k > LEVEL {
            *why |= why::CHECKER;
        }
    }
    sf.color.map(|c| c * k)
}

/// Traces the pixel whose camera ray is `dir` through a scene with lights, planes or
/// mirrors: the reference pixel and why it is undecidable, if it is.
#[must_use]
pub fn trace(camera: &RefCamera, scene: &RefScene, dir: D3) -> RefPixel {
    let background = rgb(scene.background);
    let mut ray = Ray {
        o: camera.eye,
        d: dir,
        len: dir.length(),
        e_o: 0.0,
        e_off: 0.0,
        e_dir: direction_error(camera, dir),
        from: None,
        chord: None,
    };
    let mut why = 0u8;
    let mut margin = f64::INFINITY;
    let mut primary: Option<(usize, f64)> = None;
    let mut weight = 1.0;
    let mut acc = [0.0f64; 3];
    let mut depth = 0u8;
    loop {
        let sphere_hits: Vec<RayHit> = if depth == 0 {
            scene
                .spheres
                .iter()
                .enumerate()
                .map(|(k, s)| {
                    if scene.hidden.get(k).copied().unwrap_or(false) {
                        HIDDEN
                    } else {
                        intersect(ray.o, ray.d, s.center, s.radius)
                    }
                })
                .collect()
        } else {
            Vec::new()
        };
        let cands = candidates(scene, &ray, &sphere_hits);
        let best = closest(&cands);
        let n_spheres = scene.spheres.len();
        if depth == 0 {
            primary = best.and_then(|b| b.t.map(|t| (b.index, t * ray.len)));
            // Sphere silhouettes and sphere–sphere ties: the reference's own band, as
            // for Lab #1 scenes; in front of whatever is visible.
            let front = best.and_then(|b| {
                let t = b.t?;
                Some(match sphere_hits.get(b.index) {
                    Some(h) => (b.index, t, h.t_err),
                    None => (usize::MAX, t, 0.0),
                })
            });
            let (undecidable, m) = sphere_doubt(&sphere_hits, front);
            margin = m;
            if undecidable {
                why |= why::SILHOUETTE;
            }
            // Every decision that involves a plane: f32 rounding.
            if plane_doubt(&cands, best, n_spheres) {
                why |= why::HORIZON;
            }
            for c in cands.iter().filter(|c| c.index >= n_spheres) {
                let Some(pl) = scene.planes.get(c.index - n_spheres) else {
                    continue;
                };
                let Some((n, _, _)) = pl.frame else {
                    continue;
                };
                let shown = best.map(|b| b.index);
                if shown.is_none() || shown == Some(c.index) {
                    margin = margin.min(ray.d.dot(n).abs() / ray.len);
                }
                if let (Some(b), Some(t)) = (best, c.t) {
                    if let Some(bt) = b.t.filter(|_| b.index != c.index) {
                        margin = margin.min((t - bt).abs() / bt);
                    }
                }
            }
        } else if weight * 255.0 > LEVEL && object_doubt(&cands, best) {
            why |= why::MIRROR;
        }
        let Some(sf) = best.and_then(|b| surface(scene, &ray, &b, camera.w)) else {
            for (a, b) in acc.iter_mut().zip(background) {
                *a += weight * b;
            }
            break;
        };
        let from = best.map_or(usize::MAX, |b| b.index);
        let r = sf.material.reflect;
        let w_local = weight * (1.0 - r);
        let local = if scene.lights.is_empty() {
            lab1_local(&sf, w_local, &mut why)
        } else {
            phong(scene, &ray, from, &sf, w_local, &mut why, camera.eye)
        };
        for (a, c) in acc.iter_mut().zip(local) {
            *a += w_local * c;
        }
        if !(r > 0.0) {
            break;
        }
        if depth >= scene.max_depth {
            // At the depth limit the background stands in for the reflected ray.
            for (a, b) in acc.iter_mut().zip(background) {
                *a += weight * r * b;
            }
            break;
        }
        // Mirror: reflect about the normal, d − 2(d·n)n, from the hit point.
        let d_hat = ray.d * (1.0 / ray.len);
        let refl = d_hat - sf.n * (2.0 * d_hat.dot(sf.n));
        ray = Ray {
            o: sf.p,
            d: refl,
            len: refl.length(),
            e_o: sf.e_p,
            e_off: sf.e_off_next,
            e_dir: sf.e_dir_next,
            from: Some(from),
            chord: sf.chord,
        };
        weight *= r;
        depth += 1;
    }
    // Rounded to 8 bits once, halves up.
    let level = |x: f64| (x + 0.5).floor().clamp(0.0, 255.0) as u8;
    let [r, g, b] = acc.map(level);
    RefPixel {
        hit: primary.map(|p| p.0),
        distance: primary.map_or(0.0, |p| p.1),
        color: Rgb888::new(r, g, b),
        undecidable: why != 0,
        margin,
        why,
    }
}
