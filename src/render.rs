//! The public renderer, [`Render`]: an embedded-graphics [`Drawable`] that traces one
//! scanline at a time straight into the target.
//!
//! It sends one `fill_contiguous` per row, the colours produced by an iterator while the
//! driver consumes them: no framebuffer, no row buffer, no allocation.
//!
//! Drawing is the pipeline of the crate docs: the [`Method`] is matched once per frame
//! (`method/dispatch.rs`), the frame's constants are built (`trace/frame.rs`), and the
//! scanline loop (`trace/scanline.rs`) feeds the rows to a sink (`output/sink.rs`): the
//! target for [`Drawable::draw`], a callback for [`Render::trace`].

use core::marker::PhantomData;

use embedded_graphics::pixelcolor::{PixelColor, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use crate::camera::Camera;
use crate::error::{BandError, FrameError, IntegerError};
use crate::integer;
use crate::math::SqrtFn;
use crate::method::dispatch::{dispatch, Visit};
use crate::method::intersect::TestStrategy;
use crate::method::stepping::Stepper;
use crate::method::{Arithmetic, Method};
use crate::output::sink::{BandSink, DrawSink, TraceSink};
use crate::sampling::{AdaptiveRows, GridRows, Sampling, SpanAdaptiveRows};
use crate::scene::Scene;
use crate::trace::lab1;
use crate::trace::lit;
pub use crate::trace::options::{Options, Sample};
use crate::trace::rows::{CenterRows, Rows};
use crate::trace::scanline::RowSink;

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
pub struct Render<'a, const N: usize, C = Rgb888, const L: usize = 0, const P: usize = 0, const D: usize = 0>
{
    scene: &'a Scene<N, L, P, D>,
    camera: &'a Camera,
    method: Method,
    options: Options,
    sampling: Sampling,
    offset: Point,
    color: PhantomData<C>,
}

impl<'a, const N: usize, C, const L: usize, const P: usize, const D: usize> Render<'a, N, C, L, P, D> {
    /// The scene through the camera with the default method, at the target's origin.
    #[must_use]
    pub const fn new(scene: &'a Scene<N, L, P, D>, camera: &'a Camera) -> Self {
        Self {
            scene,
            camera,
            method: Method::TARGET_DEFAULT,
            options: Options::DEFAULT,
            sampling: Sampling::Center,
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
    /// a sub-rectangle of a larger display), clipped to the target.
    #[must_use]
    pub const fn with_offset(mut self, offset: Point) -> Self {
        self.offset = offset;
        self
    }

    /// The same render with other [`Options`] (span culling, anchor interval).
    #[must_use]
    pub const fn with_options(mut self, options: Options) -> Self {
        self.options = options;
        self
    }

    /// The same render with `sampling` rays per pixel (default [`Sampling::Center`]:
    /// one, through the centre).
    ///
    /// A grid of sub-pixel rays averaged in linear light, everywhere or only where an
    /// edge can cross the pixel. Matched once per frame; see [`Sampling`]. A field of the
    /// render, not of [`Options`], so that a render that never sets it links none of it,
    /// whatever its options.
    ///
    /// ```
    /// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::{Rgb565, Rgb888}, prelude::*};
    /// use embedded_raytracer::{Camera, Render, Sampling, Scene, Sphere, Vec3};
    ///
    /// static SCENE: Scene<1> = Scene::from_array(
    ///     [Sphere::new(Vec3::new(0.0, 0.0, 0.0), 1.0, Rgb888::new(255, 255, 255))],
    ///     Rgb888::new(0, 0, 0),
    /// );
    /// let camera = Camera::new(
    ///     Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0),
    ///     0.5, Size::new(16, 16),
    /// )?;
    /// let sampling: Sampling = "adaptive:4".parse()?;
    /// assert_eq!(sampling, Sampling::adaptive(4)?);
    /// let mut display = MockDisplay::<Rgb565>::new();
    /// Render::new(&SCENE, &camera).with_sampling(sampling).draw(&mut display)?;
    /// // Inside the disc the centre ray alone; on its rim a grey between white and black.
    /// assert_eq!(display.get_pixel(Point::new(8, 8)), Some(Rgb565::WHITE));
    /// let rim = (0..16).filter_map(|i| display.get_pixel(Point::new(i, 8)))
    ///     .filter(|c| *c != Rgb565::WHITE && *c != Rgb565::BLACK)
    ///     .count();
    /// assert!(rim >= 2, "{rim} grey pixels on row 8");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub const fn with_sampling(mut self, sampling: Sampling) -> Self {
        self.sampling = sampling;
        self
    }

    /// The sampling in use.
    #[must_use]
    pub const fn sampling(&self) -> Sampling {
        self.sampling
    }

    /// The options in use.
    #[must_use]
    pub const fn options(&self) -> Options {
        self.options
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
    /// hit, colour) to `f`.
    ///
    /// For tests, accuracy measurements and custom sinks. `f` is called through a
    /// `dyn FnMut`, so every caller of a scene type shares one copy of the loop
    /// rather than building all the methods again for each closure.
    pub fn trace(&self, mut f: impl FnMut(Sample)) {
        let full = Rectangle::new(Point::zero(), self.camera.size());
        let mut f: &mut dyn FnMut(Sample) = &mut f;
        let mut sink = TraceSink(&mut f);
        let _ = self.render(full, Point::zero(), &mut sink);
    }
}

impl<const N: usize, C: PixelColor + From<Rgb888>, const L: usize, const P: usize, const D: usize>
    Render<'_, N, C, L, P, D>
{
    /// Traces rows `rows` (`j0..j1`) of the image into `buf`, row-major, one image row
    /// (`width` pixels) after another.
    ///
    /// No `DrawTarget`, no allocation. The pixels are the whole render's, bit for bit,
    /// for every method (a pixel never depends on the band or clip it is drawn in), so
    /// firmware can hand one band to DMA while it traces the next. The render's offset
    /// does not apply (rows are the image's).
    ///
    /// ```
    /// use embedded_graphics::{pixelcolor::{Rgb565, Rgb888}, prelude::*};
    /// use embedded_raytracer::{Camera, Render, Scene, Sphere, Vec3};
    ///
    /// static SCENE: Scene<1> = Scene::from_array(
    ///     [Sphere::new(Vec3::new(0.0, 0.0, 0.0), 1.0, Rgb888::new(255, 0, 0))],
    ///     Rgb888::new(0, 0, 0),
    /// );
    /// let camera = Camera::new(
    ///     Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0),
    ///     0.5, Size::new(16, 16),
    /// )?;
    /// let render = Render::new(&SCENE, &camera);
    /// let mut band = [Rgb565::BLACK; 16 * 4]; // four rows
    /// render.draw_band(6..10, &mut band)?;
    /// assert_eq!(band[2 * 16 + 8], Rgb565::RED); // row 8, column 8: the sphere
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`BandError::Rows`] if `rows` is empty or reaches past the image's last row;
    /// [`BandError::BufferSize`] if `buf` does not hold exactly `width × (j1 − j0)`
    /// pixels; [`BandError::Frame`] where the frame cannot be drawn exactly (see
    /// [`Render::check`]). Nothing is traced then, and `buf` keeps what it held.
    // Inlined, as `draw` is: where the method and sampling are constants (the usual
    // `Render::new`), the one dispatch then links that method's code alone, not every
    // combination of the axes.
    #[inline]
    pub fn draw_band(&self, rows: core::ops::Range<u32>, buf: &mut [C]) -> Result<(), BandError> {
        let (band, mut sink) = self.band(rows, buf)?;
        let Ok(()) = self.render(band, Point::zero(), &mut sink);
        match sink.refused {
            None => Ok(()),
            Some(why) => Err(BandError::Frame(why)),
        }
    }

    /// [`Render::draw_band`] with the integer kernel alone, as [`Render::draw_integer`]
    /// draws a frame.
    ///
    /// The band's pixels are those of `draw_band` with [`Method::INTEGER`] wherever the
    /// kernel's per-frame rule takes the frame, and no `f32` render is linked. Where the
    /// rule does not take it, nothing is traced and `buf` keeps what it held.
    ///
    /// ```
    /// use embedded_graphics::{pixelcolor::{Rgb565, Rgb888}, prelude::*};
    /// use embedded_raytracer::{BandError, Camera, IntegerError, Render, Scene, Sphere, Vec3};
    ///
    /// static SCENE: Scene<1> = Scene::from_array(
    ///     [Sphere::new(Vec3::new(0.0, 0.0, 0.0), 1.0, Rgb888::new(255, 0, 0))],
    ///     Rgb888::new(0, 0, 0),
    /// );
    /// let camera = Camera::new(
    ///     Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0),
    ///     0.5, Size::new(16, 16),
    /// )?;
    /// let render = Render::new(&SCENE, &camera);
    /// let mut band = [Rgb565::BLUE; 16 * 4]; // four rows
    /// render.draw_band_integer(6..10, &mut band)?;
    /// assert_eq!(band[2 * 16 + 8], Rgb565::RED); // row 8, column 8: the sphere
    /// assert_eq!(band[0], Rgb565::BLACK); // row 6, column 0: the background
    ///
    /// // The band's own errors come back as the target's.
    /// assert_eq!(
    ///     render.draw_band_integer(6..10, &mut band[..16]),
    ///     Err(IntegerError::Target(BandError::BufferSize { expected: 64, found: 16 })),
    /// );
    /// // An eye inside the sphere: the rule does not take the frame, the band is untouched.
    /// let inside = Camera::new(Vec3::new(0.0, 0.0, 0.5), Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0),
    ///     0.5, Size::new(16, 16))?;
    /// let mut untouched = [Rgb565::BLUE; 16 * 4];
    /// assert_eq!(
    ///     Render::new(&SCENE, &inside).draw_band_integer(6..10, &mut untouched),
    ///     Err(IntegerError::Refused),
    /// );
    /// assert!(untouched.iter().all(|&p| p == Rgb565::BLUE));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`IntegerError::Refused`] as for [`Render::draw_integer`]; `draw_band`'s errors
    /// ([`BandError`]) as [`IntegerError::Target`]. Nothing is traced then.
    pub fn draw_band_integer(
        &self,
        rows: core::ops::Range<u32>,
        buf: &mut [C],
    ) -> Result<(), IntegerError<BandError>> {
        let (band, mut sink) = self.band(rows, buf).map_err(IntegerError::Target)?;
        match self.integer_only(band, Point::zero(), &mut sink) {
            Ok(()) => Ok(()),
            Err(IntegerError::Refused) => Err(IntegerError::Refused),
            Err(IntegerError::Target(never)) => match never {},
        }
    }

    /// `rows` of the image as a clip (every column, image coordinates) and the sink
    /// that writes them into `buf`, or why they cannot be drawn.
    pub(crate) fn band<'b>(
        &self,
        rows: core::ops::Range<u32>,
        buf: &'b mut [C],
    ) -> Result<(Rectangle, BandSink<'b, C>), BandError> {
        let size = self.camera.size();
        if !(rows.start < rows.end && rows.end <= size.height) {
            return Err(BandError::Rows {
                start: rows.start,
                end: rows.end,
                height: size.height,
            });
        }
        let expected = size.width as usize * (rows.end - rows.start) as usize;
        if buf.len() != expected {
            return Err(BandError::BufferSize {
                expected,
                found: buf.len(),
            });
        }
        let band = Rectangle::new(
            Point::new(0, rows.start as i32),
            Size::new(size.width, rows.end - rows.start),
        );
        let sink = BandSink {
            buf,
            width: size.width,
            j0: rows.start,
            refused: None,
        };
        Ok((band, sink))
    }

    /// Draws the frame with the integer kernel alone, whatever the render's method, or
    /// nothing where the kernel's per-frame rule does not take it.
    ///
    /// Where the rule does not take the frame (see [`Arithmetic::Integer`]; as
    /// [`Render::arithmetic`] would answer `F32`) it returns [`IntegerError::Refused`].
    /// The pixels are those of [`Drawable::draw`] with [`Method::INTEGER`] wherever the
    /// rule holds.
    ///
    /// For firmware on a chip without an FPU that must stay small: no `f32` render is
    /// linked (`draw` with `Method::INTEGER` links the `f32` method as its fallback), so
    /// no soft-float routine is reachable from any pixel loop; the per-frame set-up (the
    /// camera, the rule, the silhouettes) still computes in floating point, once a frame.
    ///
    /// ```
    /// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::{Rgb565, Rgb888}, prelude::*};
    /// use embedded_raytracer::{Camera, IntegerError, Render, Scene, Sphere, Vec3};
    ///
    /// static SCENE: Scene<1> = Scene::from_array(
    ///     [Sphere::new(Vec3::new(0.0, 0.0, 0.0), 1.0, Rgb888::new(255, 0, 0))],
    ///     Rgb888::new(0, 0, 0),
    /// );
    /// let camera = Camera::new(
    ///     Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0),
    ///     0.5, Size::new(16, 16),
    /// )?;
    /// let mut display = MockDisplay::<Rgb565>::new();
    /// Render::new(&SCENE, &camera).draw_integer(&mut display)?;
    /// assert_eq!(display.get_pixel(Point::new(8, 8)), Some(Rgb565::RED));
    ///
    /// // An eye inside the sphere: the rule does not take the frame, nothing is drawn.
    /// let inside = Camera::new(Vec3::new(0.0, 0.0, 0.5), Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0),
    ///     0.5, Size::new(16, 16))?;
    /// let mut untouched = MockDisplay::<Rgb565>::new();
    /// assert_eq!(Render::new(&SCENE, &inside).draw_integer(&mut untouched), Err(IntegerError::Refused));
    /// assert_eq!(untouched.get_pixel(Point::new(8, 8)), None);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`IntegerError::Refused`] as above (also for a scene with lights, planes or
    /// mirrors, and for a sampling other than [`Sampling::Center`]); the target's own
    /// error as [`IntegerError::Target`].
    pub fn draw_integer<Tg>(&self, target: &mut Tg) -> Result<(), IntegerError<Tg::Error>>
    where
        Tg: DrawTarget<Color = C>,
    {
        let clip = target.bounding_box();
        let mut sink = DrawSink {
            target,
            color: PhantomData,
        };
        self.integer_only(clip, self.offset, &mut sink)
    }

    /// The integer kernel alone on the part of the image at `offset` that `clip`
    /// shows, or `Refused` with nothing drawn.
    fn integer_only<K: RowSink>(
        &self,
        clip: Rectangle,
        offset: Point,
        sink: &mut K,
    ) -> Result<(), IntegerError<K::Error>> {
        if !self.integer_kind() {
            return Err(IntegerError::Refused);
        }
        match integer::render::<N, _, _>(
            self.scene.spheres(),
            self.scene.background(),
            self.camera,
            self.options,
            core::iter::once(clip),
            offset,
            sink,
        ) {
            Some(done) => done.map_err(IntegerError::Target),
            None => Err(IntegerError::Refused),
        }
    }
}

impl<const N: usize, C, const L: usize, const P: usize, const D: usize> Drawable for Render<'_, N, C, L, P, D>
where
    C: PixelColor + From<Rgb888>,
{
    type Color = C;
    type Output = ();

    #[inline]
    fn draw<Tg>(&self, target: &mut Tg) -> Result<(), Tg::Error>
    where
        Tg: DrawTarget<Color = C>,
    {
        let clip = target.bounding_box();
        let mut sink = DrawSink {
            target,
            color: PhantomData,
        };
        self.render(clip, self.offset, &mut sink)
    }
}

impl<const N: usize, C, const L: usize, const P: usize, const D: usize> Render<'_, N, C, L, P, D> {
    /// The arithmetic a whole-image frame of this render uses.
    ///
    /// It is the integer kernel where the method asks for it, the sampling is
    /// [`Sampling::Center`] (sub-pixel rays are traced in `f32`) and its per-frame rule
    /// admits the scene and camera (see [`Arithmetic::Integer`]), `F32` otherwise.
    #[must_use]
    pub fn arithmetic(&self) -> Arithmetic {
        let full = Rectangle::new(Point::zero(), self.camera.size());
        // The draw's own decision (`IntFrame::new`: the rule, then something visible),
        // without the silhouettes the rule does not depend on.
        let integer = self.method.arithmetic == Arithmetic::Integer
            && self.integer_kind()
            && integer::regions::<N>(
                self.scene.spheres(),
                self.camera,
                self.options,
                |_| false,
                |_, _| {},
            )
            .is_some()
            && crate::trace::frame::visible(self.camera.size(), Point::zero(), full).is_some();
        if integer {
            Arithmetic::Integer
        } else {
            Arithmetic::F32
        }
    }

    /// Whether the frame can be drawn exactly, decided as a draw decides it.
    ///
    /// The decision is made once per frame, from the scene, camera, method, options and
    /// sampling; no pixel is traced. `Err` where [`Drawable::draw`] would leave the
    /// target as it was and [`Render::draw_band`] return [`BandError::Frame`], rather
    /// than draw a wrong picture — objects whose sizes no one `f32` frame can hold (see
    /// [`FrameError`]).
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::Rgb888;
    /// use embedded_raytracer::{Camera, FrameError, Light, ObjectRef, Render, Scene, Sphere, Vec3};
    ///
    /// let camera = Camera::new(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), 1.0,
    ///     embedded_graphics::geometry::Size::new(16, 16))?;
    /// let mut scene: Scene<1, 1> = Scene::new(Rgb888::new(0, 0, 0));
    /// scene.push(Sphere::new(Vec3::ZERO, 1.0, Rgb888::new(255, 0, 0)))?;
    /// assert_eq!(Render::<_, Rgb888, 1>::new(&scene, &camera).check(), Ok(()));
    /// // A lamp 10³⁰ away: the sphere's squares would be subnormal in any frame that holds it.
    /// scene.push_light(Light::point(Vec3::new(1e30, 1e30, 1e30), 1.0))?;
    /// assert_eq!(
    ///     Render::<_, Rgb888, 1>::new(&scene, &camera).check(),
    ///     Err(FrameError::Magnitudes { far: ObjectRef::Light(0), near: ObjectRef::Sphere(0) }),
    /// );
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// The frame's [`FrameError`].
    pub fn check(&self) -> Result<(), FrameError> {
        if self.arithmetic() == Arithmetic::Integer {
            return Ok(());
        }
        dispatch(self.method, Check(self))
    }

    /// The scene drawn.
    pub(crate) const fn scene(&self) -> &Scene<N, L, P, D> {
        self.scene
    }

    /// The camera it is seen through.
    pub(crate) const fn camera(&self) -> &Camera {
        self.camera
    }

    /// Where the image's upper-left pixel sits on the target.
    pub(crate) const fn offset(&self) -> Point {
        self.offset
    }

    /// Whether the integer kernel can draw this kind of render at all: a scene without
    /// lights, planes or mirrors, one ray a pixel (its rule then decides per frame).
    fn integer_kind(&self) -> bool {
        !Scene::<N, L, P, D>::FEATURES && self.sampling == Sampling::Center
    }

    /// The frame through the one dispatch: the part of the image at `offset` that
    /// `clip` shows, into `sink`.
    #[inline(always)]
    pub(crate) fn render<K: RowSink>(
        &self,
        clip: Rectangle,
        offset: Point,
        sink: &mut K,
    ) -> Result<(), K::Error> {
        self.render_clips(core::iter::once(clip), offset, sink)
    }

    /// [`Self::render`] for each of `clips` in turn, as one frame.
    ///
    /// The frame's per-frame work (scale, silhouettes, shadow regions, ties, the integer
    /// kernel's rule and quantisation) is done once for all of them, except with adaptive
    /// sampling (whose rows hold their clip: a frame each). Each clip's pixels are those
    /// of its own render.
    #[inline(always)]
    pub(crate) fn render_clips<K: RowSink, I: Iterator<Item = Rectangle> + Clone>(
        &self,
        clips: I,
        offset: Point,
        sink: &mut K,
    ) -> Result<(), K::Error> {
        self.render_clips_as(clips, offset, sink, self.method.arithmetic == Arithmetic::Integer)
    }

    /// [`Self::render_clips`] by the `f32` method alone: an integer render's frame where
    /// its kernel's rule is known to refuse it (the integer kernel's code is then not
    /// linked for the caller).
    #[inline(always)]
    pub(crate) fn render_clips_f32<K: RowSink, I: Iterator<Item = Rectangle> + Clone>(
        &self,
        clips: I,
        offset: Point,
        sink: &mut K,
    ) -> Result<(), K::Error> {
        self.render_clips_as(clips, offset, sink, false)
    }

    #[inline(always)]
    fn render_clips_as<K: RowSink, I: Iterator<Item = Rectangle> + Clone>(
        &self,
        clips: I,
        offset: Point,
        sink: &mut K,
        integer: bool,
    ) -> Result<(), K::Error> {
        dispatch(
            self.method,
            Frame {
                scene: self.scene,
                camera: self.camera,
                options: self.options,
                sampling: self.sampling,
                clips,
                offset,
                sink,
                integer,
            },
        )
    }
}

/// [`Render::check`], as a visitor of the method's strategy types: the frame's scale
/// as the render would decide it.
struct Check<'r, 'a, const N: usize, C, const L: usize, const P: usize, const D: usize>(
    &'r Render<'a, N, C, L, P, D>,
);

impl<const N: usize, C, const L: usize, const P: usize, const D: usize> Visit
    for Check<'_, '_, N, C, L, P, D>
{
    type Output = Result<(), FrameError>;
    fn visit<S: Stepper, T: TestStrategy, Q: SqrtFn>(self) -> Self::Output {
        let r = self.0;
        // Only a Lab #1 frame of one ray a pixel culls for its scale (as `lab1.rs` does).
        let cull = !Scene::<N, L, P, D>::FEATURES && r.sampling == Sampling::Center;
        crate::trace::frame::frame_scale::<N, L, P, D>(r.scene, r.camera, S::error_bound(r.camera), cull)
            .map(|_| ())
    }
}

/// Rendering one frame, as a visitor of the method's strategy types: the part of the
/// image each of `clips` shows (one clip for a whole or clipped draw).
struct Frame<'a, 'k, const N: usize, const L: usize, const P: usize, const D: usize, K, I> {
    scene: &'a Scene<N, L, P, D>,
    camera: &'a Camera,
    options: Options,
    sampling: Sampling,
    clips: I,
    offset: Point,
    sink: &'k mut K,
    /// The integer kernel was asked for (Lab #1 scenes only).
    integer: bool,
}

impl<const N: usize, const L: usize, const P: usize, const D: usize, K, I> Visit
    for Frame<'_, '_, N, L, P, D, K, I>
where
    K: RowSink,
    I: Iterator<Item = Rectangle> + Clone,
{
    type Output = Result<(), K::Error>;
    #[inline(always)]
    fn visit<S: Stepper, T: TestStrategy, Q: SqrtFn>(self) -> Self::Output {
        // The sampling, once per frame: `Center` is the one-ray row loop.
        match self.sampling {
            Sampling::Center => self.with_rows::<S, T, Q, _>(CenterRows),
            Sampling::Grid(n) => self.with_rows::<S, T, Q, _>(GridRows(n.get())),
            // A Lab #1 scene's colours jump only at silhouettes: its edge pixels come
            // from them; a scene with features shares samples between neighbours.
            // Adaptive rows hold their clip: one frame per clip.
            Sampling::Adaptive(n) => {
                for clip in self.clips.clone() {
                    let one = Frame {
                        scene: self.scene,
                        camera: self.camera,
                        options: self.options,
                        sampling: self.sampling,
                        clips: core::iter::once(clip),
                        offset: self.offset,
                        sink: &mut *self.sink,
                        integer: self.integer,
                    };
                    if Scene::<N, L, P, D>::FEATURES {
                        one.with_rows::<S, T, Q, _>(AdaptiveRows { n: n.get(), clip })?;
                    } else {
                        one.with_rows::<S, T, Q, _>(SpanAdaptiveRows { n: n.get(), clip })?;
                    }
                }
                Ok(())
            }
        }
    }
}

impl<const N: usize, const L: usize, const P: usize, const D: usize, K, I> Frame<'_, '_, N, L, P, D, K, I>
where
    K: RowSink,
    I: Iterator<Item = Rectangle> + Clone,
{
    #[inline(always)]
    fn with_rows<S: Stepper, T: TestStrategy, Q: SqrtFn, G: Rows>(self, rows: G) -> Result<(), K::Error> {
        // The scene's type decides the loop at compile time: Lab #1 on spheres, or the
        // scene-features path (lights, planes, mirrors); each does its per-frame work
        // once for every clip.
        if Scene::<N, L, P, D>::FEATURES {
            lit::render::<N, L, P, D, K, S, T, Q, G, I>(
                self.scene,
                self.camera,
                self.options,
                (self.clips, rows),
                self.offset,
                self.sink,
            )
        } else if self.integer && G::CENTER {
            // The arithmetic, once per frame: the integer kernel where its rule takes the
            // frame, else this f32 method (both out of line, so their stacks never add).
            // Sub-pixel rays are the f32 method's.
            integer::render_or_f32::<N, L, P, D, K, S, T, Q, I>(
                self.scene,
                self.camera,
                self.options,
                self.clips,
                self.offset,
                self.sink,
            )
        } else {
            lab1::render::<N, L, P, D, K, S, T, Q, G, I>(
                self.scene,
                self.camera,
                self.options,
                (self.clips, rows),
                self.offset,
                self.sink,
            )
        }
    }
}
