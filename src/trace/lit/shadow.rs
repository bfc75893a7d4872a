//! Shadows on the first plane as the image sees them, and the shadow ray.
//!
//! Where a sphere's shadow can fall ([`shadow_disc`], [`shadow_silhouette`],
//! [`shadow_regions`]), each row's cut of those regions ([`ShadowRow`]), and a shadow
//! ray ([`ShadowRay`]).
//!
//! Per frame, each (light, sphere) pair gets the silhouette of a region of the image
//! that holds the sphere's shadow on the first plane; per row, the columns of each; per
//! pixel, a hit on that plane tests only the spheres whose column span holds it. The
//! incremental frames ask the same discs for the regions a moved sphere's shadow can
//! leave or reach ([`shadow_regions`]).

use core::cell::Cell;

use crate::camera::span::Silhouette;
use crate::camera::Camera;
use crate::math::vec3::Vec3;
use crate::method::intersect::{Scale, SphereGeom};
use crate::scene::sphere::Sphere;
use crate::scene::Scene;
use crate::trace::lit::consts::{FrameLight, FramePlane};
use crate::trace::lit::object::ObjectId;

/// A shadow ray: the open segment `o + s·l`, `0 < s < dist`, from a surface point
/// toward a light.
#[derive(Clone, Copy)]
pub(super) struct ShadowRay {
    /// The origin, on the surface it leaves (eye-relative, scaled).
    pub(super) o: Vec3,
    /// The unit direction toward the light.
    pub(super) l: Vec3,
    /// Where the segment ends: the lamp's distance (`∞` for a directional light).
    pub(super) dist: f32,
    /// The object `o` lies on.
    pub(super) from: ObjectId,
    /// `o` lies on a sphere's inner surface.
    pub(super) inside: bool,
}

/// One light's shadow spans on the current row: the spheres whose shadow on the first
/// plane can fall on the row, `(sphere, lo, len)` (columns `[lo, lo + len)`), packed
/// at the front.
pub(super) struct ShadowRow<const N: usize> {
    pub(super) count: Cell<usize>,
    pub(super) spans: [Cell<(ObjectId, u32, u32)>; N],
}

impl<const N: usize> ShadowRow<N> {
    /// A row without spans.
    pub(super) fn empty() -> Self {
        Self {
            count: Cell::new(0),
            spans: core::array::from_fn(|_| Cell::new((ObjectId::new(0), 0, 0))),
        }
    }
}

/// Where on the image the shadow that sphere `g` casts on `floor` under `light` can be
/// seen: the pixels whose ray meets the floor inside a disc that holds the shadow
/// (and, for a directional light, inside the shadow's own cylinder).
///
/// A primary ray that hits the floor outside it cannot be in that sphere's shadow;
/// `Silhouette::ALL` (no culling) where the shadow is not bounded.
///
/// - Directional light (unit `l` toward it): the shadow is the cut of the cylinder of
///   radius `r` along `l` through the centre `C` with the plane — an ellipse centred
///   where the axis meets the plane, `C − l·h_C/(l·n)` (`h_C` the centre's height),
///   with semi-major axis `r/|l·n|`.
/// - Point light at height `h_P` above the plane (the side it is on): the shadow lies
///   in the cut of the cone from the light that contains the sphere (half-angle
///   `α = asin(r/|C − P|)`, axis at angle `γ` from the plane's downward normal),
///   bounded when `γ + α < 90°`. Centred where the axis meets the plane (`h_C/cos γ`
///   beyond the centre along the axis), the cut reaches along the tilt at most
///   `h_P·(tan(γ + α) − tan γ) = h_P·sin α/(cos(γ + α)·cos γ)` (a direction within `α`
///   of the axis projects, in the vertical plane of the axis, within `α` of it; the
///   side toward the horizon is the longer) and across it at most
///   `|p − P|·sin α ≤ h_P·sin α / cos(γ + α)`: the root of the sum of their squares
///   bounds its radius. Products, not differences, and no point computed from the
///   light's position: nothing cancels for a light however far.
///
/// **Margins.** The shadow test may report a ray blocked where it passes up to
/// `r_eff` from the centre, `r_eff² = r²·(1 + 2⁻¹⁰) + 2⁻¹⁷·|C − o|²` for the tests that
/// cancel squares (the larger of the two margins of `camera::span`'s tests, so it
/// holds whichever test the method runs): the disc is that of the sphere of radius
/// `r_eff`, with `|C − o|` bounded by twice the farthest point of the sphere's own
/// disc from `C` (checked on the enlarged disc; otherwise no culling). That bound
/// assumes no origin farther away is in the shadow of a sphere enlarged for its own
/// distance: the enlarged shadow must grow more slowly than the distance, true unless
/// the light all but grazes the floor (a sun within about `2⁻⁷` of the plane), where
/// the random scenes of `tests/api/lit.rs` reach but no proof here does. The disc (and
/// the cylinder) is then enlarged by `2⁻⁸` of the lengths involved (far beyond the
/// `f32` rounding of the hit point and of the shadow ray's direction, a few `2⁻²⁴` of
/// them), and its image by the stepping's error bound ([`Silhouette::on_plane`]): the
/// disc on the plane, not a ball around it, so a low sun's long ellipse is not culled
/// as the circle around its long axis. Culling changes no pixel (`tests/api/lit.rs`
/// compares with the unculled loop on random lit scenes).
pub(super) fn shadow_silhouette(
    light: &FrameLight,
    g: &SphereGeom,
    floor: &FramePlane,
    camera: &Camera,
    step_err: f32,
) -> Silhouette {
    let (c, r) = (v64(g.l), libm::sqrt(f64::from(g.r2)));
    // The farthest a shadow ray's origin in the disc is from the centre.
    let reach = |d: &ShadowDisc| norm(sub(d.centre, c)) + d.radius;
    let Some(own) = shadow_disc(light, c, r, floor) else {
        return Silhouette::ALL;
    };
    let far = 2.0 * reach(&own);
    let r_eff = libm::sqrt(r * r * (1.0 + TWO_M10) + far * far * TWO_M17);
    match shadow_disc(light, c, r_eff, floor) {
        Some(disc) if reach(&disc) <= far => disc_silhouette(&disc, camera, step_err),
        _ => Silhouette::ALL,
    }
}

/// `2⁻¹⁰` and `2⁻¹⁷`: the shadow test's margin ([`shadow_silhouette`]), as the span
/// culling's quadratic one.
const TWO_M10: f64 = 1.0 / 1024.0;
const TWO_M17: f64 = 1.0 / 131_072.0;

/// A vector in `f64`.
fn v64(v: Vec3) -> [f64; 3] {
    [f64::from(v.x), f64::from(v.y), f64::from(v.z)]
}

/// `a − b`.
fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `|a|`.
fn norm(a: [f64; 3]) -> f64 {
    libm::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])
}

/// The pixels whose ray meets the plane inside `disc` (and for a directional light,
/// inside its cylinder): [`Silhouette::on_plane`].
fn disc_silhouette(disc: &ShadowDisc, camera: &Camera, step_err: f32) -> Silhouette {
    Silhouette::on_plane(
        disc.centre,
        disc.normal,
        disc.radius,
        disc.cylinder.map(|c| (c.axis, c.radius)),
        camera,
        step_err,
    )
}

/// A disc of a plane that holds a sphere's shadow ([`shadow_disc`]), in `f64`.
#[derive(Clone, Copy, Debug)]
struct ShadowDisc {
    /// The disc's centre, relative to the eye.
    centre: [f64; 3],
    radius: f64,
    /// The plane's unit normal (for a point light, pointing to the light's side).
    normal: [f64; 3],
    /// For a directional light, the shadow's own cylinder, whose cut with the plane the
    /// disc holds.
    cylinder: Option<ShadowCylinder>,
}

/// The cylinder of a directional light's shadow: every point within `radius` of the
/// line through the disc's centre along `axis`.
#[derive(Clone, Copy, Debug)]
struct ShadowCylinder {
    /// Unit direction toward the light.
    axis: [f64; 3],
    radius: f64,
}

/// The disc of `floor` that holds the shadow the sphere of centre `c` (relative to the
/// eye) and radius `r` casts under `light` ([`shadow_silhouette`]), and for a
/// directional light the cylinder it is the cut of; `None` where the shadow is not
/// bounded.
///
/// The cylinder's radius is enlarged by `2⁻⁸` of the lengths involved, and the disc's,
/// `r/|l·n|` (the cut's semi-major axis), by that slack over `|l·n|`: the disc holds
/// the enlarged cylinder's cut.
fn shadow_disc(light: &FrameLight, c: [f64; 3], r: f64, floor: &FramePlane) -> Option<ShadowDisc> {
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let along = |a: [f64; 3], b: [f64; 3], k: f64| [a[0] + b[0] * k, a[1] + b[1] * k, a[2] + b[2] * k];
    let (q, mut n) = (v64(floor.q), v64(floor.n));
    let h_c = dot(along(c, q, -1.0), n);
    // `stretch`: how much wider than the sphere's radius the disc must grow when the
    // radius does (a cylinder's cut is `1/|l·n|` times its radius along the tilt).
    let (centre, radius, axis, stretch) = match *light {
        FrameLight::Directional { l, .. } => {
            let l = v64(l);
            let ln = dot(l, n);
            let len = libm::sqrt(dot(l, l));
            let unit = [l[0] / len, l[1] / len, l[2] / len];
            (along(c, l, -h_c / ln), r / ln.abs(), Some(unit), 1.0 / ln.abs())
        }
        FrameLight::Point { p, .. } => {
            let p = v64(p);
            let mut h_p = dot(along(p, q, -1.0), n);
            if h_p < 0.0 {
                // Measure heights on the light's side.
                n = [-n[0], -n[1], -n[2]];
                h_p = -h_p;
            }
            let to_c = along(c, p, -1.0);
            let dist = libm::sqrt(dot(to_c, to_c));
            if !(dist > r && h_p > 0.0) {
                return None;
            }
            let axis = [to_c[0] / dist, to_c[1] / dist, to_c[2] / dist];
            let alpha = libm::asin(r / dist);
            let gamma = libm::acos((-dot(axis, n)).clamp(-1.0, 1.0));
            if !(gamma + alpha < core::f64::consts::FRAC_PI_2 - 1e-6) {
                return None;
            }
            // Along the tilt, a cut point lies h_P·tan θ from the light's foot with θ
            // within α of γ: at most h_P·(tan(γ + α) − tan γ) = h_P·sin α/(cos(γ + α)·cos γ)
            // from the axis' point (the larger side: cos(γ + α) < cos(γ − α)); across
            // it, at most |p − P|·sin α ≤ h_P·sin α/cos(γ + α). Written as products,
            // not differences of tangents, and the axis' point found from the sphere's
            // centre, not from the light: nothing cancels, however far the light (a
            // light 10¹⁷ away has α below f64's resolution of tan γ).
            let (sin_a, cos_g, cos_ga) = (libm::sin(alpha), libm::cos(gamma), libm::cos(gamma + alpha));
            let tilt = sin_a / (cos_ga * cos_g);
            let across = sin_a / cos_ga;
            let reach = libm::sqrt(tilt * tilt + across * across);
            // C's height on the light's side: the axis meets the plane h_C/cos γ on.
            let h_c = dot(along(c, q, -1.0), n);
            (along(c, axis, h_c / cos_g), h_p * reach, None, 1.0)
        }
    };
    let size = libm::sqrt(dot(centre, centre)) + libm::sqrt(dot(c, c)) + r;
    let slack = (radius + size) * (1.0 / 256.0);
    // Under the sun the disc holds the enlarged cylinder's whole cut: `(r + slack)/|l·n|`.
    let radius = radius + slack * stretch.max(1.0);
    if !(radius.is_finite() && size.is_finite()) {
        return None;
    }
    Some(ShadowDisc {
        centre,
        radius,
        normal: n,
        cylinder: axis.map(|axis| ShadowCylinder {
            axis,
            radius: r + slack,
        }),
    })
}

/// Where on the image the shadow that `sphere` casts on the scene's first plane under
/// each of its lights can be seen, one silhouette per usable light, passed to `f`.
///
/// Each is the image of the disc of the plane that holds the shadow ([`shadow_disc`]),
/// the same image the features frame culls its shadow rays with
/// ([`shadow_silhouette`]), in the frame's units (`scale`). Nothing for a scene without
/// a plane.
pub(crate) fn shadow_regions<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    sphere: &Sphere,
    camera: &Camera,
    (scale, step_err): (Scale, f32),
    mut f: impl FnMut(Silhouette),
) {
    let eye = camera.eye();
    let Some(plane) = scene.planes().first() else {
        return;
    };
    let floor = FramePlane::new(plane, eye, scale).unwrap_or(FramePlane::NEVER);
    let geom = SphereGeom::new(sphere.center, sphere.radius, eye, scale);
    for l in scene.lights() {
        if let Some(light) = FrameLight::new(l, eye, scale, f32::INFINITY) {
            f(
                match shadow_disc(&light, v64(geom.l), libm::sqrt(f64::from(geom.r2)), &floor) {
                    Some(disc) => disc_silhouette(&disc, camera, step_err),
                    None => Silhouette::ALL,
                },
            );
        }
    }
}
