//! The accuracy lab (feature `std`, host only): an independent `f64` reference
//! renderer, the error metrics that compare a [`Render`] with it, and the stability
//! sweeps ([`sweeps`]) that find where each method fails.
//!
//! The reference shares **no arithmetic** with the kernel: it has its own `f64`
//! vector type ([`D3`]), builds the seed's camera in `f64` from
//! [`Camera::params`](embedded_raytracer::Camera::params) (only the `f32` inputs are shared),
//! evaluates every pixel's direction directly,
//! `p(i,j) − eye = w + ((i + ½) − W/2)·pw·u + (H/2 − (j + ½))·ph·v`,
//! intersects with Haines et al.'s robust test in `f64` and shades with Lab #1. A bug
//! in the kernel's `Vec3`, sphere tests or shading therefore cannot hide in both.
//! Scenes with lights, planes or mirrors are traced by [`lit`], written from the
//! shading rules alone (Phong with hard shadows, checker floors, the mirror loop).
//!
//! Each reference pixel says whether a correct implementation may decide it either way
//! ([`RefPixel::undecidable`], with the reasons in [`RefPixel::why`]): silhouettes and
//! depth ties within the reference's own band, and — derived in [`lit`] — shadow
//! boundaries, checker edges, the `n·l > 0` gate and mirror chains within `f32`
//! rounding. [`compare`] counts those apart; [`Metrics::over_2`] counts the pixels
//! more than 2 levels off outside them.
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb888, prelude::*};
//! use embedded_raytracer::{Camera, Render, Scene, Sphere, Vec3};
//! use embedded_raytracer_lab::reference;
//!
//! let mut scene: Scene<1> = Scene::new(Rgb888::BLACK);
//! scene.push(Sphere::new(Vec3::ZERO, 1.0, Rgb888::new(255, 64, 64)))?;
//! let camera = Camera::new(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), 0.6, Size::new(32, 24))?;
//!
//! let truth = reference::render(&scene, &camera);
//! let metrics = reference::compare(&Render::<1, Rgb888>::new(&scene, &camera), &truth);
//! assert_eq!(metrics.coverage_errors, 0);
//! assert!(metrics.shade_max <= 1);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use core::ops::{Add, Mul, Sub};
use std::vec::Vec;

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};

use embedded_raytracer::Scene;
use embedded_raytracer::Vec3;
use embedded_raytracer::{Camera, CameraParams};
use embedded_raytracer::{Render, Sample};

pub mod aa;
pub mod lit;
pub mod sweeps;

/// Relative width of the reference's own rounding band, in units of `f64::EPSILON`.
///
/// The robust discriminant `r² − |L − (b/a)·d|²` is a sum of a few dozen `f64`
/// operations on numbers of size `|L|` and `r`; each rounds by ≤ ½ ulp, so its
/// absolute error is well below `64·ε·r·(|L| + r)`. A pixel whose discriminant is
/// inside that band is one the reference cannot decide.
pub const BAND_ULPS: f64 = 64.0;

/// A 3-vector of `f64`: the reference's own, so no kernel arithmetic is shared.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct D3 {
    /// x component.
    pub x: f64,
    /// y component.
    pub y: f64,
    /// z component.
    pub z: f64,
}

impl D3 {
    /// A vector from its components.
    #[must_use]
    pub const fn new(x: f64, y: f64, z: f64) -> Self {
        Self { x, y, z }
    }

    /// The exact `f64` value of a kernel vector (reads the data, no kernel arithmetic).
    #[must_use]
    pub fn of(v: Vec3) -> Self {
        Self::new(f64::from(v.x), f64::from(v.y), f64::from(v.z))
    }

    /// Dot product.
    #[must_use]
    pub fn dot(self, o: D3) -> f64 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// Cross product (right-handed).
    #[must_use]
    pub fn cross(self, o: D3) -> D3 {
        D3::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }

    /// Euclidean length.
    #[must_use]
    pub fn length(self) -> f64 {
        self.dot(self).sqrt()
    }

    /// Unit vector, or `None` for a zero or non-finite vector.
    #[must_use]
    pub fn normalize(self) -> Option<D3> {
        let len = self.length();
        (len.is_finite() && len > 0.0).then(|| self * (1.0 / len))
    }
}

impl Add for D3 {
    type Output = D3;
    fn add(self, o: D3) -> D3 {
        D3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl Sub for D3 {
    type Output = D3;
    fn sub(self, o: D3) -> D3 {
        D3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl Mul<f64> for D3 {
    type Output = D3;
    fn mul(self, s: f64) -> D3 {
        D3::new(self.x * s, self.y * s, self.z * s)
    }
}

/// The seed's camera in `f64`, built from the same `f32` parameters as the kernel's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefCamera {
    /// Eye position.
    pub eye: D3,
    /// Unit view direction.
    pub w: D3,
    /// Unit right vector, `normalize(w × up)`.
    pub u: D3,
    /// Unit up vector on the image, `u × w`.
    pub v: D3,
    /// Pixel width on the image plane (D = 1).
    pub pixel_width: f64,
    /// Pixel height on the image plane (D = 1).
    pub pixel_height: f64,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

impl RefCamera {
    /// The camera of `params` in `f64`; `None` if the basis is degenerate (the kernel
    /// refuses such parameters too).
    #[must_use]
    pub fn new(params: &CameraParams) -> Option<Self> {
        let eye = D3::of(params.eye);
        // Basis: w toward the look-at point, u = normalize(w × up), v = u × w.
        let w = (D3::of(params.look_at) - eye).normalize()?;
        let u = w.cross(D3::of(params.up)).normalize()?;
        let v = u.cross(w);
        let (width, height) = (params.size.width, params.size.height);
        if width == 0 || height == 0 {
            return None;
        }
        // Pixel size from the field of view; square pixels unless fov_x is given.
        let pixel_height = 2.0 * (f64::from(params.fov_y) / 2.0).tan() / f64::from(height);
        let pixel_width = match params.fov_x {
            Some(fov_x) => 2.0 * (f64::from(fov_x) / 2.0).tan() / f64::from(width),
            None => pixel_height,
        };
        Some(Self {
            eye,
            w,
            u,
            v,
            pixel_width,
            pixel_height,
            width,
            height,
        })
    }

    /// Image-plane coordinates of pixel `(i, j)`'s centre along `u` and `v`:
    /// `((i + ½) − W/2)·pw` and `(H/2 − (j + ½))·ph`.
    #[must_use]
    pub fn plane(&self, i: u32, j: u32) -> (f64, f64) {
        let x = ((f64::from(i) + 0.5) - f64::from(self.width) / 2.0) * self.pixel_width;
        let y = (f64::from(self.height) / 2.0 - (f64::from(j) + 0.5)) * self.pixel_height;
        (x, y)
    }

    /// `p(i,j) − eye = w + x·u + y·v`, evaluated directly.
    #[must_use]
    pub fn direction(&self, i: u32, j: u32) -> D3 {
        let (x, y) = self.plane(i, j);
        self.w + self.u * x + self.v * y
    }
}

/// One sphere seen along one ray by the `f64` robust test.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHit {
    /// Nearest root `t > 0` (exit point when the eye is inside), `None` for a miss.
    pub t: Option<f64>,
    /// The discriminant `r² − |perp|²` (in length², for a unit-length ray).
    pub disc: f64,
    /// The discriminant is within the reference's rounding band: the ray grazes the
    /// silhouette so closely that `f64` cannot say hit or miss.
    pub undecidable: bool,
    /// Uncertainty of `t` from the rounding band (absolute), for depth ties.
    pub t_err: f64,
    /// Angular clearance from the silhouette: `| |perp| − r | / max(|L|, r)`.
    pub clearance: f64,
    /// Ray parameter of the point closest to the centre (`b/a`).
    pub t_closest: f64,
    /// The sphere can be hit only at `t ≤ 0` for any nearby ray (behind an eye that is
    /// outside it), so its silhouette cannot matter.
    pub behind: bool,
}

/// Haines et al.'s robust ray–sphere test in `f64` (Ray Tracing Gems, ch. 7):
/// `b = L·d`, perpendicular `L − (b/a)·d`, discriminant `r² − |perp|²`, stable roots
/// `q = b + sign(b)·√(a·disc)`, `t = c/q` and `q/a`; the nearest with `t > 0`.
#[must_use]
pub fn intersect(eye: D3, dir: D3, center: D3, radius: f64) -> RayHit {
    let l = center - eye;
    let a = dir.dot(dir);
    let b = dir.dot(l);
    let l2 = l.dot(l);
    let r2 = radius * radius;
    let c = l2 - r2;
    let perp = l - dir * (b / a);
    let p2 = perp.dot(perp);
    let disc = r2 - p2;
    let eps = f64::EPSILON;
    let l_len = l2.sqrt();
    let band = BAND_ULPS * eps * radius * (l_len + radius);
    let undecidable = disc.abs() <= band;
    let clearance = (p2.sqrt() - radius).abs() / l_len.max(radius);
    let behind = b <= 0.0 && c > 0.0;
    let t_closest = b / a;
    if disc < 0.0 {
        return RayHit {
            t: None,
            disc,
            undecidable,
            t_err: 0.0,
            clearance,
            t_closest,
            behind,
        };
    }
    let root = (a * disc).sqrt();
    let q = if b >= 0.0 { b + root } else { b - root };
    let (t0, t1) = if b >= 0.0 { (c / q, q / a) } else { (q / a, c / q) };
    let t = if t0 > 0.0 {
        Some(t0)
    } else if t1 > 0.0 {
        Some(t1)
    } else {
        None
    };
    // Uncertainty of √(a·disc) from the band: a·band/(2√(a·disc)), at most √(a·band).
    let d_root = if root > 0.0 {
        (a * band / (2.0 * root)).min((a * band).sqrt())
    } else {
        (a * band).sqrt()
    };
    let t_err = t.map_or(0.0, |t| {
        t * (BAND_ULPS * eps + d_root / q.abs().max(f64::MIN_POSITIVE))
    });
    RayHit {
        t,
        disc,
        undecidable,
        t_err,
        clearance,
        t_closest,
        behind,
    }
}

/// What a sphere that another one hides completely is along every ray: a miss whose
/// silhouette never counts.
pub const HIDDEN: RayHit = RayHit {
    t: None,
    disc: f64::NEG_INFINITY,
    undecidable: false,
    t_err: 0.0,
    clearance: f64::INFINITY,
    t_closest: 0.0,
    behind: true,
};

/// Whether sphere `k` of `spheres` (`(centre, radius)`) has a lower-numbered twin: the
/// same centre and radius, bit for bit. Coincident spheres are one surface, shown in
/// the lower index's colour: the twin is never seen.
#[must_use]
pub fn has_twin(spheres: &[(D3, f64)], k: usize) -> bool {
    let key = |(c, r): (D3, f64)| (c.x.to_bits(), c.y.to_bits(), c.z.to_bits(), r.to_bits());
    match spheres.get(k) {
        Some(&s) => spheres.iter().take(k).any(|&t| key(t) == key(s)),
        None => false,
    }
}

/// Lab #1 in `f64`: `round(c × clamp(n_z, 0.3, 1.0))` per 8-bit channel, halves up.
#[must_use]
pub fn lab1(color: Rgb888, n_z: f64) -> Rgb888 {
    let k = n_z.clamp(0.3, 1.0);
    // k ∈ [0.3, 1], so the result is in [0, 255.5): the cast cannot saturate wrongly.
    let scale = |c: u8| (f64::from(c) * k + 0.5).floor() as u8;
    Rgb888::new(scale(color.r()), scale(color.g()), scale(color.b()))
}

/// One reference pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefPixel {
    /// The sphere hit (index into the scene), `None` for the background.
    pub hit: Option<usize>,
    /// Euclidean distance from the eye to the hit point (`0` for a miss).
    pub distance: f64,
    /// The shaded colour.
    pub color: Rgb888,
    /// The reference cannot decide this pixel: a silhouette within its rounding band,
    /// or two spheres' hit distances within their rounding of each other.
    pub undecidable: bool,
    /// How far the decision is from flipping: the smallest angular clearance from a
    /// relevant silhouette and the relative depth gap to the next sphere hit.
    /// A method whose ray directions are off by less than this (in radians) cannot
    /// change the pixel's object.
    pub margin: f64,
    /// Why the pixel is undecidable: a set of [`why`] bits, `0` for a decidable pixel.
    pub why: u8,
}

/// The reasons a pixel is undecidable, as bits of [`RefPixel::why`].
pub mod why {
    /// A primary ray's silhouette or sphere–sphere depth tie within the reference's own
    /// rounding band ([`BAND_ULPS`](super::BAND_ULPS)).
    pub const SILHOUETTE: u8 = 1;
    /// A primary ray's decision involving a plane within `f32` rounding: its horizon,
    /// or a depth tie between a plane and another object.
    pub const HORIZON: u8 = 2;
    /// A shadow ray's decision against an occluder within `f32` rounding, where the
    /// light moves the colour by more than a level.
    pub const SHADOW: u8 = 4;
    /// A checker edge within `f32` rounding of the hit point.
    pub const CHECKER: u8 = 8;
    /// The `n·l > 0` gate within rounding of `0`, or `l + v` within rounding of `0`,
    /// where the specular term moves the colour by more than a level.
    pub const GATE: u8 = 16;
    /// Which object a reflected ray shows is within `f32` rounding (its silhouette,
    /// horizon, self-hit or a depth tie), at a mirror weight that can move the colour
    /// by more than a level.
    pub const MIRROR: u8 = 32;
}

/// The reference image of a scene: every pixel, row-major, and the camera.
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceImage {
    /// The `f64` camera.
    pub camera: RefCamera,
    /// Pixels in row-major order (`j * width + i`).
    pub pixels: Vec<RefPixel>,
}

impl ReferenceImage {
    /// The pixel at column `i`, row `j`.
    #[must_use]
    pub fn get(&self, i: u32, j: u32) -> Option<&RefPixel> {
        if i >= self.camera.width || j >= self.camera.height {
            return None;
        }
        self.pixels
            .get(j as usize * self.camera.width as usize + i as usize)
    }

    /// Number of undecidable pixels.
    #[must_use]
    pub fn undecidable(&self) -> usize {
        self.pixels.iter().filter(|p| p.undecidable).count()
    }

    /// Number of undecidable pixels with any of the [`why`] bits in `mask`.
    #[must_use]
    pub fn undecidable_by(&self, mask: u8) -> usize {
        self.pixels.iter().filter(|p| p.why & mask != 0).count()
    }

    /// Undecidable pixels as a fraction of all pixels (0 for an empty image).
    #[must_use]
    pub fn undecidable_fraction(&self) -> f64 {
        if self.pixels.is_empty() {
            0.0
        } else {
            self.undecidable() as f64 / self.pixels.len() as f64
        }
    }

    /// Number of pixels that show sphere `index`.
    #[must_use]
    pub fn count_hits(&self, index: usize) -> usize {
        self.pixels.iter().filter(|p| p.hit == Some(index)).count()
    }
}

/// A sphere as the reference sees it: `f64` centre, radius and colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefSphere {
    /// Centre.
    pub center: D3,
    /// Radius.
    pub radius: f64,
    /// Colour.
    pub color: Rgb888,
}

/// The closest sphere hit of a ray from its per-sphere tests: `(index, t, t_err)`, the
/// first index on exact ties (as the kernel's strict `t < t_max`).
#[must_use]
pub fn closest_sphere(hits: &[RayHit]) -> Option<(usize, f64, f64)> {
    let mut best: Option<(usize, f64, f64)> = None;
    for (k, h) in hits.iter().enumerate() {
        if let Some(t) = h.t {
            if best.is_none_or(|(_, bt, _)| t < bt) {
                best = Some((k, t, h.t_err));
            }
        }
    }
    best
}

/// Whether the reference can decide which sphere a ray shows, and by how much:
/// `(undecidable, margin)` for the visible hit `front` (`(index, t, t_err)`; an index
/// past the spheres for another object): a silhouette in front of it within the
/// reference's rounding band ([`BAND_ULPS`]), or a sphere hit within the rounding of
/// `t` of it (a depth tie). The margin is the smallest angular clearance from such a
/// silhouette and relative depth gap to another sphere hit.
#[must_use]
pub fn sphere_doubt(hits: &[RayHit], front: Option<(usize, f64, f64)>) -> (bool, f64) {
    let mut undecidable = false;
    let mut margin = f64::INFINITY;
    for (k, h) in hits.iter().enumerate() {
        // A silhouette matters if it lies in front of the visible hit.
        let in_front = front.is_none_or(|(bk, bt, _)| k == bk || h.t_closest < bt);
        if !h.behind && in_front {
            undecidable |= h.undecidable;
            margin = margin.min(h.clearance);
        }
        // Depth ties: another sphere hit at (almost) the same distance.
        if let (Some((bk, bt, berr)), Some(t)) = (front, h.t) {
            if k != bk {
                undecidable |= (t - bt).abs() <= berr + h.t_err;
                margin = margin.min((t - bt).abs() / bt);
            }
        }
    }
    (undecidable, margin)
}

/// Traces one ray through `spheres` in `f64` under Lab #1: the reference pixel.
#[must_use]
pub fn trace_ray(camera: &RefCamera, spheres: &[RefSphere], background: Rgb888, dir: D3) -> RefPixel {
    let mut hits: Vec<RayHit> = spheres
        .iter()
        .map(|s| intersect(camera.eye, dir, s.center, s.radius))
        .collect();
    // A hit on a coincident sphere is its lower-numbered twin's (checked only for hits).
    if hits.iter().filter(|h| h.t.is_some()).count() > 1 {
        let geometry: Vec<(D3, f64)> = spheres.iter().map(|s| (s.center, s.radius)).collect();
        for (k, h) in hits.iter_mut().enumerate() {
            if h.t.is_some() && has_twin(&geometry, k) {
                *h = HIDDEN;
            }
        }
    }
    let best = closest_sphere(&hits);
    let (undecidable, margin) = sphere_doubt(&hits, best);
    let why = if undecidable { why::SILHOUETTE } else { 0 };
    let len = dir.length();
    match best.and_then(|(k, t, _)| spheres.get(k).map(|s| (k, t, s))) {
        Some((k, t, s)) => {
            // View-space normal: n·(−w) = ((L − t·d)·w)/r, camera-relative.
            let l = s.center - camera.eye;
            let n_z = (l.dot(camera.w) - t * dir.dot(camera.w)) / s.radius;
            RefPixel {
                hit: Some(k),
                distance: t * len,
                color: lab1(s.color, n_z),
                undecidable,
                margin,
                why,
            }
        }
        None => RefPixel {
            hit: None,
            distance: 0.0,
            color: background,
            undecidable,
            margin,
            why,
        },
    }
}

/// Renders `scene` as `camera` sees it, in `f64`, every pixel direct.
///
/// Uses only the camera's `f32` parameters ([`Camera::params`]) and the scene's data,
/// never the kernel's derived values. A scene with lights, planes or mirrors is traced
/// by [`lit`]; one with none of them by Lab #1 over the spheres, as always.
#[must_use]
pub fn render<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
) -> ReferenceImage {
    render_params(scene, camera.params()).unwrap_or_else(|| ReferenceImage {
        camera: RefCamera {
            eye: D3::default(),
            w: D3::default(),
            u: D3::default(),
            v: D3::default(),
            pixel_width: 0.0,
            pixel_height: 0.0,
            width: 0,
            height: 0,
        },
        pixels: Vec::new(),
    })
}

/// [`render`] from raw parameters; `None` when the `f64` basis is degenerate.
#[must_use]
pub fn render_params<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    params: &CameraParams,
) -> Option<ReferenceImage> {
    render_with(scene, params, true)
}

/// [`render`] with the on-surface rule for point lights switched off
/// ([`lit::RefScene::lamp_ties`]): a lamp near a surface is decided by the general
/// segment test alone. Not the kernel's contract (a lamp on a surface is in doubt
/// there); the independent check of the rule where a lamp is near a surface but
/// clearly off it. `None` when the `f64` basis is degenerate.
#[must_use]
pub fn render_without_lamp_ties<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
) -> Option<ReferenceImage> {
    render_with(scene, camera.params(), false)
}

fn render_with<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    params: &CameraParams,
    lamp_ties: bool,
) -> Option<ReferenceImage> {
    let camera = RefCamera::new(params)?;
    let lit = lit::RefScene {
        lamp_ties,
        ..lit::RefScene::of(scene)
    };
    let mut pixels = Vec::with_capacity(camera.width as usize * camera.height as usize);
    if lit.is_lab1() {
        let spheres: Vec<RefSphere> = scene
            .spheres()
            .iter()
            .map(|s| RefSphere {
                center: D3::of(s.center),
                radius: f64::from(s.radius),
                color: s.color,
            })
            .collect();
        for j in 0..camera.height {
            for i in 0..camera.width {
                pixels.push(trace_ray(
                    &camera,
                    &spheres,
                    scene.background(),
                    camera.direction(i, j),
                ));
            }
        }
    } else {
        for j in 0..camera.height {
            for i in 0..camera.width {
                pixels.push(lit::trace(&camera, &lit, camera.direction(i, j)));
            }
        }
    }
    Some(ReferenceImage { camera, pixels })
}

/// How a render differs from the reference.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Metrics {
    /// Pixels compared.
    pub pixels: usize,
    /// Pixels the reference cannot decide (not counted below).
    pub undecidable: usize,
    /// Decidable pixels whose hit/miss or hit object differs from the reference.
    pub coverage_errors: usize,
    /// The largest reference [`margin`](RefPixel::margin) among the coverage errors
    /// (0 when there are none): how far from any silhouette or depth tie the worst
    /// misclassified pixel is, in radians.
    pub worst_error_margin: f64,
    /// Pixels where both show the same sphere.
    pub agreeing_hits: usize,
    /// Largest absolute channel difference (8-bit levels) over `agreeing_hits`.
    pub shade_max: u8,
    /// Mean absolute channel difference over `agreeing_hits` (all three channels).
    pub shade_mean: f64,
    /// Largest relative error of the hit distance `t·|d|` over `agreeing_hits`.
    pub distance_rel_max: f64,
    /// Largest pixel-centre drift, in pixels: the method's ray direction against the
    /// reference's direct one, both scaled to unit `w`-component and compared along
    /// `u` (in pixel widths) and `v` (in pixel heights).
    pub drift_max: f64,
    /// Decidable pixels (whatever they show) with some channel more than 2 levels off
    /// the reference: the accuracy tables' error count.
    pub over_2: usize,
    /// Largest absolute channel difference (8-bit levels) over all decidable pixels.
    pub color_max: u8,
    /// Mean absolute channel difference over all decidable pixels (all three channels).
    pub color_mean: f64,
    /// Samples with a NaN or infinite direction or hit distance.
    pub non_finite: usize,
    /// Samples outside the image or seen twice (each pixel must come exactly once).
    pub bad_samples: usize,
}

impl Metrics {
    /// `coverage_errors` as a fraction of the decidable pixels.
    #[must_use]
    pub fn coverage_fraction(&self) -> f64 {
        let decidable = self.pixels.saturating_sub(self.undecidable);
        if decidable == 0 {
            0.0
        } else {
            self.coverage_errors as f64 / decidable as f64
        }
    }
}

/// Drift of one kernel direction against the reference's direct one, in pixels.
#[must_use]
pub fn drift(camera: &RefCamera, i: u32, j: u32, direction: Vec3) -> f64 {
    let d = D3::of(direction);
    let along_w = d.dot(camera.w);
    if !(along_w > 0.0) {
        return f64::INFINITY;
    }
    // Directions are defined up to scale: compare on the image plane (w-component 1).
    let q = d * (1.0 / along_w);
    let (x, y) = camera.plane(i, j);
    let dx = (q.dot(camera.u) - x) / camera.pixel_width;
    let dy = (q.dot(camera.v) - y) / camera.pixel_height;
    dx.abs().max(dy.abs())
}

/// Compares a render with the reference, pixel by pixel, through [`Render::trace`]
/// (the same monomorphised loop that draws).
#[must_use]
pub fn compare<const N: usize, C, const L: usize, const P: usize, const D: usize>(
    render: &Render<'_, N, C, L, P, D>,
    reference: &ReferenceImage,
) -> Metrics {
    let mut m = Metrics::default();
    let mut seen = std::vec![false; reference.pixels.len()];
    let mut shade_sum = 0u64;
    let mut color_sum = 0u64;
    let cam = &reference.camera;
    render.trace(|s: Sample| {
        let (Ok(i), Ok(j)) = (u32::try_from(s.pixel.x), u32::try_from(s.pixel.y)) else {
            m.bad_samples += 1;
            return;
        };
        let Some(r) = reference.get(i, j) else {
            m.bad_samples += 1;
            return;
        };
        let index = j as usize * cam.width as usize + i as usize;
        match seen.get_mut(index) {
            Some(flag) if !*flag => *flag = true,
            _ => {
                m.bad_samples += 1;
                return;
            }
        }
        m.pixels += 1;
        if !s.direction.is_finite() || s.hit.is_some_and(|h| !h.t.is_finite()) {
            m.non_finite += 1;
        }
        m.drift_max = m.drift_max.max(drift(cam, i, j, s.direction));
        if r.undecidable {
            m.undecidable += 1;
            return;
        }
        let ds = channel_diffs(s.color, r.color);
        if ds.iter().any(|&d| d > 2) {
            m.over_2 += 1;
        }
        for d in ds {
            m.color_max = m.color_max.max(d);
            color_sum += u64::from(d);
        }
        let kernel_hit = s.hit.map(|h| h.index);
        if kernel_hit != r.hit {
            m.coverage_errors += 1;
            m.worst_error_margin = m.worst_error_margin.max(r.margin);
            return;
        }
        if let Some(h) = s.hit {
            m.agreeing_hits += 1;
            for d in ds {
                m.shade_max = m.shade_max.max(d);
                shade_sum += u64::from(d);
            }
            let distance = f64::from(h.t) * D3::of(s.direction).length();
            let rel = (distance - r.distance).abs() / r.distance;
            m.distance_rel_max = m.distance_rel_max.max(rel);
        }
    });
    m.bad_samples += seen.iter().filter(|s| !**s).count();
    if m.agreeing_hits > 0 {
        m.shade_mean = shade_sum as f64 / (3 * m.agreeing_hits) as f64;
    }
    let decidable = m.pixels.saturating_sub(m.undecidable);
    if decidable > 0 {
        m.color_mean = color_sum as f64 / (3 * decidable) as f64;
    }
    m
}

/// Absolute differences of two colours per 8-bit channel.
fn channel_diffs(a: Rgb888, b: Rgb888) -> [u8; 3] {
    [
        a.r().abs_diff(b.r()),
        a.g().abs_diff(b.g()),
        a.b().abs_diff(b.b()),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::geometry::Size;

    fn params(eye: [f32; 3], look: [f32; 3], fov_y: f32, w: u32, h: u32) -> CameraParams {
        CameraParams::new(
            Vec3::new(eye[0], eye[1], eye[2]),
            Vec3::new(look[0], look[1], look[2]),
            Vec3::new(0.0, 1.0, 0.0),
            fov_y,
            Size::new(w, h),
        )
    }

    #[test]
    fn camera_basis_and_directions_by_hand() {
        // Lab camera: eye on +z looking down −z, 90° so tan(45°) = 1: ph = 2/H.
        let cam = RefCamera::new(&params(
            [0.0, 0.0, 5.0],
            [0.0; 3],
            core::f32::consts::FRAC_PI_2,
            4,
            2,
        ))
        .unwrap();
        assert_eq!(cam.w, D3::new(0.0, 0.0, -1.0));
        // u = w × up = (0,0,−1) × (0,1,0) = (1, 0, 0); v = u × w = (0, 1, 0).
        assert_eq!(cam.u, D3::new(1.0, 0.0, 0.0));
        assert_eq!(cam.v, D3::new(0.0, 1.0, 0.0));
        // f32 π/2 is not exactly π/2: tan is 1 within 1e-7.
        assert!((cam.pixel_height - 1.0).abs() < 1e-7, "{}", cam.pixel_height);
        assert_eq!(cam.pixel_width, cam.pixel_height);
        // p(0,0) − eye = w + (½ − 2)·pw·u + (1 − ½)·ph·v = (−1.5, 0.5, −1).
        let d = cam.direction(0, 0);
        assert!(
            (d.x + 1.5).abs() < 1e-6 && (d.y - 0.5).abs() < 1e-6 && d.z == -1.0,
            "{d:?}"
        );
        let d = cam.direction(3, 1);
        assert!((d.x - 1.5).abs() < 1e-6 && (d.y + 0.5).abs() < 1e-6, "{d:?}");
        // Non-square pixels: fov_x given separately.
        let p = params([0.0, 0.0, 5.0], [0.0; 3], 1.0, 10, 10).with_fov_x(2.0);
        let cam = RefCamera::new(&p).unwrap();
        assert!((cam.pixel_width - 2.0 * 1f64.tan() / 10.0).abs() < 1e-7);
        assert!((cam.pixel_height - 2.0 * 0.5f64.tan() / 10.0).abs() < 1e-7);
        // Up parallel to the view: no basis.
        let p = CameraParams::new(
            Vec3::ZERO,
            Vec3::new(0.0, 2.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            1.0,
            Size::new(2, 2),
        );
        assert!(RefCamera::new(&p).is_none());
    }

    #[test]
    fn robust_intersection_by_hand() {
        let eye = D3::new(0.0, 0.0, 0.0);
        let c = D3::new(0.0, 0.0, -5.0);
        // Head on: entry at 4.
        let h = intersect(eye, D3::new(0.0, 0.0, -1.0), c, 1.0);
        assert_eq!(h.t, Some(4.0));
        assert!(!h.undecidable);
        // Unnormalised direction: same point, t halves.
        assert_eq!(intersect(eye, D3::new(0.0, 0.0, -2.0), c, 1.0).t, Some(2.0));
        // Off-axis by 0.6: perp 0.6, t = 5 − √(1 − 0.36) = 4.2.
        let h = intersect(D3::new(0.6, 0.0, 0.0), D3::new(0.0, 0.0, -1.0), c, 1.0);
        assert!((h.t.unwrap() - 4.2).abs() < 1e-12);
        assert!((h.disc - 0.64).abs() < 1e-12);
        // Miss by 0.5 outside the silhouette; clearance 0.5/|L|.
        let h = intersect(D3::new(1.5, 0.0, 0.0), D3::new(0.0, 0.0, -1.0), c, 1.0);
        assert_eq!(h.t, None);
        assert!((h.clearance - 0.5 / 27.25f64.sqrt()).abs() < 1e-12);
        // Exactly tangent: discriminant 0, undecidable.
        let h = intersect(D3::new(1.0, 0.0, 0.0), D3::new(0.0, 0.0, -1.0), c, 1.0);
        assert_eq!(h.disc, 0.0);
        assert!(h.undecidable);
        // Eye inside: the exit point.
        let h = intersect(c, D3::new(1.0, 0.0, 0.0), c, 1.0);
        assert_eq!(h.t, Some(1.0));
        // Behind the eye: a miss, flagged as irrelevant.
        let h = intersect(eye, D3::new(0.0, 0.0, 1.0), c, 1.0);
        assert_eq!(h.t, None);
        assert!(h.behind);
        // Far and small, where f32 forms cancel: distance 1e5, edge ray at 0.999 r.
        let c = D3::new(0.0, 0.0, -1e5);
        let h = intersect(eye, D3::new(0.999e-5, 0.0, -1.0), c, 1.0);
        assert!(h.t.is_some() && !h.undecidable, "{h:?}");
        let h = intersect(eye, D3::new(1.001e-5, 0.0, -1.0), c, 1.0);
        assert!(h.t.is_none() && !h.undecidable, "{h:?}");
    }

    #[test]
    fn lab1_by_hand() {
        let c = Rgb888::new(255, 100, 10);
        assert_eq!(lab1(c, 1.0), c);
        // 127.5 → 128 (halves up), 50, 5.
        assert_eq!(lab1(c, 0.5), Rgb888::new(128, 50, 5));
        // Clamped at 0.3: 76.5 → 77, 30, 3.
        assert_eq!(lab1(c, -1.0), Rgb888::new(77, 30, 3));
        assert_eq!(lab1(c, 2.0), c);
    }

    #[test]
    fn reference_image_by_hand() {
        // One unit sphere 5 ahead, 3×3 pixels, 90°: the centre pixel hits head on
        // (n_z = 1, full colour), the corners (direction (±1, ±1, −1)·… ) miss.
        let mut scene: Scene<2> = Scene::new(Rgb888::new(1, 2, 3));
        scene
            .push(embedded_raytracer::Sphere::new(
                Vec3::new(0.0, 0.0, 0.0),
                1.0,
                Rgb888::new(200, 100, 50),
            ))
            .unwrap();
        let p = params([0.0, 0.0, 5.0], [0.0; 3], core::f32::consts::FRAC_PI_2, 3, 3);
        let img = render_params(&scene, &p).unwrap();
        let centre = img.get(1, 1).unwrap();
        assert_eq!(centre.hit, Some(0));
        assert_eq!(centre.color, Rgb888::new(200, 100, 50));
        assert!((centre.distance - 4.0).abs() < 1e-12);
        assert_eq!(img.get(0, 0).unwrap().hit, None);
        assert_eq!(img.get(0, 0).unwrap().color, Rgb888::new(1, 2, 3));
        assert_eq!(img.count_hits(0), 1);
        assert_eq!(img.undecidable(), 0);
        // Two touching spheres seen side on: the contact ray is a depth tie.
        let mut scene: Scene<2> = Scene::new(Rgb888::BLACK);
        for x in [-1.0, 1.0] {
            scene
                .push(embedded_raytracer::Sphere::new(
                    Vec3::new(x, 0.0, 0.0),
                    1.0,
                    Rgb888::WHITE,
                ))
                .unwrap();
        }
        let p = CameraParams::new(
            Vec3::new(0.0, 0.0, 10.0),
            Vec3::ZERO,
            Vec3::new(0.0, 1.0, 0.0),
            0.5,
            Size::new(1, 1),
        );
        let img = render_params(&scene, &p).unwrap();
        assert!(img.get(0, 0).unwrap().undecidable, "{:?}", img.get(0, 0));
    }

    #[test]
    fn compare_counts_what_it_should() {
        let mut scene: Scene<1> = Scene::new(Rgb888::BLACK);
        scene
            .push(embedded_raytracer::Sphere::new(
                Vec3::ZERO,
                1.0,
                Rgb888::new(255, 64, 64),
            ))
            .unwrap();
        let cam = Camera::new(
            Vec3::new(0.0, 0.0, 5.0),
            Vec3::ZERO,
            Vec3::new(0.0, 1.0, 0.0),
            0.6,
            Size::new(16, 12),
        )
        .unwrap();
        let truth = render(&scene, &cam);
        let m = compare(&Render::<1, Rgb888>::new(&scene, &cam), &truth);
        assert_eq!((m.pixels, m.bad_samples, m.non_finite), (16 * 12, 0, 0));
        assert_eq!(m.coverage_errors, 0);
        assert_eq!(m.agreeing_hits, truth.count_hits(0));
        assert!(m.drift_max < 1e-3, "{m:?}");
        // Against a reference of a different scene (no sphere) every hit is an error.
        let empty: Scene<1> = Scene::new(Rgb888::BLACK);
        let m = compare(&Render::<1, Rgb888>::new(&scene, &cam), &render(&empty, &cam));
        assert_eq!(m.coverage_errors, truth.count_hits(0));
        assert!(m.worst_error_margin.is_infinite());
    }

    #[test]
    fn colour_metrics_count_every_decidable_pixel() {
        let sphere = embedded_raytracer::Sphere::new(Vec3::ZERO, 1.0, Rgb888::new(255, 64, 64));
        let scene_on = |bg: Rgb888| {
            let mut scene: Scene<1> = Scene::new(bg);
            scene.push(sphere).unwrap();
            scene
        };
        let scene = scene_on(Rgb888::new(10, 10, 10));
        let cam = Camera::new(
            Vec3::new(0.0, 0.0, 5.0),
            Vec3::ZERO,
            Vec3::new(0.0, 1.0, 0.0),
            0.6,
            Size::new(16, 12),
        )
        .unwrap();
        let render_it = Render::<1, Rgb888>::new(&scene, &cam);
        // Against its own reference: nothing more than 2 levels off.
        let m = compare(&render_it, &render(&scene, &cam));
        assert_eq!(m.over_2, 0);
        assert!(m.color_max <= 1 && m.color_mean < 1.0, "{m:?}");
        // A reference whose background is 3 levels redder: every decidable background
        // pixel is over 2 (the sphere's are not), the largest error is 3.
        let other = render(&scene_on(Rgb888::new(13, 10, 10)), &cam);
        let background = other
            .pixels
            .iter()
            .filter(|p| p.hit.is_none() && !p.undecidable)
            .count();
        assert!(background > 50, "{background}");
        let m = compare(&render_it, &other);
        assert_eq!(m.over_2, background);
        assert_eq!(m.color_max, 3);
        let decidable = (m.pixels - m.undecidable) as f64;
        assert!(m.color_mean >= background as f64 / decidable, "{m:?}");
        // Two levels are within tolerance.
        let m = compare(&render_it, &render(&scene_on(Rgb888::new(12, 10, 10)), &cam));
        assert_eq!((m.over_2, m.color_max), (0, 2));
    }
}
