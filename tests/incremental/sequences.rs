//! Random sequences of incremental frames, each compared with the full render of the
//! same frame, every pixel: `Incremental`'s promise that the display holds the last
//! frame's full render, for every method, sampling and target, through
//! `Incremental::draw` and through `update` with `Changes::draw_band` alike.
//!
//! The scenes are built in code: spheres smaller than a pixel (and their shadows),
//! one-row and one-column images, spheres that touch, overlap, nest and part, tiny and
//! huge radii, far spheres the `f32` frame refuses, lights and floors with shadows and
//! mirrors; every method (`Method::ALL` and `Method::INTEGER`), every sampling; whole,
//! offset and clipped targets; areas scribbled over and then invalidated. A failing
//! sequence names its seed; `sequence(seed)` replays it.
//!
//! The quick sweep runs in `cargo test`; the slow one (`--ignored`, in release) runs
//! enough sequences to find a failure of one sequence in a hundred with high
//! probability.

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raytracer::{
    BandError, Camera, FrameStats, Incremental, Light, Material, Method, Plane, Render, Sampling, Scene,
    Settings, Sphere, Vec3,
};

use crate::common::Rng;
use crate::framebuffer::Buffer;

/// Where the frames go: a display of `size`, the image at `offset` on it, drawn
/// through `clip` (a part of the display) if any.
#[derive(Clone, Copy, Debug)]
pub struct Target {
    pub size: Size,
    pub offset: Point,
    pub clip: Option<Rectangle>,
}

impl Target {
    /// The image alone.
    pub fn whole(image: Size) -> Self {
        Self {
            size: image,
            offset: Point::zero(),
            clip: None,
        }
    }

    /// The part of the display the frames can draw on: the clip, within the display.
    fn drawn_area(&self) -> Rectangle {
        let display = Rectangle::new(Point::zero(), self.size);
        self.clip.map_or(display, |c| c.intersection(&display))
    }
}

/// What one frame did on each path: pixels of the display (`draw`) and of the image
/// (`update` + `draw_band`) that differ from the frame's full render, and the draw's
/// statistics.
#[derive(Clone, Copy, Debug)]
pub struct Drift {
    pub drawn: usize,
    pub banded: usize,
    pub stats: FrameStats,
}

/// Two displays that show the same frames: one drawn through `Incremental::draw`, one
/// (the image at the origin) through `Incremental::update` and `Changes::draw_band`, in
/// bands of `band_rows` rows, as a DMA sender copies the changed runs.
pub struct Check<C, const N: usize, const L: usize, const P: usize, const D: usize> {
    pub target: Target,
    fill: C,
    drawn: Incremental<N, L, P, D>,
    display: Buffer<C>,
    banded: Incremental<N, L, P, D>,
    image: Buffer<C>,
    band_rows: u32,
}

impl<C, const N: usize, const L: usize, const P: usize, const D: usize> Check<C, N, L, P, D>
where
    C: PixelColor + From<Rgb888> + core::fmt::Debug,
{
    pub fn new(image: Size, target: Target, band_rows: u32, fill: C) -> Self {
        Self {
            target,
            fill,
            drawn: Incremental::new(),
            display: Buffer::new(target.size, fill),
            banded: Incremental::new(),
            image: Buffer::new(image, fill),
            band_rows: band_rows.max(1),
        }
    }

    /// Draws `render` (its offset is the target's) both ways; `Err` says what went
    /// wrong besides pixels (a refusal not reported, a band that failed).
    pub fn frame(&mut self, render: &Render<'_, N, C, L, P, D>) -> Result<Drift, String> {
        let render = render.with_offset(self.target.offset);
        let expected = render.check().err();
        let stats = self
            .drawn
            .draw(&render, self.display.clipped_to(self.target.clip))
            .unwrap();
        if stats.refused != expected || (expected.is_some() && (stats.full || stats.sent != 0)) {
            return Err(format!(
                "draw: {stats:?}, but the frame's check says {expected:?}"
            ));
        }
        if stats.arithmetic != render.arithmetic() {
            return Err(format!(
                "draw: {stats:?}, but the render's arithmetic is {:?}",
                render.arithmetic()
            ));
        }
        let mut full = Buffer::new(self.target.size, self.fill);
        render.draw(full.clipped_to(self.target.clip)).unwrap();
        // A refused frame draws nothing: the display keeps the last frame.
        let drawn = if expected.is_none() {
            self.display.diff(&full)
        } else {
            0
        };

        let render = render.with_offset(Point::zero());
        let changes = self.banded.update(&render);
        if changes.refused() != expected || (expected.is_some() && changes.is_full()) {
            return Err(format!(
                "update: refused {:?}, full {}, but the frame's check says {expected:?}",
                changes.refused(),
                changes.is_full()
            ));
        }
        if changes.arithmetic() != render.arithmetic() {
            return Err(format!(
                "update: arithmetic {:?}, but the render's is {:?}",
                changes.arithmetic(),
                render.arithmetic()
            ));
        }
        let (width, height) = (self.image.size.width, self.image.size.height);
        let mut j0 = 0;
        while j0 < height {
            let rows = j0..(j0 + self.band_rows).min(height);
            let mut band = vec![self.fill; (width * rows.len() as u32) as usize];
            let result = changes.draw_band(&render, rows.clone(), &mut band);
            match (result, expected) {
                (Ok(()), None) => {}
                (Err(BandError::Frame(why)), Some(e)) if why == e => {}
                (r, _) => {
                    return Err(format!(
                        "draw_band {rows:?}: {r:?}, the frame's check says {expected:?}"
                    ))
                }
            }
            if expected.is_none() {
                for j in rows.clone() {
                    for (lo, hi) in changes.runs(j) {
                        let at = (j * width) as usize;
                        let from = ((j - j0) * width) as usize;
                        self.image.px[at + lo as usize..at + hi as usize]
                            .copy_from_slice(&band[from + lo as usize..from + hi as usize]);
                    }
                }
            }
            j0 = rows.end;
        }
        let banded = if expected.is_none() {
            let mut full = Buffer::new(self.image.size, self.fill);
            render.draw_band(0..height, &mut full.px).unwrap();
            self.image.diff(&full)
        } else {
            0
        };
        Ok(Drift { drawn, banded, stats })
    }

    /// Scribbles over `area` of the image (image coordinates, within it) on both
    /// displays, as an overlay would, and tells each `Incremental`.
    pub fn scribble(&mut self, area: Rectangle, color: C) {
        let on_target = Rectangle::new(area.top_left + self.target.offset, area.size);
        let drawn = on_target.intersection(&self.target.drawn_area());
        self.display.clipped_to(None).fill_solid(&drawn, color).unwrap();
        self.drawn.invalidate_area(on_target);
        self.image.fill_solid(&area, color).unwrap();
        self.banded.invalidate_area(area);
    }
}

// ---------------------------------------------------------------------------------------
// Random sequences.

/// A random integer in `0..n`.
fn below(rng: &mut Rng, n: usize) -> usize {
    ((rng.next() * n as f32) as usize).min(n - 1)
}

fn color(rng: &mut Rng) -> Rgb888 {
    Rgb888::new(
        below(rng, 256) as u8,
        below(rng, 256) as u8,
        below(rng, 256) as u8,
    )
}

fn unit(rng: &mut Rng) -> Vec3 {
    loop {
        let v = rng.vec(1.0);
        let len = v.dot(v).sqrt();
        if len > 0.1 && len <= 1.0 {
            return v * (1.0 / len);
        }
    }
}

/// Every sampling: the centre ray, grids and adaptive grids of 2 to 4.
fn sampling(rng: &mut Rng) -> Sampling {
    let n = 2 + below(rng, 3) as u32;
    match below(rng, 3) {
        0 => Sampling::Center,
        1 => Sampling::grid(n).unwrap(),
        _ => Sampling::adaptive(n).unwrap(),
    }
}

/// Every method, the integer kernel as often as a sixth of them.
fn method(rng: &mut Rng) -> Method {
    if rng.next() < 1.0 / 6.0 {
        Method::INTEGER
    } else {
        Method::ALL[below(rng, Method::ALL.len())]
    }
}

/// The view: a camera around the origin, an image of at most `max` pixels each way
/// (one row or one column now and then), a field of view wide, usual, narrow or very
/// narrow.
fn view(rng: &mut Rng, max: Size) -> Camera {
    let mut width = 1 + below(rng, max.width as usize) as u32;
    let mut height = 1 + below(rng, max.height as usize) as u32;
    match below(rng, 8) {
        0 => height = 1,
        1 => width = 1,
        _ => {}
    }
    // A very narrow view makes the lecture notes' tests' culling ellipses (their margin
    // `2⁻¹⁷·|L|²` on `r²`) several to twenty pixels around a sphere smaller than a
    // pixel: an image of 32 to 48 pixels holds such an ellipse's bounding box.
    let fov = match below(rng, 8) {
        0 => {
            width = 32 + below(rng, 17) as u32;
            height = 32 + below(rng, 17) as u32;
            height as f32 * rng.range(1.5e-4, 4e-4)
        }
        1 => rng.range(0.01, 0.1),
        2 => rng.range(1.6, 2.6),
        _ => rng.range(0.4, 1.2),
    };
    let eye = Vec3::new(rng.range(-3.0, 3.0), rng.range(-1.0, 4.0), rng.range(5.0, 10.0));
    let look = rng.vec(0.5);
    Camera::new(eye, look, Vec3::new(0.0, 1.0, 0.0), fov, Size::new(width, height)).unwrap()
}

/// A point the camera sees at distance `dist`, about `spread` of the half-field off
/// its axis.
fn in_view(rng: &mut Rng, camera: &Camera, dist: f32, spread: f32) -> Vec3 {
    let half = (camera.params().fov_y / 2.0).tan();
    let aspect = camera.size().width as f32 / camera.size().height as f32;
    let x = rng.range(-spread, spread) * half * aspect;
    let y = rng.range(-spread, spread) * half;
    camera.eye() + (camera.w() + camera.u() * x + camera.v() * y) * dist
}

/// The size of a pixel (world units) at distance `dist`.
fn pixel_at(camera: &Camera, dist: f32) -> f32 {
    2.0 * (camera.params().fov_y / 2.0).tan() / camera.size().height as f32 * dist
}

/// A material, a mirror only where the scene type has a reflection depth.
fn material(rng: &mut Rng, mirrors: bool) -> Material {
    let reflect = if mirrors { rng.range(0.0, 0.8) } else { 0.0 };
    Material::new(rng.range(0.0, 1.0), rng.range(1.0, 64.0), reflect)
}

/// A sphere of one of the kinds the rule must handle, beside the scene's others and
/// under its lights.
fn sphere(rng: &mut Rng, camera: &Camera, others: &[Sphere], lights: &[Light], mirrors: bool) -> Sphere {
    let kind = below(rng, 12);
    sphere_of(kind, rng, camera, others, lights, mirrors)
}

/// A sphere of kind `kind` (see [`sphere`]).
fn sphere_of(
    kind: usize,
    rng: &mut Rng,
    camera: &Camera,
    others: &[Sphere],
    lights: &[Light],
    mirrors: bool,
) -> Sphere {
    let c = color(rng);
    let mut s = match kind {
        // Small and far from the floor toward a light, whose shadow rays from the floor
        // are hundreds of radii long: where the lecture notes' tests are far from exact.
        6 | 7 if !lights.is_empty() => {
            let r = rng.range(0.005, 0.1);
            let centre = match lights[below(rng, lights.len())] {
                Light::Point { position, .. } => {
                    position - Vec3::new(0.0, rng.range(0.2, 3.0), 0.0) + rng.vec(0.1)
                }
                Light::Directional { direction, .. } => {
                    let toward = direction * (-1.0 / direction.dot(direction).sqrt());
                    Vec3::new(rng.range(-2.0, 2.0), -1.0, rng.range(-2.0, 2.0))
                        + toward * rng.range(20.0, 200.0)
                }
            };
            Sphere::new(centre, r, c)
        }
        // Smaller than a pixel, often between two rows' or columns' centres.
        0 | 1 => {
            let dist = rng.range(2.0, 15.0);
            let r = pixel_at(camera, dist) * rng.range(0.02, 0.6);
            Sphere::new(in_view(rng, camera, dist, 1.1), r, c)
        }
        // Touching another (exactly, or just apart or into it), or nested in it.
        2 | 3 if !others.is_empty() => {
            let a = others[below(rng, others.len())];
            let d = unit(rng);
            let r = a.radius * rng.range(0.05, 1.5);
            if rng.next() < 0.25 {
                let r = a.radius * rng.range(0.05, 0.9);
                Sphere::new(a.center + d * ((a.radius - r) * rng.next()), r, c)
            } else {
                let gap = [0.0, 1e-6, -1e-6, 1e-3, -1e-3, 0.05][below(rng, 6)];
                Sphere::new(a.center + d * ((a.radius + r) * (1.0 + gap)), r, c)
            }
        }
        // Smaller than a pixel in front of another, on a line of sight to it: the
        // small one's pixels then show the other's shading.
        8 if !others.is_empty() => {
            let a = others[below(rng, others.len())];
            let at = camera.eye() + (a.center + rng.vec(a.radius) - camera.eye()) * rng.range(0.2, 0.95);
            let dist = (at - camera.eye()).dot(camera.w()).abs().max(0.01);
            Sphere::new(at, pixel_at(camera, dist) * rng.range(0.02, 0.6), c)
        }
        // Straight ahead, in view however narrow the view, often its rim (where its
        // shading changes fastest) on the axis.
        9 => {
            let dist = rng.range(3.0, 12.0);
            let r = rng.range(0.1, 1.2);
            let angle = rng.range(0.0, 6.3);
            let rim = (camera.u() * angle.cos() + camera.v() * angle.sin()) * (r * rng.range(0.0, 0.97));
            Sphere::new(in_view(rng, camera, dist, 0.5) + rim, r, c)
        }
        // Huge, far, or around the eye.
        4 => {
            let r = rng.range(3.0, 60.0);
            let dist = if rng.next() < 0.2 {
                r * rng.range(0.1, 0.9)
            } else {
                r + rng.range(1.0, 50.0)
            };
            Sphere::new(camera.eye() + unit(rng) * dist, r, c)
        }
        // Tiny and far away.
        5 => {
            let dist = rng.range(50.0, 5000.0);
            Sphere::new(in_view(rng, camera, dist, 1.0), dist * rng.range(1e-5, 1e-2), c)
        }
        // An ordinary sphere near the middle.
        _ => Sphere::new(rng.vec(2.0), rng.range(0.1, 1.2), c),
    };
    if rng.next() < 0.2 {
        s = s.with_material(material(rng, mirrors));
    }
    s
}

/// One random change between frames.
fn motion<const N: usize, const L: usize, const P: usize, const D: usize>(
    rng: &mut Rng,
    camera: &Camera,
    scene: &mut Scene<N, L, P, D>,
) {
    let n = scene.spheres().len();
    if n == 0 {
        return;
    }
    let k = below(rng, n);
    let mut s = scene.spheres()[k];
    let pixel = pixel_at(camera, (s.center - camera.eye()).dot(camera.w()).abs().max(0.1));
    match below(rng, 16) {
        // A step of a fraction of a pixel, or a few.
        0 | 1 => {
            let step = pixel * rng.range(0.1, 4.0);
            s.center += rng.vec(step);
        }
        2 => s.center += rng.vec(1.0),
        // A jump: another sphere of any kind.
        3 | 4 => {
            let others: Vec<Sphere> = scene
                .spheres()
                .iter()
                .enumerate()
                .filter(|&(m, _)| m != k)
                .map(|(_, s)| *s)
                .collect();
            s = sphere(rng, camera, &others, scene.lights(), D > 0);
        }
        // Into contact with another, or apart from it.
        5 | 13 if n > 1 => {
            let a = scene.spheres()[(k + 1 + below(rng, n - 1)) % n];
            let gap = [0.0, 1e-6, -1e-6, 1e-3, 0.02, 0.3][below(rng, 6)];
            s.center = a.center + unit(rng) * ((a.radius + s.radius) * (1.0 + gap));
        }
        6 => s.radius *= rng.range(0.5, 1.5),
        // A step of about its own radius, however small.
        12 => {
            let step = s.radius * rng.range(0.1, 2.0);
            s.center += rng.vec(step);
        }
        7 => s.color = color(rng),
        8 => s.material = material(rng, D > 0),
        9 => s.center.x = if s.center.x == 0.0 { -0.0 } else { 0.0 },
        // Far away: a frame the `f32` kernel refuses beside near spheres, or the
        // integer kernel's rule does not take.
        10 => s.center = camera.eye() + unit(rng) * [1e3, 1e8, 1e30][below(rng, 3)],
        // A light or a plane moves (frame-wide).
        11 if !scene.lights().is_empty() && rng.next() < 0.5 => {
            let m = below(rng, scene.lights().len());
            scene.set_light(m, light(rng)).unwrap();
            return;
        }
        11 if !scene.planes().is_empty() => {
            let m = below(rng, scene.planes().len());
            scene.set_plane(m, plane(rng, D > 0)).unwrap();
            return;
        }
        _ => return,
    }
    scene.set_sphere(k, s).unwrap();
}

/// The sun, or a lamp near the scene or high above it.
fn light(rng: &mut Rng) -> Light {
    if rng.next() < 0.5 {
        Light::directional(
            Vec3::new(rng.range(-1.0, 1.0), rng.range(-1.5, -0.1), rng.range(-1.0, 1.0)),
            0.8,
        )
    } else {
        let height = if rng.next() < 0.5 {
            rng.range(30.0, 300.0)
        } else {
            rng.range(1.0, 6.0)
        };
        Light::point(Vec3::new(rng.range(-4.0, 4.0), height, rng.range(-4.0, 4.0)), 0.7)
    }
}

fn plane(rng: &mut Rng, mirrors: bool) -> Plane {
    let mut p = Plane::new(
        Vec3::new(0.0, rng.range(-2.0, -0.5), 0.0),
        Vec3::new(rng.range(-0.2, 0.2), 1.0, rng.range(-0.2, 0.2)),
        color(rng),
    );
    if rng.next() < 0.5 {
        p = p.with_checker(color(rng), rng.range(0.2, 1.5));
    }
    if mirrors && rng.next() < 0.15 {
        p = p.with_material(Material::new(0.5, 16.0, 0.5));
    }
    p
}

/// A random scene of up to `N` spheres, and, as the type allows, lights, planes and a
/// reflection depth.
fn scene<const N: usize, const L: usize, const P: usize, const D: usize>(
    rng: &mut Rng,
    camera: &Camera,
) -> Scene<N, L, P, D> {
    let mut scene = Scene::new(color(rng));
    if L > 0 {
        for _ in 0..1 + below(rng, L) {
            scene.push_light(light(rng)).unwrap();
        }
    }
    if P > 0 {
        for _ in 0..1 + below(rng, P) {
            scene.push_plane(plane(rng, D > 0)).unwrap();
        }
    }
    // A very narrow view sees little of a random scene: there, a sphere straight ahead
    // and one smaller than a pixel in front of it.
    let narrow = camera.params().fov_y < 5e-4 * camera.size().height as f32;
    for k in 0..1 + below(rng, N) {
        let s = match k {
            0 | 1 if narrow => sphere_of([9, 8][k], rng, camera, scene.spheres(), scene.lights(), D > 0),
            _ => sphere(rng, camera, scene.spheres(), scene.lights(), D > 0),
        };
        scene.push(s).unwrap();
    }
    let settings = Settings::DEFAULT
        .with_shadows(rng.next() < 0.8)
        .with_max_depth(below(rng, D + 1) as u8);
    scene.set_settings(settings).unwrap();
    scene
}

/// Where the frames go: the image alone, or on a larger display at an offset (parts
/// off the display now and then), or through a clip.
fn target(rng: &mut Rng, image: Size) -> Target {
    match below(rng, 3) {
        0 => Target::whole(image),
        _ => {
            let size = Size::new(
                image.width + below(rng, 6) as u32,
                image.height + below(rng, 6) as u32,
            );
            let offset = Point::new(below(rng, 8) as i32 - 2, below(rng, 8) as i32 - 2);
            let clip = (rng.next() < 0.5).then(|| {
                let x = below(rng, size.width as usize) as i32;
                let y = below(rng, size.height as usize) as i32;
                let w = 1 + below(rng, size.width as usize - x as usize) as u32;
                let h = 1 + below(rng, size.height as usize - y as usize) as u32;
                Rectangle::new(Point::new(x, y), Size::new(w, h))
            });
            Target { size, offset, clip }
        }
    }
}

/// One random sequence of frames of a scene of type `Scene<N, L, P, D>` in colour `C`;
/// `Err` describes the first frame whose display differs from its full render.
fn run<C, const N: usize, const L: usize, const P: usize, const D: usize>(
    rng: &mut Rng,
    max: Size,
    frames: usize,
    fill: C,
) -> Result<(), String>
where
    C: PixelColor + From<Rgb888> + core::fmt::Debug,
{
    let camera = view(rng, max);
    let mut scene: Scene<N, L, P, D> = scene(rng, &camera);
    let (method, sampling) = (method(rng), sampling(rng));
    let image = camera.size();
    let target = target(rng, image);
    let band_rows = 1 + below(rng, image.height as usize) as u32;
    let mut check = Check::new(image, target, band_rows, fill);
    for f in 0..frames {
        if f > 0 {
            for _ in 0..1 + below(rng, 2) {
                motion(rng, &camera, &mut scene);
            }
        }
        if f > 0 && rng.next() < 0.1 {
            let x = below(rng, image.width as usize) as i32;
            let y = below(rng, image.height as usize) as i32;
            let w = 1 + below(rng, image.width as usize - x as usize) as u32;
            let h = 1 + below(rng, image.height as usize - y as usize) as u32;
            check.scribble(
                Rectangle::new(Point::new(x, y), Size::new(w, h)),
                C::from(color(rng)),
            );
        }
        let render = Render::new(&scene, &camera)
            .with_method(method)
            .with_sampling(sampling);
        let what = || {
            format!(
                "frame {f}: {method} {sampling:?}, image {image:?}, {target:?}, bands of {band_rows}\n{scene:?}\n{:?}",
                camera.params()
            )
        };
        let drift = check.frame(&render).map_err(|e| format!("{e}; {}", what()))?;
        if drift.drawn != 0 || drift.banded != 0 {
            return Err(format!(
                "{} pixels of the display and {} of the banded image differ from the full render ({:?}); {}",
                drift.drawn,
                drift.banded,
                drift.stats,
                what()
            ));
        }
    }
    Ok(())
}

/// Sequence `seed`: its scene type, colour and size from the seed.
pub fn sequence(seed: u64, max: Size, frames: usize) -> Result<(), String> {
    let mut rng = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    rng.next();
    match below(&mut rng, 6) {
        0 | 1 => run::<Rgb565, 4, 0, 0, 0>(&mut rng, max, frames, Rgb565::new(3, 7, 11)),
        2 => run::<Rgb888, 3, 0, 0, 0>(&mut rng, max, frames, Rgb888::new(9, 8, 7)),
        3 | 4 => run::<Rgb565, 3, 2, 1, 0>(&mut rng, max, frames, Rgb565::new(3, 7, 11)),
        _ => run::<Rgb565, 3, 1, 2, 2>(&mut rng, max, frames, Rgb565::new(3, 7, 11)),
    }
}

/// Runs sequences `seeds`, and fails naming every failing seed (each printed with what
/// went wrong as it is found).
///
/// The sequences are independent: the seeds are cut into one run of consecutive seeds
/// per core, each on a thread of its own.
fn sweep(seeds: core::ops::Range<u64>, max: Size, frames: usize) {
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()) as u64;
    let chunk = (seeds.end - seeds.start).div_ceil(threads);
    let failed: Vec<u64> = std::thread::scope(|scope| {
        let runs: Vec<_> = (0..threads)
            .map(|t| {
                let lo = (seeds.start + t * chunk).min(seeds.end);
                let hi = (lo + chunk).min(seeds.end);
                scope.spawn(move || {
                    let mut failed = Vec::new();
                    for seed in lo..hi {
                        if let Err(e) = sequence(seed, max, frames) {
                            println!("seed {seed}: {e}\n");
                            failed.push(seed);
                        }
                    }
                    failed
                })
            })
            .collect();
        runs.into_iter()
            .flat_map(|run| run.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    });
    assert!(
        failed.is_empty(),
        "{} of {} sequences end with a display that differs from the full render; seeds {failed:?} (replay one with `sequence(seed, {max:?}, {frames})`)",
        failed.len(),
        seeds.end - seeds.start
    );
}

#[test]
fn random_sequences_equal_the_full_render() {
    sweep(0..300, Size::new(14, 10), 5);
}

/// 10,000 sequences of six frames up to 20×14 (60,000 small frames, most of them
/// incremental): a rule that fails one sequence in a hundred passes with probability
/// `0.99^10000 < 10⁻⁴³`. Small images keep sub-pixel spheres, one-row and one-column
/// images and touching silhouettes frequent; run by `.ci/run` in the test profile the
/// quick sweep is built in (under two minutes on two cores, no second build).
#[test]
#[ignore = "slow: a minute or two; run by .ci/run with --ignored"]
fn many_random_sequences_equal_the_full_render() {
    sweep(1_000_000..1_010_000, Size::new(20, 14), 6);
}
