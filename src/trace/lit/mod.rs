//! Scenes beyond Lab #1 spheres: planes (checkered floors), lights with shadow rays,
//! and mirrors. Chosen at compile time by the scene's type (`Scene<N, L, P, D>` with
//! any of `L`, `P`, `D` above 0): a `Scene<N>` never links this module.
//!
//! - **Per frame**: the spheres' constants as for Lab #1 (`frame.rs`, with
//!   [`LitSphere`]'s per-sphere shading constants), each plane's unit normal, signed
//!   distance and checker basis, each light's unit direction or eye-relative position —
//!   all in the frame's eye-relative, scaled units ([`Scale`]).
//! - **Per row**: each plane's span — a plane covers one side of its horizon line, and
//!   `d·n` is linear along the row — enlarged by the stepping's error bound.
//! - **Per pixel**: the closest hit over the active spheres (the method's own test, as
//!   in the Lab #1 loop) and the planes whose span holds the column; then the shading
//!   loop: the local colour (Lab #1 without lights; with lights, Phong with a shadow
//!   ray per light), and while the surface is a mirror and the depth allows, the
//!   reflected ray, traced with the method's single-ray test. A loop, not recursion:
//!   the stack does not grow with the depth.
//!
//! **Secondary rays start on a surface**, at a hit point computed in `f32`
//! ([`SecondaryOrigin`]): the default, [`SecondaryOrigin::Convex`], needs no epsilon —
//! a sphere or plane is convex, so a ray that leaves its outside cannot meet it again
//! and it is not tested; a ray leaving a sphere's inner surface meets it once more, at
//! `s = 2·(C − p)·r/(r·r)`, computed directly (no root near 0 to misjudge). The
//! textbook [`SecondaryOrigin::Epsilon`] starts the ray at `s = ε` and tests every
//! object: it is kept to show where it fails (`lab/tests/lab/lit_stability.rs`).
//! A shadow ray's other end, a point light, may lie on a surface too: the segment is
//! open there, and such a (light, object) pair is decided per frame without a root at
//! the lamp ([`Ties`]), as are coincident objects, which are one surface.

use core::cell::Cell;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::Vec;

use crate::camera::span::{Margin, Silhouette};
use crate::camera::Camera;
use crate::math::vec3::Vec3;
use crate::math::{sqrt_exact, SqrtFn, UNIT_ROUNDOFF};
use crate::method::intersect::{Auto, Robust, Scale, SphereGeom, TestStrategy, AUTO_FD_CAPACITY};
use crate::method::stepping::Stepper;
use crate::scene::light::Light;
use crate::scene::material::Material;
use crate::scene::sphere::Sphere;
use crate::scene::Scene;
use crate::trace::frame::{frame_scale, hull, Frame, FrameSphere};
use crate::trace::options::{Options, SecondaryOrigin};
use crate::trace::rows::{Fnv, Ident, Rows};
use crate::trace::scanline::RowSink;
use crate::trace::scanline::RowTracer;
use crate::trace::shade::{channels, lab1_factor, Shader};

/// How a secondary ray leaves its surface, as a strategy type.
pub(crate) trait Exit {
    /// Whether the surface the ray leaves is tested like any other object.
    const TESTS_SELF: bool;
    /// The ray's origin for a ray leaving `p` along `dir`.
    fn start(p: Vec3, dir: Vec3, eps: f32) -> Vec3;
}

/// [`SecondaryOrigin::Convex`].
pub(crate) struct ConvexExit;
/// [`SecondaryOrigin::Epsilon`].
pub(crate) struct EpsilonExit;

impl Exit for ConvexExit {
    const TESTS_SELF: bool = false;
    #[inline(always)]
    fn start(p: Vec3, _dir: Vec3, _eps: f32) -> Vec3 {
        p
    }
}

impl Exit for EpsilonExit {
    const TESTS_SELF: bool = true;
    #[inline(always)]
    fn start(p: Vec3, dir: Vec3, eps: f32) -> Vec3 {
        p + dir * (eps / sqrt_exact(dir.dot(dir)))
    }
}

/// The per-sphere shading constants of the scene-features path.
pub(crate) struct LitSphere;

/// [`LitSphere`]'s constants.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LitObject {
    /// The colour's channels as `f32`.
    rgb: [f32; 3],
    /// `1/r` in scaled units.
    inv_r: f32,
    material: Material,
}

impl Shader for LitSphere {
    type Object = LitObject;

    #[inline(always)]
    fn object(sphere: &Sphere, _g: &SphereGeom, scale: Scale, _w: Vec3) -> LitObject {
        LitObject {
            rgb: channels(sphere.color),
            inv_r: 1.0 / (sphere.radius * scale.0),
            material: sphere.material,
        }
    }
}

/// A plane as the frame sees it.
#[derive(Clone, Copy, Debug)]
struct FramePlane {
    /// The plane's anchor relative to the eye ([`Plane::anchor`]), scaled.
    q: Vec3,
    /// The unit normal, as given (not turned).
    n: Vec3,
    /// `q·n`: the eye's signed distance, negated; a ray hits where `d·n` has its sign.
    s: f32,
    rgb: [f32; 3],
    /// The odd cells' colour; `None`: not checkered.
    checker: Option<[f32; 3]>,
    /// The checker basis `e₁`, `e₂` and `1/size` (scaled).
    e1: Vec3,
    e2: Vec3,
    inv_size: f32,
    material: Material,
}

impl FramePlane {
    /// A plane no ray meets (`s = 0` and a zero normal: every `t` it gives is NaN or
    /// not positive): what an unusable plane of an unchecked scene becomes, so the
    /// other planes keep their object numbers.
    const NEVER: FramePlane = FramePlane {
        q: Vec3::ZERO,
        n: Vec3::ZERO,
        s: 0.0,
        rgb: [0.0; 3],
        checker: None,
        e1: Vec3::ZERO,
        e2: Vec3::ZERO,
        inv_size: 0.0,
        material: Material::DEFAULT,
    };

    /// The plane's constants; `None` for a zero or non-finite normal.
    fn new(plane: &crate::scene::plane::Plane, eye: Vec3, scale: Scale) -> Option<Self> {
        let (n, e1, e2) = plane.basis()?;
        let q = plane.anchor(eye) * scale.0;
        Some(Self {
            q,
            n,
            s: q.dot(n),
            rgb: channels(plane.color),
            checker: plane.checker.map(channels),
            e1,
            e2,
            inv_size: 1.0 / (plane.checker_size * scale.0),
            material: plane.material,
        })
    }

    /// The ray parameter where `o + t·dir` meets the plane (NaN or ±∞ where the ray is
    /// parallel to it, which every `t > 0 && t < t_max` test rejects).
    #[inline(always)]
    fn t_from(&self, o: Vec3, dir: Vec3) -> f32 {
        (self.q - o).dot(self.n) / dir.dot(self.n)
    }

    /// The colour at `p` (eye-relative, scaled): the checker cell's.
    #[inline(always)]
    fn color_at(&self, p: Vec3) -> [f32; 3] {
        match self.checker {
            None => self.rgb,
            Some(odd) => {
                let x = p - self.q;
                let cell =
                    floor(x.dot(self.e1) * self.inv_size).wrapping_add(floor(x.dot(self.e2) * self.inv_size));
                if cell & 1 == 0 {
                    self.rgb
                } else {
                    odd
                }
            }
        }
    }
}

/// The second root of the sphere `g` along `o + t·dir` (`a = dir·dir`) for an origin `o`
/// on its surface, where the first root is 0: `t = 2·(C − o)·dir/a`, positive only when
/// the ray goes into the sphere — computed directly, with no root near 0 to misjudge.
#[inline(always)]
fn far_root(g: &SphereGeom, o: Vec3, dir: Vec3, a: f32) -> f32 {
    2.0 * (g.l - o).dot(dir) / a
}

/// `floor(x)` as an `i32` (saturating at `±2³¹`, NaN → 0): only its parity is used.
/// `i32`, not `i64`: on a Cortex-M the `f32 → i32` conversion is one instruction and
/// the `i64` one a library call. Beyond `2³¹` cells from the plane's point every cell
/// is far smaller than a pixel (the checker is aliasing noise there, for the reference
/// too), so the saturated parity costs nothing visible.
#[inline(always)]
fn floor(x: f32) -> i32 {
    let t = x as i32;
    if (t as f32) > x {
        t.wrapping_sub(1)
    } else {
        t
    }
}

/// A light as the frame sees it.
#[derive(Clone, Copy, Debug)]
enum FrameLight {
    /// Unit vector toward the light.
    Directional { l: Vec3, intensity: f32 },
    /// Eye-relative, scaled position.
    Point { p: Vec3, intensity: f32 },
}

impl FrameLight {
    fn new(light: &Light, eye: Vec3, scale: Scale) -> Option<Self> {
        Some(match *light {
            Light::Directional { direction, intensity } => FrameLight::Directional {
                l: -direction.try_normalize()?,
                intensity,
            },
            Light::Point { position, intensity } => FrameLight::Point {
                p: (position - eye) * scale.0,
                intensity,
            },
        })
    }

    /// The lamp's position (a point light's), for the exact shadow path.
    #[inline(always)]
    fn at(&self) -> Vec3 {
        match *self {
            FrameLight::Point { p, .. } => p,
            FrameLight::Directional { .. } => Vec3::ZERO,
        }
    }
}

/// How close to a surface a lamp counts as lying on it, relative to the frame's
/// lengths: `2⁻¹⁶` (see [`Ties`]).
const ON_SURFACE: f64 = 1.0 / 65_536.0;

/// The frame's exact ties between objects, decided once per frame in `f64` from the
/// scene's own `f32` values (not from the rounded eye-relative ones), so that every
/// target decides them alike:
///
/// - **A lamp on a surface.** A point light `P` lies on sphere `(C, r)` when
///   `| |P − C| − r | ≤ 2⁻¹⁶·(|P − E| + |C − E| + r)`, on a plane through `Q` with
///   unit normal `n` when `|(P − Q)·n| ≤ 2⁻¹⁶·(|P − E| + |Q − E|)` (`E` the eye). A
///   shadow segment toward such a lamp ends on that surface, where the test's root at
///   `t ≈ dist` is compared with `dist`: both carry the rounding of the test, about
///   `8u·(|C − o| + r + |P − o|)` (`u = 2⁻²⁴`) across the surface, so the comparison is
///   a coin toss (speckles). For origins `o` within `S = |P − E| + |C − E| + r` of the
///   eye that rounding is at most `24u·S`, under a tenth of the bound `2⁻¹⁶·S =
///   256u·S`: a lamp farther from the surface than the bound is decided by the roots,
///   clear of the coin toss (origins farther out carry a rounding that grows with
///   their distance, as the reference's shadow band does). Within the bound the
///   segment is decided by the side it reaches the lamp from, with no root near
///   `dist`:
///   - a plane through the lamp never blocks (the segment meets it only at its open
///     end);
///   - the line through the lamp meets the sphere at the lamp and at `2σ` before it,
///     `σ = (P − C)·l` (`l` the unit direction toward the lamp): the segment is inside
///     the sphere just before the lamp iff `σ > 0`, and then blocked iff the other
///     root lies on it, `0 < 2σ < dist`. From the outside side (`σ ≤ 0`) the sphere
///     does not block; a segment from within the sphere (`2σ ≥ dist`, e.g. from its
///     own inner surface) does not either. A lamp inside a sphere (farther than the
///     bound from it) is decided by the roots, as any occluder.
/// - **Coincident objects.** A sphere with the same centre and radius bits as a
///   lower-numbered one (a plane with the same point and normal bits) is the same
///   surface: every test computes the same bits for both, so a primary ray shows the
///   lower number (the strict `t < t_max`), and a secondary ray leaving either treats
///   the other as the surface it leaves (the convex exit): no ray sees one twin from
///   the other at `t ≈ 0`.
///
/// A frame without either tie draws the pixels it would without this rule: its rows
/// call the plain shadow test (through the pointer each row picks,
/// [`LitRow::shadow`]) and its reflected rays test one flag.
#[derive(PartialEq)]
struct Ties<const N: usize, const L: usize, const P: usize> {
    /// Per light (the frame's numbering) and sphere: the lamp lies on it.
    on_sphere: [[bool; N]; L],
    /// Per light and plane: the lamp lies on it.
    on_plane: [[bool; P]; L],
    /// Per sphere: the lowest-numbered sphere identical to it (itself if none).
    sphere_twin: [Object; N],
    /// Per plane: the object number of the lowest-numbered identical plane.
    plane_twin: [Object; P],
    /// Some object has a lower-numbered twin.
    twins: bool,
    /// Per light: its shadow rays need the ties (see [`Ties::exact`]).
    exact: [bool; L],
    /// Some light's do: one test per shadow ray for a frame without ties.
    any: bool,
}

impl<const N: usize, const L: usize, const P: usize> Ties<N, L, P> {
    /// The ties of `scene` seen from `eye`, and each light's `exact` flag (the frame's
    /// lights: the scene's in order, less the unusable ones). Once per frame, out of
    /// line.
    #[cold]
    #[inline(never)]
    fn new<const D: usize>(scene: &Scene<N, L, P, D>, eye: Vec3) -> Self {
        let v = |a: Vec3| [f64::from(a.x), f64::from(a.y), f64::from(a.z)];
        let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let len = |a: [f64; 3]| libm::sqrt(dot(a, a));
        let e = v(eye);
        let spheres = scene.spheres();
        let planes = scene.planes();
        let n_spheres = spheres.len();
        let bits = |a: Vec3| (a.x.to_bits(), a.y.to_bits(), a.z.to_bits());
        let mut sphere_twin: [Object; N] = core::array::from_fn(|k| k);
        let mut plane_twin: [Object; P] = core::array::from_fn(|k| n_spheres + k);
        let mut twins = false;
        for (k, s) in spheres.iter().enumerate() {
            let key = (bits(s.center), s.radius.to_bits());
            if let (Some(j), Some(slot)) = (
                spheres
                    .iter()
                    .position(|t| (bits(t.center), t.radius.to_bits()) == key),
                sphere_twin.get_mut(k),
            ) {
                *slot = j;
                twins |= j != k;
            }
        }
        for (k, p) in planes.iter().enumerate() {
            let key = (bits(p.point), bits(p.normal));
            if let (Some(j), Some(slot)) = (
                planes.iter().position(|q| (bits(q.point), bits(q.normal)) == key),
                plane_twin.get_mut(k),
            ) {
                *slot = n_spheres + j;
                twins |= j != k;
            }
        }
        let mut on_sphere = [[false; N]; L];
        let mut on_plane = [[false; P]; L];
        let usable = scene.lights().iter().filter(|l| match **l {
            Light::Directional { direction, .. } => direction.try_normalize().is_some(),
            Light::Point { .. } => true,
        });
        let mut exact = [false; L];
        let mut any = false;
        for (((light, exact), row), prow) in usable.zip(&mut exact).zip(&mut on_sphere).zip(&mut on_plane) {
            let mut on = false;
            if let Light::Point { position, .. } = *light {
                let at = v(position);
                let pe = len(sub(at, e));
                for (flag, s) in row.iter_mut().zip(spheres) {
                    let (c, r) = (v(s.center), f64::from(s.radius));
                    let gap = len(sub(at, c)) - r;
                    *flag = gap.abs() <= ON_SURFACE * (pe + len(sub(c, e)) + r);
                    on |= *flag;
                }
                for (flag, p) in prow.iter_mut().zip(planes) {
                    let Some(n) = p.normal.try_normalize() else {
                        continue;
                    };
                    let q = v(p.point);
                    let h = dot(sub(at, q), v(n));
                    *flag = h.abs() <= ON_SURFACE * (pe + len(sub(q, e)));
                    on |= *flag;
                }
            }
            *exact = on || twins;
            any |= *exact;
        }
        Self {
            on_sphere,
            on_plane,
            sphere_twin,
            plane_twin,
            twins,
            exact,
            any,
        }
    }

    /// Which lights' shadow rays take [`LitRow::occluded_exact`] (their lamp lies on
    /// some object, or the frame has coincident objects), as a mask for the pixel loop:
    /// bit `k` for light `k`, bit 31 for every light from 31 on.
    fn exact_mask(&self) -> u32 {
        if !self.any {
            return 0;
        }
        let mut mask = 0;
        for (k, &e) in self.exact.iter().enumerate() {
            if e {
                mask |= 1 << k.min(31);
            }
        }
        mask
    }
}

/// The object a hit is on: spheres `0 … n − 1`, then planes.
type Object = usize;

/// Per-frame state of the scene-features path.
struct LitFrame<'a, T: TestStrategy, const N: usize, const L: usize, const P: usize> {
    spheres: &'a [FrameSphere<T, LitSphere>],
    /// Lamps on surfaces and coincident objects.
    ties: &'a Ties<N, L, P>,
    /// [`Ties::exact_mask`]: 0 in a frame without ties, one test per shadow ray.
    exact_lights: u32,
    /// [`Ties::twins`], where the reflected ray's loop reads it.
    twins: bool,
    /// Per light and sphere: where on the image the sphere's shadow on the first plane
    /// can be (see [`shadow_silhouette`]).
    shadow: &'a [[Silhouette; N]; L],
    /// Per light, the current row's cut of those silhouettes: one buffer for the
    /// frame, rewritten per row (a per-row array of `N × L` spans would be zeroed and
    /// moved for every row).
    shadow_rows: &'a [ShadowRow<N>; L],
    planes: &'a [FramePlane],
    lights: &'a [FrameLight],
    camera: &'a Camera,
    w: Vec3,
    background: Rgb888,
    bg: [f32; 3],
    ambient: f32,
    max_depth: u8,
    shadows: bool,
    any_hit: bool,
    span_culling: bool,
    /// The epsilon of [`SecondaryOrigin::Epsilon`], scaled.
    eps: f32,
    /// The stepping's direction error bound plus the dot product's rounding: how far a
    /// computed `d·n` can be from the ideal one (planes' span margin).
    dn_margin: f64,
    /// Visible columns.
    i0: u32,
    i1: u32,
}

/// A surface point: its normal turned toward the ray's origin, the normal Lab #1 uses,
/// colour and material.
struct Surface {
    n: Vec3,
    /// `n·(−w)` with a sphere's outward normal or a plane's turned one (Lab #1).
    lab_nz: f32,
    rgb: [f32; 3],
    material: Material,
    /// The ray met a sphere's inner surface (it can meet it again).
    inside: bool,
}

/// One light's shadow spans on the current row: the spheres whose shadow on the first
/// plane can fall on the row, `(sphere, lo, len)` (columns `[lo, lo + len)`), packed
/// at the front.
struct ShadowRow<const N: usize> {
    count: Cell<usize>,
    spans: [Cell<(Object, u32, u32)>; N],
}

impl<const N: usize> ShadowRow<N> {
    fn empty() -> Self {
        Self {
            count: Cell::new(0),
            spans: core::array::from_fn(|_| Cell::new((0, 0, 0))),
        }
    }
}

/// Renders one frame of a scene with lights, planes or mirrors.
///
/// Out of line, as `lab1::render` is: the per-sphere constants live in this
/// function's own stack frame, so a render pays for its own method's, not for the
/// largest of all the methods the one dispatch could have chosen.
#[inline(never)]
pub(crate) fn render<
    const N: usize,
    const L: usize,
    const P: usize,
    const D: usize,
    K: RowSink,
    S: Stepper,
    T: TestStrategy,
    Q: SqrtFn,
    G: Rows,
    I: Iterator<Item = Rectangle> + Clone,
>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    options: Options,
    (clips, rows): (I, G),
    offset: Point,
    sink: &mut K,
) -> Result<(), K::Error> {
    // `Auto` in a scene type above its limit (see `AUTO_FD_CAPACITY`); a capacity
    // within it never reaches the comparison.
    if T::AUTO && N > AUTO_FD_CAPACITY {
        return auto_above_limit::<N, L, P, D, K, S, Q, G, I>(
            scene,
            camera,
            options,
            (clips, rows),
            offset,
            sink,
        );
    }
    by_origin::<N, L, P, D, K, S, T, Q, G, I>(scene, camera, options, (clips, rows), offset, sink)
}

/// `Auto` in a scene type of more than [`AUTO_FD_CAPACITY`] spheres' capacity: the
/// robust test for a scene holding more than that many, else `Auto` (each branch out
/// of line, so that their frames never add up).
#[inline(never)]
fn auto_above_limit<
    const N: usize,
    const L: usize,
    const P: usize,
    const D: usize,
    K: RowSink,
    S: Stepper,
    Q: SqrtFn,
    G: Rows,
    I: Iterator<Item = Rectangle> + Clone,
>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    options: Options,
    frame: (I, G),
    offset: Point,
    sink: &mut K,
) -> Result<(), K::Error> {
    if scene.spheres().len() > AUTO_FD_CAPACITY {
        render::<N, L, P, D, K, S, Robust, Q, G, I>(scene, camera, options, frame, offset, sink)
    } else {
        auto_within_limit::<N, L, P, D, K, S, Q, G, I>(scene, camera, options, frame, offset, sink)
    }
}

/// `Auto` in a scene holding at most [`AUTO_FD_CAPACITY`] spheres.
#[inline(never)]
fn auto_within_limit<
    const N: usize,
    const L: usize,
    const P: usize,
    const D: usize,
    K: RowSink,
    S: Stepper,
    Q: SqrtFn,
    G: Rows,
    I: Iterator<Item = Rectangle> + Clone,
>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    options: Options,
    frame: (I, G),
    offset: Point,
    sink: &mut K,
) -> Result<(), K::Error> {
    by_origin::<N, L, P, D, K, S, Auto, Q, G, I>(scene, camera, options, frame, offset, sink)
}

/// [`render`]'s frame with the secondary rays' origin rule, chosen once per frame.
#[inline(always)]
fn by_origin<
    const N: usize,
    const L: usize,
    const P: usize,
    const D: usize,
    K: RowSink,
    S: Stepper,
    T: TestStrategy,
    Q: SqrtFn,
    G: Rows,
    I: Iterator<Item = Rectangle> + Clone,
>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    options: Options,
    (clips, rows): (I, G),
    offset: Point,
    sink: &mut K,
) -> Result<(), K::Error> {
    match options.secondary {
        SecondaryOrigin::Convex => render_with::<N, L, P, D, K, S, T, Q, ConvexExit, G, I>(
            scene,
            camera,
            options,
            0.0,
            (clips, rows),
            offset,
            sink,
        ),
        SecondaryOrigin::Epsilon(eps) => render_with::<N, L, P, D, K, S, T, Q, EpsilonExit, G, I>(
            scene,
            camera,
            options,
            eps,
            (clips, rows),
            offset,
            sink,
        ),
    }
}

#[allow(clippy::too_many_arguments)]
fn render_with<
    const N: usize,
    const L: usize,
    const P: usize,
    const D: usize,
    K: RowSink,
    S: Stepper,
    T: TestStrategy,
    Q: SqrtFn,
    O: Exit,
    G: Rows,
    I: Iterator<Item = Rectangle> + Clone,
>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    options: Options,
    eps: f32,
    (clips, rows): (I, G),
    offset: Point,
    sink: &mut K,
) -> Result<(), K::Error> {
    let eye = camera.eye();
    let mut spheres = Vec::new();
    // Secondary rays can meet any object: none is culled for the frame's scale.
    // The frame's scale, from the scene, camera and method alone (never the clip).
    let step_err = S::error_bound(camera);
    let decided = match frame_scale::<N, L, P, D>(scene, camera, step_err, false) {
        Ok(decided) => decided,
        Err(why) => return sink.refused(why),
    };
    // The frame over every clip's rows (its per-frame work once), then each clip's.
    let Some(bound) = clips.clone().map(|c| rows.clip(c)).reduce(hull) else {
        return Ok(());
    };
    let Some(frame) = Frame::<T, LitSphere>::new::<N, N, L, P, D, S>(
        scene,
        camera,
        options,
        bound,
        offset,
        &mut spheres,
        step_err,
        decided,
    ) else {
        return Ok(()); // nothing visible
    };
    let mut planes: Vec<FramePlane, P> = Vec::new();
    for p in scene.planes() {
        // Never fails: the scene holds at most P planes.
        let _ = planes.push(FramePlane::new(p, eye, frame.scale).unwrap_or(FramePlane::NEVER));
    }
    let mut lights: Vec<FrameLight, L> = Vec::new();
    for l in scene.lights() {
        if let Some(fl) = FrameLight::new(l, eye, frame.scale) {
            let _ = lights.push(fl);
        }
    }
    let ties = Ties::new(scene, eye);
    let size = camera.size();
    let d_max = f64::from(camera.first_direction().length())
        + f64::from(size.width) * f64::from(camera.pixel_step().length())
        + f64::from(size.height) * f64::from(camera.scanline_step().length());
    // Shadow spans: per light and sphere, the image region where the sphere's shadow on
    // the first plane can fall — outside it a floor pixel does not test that sphere. A
    // scene without shadows casts no shadow ray, so none is built (they stay `ALL`).
    let mut shadow = [[Silhouette::ALL; N]; L];
    if let (true, true, Some(floor)) = (scene.settings().shadows, options.span_culling, planes.first()) {
        for (row, light) in shadow.iter_mut().zip(&lights) {
            for (sil, fs) in row.iter_mut().zip(frame.spheres) {
                *sil = shadow_silhouette(light, &fs.geom, floor, camera, step_err);
            }
        }
    }
    let shadow_rows: [ShadowRow<N>; L] = core::array::from_fn(|_| ShadowRow::empty());
    let lit = LitFrame {
        spheres: frame.spheres,
        ties: &ties,
        exact_lights: ties.exact_mask(),
        twins: ties.twins,
        shadow: &shadow,
        shadow_rows: &shadow_rows,
        planes: &planes,
        lights: &lights,
        camera,
        w: camera.w(),
        background: frame.background,
        bg: channels(frame.background),
        ambient: scene.settings().ambient,
        max_depth: scene.max_depth(),
        shadows: scene.settings().shadows,
        any_hit: options.shadow_any_hit,
        span_culling: options.span_culling,
        eps: eps * frame.scale.0,
        dn_margin: f64::from(step_err) + 8.0 * f64::from(UNIT_ROUNDOFF) * d_max,
        i0: frame.i0,
        i1: frame.i1,
    };
    for clip in clips {
        let Some(frame) = frame.clipped(rows.clip(clip)) else {
            continue;
        };
        let lit = LitFrame {
            i0: frame.i0,
            i1: frame.i1,
            ..lit
        };
        rows.draw_rows::<N, K, S, T, Q, LitSphere, _>(&frame, sink, |j, lo, hi| {
            LitRow::<T, Q, O, N, L, P, D>::new(&lit, j, lo, hi)
        })?;
    }
    Ok(())
}

/// One row of the scene-features path: the planes' spans, the shadow spans and, per
/// light, the object that last shadowed a pixel of the row (tested first: neighbouring
/// pixels are usually shadowed by the same occluder).
struct LitRow<'f, 's, T: TestStrategy, Q, O, const N: usize, const L: usize, const P: usize, const D: usize> {
    f: &'f LitFrame<'s, T, N, L, P>,
    /// Per plane: columns `[lo, lo + len)` whose rays can hit it.
    spans: [(u32, u32); P],
    occluder: [Object; L],
    /// The shadow test: [`Self::occluded`], or in a frame with ties
    /// [`Self::occluded_with_ties`] — chosen per row, called through a pointer, so a
    /// frame without ties runs the loop it would without them.
    shadow: Shadow<'f, 's, T, Q, O, N, L, P, D>,
    marker: core::marker::PhantomData<(Q, O)>,
}

/// [`LitRow::shadow`]'s type.
type Shadow<'f, 's, T, Q, O, const N: usize, const L: usize, const P: usize, const D: usize> =
    fn(&mut LitRow<'f, 's, T, Q, O, N, L, P, D>, usize, Vec3, Vec3, f32, Object, bool, Option<u32>) -> bool;

/// No occluder cached.
const NONE: Object = usize::MAX;

/// A reflected ray's identity where it hits nothing.
const REFLECTS_NOTHING: u32 = 0x9e37_79b9;

impl<
        'f,
        's,
        T: TestStrategy,
        Q: SqrtFn,
        O: Exit,
        const N: usize,
        const L: usize,
        const P: usize,
        const D: usize,
    > LitRow<'f, 's, T, Q, O, N, L, P, D>
{
    /// Row `j`: the planes' spans, widening the row's traced union `[lo_all, hi_all)`,
    /// and the shadow spans.
    #[inline(never)]
    fn new(f: &'f LitFrame<'s, T, N, L, P>, j: u32, lo_all: &mut u32, hi_all: &mut u32) -> Self {
        let mut spans = [(0, 0); P];
        for (span, plane) in spans.iter_mut().zip(f.planes) {
            if let Some((lo, hi)) = plane_span(f, plane, j) {
                *span = (lo, hi - lo);
                *lo_all = (*lo_all).min(lo);
                *hi_all = (*hi_all).max(hi);
            }
        }
        // The shadow spans of this row (where the first plane is in view at all).
        let floor_in_view = spans.first().is_some_and(|&(_, len)| len > 0);
        for (row, sils) in f.shadow_rows.iter().zip(f.shadow).take(f.lights.len()) {
            let mut count = 0;
            if floor_in_view {
                for (k, sil) in sils.iter().enumerate().take(f.spheres.len()) {
                    if let (Some((lo, hi)), Some(slot)) = (sil.row_span(j, f.i0, f.i1), row.spans.get(count))
                    {
                        slot.set((k, lo, hi - lo));
                        count += 1;
                    }
                }
            }
            row.count.set(count);
        }
        Self {
            f,
            spans,
            occluder: [NONE; L],
            shadow: if f.exact_lights != 0 {
                Self::occluded_with_ties
            } else {
                Self::occluded
            },
            marker: core::marker::PhantomData,
        }
    }

    /// The object a ray from `o` along `dir` meets first, and where; `from` is the
    /// object `o` lies on (`inside`: on a sphere's inner surface).
    fn closest(&self, o: Vec3, dir: Vec3, from: Object, inside: bool) -> Option<(Object, f32)> {
        let f = self.f;
        if f.twins {
            return self.closest_twins(o, dir, from, inside);
        }
        let a = dir.dot(dir);
        let mut best = None;
        let mut t_max = f32::INFINITY;
        for (k, s) in f.spheres.iter().enumerate() {
            let t = if !O::TESTS_SELF && k == from {
                // Leaving the outside: convex, never met again. Leaving the inner
                // surface: met at the far root, directly.
                if !inside {
                    continue;
                }
                let t = far_root(&s.geom, o, dir, a);
                (t > 0.0 && t < t_max).then_some(t)
            } else {
                T::ray::<Q>(&s.geom.seen_from(o), dir, a, t_max)
            };
            if let Some(t) = t {
                t_max = t;
                best = Some((k, t));
            }
        }
        let n = f.spheres.len();
        for (k, plane) in f.planes.iter().enumerate() {
            if !O::TESTS_SELF && n + k == from {
                continue; // a ray leaving a plane never meets it again
            }
            let t = plane.t_from(o, dir);
            if t > 0.0 && t < t_max {
                t_max = t;
                best = Some((n + k, t));
            }
        }
        best
    }

    /// [`Self::closest`] in a frame with coincident objects ([`Ties`]): an object with
    /// a lower-numbered twin is left out (the twin computes the same bits and wins the
    /// tie), and the twin of the surface the ray leaves is that surface.
    #[inline(always)]
    fn closest_twins(&self, o: Vec3, dir: Vec3, from: Object, inside: bool) -> Option<(Object, f32)> {
        closest_twins::<T, Q>(&self.objects(), o, dir, from, inside)
    }

    /// The frame's objects and ties as the exact paths read them.
    #[inline(always)]
    fn objects(&self) -> Objects<'_, T> {
        let f = self.f;
        Objects {
            spheres: f.spheres,
            planes: f.planes,
            sphere_twin: &f.ties.sphere_twin,
            plane_twin: &f.ties.plane_twin,
            tests_self: O::TESTS_SELF,
        }
    }

    /// Whether object `k` crosses the open segment `o + s·l`, `0 < s < dist` (`l` unit);
    /// `from`/`inside` as for [`Self::closest`].
    #[inline(always)]
    fn blocks(&self, k: Object, o: Vec3, l: Vec3, dist: f32, from: Object, inside: bool) -> bool {
        let f = self.f;
        if let Some(s) = f.spheres.get(k) {
            if !O::TESTS_SELF && k == from {
                if !inside {
                    return false;
                }
                let t = far_root(&s.geom, o, l, l.dot(l));
                return t > 0.0 && t < dist;
            }
            // A segment wholly inside a sphere ends before its far root: `t < dist` fails.
            T::ray::<Q>(&s.geom.seen_from(o), l, l.dot(l), dist).is_some()
        } else if let Some(plane) = k.checked_sub(f.spheres.len()).and_then(|p| f.planes.get(p)) {
            if !O::TESTS_SELF && k == from {
                return false;
            }
            let t = plane.t_from(o, l);
            t > 0.0 && t < dist
        } else {
            false
        }
    }

    /// Whether the light's segment from `o` is blocked: for a primary ray's hit on the
    /// first plane (`column` is its column), only the spheres whose shadow span on this
    /// row holds the column can block it, then the planes; otherwise the light's last
    /// occluder first, then every object until one blocks (any hit). The literal
    /// baseline tests every object, as a closest-hit search would. Any hit: the order
    /// of the tests changes no answer.
    #[allow(clippy::too_many_arguments)]
    fn occluded(
        &mut self,
        light: usize,
        o: Vec3,
        l: Vec3,
        dist: f32,
        from: Object,
        inside: bool,
        column: Option<u32>,
    ) -> bool {
        let f = self.f;
        let n = f.spheres.len();
        let count = n + f.planes.len();
        if !f.any_hit {
            let mut blocked = false;
            for k in 0..count {
                blocked |= self.blocks(k, o, l, dist, from, inside);
            }
            return blocked;
        }
        if let (Some(i), true, Some(row)) = (column, from == n, f.shadow_rows.get(light)) {
            for slot in row.spans.iter().take(row.count.get()) {
                let (k, lo, len) = slot.get();
                if i.wrapping_sub(lo) < len && self.blocks(k, o, l, dist, from, inside) {
                    return true;
                }
            }
            return (n..count).any(|k| self.blocks(k, o, l, dist, from, inside));
        }
        let cached = self.occluder.get(light).copied().unwrap_or(NONE);
        if cached != NONE && self.blocks(cached, o, l, dist, from, inside) {
            return true;
        }
        for k in 0..count {
            if k != cached && self.blocks(k, o, l, dist, from, inside) {
                if let Some(c) = self.occluder.get_mut(light) {
                    *c = k;
                }
                return true;
            }
        }
        false
    }

    /// [`Self::occluded`] for a light whose shadow rays need the frame's ties
    /// ([`Ties`]): its lamp lies on some object, or the frame has coincident objects.
    /// Every object is tested (no shadow span, no cached occluder): an object with a
    /// lower-numbered twin is left out, the twin of the surface `o` lies on is that
    /// surface, and an object the lamp (at `at`) lies on is decided by the side the
    /// segment reaches the lamp from.
    /// [`Self::occluded`] in a frame with ties: [`Self::occluded_exact`] for the lights
    /// that need it.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    fn occluded_with_ties(
        &mut self,
        light: usize,
        o: Vec3,
        l: Vec3,
        dist: f32,
        from: Object,
        inside: bool,
        column: Option<u32>,
    ) -> bool {
        if self.f.exact_lights & (1 << light.min(31)) != 0 {
            self.occluded_exact(light, o, l, dist, from, inside)
        } else {
            self.occluded(light, o, l, dist, from, inside, column)
        }
    }

    #[inline(always)]
    fn occluded_exact(&self, light: usize, o: Vec3, l: Vec3, dist: f32, from: Object, inside: bool) -> bool {
        let f = self.f;
        let (Some(on_sphere), Some(on_plane), Some(at)) = (
            f.ties.on_sphere.get(light),
            f.ties.on_plane.get(light),
            f.lights.get(light).map(FrameLight::at),
        ) else {
            return false;
        };
        occluded_exact::<T, Q>(
            &self.objects(),
            (on_sphere, on_plane, at),
            o,
            l,
            dist,
            from,
            inside,
        )
    }

    /// The surface at `p` of object `k`, met by a ray along `dir`.
    #[inline(always)]
    fn surface(&self, k: Object, p: Vec3, dir: Vec3) -> Surface {
        let f = self.f;
        if let Some(s) = f.spheres.get(k) {
            let n_out = (p - s.geom.l) * s.shade.inv_r;
            let inside = dir.dot(n_out) > 0.0;
            Surface {
                n: if inside { -n_out } else { n_out },
                lab_nz: -n_out.dot(f.w),
                rgb: s.shade.rgb,
                material: s.shade.material,
                inside,
            }
        } else if let Some(plane) = k.checked_sub(f.spheres.len()).and_then(|i| f.planes.get(i)) {
            let n = if dir.dot(plane.n) > 0.0 { -plane.n } else { plane.n };
            Surface {
                n,
                lab_nz: -n.dot(f.w),
                rgb: plane.color_at(p),
                material: plane.material,
                inside: false,
            }
        } else {
            // Unreachable (`k` comes from a hit); shade as the background.
            Surface {
                n: f.w,
                lab_nz: 0.0,
                rgb: f.bg,
                material: Material::DEFAULT,
                inside: false,
            }
        }
    }

    /// The local colour at `p` (not rounded): Lab #1 without lights, otherwise
    /// ambient + diffuse + specular with a shadow ray per light.
    #[inline(always)]
    fn local(&mut self, k: Object, s: &Surface, p: Vec3, dir: Vec3, column: Option<u32>) -> [f32; 3] {
        if L == 0 || self.f.lights.is_empty() {
            let kz = lab1_factor(s.lab_nz);
            return s.rgb.map(|c| c * kz);
        }
        let f = self.f;
        // v, the unit vector back along the ray, only where a highlight needs it.
        let v = if s.material.specular > 0.0 {
            dir * (-1.0 / sqrt_exact(dir.dot(dir)))
        } else {
            Vec3::ZERO
        };
        let (mut diffuse, mut spec) = (0.0f32, 0.0f32);
        for (index, light) in f.lights.iter().enumerate() {
            let (l, dist, intensity) = match *light {
                FrameLight::Directional { l, intensity } => (l, f32::INFINITY, intensity),
                FrameLight::Point { p: at, intensity } => {
                    let to = at - p;
                    let dist = sqrt_exact(to.dot(to));
                    (to * (1.0 / dist), dist, intensity)
                }
            };
            let nl = s.n.dot(l);
            // Only a light in front of the surface lights it (and needs a shadow ray).
            if !(nl > 0.0) {
                continue;
            }
            if f.shadows {
                let o = O::start(p, l, f.eps);
                let dist = if O::TESTS_SELF { dist - f.eps } else { dist };
                let blocked = (self.shadow)(self, index, o, l, dist, k, s.inside, column);
                if blocked {
                    continue;
                }
            }
            diffuse += intensity * nl;
            if s.material.specular > 0.0 {
                // n·h with h = (l + v)/|l + v|: one root and one division, no vector
                // scaling (|l + v| ≤ 2: no overflow). No highlight where l + v = 0.
                let half = l + v;
                let h2 = half.dot(half);
                if h2 > 0.0 {
                    let nh = s.n.dot(half) / sqrt_exact(h2);
                    if nh > 0.0 {
                        spec += intensity * s.material.specular * phong_power(nh, s.material.shininess);
                    }
                }
            }
        }
        let light = f.ambient + diffuse;
        let spec = 255.0 * spec;
        s.rgb.map(|c| {
            let x = c * light + spec;
            if x > 255.0 {
                255.0
            } else {
                x
            }
        })
    }

    /// The colour of a primary ray along `d` whose closest hit is `first`: the local
    /// colour, mixed with what the reflected rays see while the surface is a mirror and
    /// the depth allows, rounded to 8 bits once.
    ///
    /// Out of line: the row loop inlines the tracer twice (samples and colour runs),
    /// and shading is hundreds of instructions per pixel, so one copy per scene type
    /// costs one call per pixel and halves the path's flash.
    #[inline(never)]
    fn color(&mut self, first: Option<(Object, f32)>, d: Vec3, i: u32) -> Rgb888 {
        let f = self.f;
        let mut acc = [0.0f32; 3];
        let mut weight = 1.0f32;
        let (mut origin, mut dir, mut hit) = (Vec3::ZERO, d, first);
        let mut depth = 0u8;
        loop {
            let Some((k, t)) = hit else {
                add(&mut acc, weight, f.bg);
                break;
            };
            let p = origin + dir * t;
            let s = self.surface(k, p, dir);
            // The shadow spans hold for the primary ray only.
            let column = (depth == 0).then_some(i);
            let local = self.local(k, &s, p, dir, column);
            let r = if D == 0 { 0.0 } else { s.material.reflect };
            if !(r > 0.0) {
                add(&mut acc, weight, local);
                break;
            }
            add(&mut acc, weight * (1.0 - r), local);
            weight *= r;
            if depth >= f.max_depth {
                // At the deepest level the background stands in for the reflection.
                add(&mut acc, weight, f.bg);
                break;
            }
            // The mirror direction d − 2(d·n)n (the same for n and −n).
            dir = dir - s.n * (2.0 * dir.dot(s.n));
            origin = O::start(p, dir, f.eps);
            hit = self.closest(origin, dir, k, s.inside);
            depth += 1;
        }
        let round = |x: f32| {
            let v = (x + 0.5) as i32;
            if v > 255 {
                255
            } else {
                v as u8
            }
        };
        Rgb888::new(round(acc[0]), round(acc[1]), round(acc[2]))
    }

    /// [`Self::local`] with the ray's identity (which lights reach the point) mixed
    /// into `id`: the copy adaptive sampling's rays use, so that the one-ray path's
    /// code stays as it is.
    ///
    /// The local colour at `p` (not rounded): Lab #1 without lights, otherwise
    /// ambient + diffuse + specular with a shadow ray per light.
    #[inline(always)]
    fn local_with<I: Ident>(
        &mut self,
        k: Object,
        s: &Surface,
        p: Vec3,
        dir: Vec3,
        column: Option<u32>,
        id: &mut I,
    ) -> [f32; 3] {
        if L == 0 || self.f.lights.is_empty() {
            let kz = lab1_factor(s.lab_nz);
            return s.rgb.map(|c| c * kz);
        }
        let f = self.f;
        // v, the unit vector back along the ray, only where a highlight needs it.
        let v = if s.material.specular > 0.0 {
            dir * (-1.0 / sqrt_exact(dir.dot(dir)))
        } else {
            Vec3::ZERO
        };
        let (mut diffuse, mut spec) = (0.0f32, 0.0f32);
        for (index, light) in f.lights.iter().enumerate() {
            let (l, dist, intensity) = match *light {
                FrameLight::Directional { l, intensity } => (l, f32::INFINITY, intensity),
                FrameLight::Point { p: at, intensity } => {
                    let to = at - p;
                    let dist = sqrt_exact(to.dot(to));
                    (to * (1.0 / dist), dist, intensity)
                }
            };
            let nl = s.n.dot(l);
            // Only a light in front of the surface lights it (and needs a shadow ray).
            if !(nl > 0.0) {
                continue;
            }
            if f.shadows {
                let o = O::start(p, l, f.eps);
                let dist = if O::TESTS_SELF { dist - f.eps } else { dist };
                let blocked = (self.shadow)(self, index, o, l, dist, k, s.inside, column);
                // Which lights reach the surface: a shadow boundary is an edge.
                id.mix(2 * index as u32 + 1 + u32::from(blocked));
                if blocked {
                    continue;
                }
            }
            diffuse += intensity * nl;
            if s.material.specular > 0.0 {
                // n·h with h = (l + v)/|l + v|: one root and one division, no vector
                // scaling (|l + v| ≤ 2: no overflow). No highlight where l + v = 0.
                let half = l + v;
                let h2 = half.dot(half);
                if h2 > 0.0 {
                    let nh = s.n.dot(half) / sqrt_exact(h2);
                    if nh > 0.0 {
                        spec += intensity * s.material.specular * phong_power(nh, s.material.shininess);
                    }
                }
            }
        }
        let light = f.ambient + diffuse;
        let spec = 255.0 * spec;
        s.rgb.map(|c| {
            let x = c * light + spec;
            if x > 255.0 {
                255.0
            } else {
                x
            }
        })
    }

    /// [`Self::color`] with the ray's identity (see [`RowTracer::identified`]) mixed
    /// into `id`, for adaptive sampling (a copy: the one-ray path's code stays as it
    /// is); `CULL`: the primary ray is column `i`'s centre ray, so the row's shadow
    /// spans hold for it (a sub-pixel ray is not culled).
    #[inline(always)]
    fn color_with<I: Ident, const CULL: bool>(
        &mut self,
        first: Option<(Object, f32)>,
        d: Vec3,
        i: u32,
        id: &mut I,
    ) -> Rgb888 {
        let f = self.f;
        let mut acc = [0.0f32; 3];
        let mut weight = 1.0f32;
        let (mut origin, mut dir, mut hit) = (Vec3::ZERO, d, first);
        let mut depth = 0u8;
        loop {
            let Some((k, t)) = hit else {
                if depth > 0 {
                    id.mix(REFLECTS_NOTHING);
                }
                add(&mut acc, weight, f.bg);
                break;
            };
            let p = origin + dir * t;
            let s = self.surface(k, p, dir);
            if I::KEPT && depth == 0 {
                self.fine_checker(k, t, dir, id);
            }
            // The object, and its colour there (a checker cell).
            id.mix(k as u32 + 1);
            id.mix(s.rgb.iter().fold(0, |h, c| h.rotate_left(11) ^ c.to_bits()));
            // The shadow spans hold for the primary ray only.
            let column = (CULL && depth == 0).then_some(i);
            let local = self.local_with(k, &s, p, dir, column, id);
            let r = if D == 0 { 0.0 } else { s.material.reflect };
            if !(r > 0.0) {
                add(&mut acc, weight, local);
                break;
            }
            add(&mut acc, weight * (1.0 - r), local);
            weight *= r;
            if depth >= f.max_depth {
                // At the deepest level the background stands in for the reflection.
                add(&mut acc, weight, f.bg);
                break;
            }
            // The mirror direction d − 2(d·n)n (the same for n and −n).
            dir = dir - s.n * (2.0 * dir.dot(s.n));
            origin = O::start(p, dir, f.eps);
            hit = self.closest(origin, dir, k, s.inside);
            depth += 1;
        }
        let round = |x: f32| {
            let v = (x + 0.5) as i32;
            if v > 255 {
                255
            } else {
                v as u8
            }
        };
        Rgb888::new(round(acc[0]), round(acc[1]), round(acc[2]))
    }
}

impl<
        's,
        T: TestStrategy,
        Q: SqrtFn,
        O: Exit,
        const N: usize,
        const L: usize,
        const P: usize,
        const D: usize,
    > RowTracer<'s, T, LitSphere> for LitRow<'_, 's, T, Q, O, N, L, P, D>
{
    #[inline(always)]
    fn background(&self) -> Rgb888 {
        self.f.background
    }

    #[inline(always)]
    fn pixel(
        &mut self,
        sphere_hit: Option<(usize, f32, &'s FrameSphere<T, LitSphere>)>,
        i: u32,
        d: Vec3,
    ) -> (Option<(usize, f32)>, Rgb888) {
        let best = self.primary::<true>(sphere_hit, i, d);
        (best, self.color(best, d, i))
    }

    #[inline(always)]
    fn identified(
        &mut self,
        sphere_hit: Option<(usize, f32, &'s FrameSphere<T, LitSphere>)>,
        i: u32,
        d: Vec3,
    ) -> (u32, Rgb888) {
        let best = self.primary::<true>(sphere_hit, i, d);
        self.color_identified::<true>(best, d, i)
    }

    #[inline(always)]
    fn sub_sample(
        &mut self,
        sphere_hit: Option<(usize, f32, &'s FrameSphere<T, LitSphere>)>,
        d: Vec3,
    ) -> (u32, Rgb888) {
        let best = self.primary::<false>(sphere_hit, 0, d);
        self.color_identified::<false>(best, d, 0)
    }
}

impl<
        's,
        T: TestStrategy,
        Q: SqrtFn,
        O: Exit,
        const N: usize,
        const L: usize,
        const P: usize,
        const D: usize,
    > LitRow<'_, 's, T, Q, O, N, L, P, D>
{
    /// The closest hit of the primary ray `d`: the sphere hit, then the planes (with
    /// `CULL`, only those whose row span holds column `i`).
    #[inline(always)]
    fn primary<const CULL: bool>(
        &self,
        sphere_hit: Option<(usize, f32, &'s FrameSphere<T, LitSphere>)>,
        i: u32,
        d: Vec3,
    ) -> Option<(Object, f32)> {
        let mut best = sphere_hit.map(|(k, t, _)| (k, t));
        let mut t_max = best.map_or(f32::INFINITY, |(_, t)| t);
        let n = self.f.spheres.len();
        for (k, (plane, &(lo, len))) in self.f.planes.iter().zip(&self.spans).enumerate() {
            if !CULL || i.wrapping_sub(lo) < len {
                // t = (q·n)/(d·n): positive where d·n has the sign of q·n.
                let t = plane.s / d.dot(plane.n);
                if t > 0.0 && t < t_max {
                    t_max = t;
                    best = Some((n + k, t));
                }
            }
        }
        best
    }

    /// Whether the primary ray `dir` meeting object `k` at `t` sees a checker whose
    /// cells are less than two pixel footprints wide (then `id.fine()`): moving to the
    /// next pixel turns the ray by `du` (or `dv`), which moves its hit on the plane by
    /// at most `t·|du|·(1 + |d|/|d·n|)`.
    #[inline(always)]
    fn fine_checker<I: Ident>(&self, k: Object, t: f32, dir: Vec3, id: &mut I) {
        let f = self.f;
        let Some(plane) = k.checked_sub(f.spheres.len()).and_then(|p| f.planes.get(p)) else {
            return;
        };
        if plane.checker.is_none() {
            return;
        }
        let step = f
            .camera
            .pixel_step()
            .length()
            .max(f.camera.scanline_step().length());
        let dn = dir.dot(plane.n).abs();
        let footprint = t * step * (1.0 + dir.length() / dn);
        // NaN (a ray along the plane) fails the comparison: fine as well.
        if !(footprint * plane.inv_size <= 0.5) {
            id.fine();
        }
    }

    /// [`Self::color_with`] with the identity: out of line, like [`Self::color`].
    #[inline(never)]
    fn color_identified<const CULL: bool>(
        &mut self,
        first: Option<(Object, f32)>,
        d: Vec3,
        i: u32,
    ) -> (u32, Rgb888) {
        let mut id = Fnv(0, false);
        let c = self.color_with::<Fnv, CULL>(first, d, i, &mut id);
        (id.get(), c)
    }
}

/// Row `j`'s columns whose rays can hit `plane`, clamped to the visible ones; `None` if
/// none can. The ideal direction `F + i·du + j·dv` makes `d·n = A + i·B` linear in the
/// column; a ray hits where `σ·d·n > 0` (`σ` the sign of `q·n`). The computed `d·n` is
/// within `dn_margin` of the ideal one (the stepping's bound `E` on `|d − ideal|` with
/// `|n| = 1`, plus the dot product's rounding), so columns with `σ(A + iB) > −margin`
/// are kept; computed in `f64`, once per row and plane.
fn plane_span<T: TestStrategy, const N: usize, const L: usize, const P: usize>(
    f: &LitFrame<'_, T, N, L, P>,
    plane: &FramePlane,
    j: u32,
) -> Option<(u32, u32)> {
    let (i0, i1) = (f.i0, f.i1);
    if !(plane.s != 0.0) {
        return None; // the eye is on the plane (or NaN): no ray hits it at t > 0
    }
    if !f.span_culling {
        return Some((i0, i1));
    }
    let c = f.camera;
    let n = [f64::from(plane.n.x), f64::from(plane.n.y), f64::from(plane.n.z)];
    let dot = |v: Vec3| f64::from(v.x) * n[0] + f64::from(v.y) * n[1] + f64::from(v.z) * n[2];
    let sigma = if plane.s > 0.0 { 1.0 } else { -1.0 };
    let a = sigma * (dot(c.first_direction()) + f64::from(j) * dot(c.scanline_step()));
    let b = sigma * dot(c.pixel_step());
    let m = f.dn_margin;
    // σ(A + iB) > −m  ⇔  i·b > −m − a.
    let x = (-m - a) / b;
    let (lo, hi) = if b > 0.0 {
        // i > x: from ⌊x⌋ (one column of slack) on.
        (libm::floor(x), f64::from(i1))
    } else if b < 0.0 {
        // i < x: up to ⌊x⌋ + 1 (exclusive), one column of slack.
        (f64::from(i0), libm::floor(x) + 2.0)
    } else if a > -m {
        (f64::from(i0), f64::from(i1))
    } else {
        return None;
    };
    // Clamp with comparisons (a NaN bound keeps the whole row: conservative).
    let lo = if lo > f64::from(i0) { lo as u32 } else { i0 };
    let hi = if hi < f64::from(i1) { hi as u32 } else { i1 };
    (lo < hi).then_some((lo, hi))
}

/// The frame's objects and their coincident twins, for the exact paths
/// ([`closest_twins`], [`occluded_exact`]): slices and a flag, so that these rare
/// paths are one function per sphere test and root, not one per scene type and exit.
struct Objects<'a, T: TestStrategy> {
    spheres: &'a [FrameSphere<T, LitSphere>],
    planes: &'a [FramePlane],
    /// Per sphere and plane: the lowest-numbered identical object ([`Ties`]).
    sphere_twin: &'a [Object],
    plane_twin: &'a [Object],
    /// [`Exit::TESTS_SELF`].
    tests_self: bool,
}

impl<T: TestStrategy> Objects<'_, T> {
    /// The lowest-numbered object identical to `k` (`k` itself if none).
    #[inline(always)]
    fn twin(&self, k: Object) -> Object {
        let n = self.spheres.len();
        let twin = if k < n {
            self.sphere_twin.get(k)
        } else {
            self.plane_twin.get(k - n)
        };
        twin.copied().unwrap_or(k)
    }

    /// [`LitRow::blocks`], the exit's flag read at run time.
    #[inline(always)]
    fn blocks<Q: SqrtFn>(&self, k: Object, o: Vec3, l: Vec3, dist: f32, from: Object, inside: bool) -> bool {
        if let Some(s) = self.spheres.get(k) {
            if !self.tests_self && k == from {
                if !inside {
                    return false;
                }
                let t = far_root(&s.geom, o, l, l.dot(l));
                return t > 0.0 && t < dist;
            }
            T::ray::<Q>(&s.geom.seen_from(o), l, l.dot(l), dist).is_some()
        } else if let Some(plane) = k.checked_sub(self.spheres.len()).and_then(|p| self.planes.get(p)) {
            if !self.tests_self && k == from {
                return false;
            }
            let t = plane.t_from(o, l);
            t > 0.0 && t < dist
        } else {
            false
        }
    }
}

/// [`LitRow::closest`] in a frame with coincident objects ([`Ties`]): an object with
/// a lower-numbered twin is left out (the twin computes the same bits and wins the
/// tie), and the twin of the surface the ray leaves is that surface.
#[cold]
#[inline(never)]
fn closest_twins<T: TestStrategy, Q: SqrtFn>(
    objects: &Objects<'_, T>,
    o: Vec3,
    dir: Vec3,
    from: Object,
    inside: bool,
) -> Option<(Object, f32)> {
    let from = objects.twin(from);
    let a = dir.dot(dir);
    let mut best = None;
    let mut t_max = f32::INFINITY;
    let n = objects.spheres.len();
    for k in 0..n + objects.planes.len() {
        if objects.twin(k) != k {
            continue;
        }
        let leaves = !objects.tests_self && k == from;
        let t = match objects.spheres.get(k) {
            Some(s) if leaves => {
                if !inside {
                    continue;
                }
                Some(far_root(&s.geom, o, dir, a)).filter(|&t| t > 0.0 && t < t_max)
            }
            Some(s) => T::ray::<Q>(&s.geom.seen_from(o), dir, a, t_max),
            None if leaves => continue,
            None => objects
                .planes
                .get(k - n)
                .map(|plane| plane.t_from(o, dir))
                .filter(|&t| t > 0.0 && t < t_max),
        };
        if let Some(t) = t {
            t_max = t;
            best = Some((k, t));
        }
    }
    best
}

/// [`LitRow::occluded`] for a light whose shadow rays need the frame's ties: every
/// object is tested (no shadow span, no cached occluder), an object with a
/// lower-numbered twin is left out, the twin of the surface `o` lies on is that
/// surface, and an object the lamp (at `at`, on the objects flagged in `on`) lies on is
/// decided by the side the segment reaches the lamp from ([`Ties`]).
#[cold]
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn occluded_exact<T: TestStrategy, Q: SqrtFn>(
    objects: &Objects<'_, T>,
    (on_sphere, on_plane, at): (&[bool], &[bool], Vec3),
    o: Vec3,
    l: Vec3,
    dist: f32,
    from: Object,
    inside: bool,
) -> bool {
    let from = objects.twin(from);
    let n = objects.spheres.len();
    for k in 0..n + objects.planes.len() {
        if objects.twin(k) != k {
            continue;
        }
        let on = if k < n {
            on_sphere.get(k)
        } else {
            on_plane.get(k - n)
        };
        let blocked = match (on.copied().unwrap_or(false), objects.spheres.get(k)) {
            // A plane through the lamp meets the segment only at its open end; the
            // surface the ray leaves is never met again before the lamp on it.
            (true, None) => false,
            (true, Some(_)) if !objects.tests_self && k == from => false,
            // The lamp on the sphere: the line meets it at the lamp and 2σ before.
            (true, Some(s)) => {
                let two_sigma = 2.0 * (at - s.geom.l).dot(l);
                two_sigma > 0.0 && two_sigma < dist
            }
            (false, _) => objects.blocks::<Q>(k, o, l, dist, from, inside),
        };
        if blocked {
            return true;
        }
    }
    false
}

/// Where on the image the shadow that sphere `g` casts on `floor` under `light` can be
/// seen: the silhouette of a ball that contains the shadow, so a primary ray that hits
/// the floor outside it cannot be in that sphere's shadow. `Silhouette::ALL` (no
/// culling) where the shadow is not bounded.
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
/// The ball is enlarged by `2⁻⁸` of the lengths involved (far beyond the `f32`
/// rounding of the hit point and of the shadow test, ≈ 2⁻²² of them), and the
/// silhouette by the quadratic tests' margin and the stepping's error bound, as a
/// sphere's is: culling changes no pixel (`tests/api/lit.rs` compares with the unculled
/// loop).
fn shadow_silhouette(
    light: &FrameLight,
    g: &SphereGeom,
    floor: &FramePlane,
    camera: &Camera,
    step_err: f32,
) -> Silhouette {
    match shadow_disc(light, g, floor) {
        Some((centre, radius, _, _)) => {
            let centre = Vec3::new(centre[0] as f32, centre[1] as f32, centre[2] as f32);
            Silhouette::new(centre, radius as f32, camera, Margin::Quadratic, step_err)
        }
        None => Silhouette::ALL,
    }
}

/// A disc of shadow: its centre (relative to the eye), radius, the plane's unit normal,
/// and for a directional light the shadow's own cylinder (unit axis, radius) within it.
type ShadowDisc = ([f64; 3], f64, [f64; 3], Option<([f64; 3], f64)>);

/// The disc of `floor` that holds the shadow sphere `g` casts under `light`
/// ([`shadow_silhouette`]), and for a directional light the cylinder it is the cut of
/// (the disc's radius `r/|l·n|` is its semi-major axis), both radii enlarged by the
/// same `2⁻⁸` of the lengths involved; `None` where the shadow is not bounded.
fn shadow_disc(light: &FrameLight, g: &SphereGeom, floor: &FramePlane) -> Option<ShadowDisc> {
    let v64 = |v: Vec3| [f64::from(v.x), f64::from(v.y), f64::from(v.z)];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let along = |a: [f64; 3], b: [f64; 3], k: f64| [a[0] + b[0] * k, a[1] + b[1] * k, a[2] + b[2] * k];
    let (c, q, mut n) = (v64(g.l), v64(floor.q), v64(floor.n));
    let r = libm::sqrt(f64::from(g.r2));
    let h_c = dot(along(c, q, -1.0), n);
    let (centre, radius, axis) = match *light {
        FrameLight::Directional { l, .. } => {
            let l = v64(l);
            let ln = dot(l, n);
            let len = libm::sqrt(dot(l, l));
            let unit = [l[0] / len, l[1] / len, l[2] / len];
            (along(c, l, -h_c / ln), r / ln.abs(), Some(unit))
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
            (along(c, axis, h_c / cos_g), h_p * reach, None)
        }
    };
    let size = libm::sqrt(dot(centre, centre)) + libm::sqrt(dot(c, c)) + r;
    let slack = (radius + size) * (1.0 / 256.0);
    let radius = radius + slack;
    if !(radius.is_finite() && size.is_finite()) {
        return None;
    }
    Some((centre, radius, n, axis.map(|a| (a, r + slack))))
}

/// The frame-wide part of a features frame that a moved sphere can change besides its
/// own pixels: its ties (a lamp lying on a surface, coincident objects; see [`Ties`]),
/// which choose every row's shadow test. Equal for two scenes seen from `eye`: every
/// row takes the same path in both.
pub(crate) fn same_ties<const N: usize, const L: usize, const P: usize, const D: usize>(
    a: &Scene<N, L, P, D>,
    b: &Scene<N, L, P, D>,
    eye: Vec3,
) -> bool {
    Ties::new(a, eye) == Ties::new(b, eye)
}

/// Where on the image the shadow that `sphere` casts on the scene's first plane under
/// each of its lights can be seen: the image of the disc of the plane that holds it
/// ([`shadow_disc`], the disc the features frame culls its shadow rays with, inside the
/// ball around it that [`shadow_silhouette`] images), in the frame's units (`scale`):
/// one silhouette per usable light, passed to `f`. Nothing for a scene without a plane.
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
        if let Some(light) = FrameLight::new(l, eye, scale) {
            f(match shadow_disc(&light, &geom, &floor) {
                Some((centre, radius, n, axis)) => {
                    Silhouette::on_plane(centre, n, radius, axis, camera, step_err)
                }
                None => Silhouette::ALL,
            });
        }
    }
}

/// `x^shininess` for `x ∈ (0, 1]`: by repeated squaring when the exponent is a whole
/// number up to 1024 (the usual Phong exponents; a handful of multiplications instead
/// of `powf`'s logarithm and exponential), by `libm::powf` otherwise.
///
/// **Error bound.** Each multiplication rounds by at most `u = 2⁻²⁴` relative, and a
/// squaring doubles the relative error it is given, so the error of `x^s` is the sum
/// over the exponent's bits: at most `(s − 1)·u` to first order, `< s·u` (`< 6.2·10⁻⁵`
/// for `s = 1024`; `powf` is within 1 ulp). The highlight term `255·x^s ≤ 255` so
/// moves by less than `0.016` of a level at `s = 1024`, `5·10⁻⁴` at the default 32
/// (tested against `f64::powf`).
#[inline(always)]
fn phong_power(x: f32, shininess: f32) -> f32 {
    let whole = shininess as u32;
    if whole as f32 == shininess && whole <= 1024 {
        let (mut base, mut e, mut acc) = (x, whole, 1.0f32);
        while e > 0 {
            if e & 1 == 1 {
                acc *= base;
            }
            base *= base;
            e >>= 1;
        }
        acc
    } else {
        libm::powf(x, shininess)
    }
}

/// `acc += weight·c`, per channel.
#[inline(always)]
fn add(acc: &mut [f32; 3], weight: f32, c: [f32; 3]) {
    for (a, c) in acc.iter_mut().zip(c) {
        *a += weight * c;
    }
}

#[cfg(test)]
mod tests {
    use super::phong_power;

    /// Repeated squaring against `f64::powf`, within its stated bound, for whole
    /// exponents 1…1024 and bases across (0, 1]; fractional exponents go to `powf`.
    #[test]
    fn phong_power_within_its_bound() {
        let mut worst = 0.0f64;
        for s in (1..=1024).step_by(7).chain([2, 32, 64, 1000, 1024]) {
            let bound = f64::from(s) * f64::from(crate::math::UNIT_ROUNDOFF);
            for k in 1..=200 {
                let x = k as f32 / 200.0;
                let exact = f64::from(x).powf(f64::from(s));
                if exact < 1e-30 {
                    continue; // below f32's normal range: a contribution of nothing
                }
                let got = f64::from(phong_power(x, s as f32));
                let rel = (got - exact).abs() / exact;
                worst = worst.max(rel / bound);
                assert!(rel <= bound, "x = {x}, s = {s}: {got} vs {exact} ({rel:e})");
            }
        }
        // The bound is not loose by orders of magnitude: some case uses a tenth of it.
        assert!(worst > 0.1, "worst case {worst} of the bound");
        let frac = phong_power(0.5, 2.5);
        assert_eq!(frac, libm::powf(0.5, 2.5));
    }
}
