//! Rendering: a [`Render`] is an embedded-graphics [`Drawable`] that traces one
//! scanline at a time straight into the target — one `fill_contiguous` per row, the
//! colours produced by an iterator while the driver consumes them. No framebuffer, no
//! row buffer, no allocation.
//!
//! The [`Method`] is matched once per frame; below that match the row loop is
//! monomorphised over zero-sized strategy types (stepping, sphere test, square root),
//! so the per-pixel code has no branch on the method.

use core::fmt;
use core::marker::PhantomData;
use core::str::FromStr;

use embedded_graphics::pixelcolor::{PixelColor, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::Vec;

use crate::camera::Camera;
use crate::error::ParseMethodError;
use crate::math::{ExactSqrt, FastSqrt, SqrtFn};
use crate::scene::{closest, Hit, Scene};
use crate::shade;
use crate::sphere::{Algebraic, Geometric, HitTest, Robust, SphereConsts};
use crate::vec3::Vec3;

/// How the ray direction `p − eye` advances from pixel to pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Stepping {
    /// The slides verbatim: the pixel centre `p` is stepped in world space
    /// (`p += pw·u`, `scanlineStart −= ph·v`) and the ray is `p − eye`. Drifts: each add
    /// rounds relative to `|p| ≈ |eye|`, so far from the origin whole pixels are lost
    /// across a wide image (≥ 1 px at 1920 wide once `|eye| ≳ 10`).
    WorldSpace,
    /// Camera-relative: each scanline's first direction is computed directly
    /// (`p(0,j) − eye`, once per row), then the direction is stepped by `pw·u` per pixel.
    /// Rounding is relative to `|p − eye| ≈ 1`, independent of where the eye is.
    Incremental,
    /// Every pixel's direction evaluated directly, `first + j·dv + i·du`: no
    /// accumulation at all, three multiplies more per pixel.
    Direct,
}

/// Which ray–sphere intersection formula the pixel loop uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SphereTest {
    /// The slides' quadratic (see [`Sphere::intersect_algebraic`](crate::Sphere::intersect_algebraic)).
    Algebraic,
    /// The slides' `t_ca`/`d²` construction (see [`Sphere::intersect_geometric`](crate::Sphere::intersect_geometric)).
    Geometric,
    /// Haines et al.'s robust discriminant and stable roots (see [`Sphere::intersect_robust`](crate::Sphere::intersect_robust)).
    Robust,
}

/// Which square root the pixel loop uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sqrt {
    /// Correctly rounded ([`math::sqrt_exact`](crate::math::sqrt_exact)).
    Exact,
    /// micromath's approximation, ≤ +6.07 % ([`math::sqrt_fast`](crate::math::sqrt_fast)).
    Fast,
}

/// A point on the speed/accuracy chart: stepping × sphere test × square root.
///
/// The default is `Direct` + `Robust` + `Exact`, the only combination the accuracy lab
/// (README, "Accuracy") measures with zero coverage errors on every standard scene:
/// direct evaluation does not accumulate rounding along a row (`Incremental` does,
/// 0.016 px across 1920 pixels, enough to flip pixels that graze a silhouette), the
/// robust test has no cancellation, and the exact root keeps shading within one level
/// of an f64 reference.
///
/// ```
/// use embedded_raytracer::{Method, SphereTest, Stepping, Sqrt};
/// let m = Method::default();
/// assert_eq!((m.stepping, m.sphere_test, m.sqrt), (Stepping::Direct, SphereTest::Robust, Sqrt::Exact));
/// assert_eq!("world-space".parse::<Stepping>(), Ok(Stepping::WorldSpace));
/// assert_eq!(m.to_string(), "direct/robust/exact");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Method {
    /// Ray stepping.
    pub stepping: Stepping,
    /// Ray–sphere test.
    pub sphere_test: SphereTest,
    /// Square root.
    pub sqrt: Sqrt,
}

impl Method {
    /// The default method (see the type's docs).
    pub const DEFAULT: Method = Method::new(Stepping::Direct, SphereTest::Robust, Sqrt::Exact);

    /// The seed taken literally: world-space stepping, the quadratic, exact root.
    pub const LITERAL: Method = Method::new(Stepping::WorldSpace, SphereTest::Algebraic, Sqrt::Exact);

    /// A method from its three choices.
    #[must_use]
    pub const fn new(stepping: Stepping, sphere_test: SphereTest, sqrt: Sqrt) -> Self {
        Self {
            stepping,
            sphere_test,
            sqrt,
        }
    }

    /// Every combination, for charts and sweeps.
    // Indexing in a const initialiser is checked at compile time.
    #[allow(clippy::indexing_slicing)]
    pub const ALL: [Method; 18] = {
        let steppings = [Stepping::WorldSpace, Stepping::Incremental, Stepping::Direct];
        let tests = [SphereTest::Algebraic, SphereTest::Geometric, SphereTest::Robust];
        let sqrts = [Sqrt::Exact, Sqrt::Fast];
        let mut all = [Method::DEFAULT; 18];
        let mut k = 0;
        while k < 18 {
            all[k] = Method::new(steppings[k / 6], tests[(k / 2) % 3], sqrts[k % 2]);
            k += 1;
        }
        all
    };
}

impl Default for Method {
    fn default() -> Self {
        Method::DEFAULT
    }
}

/// `FromStr`/`Display` with kebab-case names, for CLI flags and scene tooling.
macro_rules! named_enum {
    ($ty:ident, $what:literal, $($variant:ident => $name:literal),+) => {
        impl $ty {
            /// The kebab-case name used by the CLI.
            #[must_use]
            pub const fn name(self) -> &'static str {
                match self { $($ty::$variant => $name),+ }
            }
        }
        impl fmt::Display for $ty {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(self.name())
            }
        }
        impl FromStr for $ty {
            type Err = ParseMethodError;
            fn from_str(s: &str) -> Result<Self, Self::Err> {
                match s {
                    $($name => Ok($ty::$variant),)+
                    _ => Err(ParseMethodError { what: $what, expected: concat!($($name, " "),+) }),
                }
            }
        }
    };
}

named_enum!(Stepping, "stepping", WorldSpace => "world-space", Incremental => "incremental", Direct => "direct");
named_enum!(SphereTest, "sphere test", Algebraic => "algebraic", Geometric => "geometric", Robust => "robust");
named_enum!(Sqrt, "sqrt", Exact => "exact", Fast => "fast");

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}/{}", self.stepping, self.sphere_test, self.sqrt)
    }
}

/// One traced pixel, as [`Render::trace`] reports it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Pixel position in the image (column, row), before the render's offset.
    pub pixel: Point,
    /// The ray direction `p − eye` the stepping produced for this pixel.
    pub direction: Vec3,
    /// The closest hit, if any.
    pub hit: Option<Hit>,
    /// The shaded colour.
    pub color: Rgb888,
}

/// A scene seen through a camera with a method, ready to draw.
///
/// The output colour `C` is inferred from the target (any colour that converts from
/// `Rgb888`: `Rgb888`, `Rgb565`, `Gray8`, `BinaryColor`, …).
///
/// ```
/// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::{Rgb565, Rgb888}, prelude::*};
/// use embedded_raytracer::{Camera, Render, Scene, Sphere, Vec3};
///
/// static SCENE: Scene<1> = Scene::from_array(
///     [Sphere::new(Vec3::new(0.0, 0.0, 0.0), 1.0, Rgb888::new(255, 0, 0))],
///     Rgb888::new(0, 0, 0),
/// );
/// let camera = Camera::new(
///     Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0),
///     0.5, Size::new(16, 16),
/// ).unwrap();
///
/// let mut display = MockDisplay::<Rgb565>::new();
/// Render::new(&SCENE, &camera).draw(&mut display).unwrap();
/// assert_eq!(display.get_pixel(Point::new(8, 8)), Some(Rgb565::RED)); // facing the eye
/// assert_eq!(display.get_pixel(Point::new(0, 0)), Some(Rgb565::BLACK)); // background
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Render<'a, const N: usize, C = Rgb888> {
    scene: &'a Scene<N>,
    camera: &'a Camera,
    method: Method,
    offset: Point,
    color: PhantomData<C>,
}

impl<'a, const N: usize, C> Render<'a, N, C> {
    /// The scene through the camera with the default method, at the target's origin.
    #[must_use]
    pub const fn new(scene: &'a Scene<N>, camera: &'a Camera) -> Self {
        Self {
            scene,
            camera,
            method: Method::DEFAULT,
            offset: Point::zero(),
            color: PhantomData,
        }
    }

    /// The same render with another method.
    #[must_use]
    pub const fn with_method(mut self, method: Method) -> Self {
        self.method = method;
        self
    }

    /// The same render placed with its upper-left pixel at `offset` on the target (for
    /// a sub-rectangle of a larger display). Pixels outside the target are clipped.
    #[must_use]
    pub const fn with_offset(mut self, offset: Point) -> Self {
        self.offset = offset;
        self
    }

    /// The method in use.
    #[must_use]
    pub const fn method(&self) -> Method {
        self.method
    }

    /// The area of the target the render covers (before clipping).
    #[must_use]
    pub const fn area(&self) -> Rectangle {
        Rectangle::new(self.offset, self.camera.size())
    }

    /// Traces every pixel of the image in row-major order, through exactly the same
    /// monomorphised loop as [`Drawable::draw`], and hands each [`Sample`] (direction,
    /// hit, colour) to `f`. For tests, accuracy measurements and custom sinks.
    pub fn trace(&self, mut f: impl FnMut(Sample)) {
        let full = Rectangle::new(Point::zero(), self.camera.size());
        let mut sink = TraceSink(&mut f);
        let _ = dispatch(
            self.scene,
            self.camera,
            self.method,
            full,
            Point::zero(),
            &mut sink,
        );
    }
}

impl<const N: usize, C> Drawable for Render<'_, N, C>
where
    C: PixelColor + From<Rgb888>,
{
    type Color = C;
    type Output = ();

    fn draw<D>(&self, target: &mut D) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        let clip = target.bounding_box();
        let mut sink = DrawSink {
            target,
            color: PhantomData,
        };
        dispatch(self.scene, self.camera, self.method, clip, self.offset, &mut sink)
    }
}

/// Where finished rows go: the target (draw) or a callback (trace).
trait RowSink {
    type Error;
    fn row<I: Iterator<Item = Sample>>(&mut self, area: Rectangle, pixels: I) -> Result<(), Self::Error>;
}

struct DrawSink<'t, D, C> {
    target: &'t mut D,
    color: PhantomData<C>,
}

impl<D: DrawTarget<Color = C>, C: PixelColor + From<Rgb888>> RowSink for DrawSink<'_, D, C> {
    type Error = D::Error;
    #[inline(always)]
    fn row<I: Iterator<Item = Sample>>(&mut self, area: Rectangle, pixels: I) -> Result<(), D::Error> {
        self.target
            .fill_contiguous(&area, pixels.map(|s| C::from(s.color)))
    }
}

struct TraceSink<'f, F>(&'f mut F);

impl<F: FnMut(Sample)> RowSink for TraceSink<'_, F> {
    type Error = core::convert::Infallible;
    fn row<I: Iterator<Item = Sample>>(&mut self, _area: Rectangle, pixels: I) -> Result<(), Self::Error> {
        pixels.for_each(&mut *self.0);
        Ok(())
    }
}

/// The once-per-frame `match` on the method, down to a monomorphised frame loop.
fn dispatch<const N: usize, K: RowSink>(
    scene: &Scene<N>,
    camera: &Camera,
    method: Method,
    clip: Rectangle,
    offset: Point,
    sink: &mut K,
) -> Result<(), K::Error> {
    fn with_test<const N: usize, K: RowSink, S: Stepper>(
        f: Frame<'_, N>,
        method: Method,
        sink: &mut K,
    ) -> Result<(), K::Error> {
        match method.sphere_test {
            SphereTest::Algebraic => with_sqrt::<N, K, S, Algebraic>(f, method, sink),
            SphereTest::Geometric => with_sqrt::<N, K, S, Geometric>(f, method, sink),
            SphereTest::Robust => with_sqrt::<N, K, S, Robust>(f, method, sink),
        }
    }
    fn with_sqrt<const N: usize, K: RowSink, S: Stepper, T: HitTest>(
        f: Frame<'_, N>,
        method: Method,
        sink: &mut K,
    ) -> Result<(), K::Error> {
        match method.sqrt {
            Sqrt::Exact => f.run::<K, S, T, ExactSqrt>(sink),
            Sqrt::Fast => f.run::<K, S, T, FastSqrt>(sink),
        }
    }

    let Some(frame) = Frame::new(scene, camera, clip, offset) else {
        return Ok(()); // nothing visible
    };
    match method.stepping {
        Stepping::WorldSpace => with_test::<N, K, WorldSpaceStep>(frame, method, sink),
        Stepping::Incremental => with_test::<N, K, IncrementalStep>(frame, method, sink),
        Stepping::Direct => with_test::<N, K, DirectStep>(frame, method, sink),
    }
}

/// Per-frame state: the visible part of the image and each sphere's constants.
struct Frame<'a, const N: usize> {
    camera: &'a Camera,
    spheres: Vec<SphereConsts, N>,
    background: Rgb888,
    /// Visible columns `i0..i1` and rows `j0..j1` of the image.
    i0: u32,
    i1: u32,
    j0: u32,
    j1: u32,
    offset: Point,
}

impl<'a, const N: usize> Frame<'a, N> {
    /// Clips the image (placed at `offset`) to `clip`; `None` if nothing is visible.
    fn new(scene: &Scene<N>, camera: &'a Camera, clip: Rectangle, offset: Point) -> Option<Self> {
        let size = camera.size();
        // Clip in i64: no overflow for any offset or target size.
        let span = |origin: i32, len: u32, clip_origin: i32, clip_len: u32| {
            let lo = i64::from(origin).max(i64::from(clip_origin));
            let hi = (i64::from(origin) + i64::from(len)).min(i64::from(clip_origin) + i64::from(clip_len));
            (lo < hi).then(|| ((lo - i64::from(origin)) as u32, (hi - i64::from(origin)) as u32))
        };
        let (i0, i1) = span(offset.x, size.width, clip.top_left.x, clip.size.width)?;
        let (j0, j1) = span(offset.y, size.height, clip.top_left.y, clip.size.height)?;
        // Per-sphere constants, once per frame.
        let eye = camera.eye();
        let w = camera.w();
        let spheres = scene
            .spheres()
            .iter()
            .map(|s| SphereConsts::new(s, eye, w))
            .collect();
        Some(Self {
            camera,
            spheres,
            background: scene.background(),
            i0,
            i1,
            j0,
            j1,
            offset,
        })
    }

    /// The frame loop for one method: per row, set up the stepper and hand the row's
    /// pixel iterator to the sink.
    fn run<K: RowSink, S: Stepper, T: HitTest, Q: SqrtFn>(&self, sink: &mut K) -> Result<(), K::Error> {
        let mut stepper = S::new(self.camera);
        let width = self.i1 - self.i0;
        for j in self.j0..self.j1 {
            stepper.start_row(j, self.i0);
            // Visible rows and columns fit in the target's i32 coordinates.
            let area = Rectangle::new(
                Point::new(
                    self.offset.x.wrapping_add(self.i0 as i32),
                    self.offset.y.wrapping_add(j as i32),
                ),
                Size::new(width, 1),
            );
            let row = RowPixels::<S, T, Q> {
                stepper: &mut stepper,
                spheres: &self.spheres,
                w: self.camera.w(),
                background: self.background,
                i: self.i0,
                end: self.i1,
                j,
                strategy: PhantomData,
            };
            sink.row(area, row)?;
        }
        Ok(())
    }
}

/// The pixels of one scanline, traced as the sink pulls them.
struct RowPixels<'r, S, T, Q> {
    stepper: &'r mut S,
    spheres: &'r [SphereConsts],
    w: Vec3,
    background: Rgb888,
    i: u32,
    end: u32,
    j: u32,
    strategy: PhantomData<(T, Q)>,
}

impl<S: Stepper, T: HitTest, Q: SqrtFn> Iterator for RowPixels<'_, S, T, Q> {
    type Item = Sample;

    #[inline(always)]
    fn next(&mut self) -> Option<Sample> {
        if self.i >= self.end {
            return None;
        }
        let pixel = Point::new(self.i as i32, self.j as i32);
        self.i += 1;
        // Form the ray from the eye through the pixel centre.
        let d = self.stepper.next_direction();
        let a = d.dot(d);
        // Closest hit over all spheres, then Lab #1 shading with the view-space normal:
        // n·(−w) = ((L − t·d)·w)/r, camera-relative so |eye| does not cost precision.
        let (hit, color) = match closest::<T, Q>(self.spheres, d, a) {
            Some((index, t, s)) => {
                let n_z = (s.lw - t * d.dot(self.w)) * s.inv_r;
                (Some(Hit { index, t }), shade::lab1(s.color, n_z))
            }
            None => (None, self.background),
        };
        Some(Sample {
            pixel,
            direction: d,
            hit,
            color,
        })
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = (self.end - self.i) as usize;
        (n, Some(n))
    }
}

/// How the ray direction advances: a strategy type per [`Stepping`].
trait Stepper {
    fn new(camera: &Camera) -> Self;
    /// Prepare row `j`, starting at column `i0`. Rows come in increasing order.
    fn start_row(&mut self, j: u32, i0: u32);
    /// The current pixel's direction `p − eye`; advances one pixel.
    fn next_direction(&mut self) -> Vec3;
}

/// The slides verbatim: world-space pixel centres.
struct WorldSpaceStep {
    eye: Vec3,
    du: Vec3,
    dv: Vec3,
    scanline_start: Vec3,
    /// The row `scanline_start` belongs to.
    row: u32,
    pixel_center: Vec3,
}

impl Stepper for WorldSpaceStep {
    fn new(camera: &Camera) -> Self {
        Self {
            eye: camera.eye(),
            du: camera.pixel_step(),
            dv: camera.scanline_step(),
            scanline_start: camera.upper_left_world(),
            row: 0,
            pixel_center: camera.upper_left_world(),
        }
    }

    fn start_row(&mut self, j: u32, i0: u32) {
        // scanlineStart −= ph·v, once per scanline (also for clipped rows, so a clipped
        // render sees exactly the rounding of a full one).
        while self.row < j {
            self.scanline_start += self.dv;
            self.row += 1;
        }
        self.pixel_center = self.scanline_start;
        for _ in 0..i0 {
            self.pixel_center += self.du;
        }
    }

    #[inline(always)]
    fn next_direction(&mut self) -> Vec3 {
        let d = self.pixel_center - self.eye;
        self.pixel_center += self.du;
        d
    }
}

/// Camera-relative stepping with each row anchored directly.
struct IncrementalStep {
    first: Vec3,
    du: Vec3,
    dv: Vec3,
    d: Vec3,
}

impl Stepper for IncrementalStep {
    fn new(camera: &Camera) -> Self {
        Self {
            first: camera.first_direction(),
            du: camera.pixel_step(),
            dv: camera.scanline_step(),
            d: camera.first_direction(),
        }
    }

    fn start_row(&mut self, j: u32, i0: u32) {
        // Anchor the scanline exactly (per-row work), then step to the first visible
        // column the same way the pixel loop does.
        self.d = self.first + self.dv * j as f32;
        for _ in 0..i0 {
            self.d += self.du;
        }
    }

    #[inline(always)]
    fn next_direction(&mut self) -> Vec3 {
        let d = self.d;
        self.d += self.du;
        d
    }
}

/// Direct evaluation of every pixel's direction.
struct DirectStep {
    first: Vec3,
    du: Vec3,
    dv: Vec3,
    row: Vec3,
    i: u32,
}

impl Stepper for DirectStep {
    fn new(camera: &Camera) -> Self {
        Self {
            first: camera.first_direction(),
            du: camera.pixel_step(),
            dv: camera.scanline_step(),
            row: camera.first_direction(),
            i: 0,
        }
    }

    fn start_row(&mut self, j: u32, i0: u32) {
        self.row = self.first + self.dv * j as f32;
        self.i = i0;
    }

    #[inline(always)]
    fn next_direction(&mut self) -> Vec3 {
        let d = self.row + self.du * self.i as f32;
        self.i += 1;
        d
    }
}
