//! Frames that re-trace and re-send only what changed: [`Incremental`] remembers what the
//! display shows (the scene, camera and render settings of the last frame drawn, never
//! its pixels) and draws the next frame by tracing only the pixels that can differ from
//! it and sending only those — the display then shows the next frame's full render, bit
//! for bit.
//!
//! ## The rule: which pixels can differ
//!
//! A pixel is a function of the scene, the camera, the method and the pixel alone, and
//! never of the clip it is drawn in; and a sphere takes part in a pixel only inside its
//! silhouette, the ellipse the frame culls with (enlarged by the test's and the
//! stepping's proven margins: outside it the kernel never tests that sphere). So:
//!
//! 1. **Frame-wide state** equal in both frames, else the whole frame is drawn: the
//!    camera, the method, sampling, options and offset, the target's bounding box, the
//!    background and settings, every light and plane, the number of spheres, the
//!    frame's scale (its power of two) and whether it left far spheres out, the features frame's ties
//!    (a lamp on a surface, coincident objects); for the integer kernel, its
//!    per-frame rule's decision and quantisation (pixel unit, focal length, shade
//!    shift, length unit) — its spheres' regions are then the cuts its rows are culled
//!    with.
//! 2. **Each sphere whose bits changed** (`-0.0` and `0.0` differ): its old and its new
//!    silhouette. With lights and shadows, also where the old and new shadows it casts on
//!    the first plane under each light can be seen (the image of the disc of the plane
//!    that holds each, enlarged as the features frame's culling of shadow rays is, and
//!    for the stepping's direction error), and the silhouettes of the other spheres (on which its shadow can fall);
//!    a second plane (whose shadow rays are not culled) draws the whole frame. With a
//!    reflection depth, the silhouettes of every mirror sphere (a mirror can show
//!    anything); a mirror plane draws the whole frame.
//! 3. **Sampling** widens each silhouette by its footprint: `Grid(n)`'s sub-pixel rays
//!    lie within half a pixel of the centre (the silhouette's reach over the pixel's
//!    rows, as anti-aliasing culls its sub-pixel rays, and half a
//!    column), and `Adaptive(n)` decides a pixel from its neighbours' samples too (three
//!    pixels more each way).
//! 4. **What the display lost** ([`Incremental::invalidate`],
//!    [`Incremental::invalidate_area`]).
//!
//! Outside the union, every pixel is computed from the same inputs in both frames by the
//! same code: it is the same. Inside it, the pixels are traced by the render itself,
//! clipped to rectangles around the regions: a clipped render's pixels are the whole
//! render's. The regions are cut into runs per row; runs of a row closer than
//! [`MERGE_GAP`] pixels are sent as one.
//!
//! More than [`MAX_REGIONS`] regions, or one that is not a bounded ellipse (culling off,
//! a sphere around the eye), draw the whole frame: slower, never wrong.

use core::marker::PhantomData;

use embedded_graphics::pixelcolor::{PixelColor, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::Vec;

use crate::camera::span::{IntCut, Margin, Silhouette, ViewCone};
use crate::camera::{Camera, CameraParams};
use crate::error::{BandError, FrameError};
use crate::math::vec3::Vec3;
use crate::math::SqrtFn;
use crate::method::dispatch::{dispatch, Visit};
use crate::method::intersect::{Scale, SphereGeom, TestStrategy};
use crate::method::stepping::Stepper;
use crate::method::{Arithmetic, Method};
use crate::render::Render;
use crate::sampling::Sampling;
use crate::scene::light::Light;
use crate::scene::material::Material;
use crate::scene::plane::Plane;
use crate::scene::sphere::Sphere;
use crate::scene::{Scene, Settings};
use crate::trace::lit::shadow::shadow_regions;
use crate::trace::lit::ties::same_ties;
use crate::trace::options::{Options, SecondaryOrigin};
use crate::trace::scanline::{ColorRuns, PixelRow, RowSink};

/// At most this many regions (silhouettes and rectangles) a frame re-traces; more draw
/// the whole frame. With the strips it bounds the plan's size ([`Changes`]).
pub const MAX_REGIONS: usize = 12;

/// Two runs of a row at most this many pixels apart are sent as one. A display
/// controller of the ST7789/ILI9341 family opens a window with 11 bytes (column and row
/// address commands with four bytes each, the memory-write command); re-sending a gap
/// of `g` unchanged `Rgb565` pixels costs `2g` bytes: up to 5 pixels, less than a
/// second window.
pub const MERGE_GAP: u32 = 5;

/// A traced rectangle is cut into strips of rows that follow the changed runs; a strip
/// grows while it traces at most this many pixels outside the runs: roughly what a new
/// strip costs, in traced pixels, `[one ray a pixel or a grid, adaptive sampling]`. The
/// strips of a frame are traced as one frame, its set-up (scale, silhouettes, shadow
/// regions, the integer kernel's rule) paid once, so a strip costs only its rows'
/// start; adaptive sampling's rows hold their clip, so there each strip is a frame of
/// its own and pays the set-up. On the Cortex-M4F `bounce`'s worst frame traces 5,158
/// pixels in 20 strips for 3.42 M instructions (`lab/firmware/examples/qemu_animation.rs`,
/// `lab/data/qemu_animation_cortex_m4.txt`). Tuning constants: any values draw the
/// same pixels.
pub const STRIP_SETUP: [u32; 2] = [16, 512];

/// At most this many strips a frame; more trace each rectangle whole.
const MAX_STRIPS: usize = 48;

/// What one incremental frame cost: pixels traced (the area of the rectangles the render
/// was clipped to, where the kernel traced every pixel its spans reach), pixels sent and
/// the windows (runs) they were sent in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct FrameStats {
    /// The whole frame was drawn (the first frame, a frame-wide change, or too many
    /// regions).
    pub full: bool,
    /// Pixels in the rectangles the render traced.
    pub traced: u32,
    /// Pixels sent to the display.
    pub sent: u32,
    /// Runs (one `fill_contiguous` each) they were sent in.
    pub windows: u32,
    /// Strips (rectangles of rows) traced, as one frame that pays its set-up once;
    /// under adaptive sampling each strip is a frame of its own.
    pub strips: u32,
    /// The frame could not be drawn exactly ([`Render::check`]): nothing was sent, and
    /// the next frame is drawn whole.
    pub refused: Option<FrameError>,
}

/// What the display shows, remembered for the next frame: the scene, camera and render
/// settings of the last frame drawn. Its size is the scene's
/// (`size_of::<Scene<N, L, P, D>>()`: 32 bytes a sphere of capacity `N`, 24 a light, 56
/// a plane, and 40) and 128 bytes more; it holds no pixel. While it draws, its plan of
/// the frame ([`Changes`], 996 bytes on a 32-bit target) is on the stack beside the
/// render's own: measured on a Cortex-M4F, an incremental frame of a 3-sphere Lab #1
/// scene (integer kernel) takes 1,844 bytes of stack against 1,772 drawn whole, of a
/// lit 3-sphere scene with a floor 2,148 against 1,808 (`docs/animation.md`).
///
/// ```
/// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::{Rgb565, Rgb888}, prelude::*};
/// use embedded_raytracer::{Camera, Incremental, Render, Scene, Sphere, Vec3};
///
/// let ball = Sphere::new(Vec3::new(-1.0, 0.0, 0.0), 0.5, Rgb888::new(255, 64, 64));
/// let mut scene: Scene<2> = Scene::from_array(
///     [ball, Sphere::new(Vec3::new(1.0, 0.0, 0.0), 0.5, Rgb888::new(64, 255, 64))],
///     Rgb888::new(0, 0, 0),
/// );
/// let camera = Camera::new(Vec3::new(0.0, 0.0, 6.0), Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0),
///     0.6, Size::new(64, 64))?;
/// let mut display = MockDisplay::<Rgb565>::new();
/// display.set_allow_overdraw(true);
/// let mut shown = Incremental::new();
///
/// // The first frame is drawn whole.
/// let first = shown.draw(&Render::new(&scene, &camera), &mut display)?;
/// assert!(first.full && first.sent == 64 * 64);
///
/// // The one-frame loop: move what moves, draw what changed.
/// for frame in 1..4 {
///     scene.set_sphere(0, Sphere { center: Vec3::new(-1.0, 0.1 * frame as f32, 0.0), ..ball })?;
///     let stats = shown.draw(&Render::new(&scene, &camera), &mut display)?;
///     assert!(!stats.full && stats.sent < 64 * 64 / 4);
/// }
/// // Nothing moved: nothing is sent.
/// assert_eq!(shown.draw(&Render::new(&scene, &camera), &mut display)?.sent, 0);
///
/// // The display shows the last frame's full render, bit for bit.
/// let mut full = MockDisplay::<Rgb565>::new();
/// Render::new(&scene, &camera).draw(&mut full)?;
/// display.assert_eq(&full);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct Incremental<const N: usize, const L: usize = 0, const P: usize = 0, const D: usize = 0> {
    shown: Option<Shown<N, L, P, D>>,
    /// A part of the image (image coordinates) the display no longer shows.
    stale: Option<Rectangle>,
}

#[derive(Clone, Debug)]
struct Shown<const N: usize, const L: usize, const P: usize, const D: usize> {
    scene: Scene<N, L, P, D>,
    params: CameraParams,
    method: Method,
    sampling: Sampling,
    options: Options,
    offset: Point,
    /// The target's bounding box (for bands: the image).
    target: Rectangle,
}

impl<const N: usize, const L: usize, const P: usize, const D: usize> Default for Incremental<N, L, P, D> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize, const L: usize, const P: usize, const D: usize> Incremental<N, L, P, D> {
    /// Nothing known about the display: the first frame is drawn whole.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            shown: None,
            stale: None,
        }
    }

    /// The display no longer shows the last frame (it was cleared, or a draw returned
    /// an error): the next frame is drawn whole.
    pub fn invalidate(&mut self) {
        self.shown = None;
        self.stale = None;
    }

    /// The display no longer shows the last frame in `area` (target coordinates: an
    /// overlay such as a frame-rate counter or a message was drawn over it): the next
    /// frame redraws that rectangle too.
    pub fn invalidate_area(&mut self, area: Rectangle) {
        let Some(shown) = &self.shown else {
            return;
        };
        let image = Rectangle::new(shown.offset, shown.params.size);
        let area = area.intersection(&image);
        if area.is_zero_sized() {
            return;
        }
        let area = Rectangle::new(area.top_left - shown.offset, area.size);
        self.stale = Some(match self.stale {
            None => area,
            Some(old) => crate::trace::frame::hull(old, area),
        });
    }

    /// Draws `render`'s frame onto `target`, which shows the last frame drawn through
    /// this `Incremental`: traces the pixels that can differ (see the [module
    /// rule](crate::incremental)) and sends each changed run of a row as its own
    /// `fill_contiguous`, so an SPI display driver sends only that window. Afterwards
    /// the target shows `render`'s full frame, bit for bit.
    ///
    /// # Errors
    ///
    /// The target's. The display's state is then unknown: the next frame is drawn
    /// whole.
    // Inlined, as `Render::draw` is: with a constant method only its code is linked.
    #[inline(always)]
    pub fn draw<C, Tg>(
        &mut self,
        render: &Render<'_, N, C, L, P, D>,
        target: &mut Tg,
    ) -> Result<FrameStats, Tg::Error>
    where
        C: PixelColor + From<Rgb888>,
        Tg: DrawTarget<Color = C>,
    {
        let bbox = target.bounding_box();
        let plan = self.plan(render, bbox);
        // What the display shows if the draw fails is unknown: forget it until done.
        let shown = self.shown.take();
        let result = plan.draw(render, target);
        match (&result, plan.refused) {
            (Ok(_), None) => self.remember(render, bbox),
            _ => drop(shown),
        }
        result
    }

    /// Plans the next frame for a caller that sends bands itself (DMA): the returned
    /// [`Changes`] says which runs of each row changed ([`Changes::runs`]) and traces
    /// them into a band buffer ([`Changes::draw_band`]). The image is at the origin
    /// (bands have no offset). The frame is taken as shown from now on: a caller that
    /// fails to send it calls [`Incremental::invalidate`].
    // Inlined, as `Render::draw` is: with a constant method only its code is linked.
    #[inline(always)]
    pub fn update<C>(&mut self, render: &Render<'_, N, C, L, P, D>) -> Changes
    where
        C: PixelColor + From<Rgb888>,
    {
        let image = Rectangle::new(Point::zero(), render.camera().size());
        let plan = self.plan_at(render, image, Point::zero());
        if plan.refused.is_none() {
            self.remember_at(render, image, Point::zero());
        } else {
            self.invalidate();
        }
        plan
    }

    // Inlined: an out-of-line call taking the render's address would make its method a
    // value in memory for the whole draw, and every method's kernel would be linked.
    #[inline(always)]
    fn remember<C>(&mut self, render: &Render<'_, N, C, L, P, D>, target: Rectangle) {
        self.remember_at(render, target, render.offset());
    }

    #[inline(always)]
    fn remember_at<C>(&mut self, render: &Render<'_, N, C, L, P, D>, target: Rectangle, offset: Point) {
        self.shown = Some(Shown {
            scene: render.scene().clone(),
            params: *render.camera().params(),
            method: render.method(),
            sampling: render.sampling(),
            options: render.options(),
            offset,
            target,
        });
        self.stale = None;
    }

    // Inlined, as `Render::draw` is: with a constant method only its code is linked.
    #[inline(always)]
    fn plan<C>(&self, render: &Render<'_, N, C, L, P, D>, target: Rectangle) -> Changes {
        self.plan_at(render, target, render.offset())
    }

    /// The rule (module docs), once per frame.
    // Inlined, as `Render::draw` is: with a constant method only its code is linked.
    #[inline(always)]
    fn plan_at<C>(&self, render: &Render<'_, N, C, L, P, D>, target: Rectangle, offset: Point) -> Changes {
        let camera = render.camera();
        let size = camera.size();
        let scene = render.scene();
        let features = Scene::<N, L, P, D>::FEATURES;
        let integer = render.method().arithmetic == Arithmetic::Integer
            && !features
            && render.sampling() == Sampling::Center;
        if integer {
            if let Some(plan) = self.plan_integer(render, target, offset) {
                return plan;
            }
        }
        let new = dispatch(
            render.method(),
            Probe {
                scene,
                camera,
                sampling: render.sampling(),
            },
        );
        let (scale, culled, margin, step_err) = match new {
            Ok(p) => p,
            Err(why) => return Changes::refusal(size, why),
        };
        let full = || Changes::full(size);
        let shown = match &self.shown {
            Some(shown) if shown.same_frame(render, target, offset) => shown,
            _ => return full(),
        };
        let old = dispatch(
            render.method(),
            Probe {
                scene: &shown.scene,
                camera,
                sampling: render.sampling(),
            },
        );
        match old {
            Ok((s, c, _, _)) if s.0.to_bits() == scale.0.to_bits() && c == culled => {}
            _ => return full(),
        }
        let changed = |k: usize| shown.changed(scene, k);
        let any_changed = (0..scene.spheres().len()).any(changed);
        if any_changed && features && !same_ties(&shown.scene, scene, camera.eye()) {
            return full();
        }
        let pad = match render.sampling() {
            Sampling::Center => 0,
            Sampling::Grid(_) => 1,
            Sampling::Adaptive(_) => 3,
        };
        let shadows = features && L > 0 && scene.settings().shadows;
        let mirrors = features && scene.max_depth() > 0;
        if any_changed
            && ((shadows && scene.planes().len() > 1)
                || (mirrors && scene.planes().iter().any(|p| p.material.reflect != 0.0)))
        {
            return full();
        }
        let cone = if culled {
            ViewCone::new(camera, step_err)
        } else {
            None
        };
        let strip_setup = if matches!(render.sampling(), Sampling::Adaptive(_)) {
            STRIP_SETUP[1]
        } else {
            STRIP_SETUP[0]
        };
        let mut plan = Changes::empty(size, strip_setup, pad);
        let frame = Sil {
            camera,
            scale,
            margin,
            step_err,
            cone: cone.as_ref(),
            span_culling: render.options().span_culling,
        };
        let mut ok = true;
        let add_sphere = |plan: &mut Changes, s: &Sphere| plan.push_silhouette(frame.of(s));
        for (k, new_s) in scene.spheres().iter().enumerate() {
            if !changed(k) {
                continue;
            }
            ok &= add_sphere(&mut plan, new_s);
            if let Some(old_s) = shown.scene.spheres().get(k) {
                ok &= add_sphere(&mut plan, old_s);
                if shadows {
                    for s in [old_s, new_s] {
                        shadow_regions(scene, s, camera, (scale, step_err), |sil| {
                            ok &= plan.push_silhouette(sil);
                        });
                    }
                }
            }
        }
        if any_changed {
            // The surfaces a moved sphere's shadow can fall on, and the mirrors that can
            // show it: each unchanged sphere once.
            for (k, s) in scene.spheres().iter().enumerate() {
                let receives = shadows
                    && (0..scene.spheres().len()).filter(|&m| changed(m)).any(|m| {
                        [shown.scene.spheres().get(m), scene.spheres().get(m)]
                            .into_iter()
                            .flatten()
                            .any(|mover| scene.lights().iter().any(|l| can_shadow(mover, s, l)))
                    });
                if !changed(k) && (receives || (mirrors && s.material.reflect != 0.0)) {
                    ok &= add_sphere(&mut plan, s);
                }
            }
        }
        if let Some(stale) = self.stale {
            ok &= plan.push_rect(stale);
        }
        if !ok {
            return full();
        }
        plan.merge();
        plan
    }
}

impl<const N: usize, const L: usize, const P: usize, const D: usize> Incremental<N, L, P, D> {
    /// The rule for a frame the integer kernel can draw: its frame-wide quantisation
    /// equal in both frames, and each changed sphere's old and new cut (the columns
    /// its rows are culled to). `None` where neither frame is the integer kernel's (the
    /// `f32` rule then applies).
    // Inlined, as `Render::draw` is: with a constant method only its code is linked.
    #[inline(always)]
    fn plan_integer<C>(
        &self,
        render: &Render<'_, N, C, L, P, D>,
        target: Rectangle,
        offset: Point,
    ) -> Option<Changes> {
        let (camera, scene, options) = (render.camera(), render.scene(), render.options());
        let size = camera.size();
        let shown = match &self.shown {
            Some(shown) if shown.same_frame(render, target, offset) => shown,
            // The whole frame, if the integer kernel's rule takes it.
            _ => {
                return crate::integer::regions::<N>(scene.spheres(), camera, options, |_| false, |_, _| {})
                    .map(|_| Changes::full(size));
            }
        };
        let changed = |k: usize| shown.changed(scene, k);
        let mut plan = Changes::empty(size, STRIP_SETUP[0], 0);
        let mut ok = true;
        let mut add = |rows: (u32, u32), cut| ok &= plan.push_cut(rows, cut);
        // Each frame's quantisation, found with its changed spheres' cuts: the cuts are
        // the plan only if the two quantisations are equal.
        let new_key = crate::integer::regions::<N>(scene.spheres(), camera, options, changed, &mut add);
        let old_key = crate::integer::regions::<N>(shown.scene.spheres(), camera, options, changed, &mut add);
        match (old_key, new_key) {
            (None, None) => return None,
            (Some(a), Some(b)) if a == b => {}
            _ => return Some(Changes::full(size)),
        }
        if let Some(stale) = self.stale {
            ok &= plan.push_rect(stale);
        }
        if !ok {
            return Some(Changes::full(size));
        }
        plan.merge();
        Some(plan)
    }
}

impl<const N: usize, const L: usize, const P: usize, const D: usize> Shown<N, L, P, D> {
    /// Whether `render`, drawn onto `target` (its bounding box) at `offset`, keeps this
    /// frame's frame-wide state (rule step 1) as far as the inputs say: the camera, the
    /// method, sampling, options, offset and target, and the scene's frame-wide numbers.
    /// What the method derives from them (the frame's scale, the integer kernel's
    /// quantisation) each rule compares itself.
    fn same_frame<C>(&self, render: &Render<'_, N, C, L, P, D>, target: Rectangle, offset: Point) -> bool {
        same_params(&self.params, render.camera().params())
            && self.method == render.method()
            && self.sampling == render.sampling()
            && same_options(render.options(), self.options)
            && self.offset == offset
            && self.target == target
            && same_frame_wide(&self.scene, render.scene())
    }

    /// Whether sphere `k` of `scene` differs from this frame's bit for bit (rule step
    /// 2); a sphere only one of them has differs.
    fn changed(&self, scene: &Scene<N, L, P, D>, k: usize) -> bool {
        match (self.scene.spheres().get(k), scene.spheres().get(k)) {
            (Some(a), Some(b)) => !same_sphere(a, b),
            _ => true,
        }
    }
}

/// The frame-wide inputs a probe of the method's strategy types reports: the frame's
/// scale and whether it left far spheres out, the test's margin and the stepping's
/// error bound (what each silhouette is enlarged by).
type Probed = (Scale, bool, Margin, f32);

/// The frame's scale and the silhouettes' margins, as the render decides them.
struct Probe<'a, const N: usize, const L: usize, const P: usize, const D: usize> {
    scene: &'a Scene<N, L, P, D>,
    camera: &'a Camera,
    sampling: Sampling,
}

impl<const N: usize, const L: usize, const P: usize, const D: usize> Visit for Probe<'_, N, L, P, D> {
    type Output = Result<Probed, FrameError>;
    fn visit<S: Stepper, T: TestStrategy, Q: SqrtFn>(self) -> Self::Output {
        // Only a Lab #1 frame of one ray a pixel culls for its scale (as `lab1.rs` does).
        let cull = !Scene::<N, L, P, D>::FEATURES && self.sampling == Sampling::Center;
        let step_err = S::error_bound(self.camera);
        crate::trace::frame::frame_scale::<N, L, P, D>(self.scene, self.camera, step_err, cull)
            .map(|(scale, culled)| (scale, culled, T::MARGIN, step_err))
    }
}

/// A sphere's silhouette as the frame builds it (`frame.rs`): in the frame's units,
/// with the test's margin and the stepping's error bound; none where the frame's cone
/// left the sphere out.
struct Sil<'a> {
    camera: &'a Camera,
    scale: Scale,
    margin: Margin,
    step_err: f32,
    cone: Option<&'a ViewCone>,
    span_culling: bool,
}

impl Sil<'_> {
    fn of(&self, s: &Sphere) -> Silhouette {
        let eye = self.camera.eye();
        if self.cone.is_some_and(|c| c.misses(s.center - eye, s.radius)) {
            return Silhouette::NONE;
        }
        if !self.span_culling {
            return Silhouette::ALL;
        }
        let geom = SphereGeom::new(s.center, s.radius, eye, self.scale);
        Silhouette::new(
            geom.l,
            s.radius * self.scale.0,
            self.camera,
            self.margin,
            self.step_err,
        )
    }
}

// Every edge of a rectangle of the image fits an `Area`'s `u16`.
const _: () = assert!(crate::math::limits::MAX_RESOLUTION <= u16::MAX as u32);

/// A rectangle of the image, `[x0, x1) × [y0, y1)` in pixels. An image is at most
/// `MAX_RESOLUTION` pixels each way, so each edge is a `u16`: half a `Rectangle`, for
/// the plan's rectangles and strips.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Area {
    x0: u16,
    y0: u16,
    x1: u16,
    y1: u16,
}

impl Area {
    /// From edges of the image (each at most `MAX_RESOLUTION`).
    fn new(x0: u32, y0: u32, x1: u32, y1: u32) -> Self {
        Self {
            x0: edge(x0),
            y0: edge(y0),
            x1: edge(x1),
            y1: edge(y1),
        }
    }

    /// A rectangle of the image.
    fn of(r: Rectangle) -> Self {
        let (x0, y0) = (r.top_left.x.max(0) as u32, r.top_left.y.max(0) as u32);
        Self::new(x0, y0, x0 + r.size.width, y0 + r.size.height)
    }

    fn rect(self) -> Rectangle {
        let ((x0, x1), (y0, y1)) = (self.cols(), self.rows());
        Rectangle::new(
            Point::new(x0 as i32, y0 as i32),
            Size::new(x1.saturating_sub(x0), y1.saturating_sub(y0)),
        )
    }

    fn cols(self) -> (u32, u32) {
        (u32::from(self.x0), u32::from(self.x1))
    }

    fn rows(self) -> (u32, u32) {
        (u32::from(self.y0), u32::from(self.y1))
    }

    fn has_row(self, j: u32) -> bool {
        u32::from(self.y0) <= j && j < u32::from(self.y1)
    }

    fn pixels(self) -> u32 {
        let ((x0, x1), (y0, y1)) = (self.cols(), self.rows());
        x1.saturating_sub(x0) * y1.saturating_sub(y0)
    }

    /// Whether the two share a pixel.
    fn meets(self, o: Area) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }

    /// The smallest rectangle holding both.
    fn bounding(self, o: Area) -> Area {
        Area {
            x0: self.x0.min(o.x0),
            y0: self.y0.min(o.y0),
            x1: self.x1.max(o.x1),
            y1: self.y1.max(o.y1),
        }
    }
}

/// An edge or size of the image as a `u16` (it is at most `MAX_RESOLUTION`).
fn edge(v: u32) -> u16 {
    u16::try_from(v).unwrap_or(u16::MAX)
}

/// One region of the image that can have changed; its rows and columns are its entry's
/// bounding box.
#[derive(Clone, Copy, Debug)]
enum Region {
    /// A silhouette, widened by the plan's `pad` pixels each way.
    Ellipse(Silhouette),
    /// A sphere's cut in the integer kernel (one that culls nothing is a `Rect`).
    Int(IntCut),
    /// Its bounding box.
    Rect,
}

impl Region {
    /// Its columns `[lo, hi)` in row `j` of an image `width` wide; for `Int` a row of
    /// its sphere's rows. `None` for `Rect` (its box is its run).
    fn cut(&self, j: u32, width: u32, pad: u32) -> Option<(u32, u32)> {
        match *self {
            Region::Rect => None,
            Region::Int(cut) => cut.row_span(j, width),
            Region::Ellipse(sil) if pad == 0 => sil.row_span(j, 0, width),
            Region::Ellipse(sil) => {
                // A pixel's rays (and, with `pad`, its neighbours') lie within
                // `pad + ½` of its centre: the silhouette's reach over those rows,
                // widened as much in columns. The reach's two roots are taken per row:
                // only a frame of several rays a pixel widens, and there they are a few
                // of the row's rays.
                let h = pad as f32 + 0.5;
                let (lo, hi) = sil.band_reach(j, h, sil.reach_consts())?;
                let lo = libm::floorf(lo - h).max(0.0).min(width as f32);
                let hi = (libm::ceilf(hi + h) + 1.0).max(0.0).min(width as f32);
                // NaN clamps to a bound: the whole row.
                let (lo, hi) = (lo as u32, hi as u32);
                (lo < hi).then_some((lo, hi))
            }
        }
    }
}

/// A region, its bounding box (the rows and columns of its runs) and its rectangle.
#[derive(Clone, Copy, Debug)]
struct Entry {
    region: Region,
    bbox: Area,
    /// The pixels of `bbox` outside the region's runs, if every row of `bbox` has a run
    /// (else, or if more, `u16::MAX`): what a strip of `bbox` alone traces outside them.
    waste: u16,
    /// The index in `Changes::rects` of the rectangle holding `bbox`.
    rect: u8,
}

impl Entry {
    /// Its run `[lo, hi)` in row `j` of an image `width` wide.
    #[inline]
    fn span(&self, j: u32, width: u32, pad: u32) -> Option<(u32, u32)> {
        if !self.bbox.has_row(j) {
            return None;
        }
        match self.region {
            Region::Rect => Some(self.bbox.cols()),
            region => region.cut(j, width, pad),
        }
    }
}

/// The regions of one frame, their rectangles, and what tracing them costs. It takes
/// 996 bytes on a 32-bit target.
#[derive(Clone, Debug)]
pub struct Changes {
    width: u16,
    height: u16,
    /// The regions. A row's runs are merged only with runs of the same rectangle.
    regions: Vec<Entry, MAX_REGIONS, u8>,
    /// The regions' boxes, those that overlap merged into one, until none does.
    rects: Vec<Area, MAX_REGIONS, u8>,
    /// The rectangles the render is clipped to: each of `rects` cut into strips of rows
    /// that follow the runs' extent.
    strips: Vec<Area, MAX_STRIPS, u8>,
    /// The frame kind's [`STRIP_SETUP`].
    strip_setup: u32,
    /// Pixels a silhouette is widened by each way: the sampling's footprint (rule step 3).
    pad: u8,
    full: bool,
    refused: Option<FrameError>,
}

// The plan sits on the stack beside the render's own while a frame draws (the size the
// `Incremental` and `Changes` docs state).
#[cfg(target_pointer_width = "32")]
const _: () = assert!(size_of::<Changes>() <= 996);

impl Changes {
    fn empty(size: Size, strip_setup: u32, pad: u32) -> Self {
        Self {
            width: edge(size.width),
            height: edge(size.height),
            regions: Vec::new(),
            rects: Vec::new(),
            strips: Vec::new(),
            strip_setup,
            pad: u8::try_from(pad).unwrap_or(u8::MAX),
            full: false,
            refused: None,
        }
    }

    fn full(size: Size) -> Self {
        let image = Area::new(0, 0, size.width, size.height);
        let mut plan = Self::empty(size, 0, 0);
        let _ = plan.regions.push(Entry {
            region: Region::Rect,
            bbox: image,
            waste: 0,
            rect: 0,
        });
        let _ = plan.rects.push(image);
        let _ = plan.strips.push(image);
        plan.full = true;
        plan
    }

    fn refusal(size: Size, why: FrameError) -> Self {
        let mut plan = Self::empty(size, 0, 0);
        plan.refused = Some(why);
        plan
    }

    /// The image's width and the silhouettes' widening, as a row's cut takes them.
    fn row_consts(&self) -> (u32, u32) {
        (u32::from(self.width), u32::from(self.pad))
    }

    /// Adds a silhouette (rule steps 2 and 3); `false` if it cannot be planned (not a
    /// bounded ellipse, or one region too many).
    fn push_silhouette(&mut self, sil: Silhouette) -> bool {
        if sil.is_all() {
            return false;
        }
        let (height, pad) = (u32::from(self.height), u32::from(self.pad));
        let (a, b) = sil.rows(height);
        let rows = if pad == 0 || a >= b {
            (a, b)
        } else {
            (a.saturating_sub(pad + 1), b.saturating_add(pad + 1).min(height))
        };
        self.push(Region::Ellipse(sil), rows)
    }

    /// Adds the integer kernel's cut of a sphere's rows `rows`; `false` if one region
    /// too many.
    fn push_cut(&mut self, rows: (u32, u32), cut: IntCut) -> bool {
        let height = u32::from(self.height);
        let (j0, j1) = (rows.0.min(height), rows.1.min(height));
        if cut == IntCut::All {
            // Every column of its rows.
            return j0 >= j1 || self.push_area(Area::new(0, j0, u32::from(self.width), j1));
        }
        self.push(Region::Int(cut), (j0, j1))
    }

    /// Adds a rectangle of the image (rule step 4); `false` if one region too many.
    fn push_rect(&mut self, r: Rectangle) -> bool {
        r.is_zero_sized() || self.push_area(Area::of(r))
    }

    fn push_area(&mut self, bbox: Area) -> bool {
        self.regions
            .push(Entry {
                region: Region::Rect,
                bbox,
                waste: 0,
                rect: 0,
            })
            .is_ok()
    }

    /// Adds a region whose runs lie in rows `j0..j1`, with its bounding box (none if it
    /// has no run: off the image); `false` if one region too many.
    fn push(&mut self, region: Region, (j0, j1): (u32, u32)) -> bool {
        let (width, pad) = self.row_consts();
        let (mut x0, mut x1, mut y0, mut y1) = (u32::MAX, 0, u32::MAX, 0);
        let (mut covered, mut gap) = (0, false);
        for j in j0..j1 {
            if let Some((lo, hi)) = region.cut(j, width, pad) {
                // A row without a run lies between this one and the last with one.
                gap |= y0 != u32::MAX && y1 != j;
                x0 = x0.min(lo);
                x1 = x1.max(hi);
                y0 = y0.min(j);
                y1 = j + 1;
                covered += hi - lo;
            }
        }
        if x0 >= x1 {
            return true;
        }
        let bbox = Area::new(x0, y0, x1, y1);
        let waste = if gap {
            u16::MAX
        } else {
            u16::try_from(bbox.pixels() - covered).unwrap_or(u16::MAX)
        };
        self.regions
            .push(Entry {
                region,
                bbox,
                waste,
                rect: 0,
            })
            .is_ok()
    }

    /// The traced rectangles: the regions' boxes, those that overlap merged into one,
    /// until none does; then each region's rectangle, and the strips.
    fn merge(&mut self) {
        self.rects.clear();
        for e in &self.regions {
            let _ = self.rects.push(e.bbox);
        }
        let mut merged = true;
        while merged {
            merged = false;
            'outer: for a in 0..self.rects.len() {
                for b in a + 1..self.rects.len() {
                    let (Some(&ra), Some(&rb)) = (self.rects.get(a), self.rects.get(b)) else {
                        continue;
                    };
                    if ra.meets(rb) {
                        if let Some(slot) = self.rects.get_mut(a) {
                            *slot = ra.bounding(rb);
                        }
                        self.rects.swap_remove(b);
                        merged = true;
                        break 'outer;
                    }
                }
            }
        }
        // The rectangles are disjoint: a box meets only the one holding it.
        for e in &mut self.regions {
            e.rect = self.rects.iter().position(|r| r.meets(e.bbox)).unwrap_or(0) as u8;
        }
        self.strips.clear();
        for r in 0..self.rects.len() {
            if !self.cut_strips(r) {
                // Too many strips: each rectangle whole.
                self.strips.clear();
                for &rect in &self.rects {
                    let _ = self.strips.push(rect);
                }
                return;
            }
        }
    }

    /// Cuts rectangle `r` into strips of rows, each as wide as its rows' runs reach: a
    /// strip grows a row while the pixels it would trace outside the runs stay within
    /// the frame kind's [`STRIP_SETUP`] (what a new strip costs); a row without a run
    /// ends it. `false` if the strips do not fit.
    fn cut_strips(&mut self, r: usize) -> bool {
        let Some(&rect) = self.rects.get(r) else {
            return true;
        };
        let group = r as u8;
        // The whole rectangle is one strip if it traces at most `STRIP_SETUP` pixels
        // outside its runs: a strip's pixels outside its runs never shrink as it grows a
        // row, so the rule below never ends it early. Bounded from the regions' boxes,
        // without a row's runs: the rectangle's rows are its boxes' rows, joined (boxes
        // that share no row never merge), so if each box has a run in every row, so has
        // the rectangle; and its runs hold any one region's.
        let outside = self
            .regions
            .iter()
            .filter(|e| e.rect == group)
            .try_fold(u32::MAX, |least, e| {
                (e.waste != u16::MAX).then(|| least.min(rect.pixels() - e.bbox.pixels() + u32::from(e.waste)))
            });
        if outside.is_some_and(|w| w <= self.strip_setup) {
            return self.strips.push(rect).is_ok();
        }
        let (width, pad) = self.row_consts();
        let (y0, y1) = rect.rows();
        // The open strip: first row, columns, and the pixels of its rows' runs' extents.
        let mut open: Option<(u32, u32, u32, u32)> = None;
        let mut ok = true;
        let mut close =
            |strips: &mut Vec<Area, MAX_STRIPS, u8>, (top, lo, hi, _): (u32, u32, u32, u32), end: u32| {
                ok &= strips.push(Area::new(lo, top, hi, end)).is_ok();
            };
        for j in y0..y1 {
            // This row's runs' extent: the rectangle's regions' (merging runs closer than
            // `MERGE_GAP` fills gaps inside it only).
            let extent = self
                .regions
                .iter()
                .filter(|e| e.rect == group)
                .filter_map(|e| e.span(j, width, pad))
                .fold(None, |e: Option<(u32, u32)>, (lo, hi)| {
                    Some(e.map_or((lo, hi), |(a, b)| (a.min(lo), b.max(hi))))
                });
            open = match (open, extent) {
                (None, None) => None,
                (None, Some((lo, hi))) => Some((j, lo, hi, hi - lo)),
                (Some(strip), None) => {
                    close(&mut self.strips, strip, j);
                    None
                }
                (Some((top, a, b, used)), Some((lo, hi))) => {
                    let (na, nb) = (a.min(lo), b.max(hi));
                    let used = used + (hi - lo);
                    if (nb - na) * (j + 1 - top) - used <= self.strip_setup {
                        Some((top, na, nb, used))
                    } else {
                        close(&mut self.strips, (top, a, b, used), j);
                        Some((j, lo, hi, hi - lo))
                    }
                }
            };
        }
        if let Some(strip) = open {
            close(&mut self.strips, strip, y1);
        }
        ok
    }

    /// Adds to `runs` the runs in row `j` of rectangle `g`'s regions that can reach
    /// columns `x0..x1`, merged. A gap is filled only between runs at most
    /// [`MERGE_GAP`] apart, so within `x0..x1` the runs of the regions reaching
    /// `x0 − MERGE_GAP..x1 + MERGE_GAP` are those of all of them.
    fn add_runs(&self, runs: &mut Runs, g: u8, j: u32, (x0, x1): (u32, u32)) {
        let (width, pad) = self.row_consts();
        let from = runs.len;
        for e in &self.regions {
            let (lo, hi) = e.bbox.cols();
            if e.rect != g || lo >= x1 + MERGE_GAP || hi + MERGE_GAP <= x0 {
                continue;
            }
            if let Some(span) = e.span(j, width, pad) {
                runs.insert(span, from, MERGE_GAP);
            }
        }
    }

    /// The whole frame is drawn.
    #[must_use]
    pub fn is_full(&self) -> bool {
        self.full
    }

    /// Nothing changed: nothing to trace or send.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.rects.is_empty()
    }

    /// Why the frame cannot be drawn ([`Render::check`]); nothing is traced then.
    #[must_use]
    pub fn refused(&self) -> Option<FrameError> {
        self.refused
    }

    /// The rectangles traced (image coordinates), disjoint.
    pub fn rectangles(&self) -> impl Iterator<Item = Rectangle> + '_ {
        self.strips.iter().map(|s| s.rect())
    }

    /// Pixels traced: the rectangles' area.
    #[must_use]
    pub fn traced(&self) -> u32 {
        self.strips.iter().map(|s| s.pixels()).sum()
    }

    /// The changed runs `[lo, hi)` of image row `j`, left to right, disjoint, runs of
    /// one rectangle closer than [`MERGE_GAP`] merged: what a DMA sender sends of the
    /// row.
    #[must_use]
    pub fn runs(&self, j: u32) -> Runs {
        let mut runs = Runs::new();
        for (g, rect) in self.rects.iter().enumerate() {
            if rect.has_row(j) {
                self.add_runs(&mut runs, g as u8, j, rect.cols());
            }
        }
        runs.sort();
        runs
    }

    /// Pixels and windows sent: the runs of every row.
    #[must_use]
    pub fn sent(&self) -> (u32, u32) {
        let (mut pixels, mut windows) = (0, 0);
        for j in 0..u32::from(self.height) {
            for (lo, hi) in self.runs(j) {
                pixels += hi - lo;
                windows += 1;
            }
        }
        (pixels, windows)
    }

    /// Traces the changed pixels of rows `rows` into `buf` (row-major, the image's
    /// width a row, as [`Render::draw_band`] takes it): the pixels of [`Changes::runs`]
    /// (and the rest of their rectangles) get the full render's colours, the others
    /// keep what `buf` held.
    ///
    /// # Errors
    ///
    /// [`Render::draw_band`]'s.
    // Inlined, as `Render::draw` is: with a constant method only its code is linked.
    #[inline(always)]
    pub fn draw_band<C, const N: usize, const L: usize, const P: usize, const D: usize>(
        &self,
        render: &Render<'_, N, C, L, P, D>,
        rows: core::ops::Range<u32>,
        buf: &mut [C],
    ) -> Result<(), BandError>
    where
        C: PixelColor + From<Rgb888>,
    {
        let (band, mut sink) = render.band(rows, buf)?;
        let clips = self
            .strips
            .iter()
            .map(|strip| strip.rect().intersection(&band))
            .filter(|clip| !clip.is_zero_sized());
        let Ok(()) = render.render_clips(clips, Point::zero(), &mut sink);
        match sink.refused {
            None => Ok(()),
            Some(why) => Err(BandError::Frame(why)),
        }
    }

    // Inlined, as `Render::draw` is: with a constant method only its code is linked.
    #[inline(always)]
    fn draw<C, Tg, const N: usize, const L: usize, const P: usize, const D: usize>(
        &self,
        render: &Render<'_, N, C, L, P, D>,
        target: &mut Tg,
    ) -> Result<FrameStats, Tg::Error>
    where
        C: PixelColor + From<Rgb888>,
        Tg: DrawTarget<Color = C>,
    {
        let mut stats = FrameStats {
            full: self.full,
            refused: self.refused,
            ..FrameStats::default()
        };
        if self.refused.is_some() {
            return Ok(stats);
        }
        let offset = render.offset();
        let bbox = target.bounding_box();
        // The strips on the target, traced as one frame (its set-up once).
        let clips = self
            .strips
            .iter()
            .map(|strip| {
                let rect = strip.rect();
                Rectangle::new(rect.top_left + offset, rect.size).intersection(&bbox)
            })
            .filter(|clip| !clip.is_zero_sized());
        for clip in clips.clone() {
            stats.traced += clip.size.width * clip.size.height;
            stats.strips += 1;
        }
        let mut sink = RunSink {
            target: &mut *target,
            changes: self,
            offset,
            stats: &mut stats,
            full: self.full,
            color: PhantomData,
        };
        render.render_clips(clips, offset, &mut sink)?;
        Ok(stats)
    }
}

/// The changed runs of one row ([`Changes::runs`]).
#[derive(Clone, Debug)]
pub struct Runs {
    runs: [(u16, u16); MAX_REGIONS],
    len: usize,
    next: usize,
}

impl Runs {
    fn new() -> Self {
        Self {
            runs: [(0, 0); MAX_REGIONS],
            len: 0,
            next: 0,
        }
    }

    /// Adds `span` to the runs from index `from` on (one rectangle's), merging it with
    /// any it overlaps or comes within `gap` of.
    fn insert(&mut self, (mut lo, mut hi): (u32, u32), from: usize, gap: u32) {
        let mut k = from;
        while k < self.len {
            let Some(&(a, b)) = self.runs.get(k) else { break };
            let (a, b) = (u32::from(a), u32::from(b));
            if lo <= b + gap && a <= hi + gap {
                lo = lo.min(a);
                hi = hi.max(b);
                // Remove run k (order is restored by `sort`).
                self.len -= 1;
                let last = self.runs.get(self.len).copied().unwrap_or((0, 0));
                if let Some(slot) = self.runs.get_mut(k) {
                    *slot = last;
                }
                k = from;
                continue;
            }
            k += 1;
        }
        if let Some(slot) = self.runs.get_mut(self.len) {
            *slot = (edge(lo), edge(hi));
            self.len += 1;
        }
    }

    fn sort(&mut self) {
        if let Some(runs) = self.runs.get_mut(..self.len) {
            runs.sort_unstable_by_key(|r| r.0);
        }
    }
}

impl Iterator for Runs {
    type Item = (u32, u32);
    fn next(&mut self) -> Option<(u32, u32)> {
        let (lo, hi) = self
            .runs
            .get(self.next)
            .copied()
            .filter(|_| self.next < self.len)?;
        self.next += 1;
        Some((u32::from(lo), u32::from(hi)))
    }
}

/// Rows of one strip into a `DrawTarget`, only their changed runs, each run its own
/// `fill_contiguous`.
struct RunSink<'t, 'c, 's, Tg, C> {
    target: &'t mut Tg,
    changes: &'c Changes,
    offset: Point,
    stats: &'s mut FrameStats,
    full: bool,
    color: PhantomData<C>,
}

impl<Tg: DrawTarget<Color = C>, C: PixelColor + From<Rgb888>> RowSink for RunSink<'_, '_, '_, Tg, C> {
    type Error = Tg::Error;
    fn row<R: PixelRow>(&mut self, area: Rectangle, row: R) -> Result<(), Tg::Error> {
        let ColorRuns {
            background,
            before,
            traced,
            traced_len: _,
            after,
        } = row.color_runs();
        let background = C::from(background);
        let mut colors = core::iter::repeat_n(background, before as usize)
            .chain(traced.map(C::from))
            .chain(core::iter::repeat_n(background, after as usize));
        if self.full {
            self.stats.sent += area.size.width;
            self.stats.windows += 1;
            return self.target.fill_contiguous(&area, colors);
        }
        // The area's columns in the image.
        let j = (area.top_left.y - self.offset.y) as u32;
        let x0 = (area.top_left.x - self.offset.x) as u32;
        let x1 = x0 + area.size.width;
        // The rectangle the row's strip was cut from (they are disjoint): its regions'
        // runs are the strip's.
        let at_row = Area::new(x0, j, x0 + 1, j + 1);
        let rect = self
            .changes
            .rects
            .iter()
            .position(|r| r.meets(at_row))
            .unwrap_or(0) as u8;
        let mut runs = Runs::new();
        self.changes.add_runs(&mut runs, rect, j, (x0, x1));
        runs.sort();
        let mut at = x0;
        for (lo, hi) in runs {
            let (lo, hi) = (lo.max(x0), hi.min(x1));
            if lo >= hi {
                continue;
            }
            // Skip to the run, then hand the target exactly the run's colours, however
            // many of them it takes.
            if lo > at {
                colors.nth((lo - at - 1) as usize);
            }
            let len = hi - lo;
            let mut taken = 0;
            let run = Rectangle::new(
                Point::new(lo as i32 + self.offset.x, area.top_left.y),
                Size::new(len, 1),
            );
            self.target
                .fill_contiguous(&run, colors.by_ref().take(len as usize).inspect(|_| taken += 1))?;
            if taken < len {
                colors.nth((len - taken - 1) as usize);
            }
            at = hi;
            self.stats.sent += len;
            self.stats.windows += 1;
        }
        Ok(())
    }
}

/// Whether sphere `k` can lie between a point of sphere `j` and `light`: whether `k`'s
/// shadow can fall on `j`. Exact geometry in `f64` with both radii enlarged by `2⁻⁸` of
/// the lengths involved (as the shadow silhouettes are; the kernel's shadow test is
/// within about `2⁻²²` of them):
/// - directional light (toward it `u`): `j`'s cylinder along `u` meets `k`, i.e. `k`'s
///   centre lies within `r_j + r_k` of the line through `j`'s centre along `u`, not
///   behind it;
/// - point light `P`: the cones from `P` around the two spheres overlap (angle between
///   their axes below the sum of their half-angles) and `j` reaches beyond `k`'s near
///   side; a light inside either sphere is always a yes.
fn can_shadow(k: &Sphere, j: &Sphere, light: &Light) -> bool {
    let v = |a: Vec3| [f64::from(a.x), f64::from(a.y), f64::from(a.z)];
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (ck, cj) = (v(k.center), v(j.center));
    let (rk, rj) = (f64::from(k.radius), f64::from(j.radius));
    match *light {
        Light::Directional { direction, .. } => {
            let d = v(direction);
            let len = libm::sqrt(dot(d, d));
            let u = [-d[0] / len, -d[1] / len, -d[2] / len];
            let w = sub(ck, cj);
            let dist = libm::sqrt(dot(w, w));
            let reach = (rk + rj) * (1.0 + 1.0 / 256.0) + dist / 256.0;
            let along = dot(w, u);
            let perp2 = dot(w, w) - along * along;
            // NaN (a zero direction) is a yes.
            !(along < -reach || perp2 > reach * reach)
        }
        Light::Point { position, .. } => {
            let p = v(position);
            let (wk, wj) = (sub(ck, p), sub(cj, p));
            let (dk, dj) = (libm::sqrt(dot(wk, wk)), libm::sqrt(dot(wj, wj)));
            let (mk, mj) = ((dk + rk) / 256.0, (dj + rj) / 256.0);
            let (rk, rj) = (rk + mk, rj + mj);
            if !(dk > rk && dj > rj) {
                return true;
            }
            let half = |r: f64, d: f64| libm::asin(r / d);
            let cos = (dot(wk, wj) / (dk * dj)).clamp(-1.0, 1.0);
            let theta = libm::acos(cos);
            !(theta > half(rk, dk) + half(rj, dj) + 1e-9 || dj + rj < dk - rk)
        }
    }
}

// Scenes are compared by their bits: `-0.0` and `0.0` differ, and a NaN equals itself,
// so a change is never missed and an unchanged object never redrawn.

fn bits(v: Vec3) -> [u32; 3] {
    [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()]
}

fn same_material(a: &Material, b: &Material) -> bool {
    [a.specular, a.shininess, a.reflect].map(f32::to_bits)
        == [b.specular, b.shininess, b.reflect].map(f32::to_bits)
}

fn same_sphere(a: &Sphere, b: &Sphere) -> bool {
    bits(a.center) == bits(b.center)
        && a.radius.to_bits() == b.radius.to_bits()
        && a.color == b.color
        && same_material(&a.material, &b.material)
}

fn same_light(a: &Light, b: &Light) -> bool {
    match (*a, *b) {
        (
            Light::Directional {
                direction: d,
                intensity: i,
            },
            Light::Directional {
                direction: e,
                intensity: j,
            },
        )
        | (
            Light::Point {
                position: d,
                intensity: i,
            },
            Light::Point {
                position: e,
                intensity: j,
            },
        ) => bits(d) == bits(e) && i.to_bits() == j.to_bits(),
        _ => false,
    }
}

fn same_plane(a: &Plane, b: &Plane) -> bool {
    bits(a.point) == bits(b.point)
        && bits(a.normal) == bits(b.normal)
        && a.color == b.color
        && a.checker == b.checker
        && a.checker_size.to_bits() == b.checker_size.to_bits()
        && same_material(&a.material, &b.material)
}

fn same_settings(a: Settings, b: Settings) -> bool {
    a.ambient.to_bits() == b.ambient.to_bits() && a.max_depth == b.max_depth && a.shadows == b.shadows
}

fn same_options(a: Options, b: Options) -> bool {
    let eps = |o: Options| match o.secondary {
        SecondaryOrigin::Convex => None,
        SecondaryOrigin::Epsilon(e) => Some(e.to_bits()),
    };
    eps(a) == eps(b)
        && a.span_culling == b.span_culling
        && a.anchor_interval == b.anchor_interval
        && a.shadow_any_hit == b.shadow_any_hit
}

fn same_params(a: &CameraParams, b: &CameraParams) -> bool {
    bits(a.eye) == bits(b.eye)
        && bits(a.look_at) == bits(b.look_at)
        && bits(a.up) == bits(b.up)
        && a.fov_y.to_bits() == b.fov_y.to_bits()
        && a.fov_x.map(f32::to_bits) == b.fov_x.map(f32::to_bits)
        && a.size == b.size
}

/// Everything of the scene but its spheres' own numbers: the background, settings,
/// lights, planes and the number of spheres.
fn same_frame_wide<const N: usize, const L: usize, const P: usize, const D: usize>(
    a: &Scene<N, L, P, D>,
    b: &Scene<N, L, P, D>,
) -> bool {
    a.background() == b.background()
        && same_settings(a.settings(), b.settings())
        && a.spheres().len() == b.spheres().len()
        && a.lights().len() == b.lights().len()
        && a.planes().len() == b.planes().len()
        && a.lights().iter().zip(b.lights()).all(|(x, y)| same_light(x, y))
        && a.planes().iter().zip(b.planes()).all(|(x, y)| same_plane(x, y))
}
