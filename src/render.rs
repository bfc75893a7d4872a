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
use crate::scene::{Hit, Scene};
use crate::shade;
use crate::span::{Margin, Silhouette};
use crate::sphere::{
    Algebraic, Auto, ForwardDiff, Geometric, Robust, RowTest, SphereConsts, FD_ANCHOR_INTERVAL,
};
use crate::vec3::Vec3;

/// How the ray direction `p − eye` advances from pixel to pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Stepping {
    /// The slides verbatim: the pixel centre `p` is stepped in world space
    /// (`p += pw·u`, `scanlineStart −= ph·v`) and the ray is `p − eye`. Drifts: each add
    /// rounds relative to `|p| ≈ |eye|`, so far from the origin whole pixels are lost
    /// across a wide image (measured by the accuracy lab: ≥ 1 px at 1920 wide from
    /// `|eye|` = 100, at 4096 wide from `|eye|` = 10; 52.9 px on `scenes/drift.toml`).
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
    /// The robust test's discriminant `a·r² − |L × d|²` and `b = L·d` forward-differenced
    /// along each scanline (three additions per sphere and pixel), re-anchored by direct
    /// evaluation at each span start and every [`FD_ANCHOR_INTERVAL`]
    /// columns. Error bound: a silhouette edge moves by at most `2⁻²⁴·K·(R + 2K)` pixels
    /// (`R` the sphere's radius on screen in pixels, `K` the anchor interval), on top of
    /// the robust test's own error. A single-ray query ([`Sphere::intersect`](crate::Sphere::intersect))
    /// is an anchor, i.e. evaluated directly.
    ForwardDiff,
    /// Adaptive: per sphere and frame, `ForwardDiff` where its error bound moves an edge
    /// by at most 1/16 pixel (`2⁻²⁴·K·(R + 2K) ≤ 1/16`, the eye outside the sphere),
    /// `Robust` otherwise. The slides' algebraic and geometric tests are never chosen:
    /// they are dearer per pixel than forward differences and fail from
    /// distance/radius ≈ 100. Single-ray queries behave as `ForwardDiff`.
    Auto,
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
/// The default is `Direct` + `Auto` + `Exact`, chosen from the speed/accuracy chart
/// (`docs/speed_vs_accuracy.md`): direct evaluation of each direction has no
/// accumulated rounding (zero coverage errors against the f64 reference on every
/// standard scene, where incremental stepping loses 14 edge pixels on the 1920-wide
/// `drift` scene) and, with span culling, costs its three multiplies only where a
/// sphere can be hit; `Auto` takes the forward-differenced test where its error bound
/// allows (every sphere of the standard scenes), which is on the Pareto front; the
/// exact root keeps shading within one level of the reference.
///
/// ```
/// use embedded_raytracer::{Method, SphereTest, Stepping, Sqrt};
/// let m = Method::default();
/// assert_eq!((m.stepping, m.sphere_test, m.sqrt), (Stepping::Direct, SphereTest::Auto, Sqrt::Exact));
/// assert_eq!("world-space".parse::<Stepping>(), Ok(Stepping::WorldSpace));
/// assert_eq!("forward-diff".parse::<SphereTest>(), Ok(SphereTest::ForwardDiff));
/// assert_eq!(m.to_string(), "direct/auto/exact");
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
    pub const DEFAULT: Method = Method::new(Stepping::Direct, SphereTest::Auto, Sqrt::Exact);

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
    pub const ALL: [Method; 30] = {
        let steppings = [Stepping::WorldSpace, Stepping::Incremental, Stepping::Direct];
        let tests = [
            SphereTest::Algebraic,
            SphereTest::Geometric,
            SphereTest::Robust,
            SphereTest::ForwardDiff,
            SphereTest::Auto,
        ];
        let sqrts = [Sqrt::Exact, Sqrt::Fast];
        let mut all = [Method::DEFAULT; 30];
        let mut k = 0;
        while k < 30 {
            all[k] = Method::new(steppings[k / 10], tests[(k / 2) % 5], sqrts[k % 2]);
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
named_enum!(SphereTest, "sphere test", Algebraic => "algebraic", Geometric => "geometric", Robust => "robust", ForwardDiff => "forward-diff", Auto => "auto");
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
    options: Options,
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
            options: Options::DEFAULT,
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

    /// The same render with span culling on (the default) or off. Off, every sphere is
    /// tested at every pixel — the seed's algorithm taken literally, for the benchmark
    /// baseline and the tests that prove culling changes no pixel.
    #[doc(hidden)]
    #[must_use]
    pub const fn with_span_culling(mut self, on: bool) -> Self {
        self.options.culling = on;
        self
    }

    /// The same render with another anchor interval K for the forward-differenced
    /// test (default [`FD_ANCHOR_INTERVAL`]; `0` is taken as 1). For the measurement
    /// of the error against K.
    #[doc(hidden)]
    #[must_use]
    pub const fn with_anchor_interval(mut self, k: u32) -> Self {
        self.options.anchor = if k == 0 { 1 } else { k };
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
            self.options,
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

    #[inline]
    fn draw<D>(&self, target: &mut D) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        let clip = target.bounding_box();
        let mut sink = DrawSink {
            target,
            color: PhantomData,
        };
        dispatch(
            self.scene,
            self.camera,
            self.method,
            self.options,
            clip,
            self.offset,
            &mut sink,
        )
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
        // Convert colours through a one-entry cache: runs of background (and of a flat
        // shade) cost a 3-byte compare instead of a conversion per pixel.
        let mut last: Option<(Rgb888, C)> = None;
        self.target.fill_contiguous(
            &area,
            pixels.map(move |s| match last {
                Some((rgb, c)) if rgb == s.color => c,
                _ => {
                    let c = C::from(s.color);
                    last = Some((s.color, c));
                    c
                }
            }),
        )
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

/// Per-frame render options besides the method (culling, anchor interval).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Options {
    culling: bool,
    anchor: u32,
}

impl Options {
    const DEFAULT: Options = Options {
        culling: true,
        anchor: FD_ANCHOR_INTERVAL,
    };
}

/// The once-per-frame `match` on the method, down to a monomorphised frame loop.
///
/// Inlined into `draw`, so that firmware whose method is a constant (the usual case:
/// `Render::new` or `with_method(CONST)`) links only that method's loop; without it the
/// `match` keeps every monomorphised loop alive (83 KB of `.text` instead of 20 KB,
/// measured on `examples/no_panic.rs`).
#[inline(always)]
fn dispatch<const N: usize, K: RowSink>(
    scene: &Scene<N>,
    camera: &Camera,
    method: Method,
    options: Options,
    clip: Rectangle,
    offset: Point,
    sink: &mut K,
) -> Result<(), K::Error> {
    #[inline(always)]
    fn with_test<const N: usize, K: RowSink, S: Stepper>(
        f: &mut Frame<'_, N>,
        method: Method,
        sink: &mut K,
    ) -> Result<(), K::Error> {
        match method.sphere_test {
            SphereTest::Algebraic => with_sqrt::<N, K, S, Algebraic>(f, method, sink),
            SphereTest::Geometric => with_sqrt::<N, K, S, Geometric>(f, method, sink),
            SphereTest::Robust => with_sqrt::<N, K, S, Robust>(f, method, sink),
            SphereTest::ForwardDiff => with_sqrt::<N, K, S, ForwardDiff>(f, method, sink),
            SphereTest::Auto => with_sqrt::<N, K, S, Auto>(f, method, sink),
        }
    }
    #[inline(always)]
    fn with_sqrt<const N: usize, K: RowSink, S: Stepper, T: RowTest>(
        f: &mut Frame<'_, N>,
        method: Method,
        sink: &mut K,
    ) -> Result<(), K::Error> {
        match method.sqrt {
            Sqrt::Exact => f.run::<K, S, T, ExactSqrt>(sink),
            Sqrt::Fast => f.run::<K, S, T, FastSqrt>(sink),
        }
    }

    // The per-frame sphere data lives here, in the caller, and the frame borrows it:
    // built in place once, never moved (a by-value `Frame` holding the `Vec` was copied
    // on return, doubling the render's stack).
    let mut spheres = Vec::new();
    let Some(mut frame) = Frame::new(scene, camera, method, options, clip, offset, &mut spheres) else {
        return Ok(()); // nothing visible
    };
    match method.stepping {
        Stepping::WorldSpace => with_test::<N, K, WorldSpaceStep>(&mut frame, method, sink),
        Stepping::Incremental => with_test::<N, K, IncrementalStep>(&mut frame, method, sink),
        Stepping::Direct => with_test::<N, K, DirectStep>(&mut frame, method, sink),
    }
}

/// A sphere as the frame sees it: its per-frame constants and its silhouette.
struct FrameSphere {
    consts: SphereConsts,
    silhouette: Silhouette,
}

/// Per-frame state: the visible part of the image and each sphere's constants.
struct Frame<'a, const N: usize> {
    camera: &'a Camera,
    spheres: &'a [FrameSphere],
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
    fn new(
        scene: &Scene<N>,
        camera: &'a Camera,
        method: Method,
        options: Options,
        clip: Rectangle,
        offset: Point,
        spheres: &'a mut Vec<FrameSphere, N>,
    ) -> Option<Self> {
        let size = camera.size();
        // Clip in i64: no overflow for any offset or target size.
        let span = |origin: i32, len: u32, clip_origin: i32, clip_len: u32| {
            let lo = i64::from(origin).max(i64::from(clip_origin));
            let hi = (i64::from(origin) + i64::from(len)).min(i64::from(clip_origin) + i64::from(clip_len));
            (lo < hi).then(|| ((lo - i64::from(origin)) as u32, (hi - i64::from(origin)) as u32))
        };
        let (i0, i1) = span(offset.x, size.width, clip.top_left.x, clip.size.width)?;
        let (j0, j1) = span(offset.y, size.height, clip.top_left.y, clip.size.height)?;
        // How far the stepping's directions can be from the ideal ones (widens the spans).
        let step_err = match method.stepping {
            Stepping::WorldSpace => WorldSpaceStep::error_bound(camera),
            Stepping::Incremental => IncrementalStep::error_bound(camera),
            Stepping::Direct => DirectStep::error_bound(camera),
        };
        // Per-sphere constants and silhouettes, once per frame.
        let eye = camera.eye();
        let w = camera.w();
        let margin = match method.sphere_test {
            SphereTest::Algebraic | SphereTest::Geometric => Margin::Quadratic,
            SphereTest::Robust | SphereTest::ForwardDiff | SphereTest::Auto => Margin::Linear,
        };
        // A push loop, not `collect()`: heapless' `FromIterator` panics on overflow, and
        // the optimiser cannot see that a `Scene<N>` never holds more than N spheres.
        spheres.clear();
        for s in scene.spheres() {
            let consts = SphereConsts::new(s, eye, w).with_row_step(
                camera.pixel_step(),
                options.anchor,
                camera.pixel_width(),
            );
            let silhouette = if options.culling {
                Silhouette::new(consts.l, s.radius, camera, margin, step_err)
            } else {
                Silhouette::All
            };
            // Never fails: the scene holds at most N spheres.
            let _ = spheres.push(FrameSphere { consts, silhouette });
        }
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

    /// The frame loop for one method: per row, set up the stepper, cut every sphere's
    /// silhouette with the scanline (the row's active spheres, in scene order), and hand
    /// the row's pixel iterator to the sink.
    fn run<K: RowSink, S: Stepper, T: RowTest, Q: SqrtFn>(&mut self, sink: &mut K) -> Result<(), K::Error> {
        let mut stepper = S::new(self.camera);
        let width = self.i1 - self.i0;
        let mut active: Vec<Active<'_, T::State>, N> = Vec::new();
        for j in self.j0..self.j1 {
            let row_step = stepper.start_row(j, self.i0);
            // Per row: the spheres whose span meets this row, and the union of the spans.
            active.clear();
            let (mut lo_all, mut hi_all) = (self.i1, self.i0);
            for (index, fs) in self.spheres.iter().enumerate() {
                if let Some((lo, hi)) = fs.silhouette.row_span(j, self.i0, self.i1) {
                    lo_all = lo_all.min(lo);
                    hi_all = hi_all.max(hi);
                    // Cannot fail: at most N spheres.
                    let _ = active.push(Active {
                        index,
                        lo,
                        hi,
                        consts: &fs.consts,
                        state: T::row_start(lo),
                    });
                }
            }
            // Visible rows and columns fit in the target's i32 coordinates.
            let area = Rectangle::new(
                Point::new(
                    self.offset.x.wrapping_add(self.i0 as i32),
                    self.offset.y.wrapping_add(j as i32),
                ),
                Size::new(width, 1),
            );
            let row = RowPixels::<S, T, Q> {
                stepper: row_step,
                active: &mut active,
                lo_all,
                hi_all,
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

/// A sphere whose span meets the current row.
struct Active<'s, St> {
    /// Index in the scene.
    index: usize,
    /// Columns `[lo, hi)` whose rays can hit it.
    lo: u32,
    hi: u32,
    consts: &'s SphereConsts,
    /// The test's per-row state (forward differences).
    state: St,
}

/// The pixels of one scanline, traced as the sink pulls them.
struct RowPixels<'r, 's, S: Stepper, T: RowTest, Q> {
    stepper: S::Row,
    active: &'r mut [Active<'s, T::State>],
    /// Union of the active spans: outside it a pixel is background without a test.
    lo_all: u32,
    hi_all: u32,
    w: Vec3,
    background: Rgb888,
    i: u32,
    end: u32,
    j: u32,
    strategy: PhantomData<(T, Q)>,
}

impl<S: Stepper, T: RowTest, Q: SqrtFn> Iterator for RowPixels<'_, '_, S, T, Q> {
    type Item = Sample;

    #[inline(always)]
    fn next(&mut self) -> Option<Sample> {
        let i = self.i;
        if i >= self.end {
            return None;
        }
        let pixel = Point::new(i as i32, self.j as i32);
        self.i += 1;
        // Form the ray from the eye through the pixel centre.
        let d = self.stepper.next_direction();
        let mut best: Option<(usize, f32, &SphereConsts)> = None;
        if i >= self.lo_all && i < self.hi_all {
            let a = d.dot(d);
            // Closest hit over the spheres whose span holds this column, in scene order;
            // each test gets the nearest t so far as its t_max.
            let mut t_max = f32::INFINITY;
            for act in self.active.iter_mut() {
                if i >= act.lo && i < act.hi {
                    if let Some(t) = T::hit::<Q>(&mut act.state, act.consts, d, a, i, t_max) {
                        t_max = t;
                        best = Some((act.index, t, act.consts));
                    }
                }
            }
        }
        // Lab #1 shading with the view-space normal:
        // n·(−w) = ((L − t·d)·w)/r, camera-relative so |eye| does not cost precision.
        let (hit, color) = match best {
            Some((index, t, s)) => {
                let n_z = (s.lw - t * d.dot(self.w)) * s.inv_r;
                (Some(Hit { index, t }), shade::lab1_channels(s.rgb, n_z))
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

/// How the ray direction advances: a strategy type per [`Stepping`]. The frame-level
/// stepper hands out a small per-row stepper by value, so the pixel loop keeps it in
/// registers.
trait Stepper {
    /// The per-row stepper.
    type Row: RowStep;
    fn new(camera: &Camera) -> Self;
    /// A bound `E` on `|d − (F + i·du + j·dv)|` (exact arithmetic on the camera's f32
    /// `F`, `du`, `dv`) over the whole image, for span culling's margin. Each f32
    /// addition or product rounds by at most 2⁻²⁴ of its result's norm.
    fn error_bound(camera: &Camera) -> f32;
    /// Prepare row `j`, starting at column `i0`. Rows come in increasing order.
    fn start_row(&mut self, j: u32, i0: u32) -> Self::Row;
}

/// A row's direction stepper.
trait RowStep {
    /// The current pixel's direction `p − eye`; advances one pixel.
    fn next_direction(&mut self) -> Vec3;
}

/// `(|F| + H·|dv| + W·|du|, W, H)`: the largest ideal direction and the image size.
fn extent(camera: &Camera) -> (f32, f32, f32) {
    let size = camera.size();
    let (w, h) = (size.width as f32, size.height as f32);
    let s = camera.first_direction().length()
        + h * camera.scanline_step().length()
        + w * camera.pixel_step().length();
    (s, w, h)
}

/// 2⁻²³: twice the unit roundoff, a safety factor of 2 on every count below.
const ROUNDING: f32 = 1.0 / 8_388_608.0;

/// The slides verbatim: world-space pixel centres.
struct WorldSpaceStep {
    eye: Vec3,
    du: Vec3,
    dv: Vec3,
    scanline_start: Vec3,
    /// The row `scanline_start` belongs to.
    row: u32,
}

/// A world-space row: the pixel centre, stepped by `du`.
struct WorldSpaceRow {
    eye: Vec3,
    du: Vec3,
    pixel_center: Vec3,
}

impl Stepper for WorldSpaceStep {
    type Row = WorldSpaceRow;

    fn error_bound(camera: &Camera) -> f32 {
        // `upper_left_world` (≤ 6 roundings of size |eye| + S), j additions of dv and
        // i additions of du (each ≤ 2⁻²⁴·|p|, |p| ≤ |eye| + S), and `p − eye`.
        let (s, w, h) = extent(camera);
        ROUNDING * (w + h + 8.0) * (camera.eye().length() + s)
    }

    fn new(camera: &Camera) -> Self {
        Self {
            eye: camera.eye(),
            du: camera.pixel_step(),
            dv: camera.scanline_step(),
            scanline_start: camera.upper_left_world(),
            row: 0,
        }
    }

    fn start_row(&mut self, j: u32, i0: u32) -> WorldSpaceRow {
        // scanlineStart −= ph·v, once per scanline (also for clipped rows, so a clipped
        // render sees exactly the rounding of a full one).
        while self.row < j {
            self.scanline_start += self.dv;
            self.row += 1;
        }
        let mut pixel_center = self.scanline_start;
        for _ in 0..i0 {
            pixel_center += self.du;
        }
        WorldSpaceRow {
            eye: self.eye,
            du: self.du,
            pixel_center,
        }
    }
}

impl RowStep for WorldSpaceRow {
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
}

/// An incremental row: the direction, stepped by `du`.
struct IncrementalRow {
    du: Vec3,
    d: Vec3,
}

impl Stepper for IncrementalStep {
    type Row = IncrementalRow;

    fn error_bound(camera: &Camera) -> f32 {
        // The row anchor `F + dv·j` (2 roundings) and i additions of du (≤ 2⁻²⁴·S each).
        let (s, w, _) = extent(camera);
        ROUNDING * (w + 4.0) * s
    }

    fn new(camera: &Camera) -> Self {
        Self {
            first: camera.first_direction(),
            du: camera.pixel_step(),
            dv: camera.scanline_step(),
        }
    }

    fn start_row(&mut self, j: u32, i0: u32) -> IncrementalRow {
        // Anchor the scanline exactly (per-row work), then step to the first visible
        // column the same way the pixel loop does.
        let mut d = self.first + self.dv * j as f32;
        for _ in 0..i0 {
            d += self.du;
        }
        IncrementalRow { du: self.du, d }
    }
}

impl RowStep for IncrementalRow {
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
}

/// A direct row: the row's first direction and the column.
struct DirectRow {
    row: Vec3,
    du: Vec3,
    i: u32,
}

impl Stepper for DirectStep {
    type Row = DirectRow;

    fn error_bound(camera: &Camera) -> f32 {
        // `F + dv·j` and `+ du·i`: four roundings of size ≤ S.
        let (s, _, _) = extent(camera);
        ROUNDING * 8.0 * s
    }

    fn new(camera: &Camera) -> Self {
        Self {
            first: camera.first_direction(),
            du: camera.pixel_step(),
            dv: camera.scanline_step(),
        }
    }

    fn start_row(&mut self, j: u32, i0: u32) -> DirectRow {
        DirectRow {
            row: self.first + self.dv * j as f32,
            du: self.du,
            i: i0,
        }
    }
}

impl RowStep for DirectRow {
    #[inline(always)]
    fn next_direction(&mut self) -> Vec3 {
        let d = self.row + self.du * self.i as f32;
        self.i += 1;
        d
    }
}
