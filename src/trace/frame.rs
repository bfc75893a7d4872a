//! Per-frame set-up: which part of the image is visible, and each sphere's per-frame
//! constants, built in one pass.
//!
//! A sphere's constants are its geometry ([`SphereGeom`]), the sphere test's own
//! ([`TestStrategy::Consts`]), the shader's ([`Shader::Object`]) and the silhouette
//! that span culling cuts per row ([`Silhouette`]). The frame is built by the
//! spheres-only render (`lab1.rs`) and the features path (`lit/mod.rs`), then handed to
//! the scanline loop (`scanline.rs`).

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::Vec;

use crate::camera::cone::ViewCone;
use crate::camera::span::{ImageBasis, Silhouette};
use crate::camera::Camera;
use crate::error::{FrameError, ObjectRef};
use crate::math::vec3::Vec3;
use crate::method::intersect::{RowGeometry, Scale, SphereGeom, TestStrategy};
use crate::method::stepping::Stepper;
use crate::scene::light::Light;
use crate::scene::plane::Plane;
use crate::scene::sphere::Sphere;
use crate::scene::Scene;
use crate::trace::options::Options;
use crate::trace::shade::Shader;

/// A sphere as the frame sees it.
///
/// `repr(C)` with the geometry first: the tests load `L` at offset 0 of the element,
/// where one `VLDM` fetches two of its components.
#[repr(C)]
pub(crate) struct FrameSphere<T: TestStrategy, Sh: Shader> {
    /// Geometry relative to the eye.
    pub geom: SphereGeom,
    /// The sphere test's per-frame constants.
    pub test: T::Consts,
    /// The shader's per-frame constants.
    pub shade: Sh::Object,
    /// Where on the image its rays can hit it.
    pub silhouette: Silhouette,
}

/// What a frame is built from besides the scene and where it is drawn: the camera, the
/// options, and the two per-frame decisions its caller made before building it.
#[derive(Clone, Copy)]
pub(crate) struct FrameSetup<'a> {
    pub camera: &'a Camera,
    pub options: Options,
    /// The stepping's direction error bound, which widens the spans.
    pub step_err: f32,
    /// The power of two the eye-relative lengths are scaled by ([`frame_scale`]).
    pub scale: Scale,
    /// Whether [`frame_scale`] left out the spheres outside the camera's view cone.
    pub culled: bool,
}

/// Per-frame state: the visible part of the image and each sphere's constants.
pub(crate) struct Frame<'a, T: TestStrategy, Sh: Shader> {
    pub camera: &'a Camera,
    /// The power of two the spheres' eye-relative lengths are scaled by.
    pub scale: Scale,
    pub spheres: &'a [FrameSphere<T, Sh>],
    pub background: Rgb888,
    /// Visible columns `i0..i1` and rows `j0..j1` of the image.
    pub i0: u32,
    pub i1: u32,
    pub j0: u32,
    pub j1: u32,
    /// Where the image's upper-left pixel sits on the target.
    pub offset: Point,
}

impl<'a, T: TestStrategy, Sh: Shader> Frame<'a, T, Sh> {
    /// Clips the image (placed at `offset`) to `clip` and builds every sphere's
    /// per-frame constants into `spheres`; `None` if nothing is visible.
    ///
    /// `M` is at least the scene's sphere count (a sphere beyond `M` would be left
    /// out). The constants are in the frame's units, as [`frame_scale`] decided them
    /// (`setup`; the spheres outside its cone, if any, given no span), and the spans
    /// are widened by the stepping's error bound.
    ///
    /// Out of line: its temporaries (the f64 silhouette computations) are dead before
    /// the scanline loop starts, so they do not add to the pixel loop's stack.
    #[inline(never)]
    pub(crate) fn new<
        const N: usize,
        const M: usize,
        const L: usize,
        const P: usize,
        const D: usize,
        S: Stepper,
    >(
        scene: &Scene<N, L, P, D>,
        setup: FrameSetup<'a>,
        clip: Rectangle,
        offset: Point,
        spheres: &'a mut Vec<FrameSphere<T, Sh>, M>,
    ) -> Option<Self> {
        let FrameSetup {
            camera,
            options,
            step_err,
            scale,
            culled,
        } = setup;
        let (i0, i1, j0, j1) = visible(camera.size(), offset, clip)?;
        // The cone outside which the scale left spheres out (rare: rebuilt here rather
        // than carried by every caller).
        let cone = if culled {
            ViewCone::new(camera, step_err)
        } else {
            None
        };
        let row = RowGeometry {
            du: camera.pixel_step(),
            anchor: options.anchor_interval,
            pixel_width: camera.pixel_width(),
        };
        // Per-sphere constants and silhouettes, once per frame, in the frame's units.
        // A push loop, not `collect()`: heapless' `FromIterator` panics on overflow, and
        // the optimiser cannot see that a `Scene<N>` never holds more than N.
        spheres.clear();
        // The camera's part of every silhouette, once for all spheres.
        let basis = ImageBasis::of(camera);
        for s in scene.spheres() {
            // A sphere the scale left out is one no ray of the frame meets: it gets
            // no span, so its constants (outside the frame's range) are never read.
            let unseen = cone.is_some_and(|c| c.misses(s.center - camera.eye(), s.radius));
            Self::push_sphere::<M, S>(spheres, s, &setup, &basis, &row, unseen);
        }
        Some(Self {
            camera,
            scale,
            spheres,
            background: scene.background(),
            i0,
            i1,
            j0,
            j1,
            offset,
        })
    }

    /// The same frame clipped to `clip` instead (target coordinates): its visible
    /// columns and rows; `None` if it shows nothing.
    ///
    /// Its pixels are the frame's.
    #[inline(always)]
    pub(crate) fn clipped(&self, clip: Rectangle) -> Option<Self> {
        let (i0, i1, j0, j1) = visible(self.camera.size(), self.offset, clip)?;
        Some(Self {
            i0,
            i1,
            j0,
            j1,
            ..*self
        })
    }

    /// One sphere's per-frame constants and silhouette, lengths scaled by the frame's
    /// scale.
    #[inline(always)]
    fn push_sphere<const N: usize, S: Stepper>(
        spheres: &mut Vec<FrameSphere<T, Sh>, N>,
        s: &Sphere,
        setup: &FrameSetup<'_>,
        basis: &ImageBasis,
        row: &RowGeometry,
        unseen: bool,
    ) {
        let FrameSetup {
            camera,
            options,
            step_err,
            scale,
            ..
        } = *setup;
        let eye = camera.eye();
        {
            let geom = SphereGeom::new(s.center, s.radius, eye, scale);
            let radius = s.radius * scale.0;
            let silhouette = if unseen {
                Silhouette::NONE
            } else if options.span_culling {
                Silhouette::new_in(geom.l, radius, basis, T::MARGIN, step_err)
            } else {
                Silhouette::ALL
            };
            // The silhouette's size on the image, for a test whose choices depend on it
            // (Auto), computed only by such a test: the culling ellipse's (an upper
            // bound), or where that is unbounded (culling off, or a stepping margin too
            // large to cull with) the sphere's own, without the stepping margin.
            let extent = || {
                silhouette
                    .extent()
                    .or_else(|| Silhouette::new_in(geom.l, radius, basis, T::MARGIN, 0.0).extent())
            };
            // Never fails: the caller's M is at least the scene's sphere count.
            let _ = spheres.push(FrameSphere {
                geom,
                test: T::consts(&geom, row, extent),
                shade: Sh::object(s, &geom, scale, camera.w()),
                silhouette,
            });
        }
    }
}

/// The columns `i0..i1` and rows `j0..j1` of an image of `size` at `offset` that `clip`
/// shows; `None` if none.
///
/// In i64: no overflow for any offset or target size. A target whose box reaches past `i32::MAX` is clipped at the last coordinate that exists, so
/// no row wraps around and no row's area runs past `i32::MAX`. Out of line: once per
/// frame and per clip, and its 64-bit arithmetic is long on a chip without 64-bit
/// instructions, where every method's frame would otherwise carry a copy.
#[inline(never)]
pub(crate) fn visible(size: Size, offset: Point, clip: Rectangle) -> Option<(u32, u32, u32, u32)> {
    let span = |origin: i32, len: u32, clip_origin: i32, clip_len: u32| {
        let lo = i64::from(origin).max(i64::from(clip_origin));
        let hi = (i64::from(origin) + i64::from(len))
            .min(i64::from(clip_origin) + i64::from(clip_len))
            .min(i64::from(i32::MAX) + 1);
        (lo < hi).then(|| ((lo - i64::from(origin)) as u32, (hi - i64::from(origin)) as u32))
    };
    let (i0, i1) = span(offset.x, size.width, clip.top_left.x, clip.size.width)?;
    let (j0, j1) = span(offset.y, size.height, clip.top_left.y, clip.size.height)?;
    Some((i0, i1, j0, j1))
}

/// The smallest rectangle holding `a` and `b` (clamped to `i32` coordinates: a clip
/// of the target, whose pixels all have them).
pub(crate) fn hull(a: Rectangle, b: Rectangle) -> Rectangle {
    let end = |o: i32, len: u32| i64::from(o) + i64::from(len);
    let x0 = a.top_left.x.min(b.top_left.x);
    let y0 = a.top_left.y.min(b.top_left.y);
    let x1 = end(a.top_left.x, a.size.width).max(end(b.top_left.x, b.size.width));
    let y1 = end(a.top_left.y, a.size.height).max(end(b.top_left.y, b.size.height));
    let len = |lo: i32, hi: i64| (hi - i64::from(lo)).clamp(0, i64::from(u32::MAX)) as u32;
    Rectangle::new(Point::new(x0, y0), Size::new(len(x0, x1), len(y0, y1)))
}

/// The sizes a frame's [`Scale`] must bring into its exact range: the largest and the
/// smallest non-zero one, and whose they are.
///
/// An object's size is its largest
/// coordinate relative to the eye, or a sphere's radius where that is larger; one that
/// overflowed `f32` (coordinates ±10³⁸ apart) is infinite, which no scale holds.
#[derive(Clone, Copy)]
struct Sizes {
    hi: f32,
    far: ObjectRef,
    lo: f32,
    near: ObjectRef,
}

impl Sizes {
    const EMPTY: Self = Self {
        hi: 0.0,
        far: ObjectRef::Sphere(0),
        lo: f32::INFINITY,
        near: ObjectRef::Sphere(0),
    };

    /// The sizes of the planes and point lights seen from `eye`.
    #[inline(never)]
    fn of_others(planes: &[Plane], lights: &[Light], eye: Vec3) -> Self {
        let mut sizes = Self::EMPTY;
        for (i, p) in planes.iter().enumerate() {
            sizes.add(p.anchor(eye).max_abs(), ObjectRef::Plane(i));
        }
        for (i, l) in lights.iter().enumerate() {
            if let Light::Point { position, .. } = *l {
                sizes.add((position - eye).max_abs(), ObjectRef::Light(i));
            }
        }
        sizes
    }

    /// These sizes and the spheres', but for the spheres `cone` proves no ray meets.
    fn with_spheres(mut self, spheres: &[Sphere], eye: Vec3, cone: Option<&ViewCone>) -> Self {
        for (i, s) in spheres.iter().enumerate() {
            self.add_sphere(i, s, eye, cone);
        }
        self
    }

    /// One sphere's size, unless `cone` proves no ray meets it.
    ///
    /// Out of line: the frame's set-up calls it from two loops.
    #[inline(never)]
    fn add_sphere(&mut self, i: usize, s: &Sphere, eye: Vec3, cone: Option<&ViewCone>) {
        let l = s.center - eye;
        if cone.is_some_and(|c| c.misses(l, s.radius)) {
            return;
        }
        let (m, r) = (l.max_abs(), s.radius.abs());
        self.add(if r > m { r } else { m }, ObjectRef::Sphere(i));
    }

    #[inline(always)]
    fn add(&mut self, m: f32, object: ObjectRef) {
        // Comparisons pass NaN over: a NaN object never decides the scale. A size of 0
        // (a point light at the eye) needs no range.
        if m > self.hi {
            self.hi = m;
            self.far = object;
        }
        if m > 0.0 && m < self.lo {
            self.lo = m;
            self.near = object;
        }
    }

    fn scale(&self) -> Result<Scale, FrameError> {
        if !(self.hi > 0.0) {
            return Ok(Scale(1.0));
        }
        Scale::for_range(self.lo, self.hi)
            .filter(|_| self.hi.is_finite())
            .ok_or(FrameError::Magnitudes {
                far: self.far,
                near: self.near,
            })
    }
}

/// The frame's [`Scale`] and whether spheres outside the camera's [`ViewCone`] were
/// left out for it, once per frame from the scene, the camera and the method.
///
/// Never from the clip, so a band, a clipped and a whole render share it: the power of
/// two nearest 1 that brings the size of every object the frame's rays can meet into
/// `[2⁻⁴⁰, 2⁵⁰)` ([`Scale::for_range`]).
///
/// Every object counts, except where the frame's rays are primary rays through pixel
/// centres alone (`cull`, a Lab #1 frame of one ray a pixel): there a sphere outside
/// the cone of the image's rays ([`ViewCone`]) is met by no ray, and is left out when
/// the others need a range it cannot share (a sphere 10³⁰ away beside or behind the
/// eye). Where no power of two fits, the frame is refused
/// ([`FrameError::Magnitudes`]): a near object's squares would fall below `f32`'s
/// normal numbers and draw a wrong picture.
#[inline(always)]
pub(crate) fn frame_scale<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    step_err: f32,
    cull: bool,
) -> Result<(Scale, bool), FrameError> {
    // Constant conditions: a scene type without planes or lights links neither loop.
    let others = if P > 0 || L > 0 {
        Sizes::of_others(scene.planes(), scene.lights(), camera.eye())
    } else {
        Sizes::EMPTY
    };
    decide(others, scene.spheres(), camera, step_err, cull)
}

/// [`frame_scale`] past the scene's type: one function for every scene and method.
#[inline(never)]
fn decide(
    others: Sizes,
    spheres: &[Sphere],
    camera: &Camera,
    step_err: f32,
    cull: bool,
) -> Result<(Scale, bool), FrameError> {
    let eye = camera.eye();
    match others.with_spheres(spheres, eye, None).scale() {
        Ok(scale) => Ok((scale, false)),
        Err(e) => {
            let Some(cone) = ViewCone::new(camera, step_err).filter(|_| cull) else {
                return Err(e);
            };
            others
                .with_spheres(spheres, eye, Some(&cone))
                .scale()
                .map(|scale| (scale, true))
        }
    }
}
