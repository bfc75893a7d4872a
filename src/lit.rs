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
//! object: it is kept to show where it fails (`tests/lit_stability.rs`).

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::Vec;

use crate::camera::Camera;
use crate::frame::{Frame, FrameSphere};
use crate::intersect::{Scale, SphereGeom, TestStrategy};
use crate::light::Light;
use crate::material::Material;
use crate::math::{sqrt_exact, SqrtFn, UNIT_ROUNDOFF};
use crate::render::Options;
use crate::scanline::{self, RowTracer};
use crate::scene::Scene;
use crate::shade::{channels, Shader, AMBIENT};
use crate::sink::RowSink;
use crate::sphere::Sphere;
use crate::stepping::Stepper;
use crate::vec3::Vec3;

/// Where a shadow or reflection ray starts: the choice of how a secondary ray leaves
/// the surface its origin was computed on. A speed/accuracy axis of its own (matched
/// once per frame, like the [`Method`](crate::Method)); only scenes with lights or
/// mirrors use it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SecondaryOrigin {
    /// No epsilon (default): the surface the ray leaves is not tested where convexity
    /// proves it cannot be met (leaving a plane, or a sphere's outside), and is met at
    /// its directly computed far root where it can (leaving a sphere's inner surface).
    /// Every other object is tested from the hit point itself.
    Convex,
    /// The textbook fixed epsilon: the ray starts at `s = ε` (scene units) along its
    /// unit direction and every object, the one it leaves included, is tested. Fails
    /// both ways: shadow acne where the hit point's rounding error (≈ 2⁻²⁴ of the
    /// coordinates' magnitude) exceeds ε, and light leaking under spheres that touch a
    /// floor where ε exceeds the occluder's chord.
    Epsilon(f32),
}

impl SecondaryOrigin {
    /// The textbook epsilon, `10⁻³` scene units.
    pub const TEXTBOOK: SecondaryOrigin = SecondaryOrigin::Epsilon(1e-3);
}

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
    /// `point − eye`, scaled.
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
    /// The plane's constants; `None` for a zero or non-finite normal (never hit).
    fn new(plane: &crate::plane::Plane, eye: Vec3, scale: Scale) -> Option<Self> {
        let n = plane.normal.try_normalize()?;
        let q = (plane.point - eye) * scale.0;
        // The checker basis: the world axis along which n is smallest (ties x, y, z).
        let (ax, ay, az) = (n.x.abs(), n.y.abs(), n.z.abs());
        let axis = if ax <= ay && ax <= az {
            Vec3::new(1.0, 0.0, 0.0)
        } else if ay <= az {
            Vec3::new(0.0, 1.0, 0.0)
        } else {
            Vec3::new(0.0, 0.0, 1.0)
        };
        let e1 = n.cross(axis).try_normalize()?;
        let e2 = n.cross(e1);
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

/// `floor(x)` as an integer (saturating far outside the `i64` range, NaN → 0): only
/// its parity is used, and every `f32` beyond 2²⁴ is an integer already.
#[inline(always)]
fn floor(x: f32) -> i64 {
    let t = x as i64;
    if (t as f32) > x {
        t - 1
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
}

/// The object a hit is on: spheres `0 … n − 1`, then planes.
type Object = usize;

/// Per-frame state of the scene-features path.
struct LitFrame<'a, T: TestStrategy> {
    spheres: &'a [FrameSphere<T, LitSphere>],
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

/// Renders one frame of a scene with lights, planes or mirrors.
pub(crate) fn render<
    const N: usize,
    const L: usize,
    const P: usize,
    const D: usize,
    K: RowSink,
    S: Stepper,
    T: TestStrategy,
    Q: SqrtFn,
>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    options: Options,
    clip: Rectangle,
    offset: Point,
    sink: &mut K,
) -> Result<(), K::Error> {
    match options.secondary {
        SecondaryOrigin::Convex => {
            render_with::<N, L, P, D, K, S, T, Q, ConvexExit>(scene, camera, options, 0.0, clip, offset, sink)
        }
        SecondaryOrigin::Epsilon(eps) => render_with::<N, L, P, D, K, S, T, Q, EpsilonExit>(
            scene, camera, options, eps, clip, offset, sink,
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
>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    options: Options,
    eps: f32,
    clip: Rectangle,
    offset: Point,
    sink: &mut K,
) -> Result<(), K::Error> {
    let eye = camera.eye();
    // The frame's scale covers the planes' points and the point lights too.
    let mut others = 0.0f32;
    let planes_at = scene.planes().iter().map(|p| p.point);
    let lights_at = scene.lights().iter().filter_map(|l| match *l {
        Light::Point { position, .. } => Some(position),
        Light::Directional { .. } => None,
    });
    for at in planes_at.chain(lights_at) {
        let m = (at - eye).max_abs();
        if m > others {
            others = m;
        }
    }
    let mut spheres = Vec::new();
    let Some(frame) = Frame::<T, LitSphere>::new::<N, L, P, D, S>(
        scene,
        camera,
        options,
        clip,
        offset,
        &mut spheres,
        others,
    ) else {
        return Ok(()); // nothing visible
    };
    let mut planes: Vec<FramePlane, P> = Vec::new();
    for p in scene.planes() {
        if let Some(fp) = FramePlane::new(p, eye, frame.scale) {
            // Never fails: the scene holds at most P planes.
            let _ = planes.push(fp);
        }
    }
    let mut lights: Vec<FrameLight, L> = Vec::new();
    for l in scene.lights() {
        if let Some(fl) = FrameLight::new(l, eye, frame.scale) {
            let _ = lights.push(fl);
        }
    }
    let size = camera.size();
    let d_max = f64::from(camera.first_direction().length())
        + f64::from(size.width) * f64::from(camera.pixel_step().length())
        + f64::from(size.height) * f64::from(camera.scanline_step().length());
    let lit = LitFrame {
        spheres: frame.spheres,
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
        dn_margin: f64::from(S::error_bound(camera)) + 8.0 * f64::from(UNIT_ROUNDOFF) * d_max,
        i0: frame.i0,
        i1: frame.i1,
    };
    scanline::draw_rows::<N, K, S, T, Q, LitSphere, _>(&frame, sink, |j, lo, hi| {
        LitRow::<T, Q, O, L, P, D>::new(&lit, j, lo, hi)
    })
}

/// One row of the scene-features path: the planes' spans and, per light, the object
/// that last shadowed a pixel of the row (tested first: neighbouring pixels are
/// usually shadowed by the same occluder).
struct LitRow<'f, 's, T: TestStrategy, Q, O, const L: usize, const P: usize, const D: usize> {
    f: &'f LitFrame<'s, T>,
    /// Per plane: columns `[lo, lo + len)` whose rays can hit it.
    spans: [(u32, u32); P],
    occluder: [Object; L],
    marker: core::marker::PhantomData<(Q, O)>,
}

/// No occluder cached.
const NONE: Object = usize::MAX;

impl<'f, 's, T: TestStrategy, Q: SqrtFn, O: Exit, const L: usize, const P: usize, const D: usize>
    LitRow<'f, 's, T, Q, O, L, P, D>
{
    /// Row `j`: the planes' spans, widening the row's traced union `[lo_all, hi_all)`.
    #[inline(never)]
    fn new(f: &'f LitFrame<'s, T>, j: u32, lo_all: &mut u32, hi_all: &mut u32) -> Self {
        let mut spans = [(0, 0); P];
        for (span, plane) in spans.iter_mut().zip(f.planes) {
            if let Some((lo, hi)) = plane_span(f, plane, j) {
                *span = (lo, hi - lo);
                *lo_all = (*lo_all).min(lo);
                *hi_all = (*hi_all).max(hi);
            }
        }
        Self {
            f,
            spans,
            occluder: [NONE; L],
            marker: core::marker::PhantomData,
        }
    }

    /// The object a ray from `o` along `dir` meets first, and where; `from` is the
    /// object `o` lies on (`inside`: on a sphere's inner surface).
    fn closest(&self, o: Vec3, dir: Vec3, from: Object, inside: bool) -> Option<(Object, f32)> {
        let f = self.f;
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
                let t = 2.0 * (s.geom.l - o).dot(dir) / a;
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
            let t = (plane.q - o).dot(plane.n) / dir.dot(plane.n);
            if t > 0.0 && t < t_max {
                t_max = t;
                best = Some((n + k, t));
            }
        }
        best
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
                let t = 2.0 * (s.geom.l - o).dot(l) / l.dot(l);
                return t > 0.0 && t < dist;
            }
            // A segment wholly inside a sphere ends before its far root: `t < dist` fails.
            T::ray::<Q>(&s.geom.seen_from(o), l, l.dot(l), dist).is_some()
        } else if let Some(plane) = k.checked_sub(f.spheres.len()).and_then(|p| f.planes.get(p)) {
            if !O::TESTS_SELF && k == from {
                return false;
            }
            let t = (plane.q - o).dot(plane.n) / l.dot(plane.n);
            t > 0.0 && t < dist
        } else {
            false
        }
    }

    /// Whether the light's segment from `o` is blocked: the light's last occluder
    /// first, then every object until one blocks (any hit), or — the literal
    /// baseline — every object, as a closest-hit search would.
    fn occluded(&mut self, light: usize, o: Vec3, l: Vec3, dist: f32, from: Object, inside: bool) -> bool {
        let count = self.f.spheres.len() + self.f.planes.len();
        if !self.f.any_hit {
            let mut blocked = false;
            for k in 0..count {
                blocked |= self.blocks(k, o, l, dist, from, inside);
            }
            return blocked;
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
    fn local(&mut self, k: Object, s: &Surface, p: Vec3, dir: Vec3) -> [f32; 3] {
        if L == 0 || self.f.lights.is_empty() {
            let kz = if s.lab_nz > 1.0 {
                1.0
            } else if s.lab_nz >= AMBIENT {
                s.lab_nz
            } else {
                AMBIENT
            };
            return s.rgb.map(|c| c * kz);
        }
        let f = self.f;
        let v = dir * (-1.0 / sqrt_exact(dir.dot(dir)));
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
                if self.occluded(index, o, l, dist, k, s.inside) {
                    continue;
                }
            }
            diffuse += intensity * nl;
            if s.material.specular > 0.0 {
                // No highlight where l + v = 0 (try_normalize refuses the zero vector).
                if let Some(h) = (l + v).try_normalize() {
                    let nh = s.n.dot(h);
                    if nh > 0.0 {
                        spec += intensity * s.material.specular * libm::powf(nh, s.material.shininess);
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
    #[inline(always)]
    fn color(&mut self, first: Option<(Object, f32)>, d: Vec3) -> Rgb888 {
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
            let local = self.local(k, &s, p, dir);
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

impl<'s, T: TestStrategy, Q: SqrtFn, O: Exit, const L: usize, const P: usize, const D: usize>
    RowTracer<'s, T, LitSphere> for LitRow<'_, 's, T, Q, O, L, P, D>
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
        let mut best = sphere_hit.map(|(k, t, _)| (k, t));
        let mut t_max = best.map_or(f32::INFINITY, |(_, t)| t);
        let n = self.f.spheres.len();
        for (k, (plane, &(lo, len))) in self.f.planes.iter().zip(&self.spans).enumerate() {
            if i.wrapping_sub(lo) < len {
                // t = (q·n)/(d·n): positive where d·n has the sign of q·n.
                let t = plane.s / d.dot(plane.n);
                if t > 0.0 && t < t_max {
                    t_max = t;
                    best = Some((n + k, t));
                }
            }
        }
        (best, self.color(best, d))
    }
}

/// Row `j`'s columns whose rays can hit `plane`, clamped to the visible ones; `None` if
/// none can. The ideal direction `F + i·du + j·dv` makes `d·n = A + i·B` linear in the
/// column; a ray hits where `σ·d·n > 0` (`σ` the sign of `q·n`). The computed `d·n` is
/// within `dn_margin` of the ideal one (the stepping's bound `E` on `|d − ideal|` with
/// `|n| = 1`, plus the dot product's rounding), so columns with `σ(A + iB) > −margin`
/// are kept; computed in `f64`, once per row and plane.
fn plane_span<T: TestStrategy>(f: &LitFrame<'_, T>, plane: &FramePlane, j: u32) -> Option<(u32, u32)> {
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

/// `acc += weight·c`, per channel.
#[inline(always)]
fn add(acc: &mut [f32; 3], weight: f32, c: [f32; 3]) {
    for (a, c) in acc.iter_mut().zip(c) {
        *a += weight * c;
    }
}
