//! Frames that re-trace and re-send only what changed ([`Incremental`]).
//!
//! An [`Incremental`] remembers what the display shows (the scene, camera and render
//! settings of the last frame drawn, never its pixels) and draws the next frame by
//! tracing only the pixels that can differ from it and sending only those — the display
//! then shows the next frame's full render, bit for bit.
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
//!    frame's scale (its power of two) and whether it left far spheres out, the features
//!    frame's ties (a lamp on a surface, coincident objects); under adaptive sampling,
//!    whether a Lab #1 frame takes its edges from the silhouettes or shares samples
//!    between neighbours (two spheres that touch anywhere, or a sphere reaching the
//!    eye's plane, switch every edge pixel of the frame); for the integer kernel, its
//!    per-frame rule's decision and quantisation (pixel unit, focal length, shade
//!    shift, length unit) — its spheres' regions are then the cuts its rows are culled
//!    with. A frame the render refuses is planned as a refusal, on every path.
//! 2. **Each sphere whose bits changed** (`-0.0` and `0.0` differ): its old and its new
//!    silhouette. With lights and shadows, also where the old and new shadows it casts on
//!    the first plane under each light can be seen (the image of the disc of the plane
//!    that holds each, enlarged as the features frame's culling of shadow rays is, and
//!    for the stepping's direction error), and the silhouettes of the other spheres (on
//!    which its shadow can fall); a second plane (whose shadow rays are not culled)
//!    draws the whole frame, and so does the lecture notes' algebraic or geometric
//!    sphere test (their shadow rays are far from exact, so their false shadows are not
//!    where an exact shadow can be). With a reflection depth, the silhouettes of every mirror
//!    sphere (a mirror can show anything); a mirror plane draws the whole frame.
//! 3. **Sampling** widens each silhouette by its footprint: `Grid(n)`'s sub-pixel rays
//!    lie within half a pixel of the centre (the silhouette's reach over the pixel's
//!    rows, as anti-aliasing culls its sub-pixel rays, and half a column), and
//!    `Adaptive(n)` decides a pixel from its neighbours' samples too (three pixels more
//!    each way). Each silhouette's rows are those its footprint reaches, whether or not
//!    a row's centre line cuts it (a sphere smaller than a pixel between two rows).
//!    Where `Adaptive(n)` shares samples, a small silhouette makes every pixel meeting
//!    its bounding box an edge pixel: that box too.
//! 4. **What the display lost** ([`Incremental::invalidate`],
//!    [`Incremental::invalidate_area`]).
//!
//! Outside the union, every pixel is computed from the same inputs in both frames by the
//! same code: it is the same. Inside it, the pixels are traced by the render itself,
//! clipped to rectangles around the regions: a clipped render's pixels are the whole
//! render's. The regions are cut into runs per row; runs of a row closer than
//! [`MERGE_GAP`] pixels are sent as one. A frame the integer kernel draws sends each
//! strip whole instead ([`Incremental::draw`]).
//!
//! More than [`MAX_REGIONS`] regions, or one that is not a bounded ellipse (culling off,
//! a sphere around the eye), draw the whole frame: slower, never wrong.

use embedded_graphics::pixelcolor::{PixelColor, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::Vec;

use crate::error::FrameError;
use crate::integer::IntSphere;
use crate::method::Arithmetic;
use crate::render::Render;

use compare::Shown;
use plan::integer_kind;
use plan_integer::IntRule;

mod can_shadow; // which spheres a moved sphere's shadow can fall on (rule step 2)
mod changes; // the plan: its regions, rectangles and strips; a band traced for DMA
mod compare; // what the display shows, compared bit for bit (rule steps 1 and 2)
mod plan; // the rule for an `f32` frame, steps 1 to 4
mod plan_integer; // the rule for a frame of the integer kernel
mod region; // the regions' geometry: silhouettes and cuts to boxes, boxes merged into rectangles
mod runs; // a row's changed runs, and the sink that sends each as its own window

pub use changes::{Changes, StripSetup, MAX_REGIONS, STRIP_SETUP};
pub use runs::{Runs, MERGE_GAP};

/// What one incremental frame cost: the pixels traced and sent, and the windows they were
/// sent in.
///
/// The pixels traced are the area of the rectangles the render was clipped to, where the
/// kernel traced every pixel its spans reach.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct FrameStats {
    /// The whole frame was drawn (the first frame, a frame-wide change, or too many
    /// regions).
    pub full: bool,
    /// Pixels in the rectangles the render traced.
    pub traced: u32,
    /// Pixels sent to the display.
    pub sent: u32,
    /// Windows (one `fill_contiguous` each) they were sent in: the changed runs, or,
    /// for a frame the integer kernel draws, the strips.
    pub windows: u32,
    /// Strips (rectangles of rows) traced, as one frame that pays its set-up once;
    /// under adaptive sampling each strip is a frame of its own.
    pub strips: u32,
    /// The frame could not be drawn exactly ([`Render::check`]): nothing was sent, and
    /// the next frame is drawn whole.
    pub refused: Option<FrameError>,
    /// The arithmetic that drew the frame, or would have drawn a refused one
    /// ([`Changes::arithmetic`]): what [`Render::arithmetic`] says of the render, without
    /// deciding the integer kernel's per-frame rule again.
    pub arithmetic: Arithmetic,
}

impl Default for FrameStats {
    fn default() -> Self {
        Self {
            full: false,
            traced: 0,
            sent: 0,
            windows: 0,
            strips: 0,
            refused: None,
            arithmetic: Arithmetic::F32,
        }
    }
}

/// What the display shows, remembered for the next frame to draw only what changed.
///
/// It remembers the scene, camera and render settings of the last frame drawn, never its
/// pixels: its size is the scene's (`size_of::<Scene<N, L, P, D>>()`: 32 bytes a sphere
/// of capacity `N`, 24 a light, 56 a plane, and 40) and at most 136 bytes more on a
/// 32-bit target (checked when the crate compiles). While it draws,
/// its plan of the frame ([`Changes`], at most 1,008 bytes on a 32-bit target) is on the
/// stack beside the render's own; the stack a frame takes, measured on the Cortex-M4F
/// against the same frame drawn whole, is in `docs/animation.md`.
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

#[cfg(target_pointer_width = "32")]
const _: () = assert!(size_of::<Incremental<1>>() - size_of::<crate::scene::Scene<1>>() <= 136);

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
    /// this `Incremental`, tracing and sending only what can differ.
    ///
    /// It traces the pixels that can differ (see the [module rule](crate::incremental))
    /// and sends each changed run of a row as its own `fill_contiguous`, so an SPI
    /// display driver sends only that window. A frame the integer kernel draws (a chip
    /// without an FPU) sends each strip it traces as one `fill_contiguous` instead: the
    /// strips follow the runs to within [`STRIP_SETUP`] pixels, and there a window a
    /// strip costs the core far less than one a run (each window is a few commands
    /// through the driver). Afterwards the target shows `render`'s full frame, bit for
    /// bit.
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
        // Decided first, while the render's method is still the constant it was built
        // with (after a call the optimiser may read it back as a value, and link every
        // method's kernel).
        let integer = integer_kind(render);
        let bbox = target.bounding_box();
        // The integer kernel's picture of the frame, built by the plan where the rule
        // takes the frame and drawn from: the rule is decided once.
        let mut picture: Vec<IntSphere, N> = Vec::new();
        let plan = self.plan(render, bbox, Some(picture.as_mut_view()));
        // What the display shows if the draw fails is unknown: forget it until done.
        let shown = self.shown.take();
        let result = plan.draw(render, target, integer.then_some(&picture[..]));
        match (&result, plan.refused) {
            (Ok(_), None) => self.remember(render, bbox, plan.int_rule),
            _ => drop(shown),
        }
        result
    }

    /// Plans the next frame for a caller that sends bands itself (DMA).
    ///
    /// The returned [`Changes`] says which runs of each row changed ([`Changes::runs`])
    /// and traces them into a band buffer ([`Changes::draw_band`]). The image is at the
    /// origin (bands have no offset). The frame is taken as shown from now on: a caller
    /// that fails to send it calls [`Incremental::invalidate`].
    // Inlined, as `Render::draw` is: with a constant method only its code is linked.
    #[inline(always)]
    pub fn update<C>(&mut self, render: &Render<'_, N, C, L, P, D>) -> Changes
    where
        C: PixelColor + From<Rgb888>,
    {
        let image = Rectangle::new(Point::zero(), render.camera().size());
        let plan = self.plan_at(render, image, Point::zero(), None);
        if plan.refused.is_none() {
            self.remember_at(render, image, Point::zero(), plan.int_rule);
        } else {
            self.invalidate();
        }
        plan
    }

    // Inlined: an out-of-line call taking the render's address would make its method a
    // value in memory for the whole draw, and every method's kernel would be linked.
    #[inline(always)]
    fn remember<C>(&mut self, render: &Render<'_, N, C, L, P, D>, target: Rectangle, int_rule: IntRule) {
        self.remember_at(render, target, render.offset(), int_rule);
    }

    #[inline(always)]
    fn remember_at<C>(
        &mut self,
        render: &Render<'_, N, C, L, P, D>,
        target: Rectangle,
        offset: Point,
        int_rule: IntRule,
    ) {
        self.shown = Some(Shown {
            scene: render.scene().clone(),
            params: *render.camera().params(),
            method: render.method(),
            sampling: render.sampling(),
            options: render.options(),
            offset,
            target,
            int_rule,
        });
        self.stale = None;
    }
}
