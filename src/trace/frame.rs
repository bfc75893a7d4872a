//! Per-frame set-up: which part of the image is visible, and each object's per-frame
//! constants — geometry ([`SphereGeom`]), the sphere test's own constants
//! ([`TestStrategy::Consts`]), the shader's ([`Shader::Object`]) and the silhouette
//! that span culling cuts per row ([`Silhouette`]) — all built in one pass.
//!
//! The frame is built by the spheres-only render (`lab1.rs`) and the features path
//! (`lit.rs`), then handed to the scanline loop (`scanline.rs`).

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::Vec;

use crate::camera::span::Silhouette;
use crate::camera::Camera;
use crate::error::{FrameError, ObjectRef};
use crate::math::vec3::Vec3;
use crate::method::intersect::{RowGeometry, Scale, SphereGeom, TestStrategy};
use crate::method::stepping::Stepper;
use crate::scene::light::Light;
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
    /// per-frame constants into `spheres` (`M` at least the scene's sphere count: a
    /// sphere beyond `M` would be left out) in the frame's units ([`frame_scale`];
    /// `cull`: the frame's rays are primary rays through pixel centres alone); `None`
    /// if nothing is visible, the frame's [`FrameError`] if it cannot be drawn exactly.
    ///
    /// Out of line: its temporaries (the f64 silhouette computations) are dead before
    /// the scanline loop starts, so they do not add to the pixel loop's stack.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new<
        const N: usize,
        const M: usize,
        const L: usize,
        const P: usize,
        const D: usize,
        S: Stepper,
    >(
        scene: &Scene<N, L, P, D>,
        camera: &'a Camera,
        options: Options,
        clip: Rectangle,
        offset: Point,
        spheres: &'a mut Vec<FrameSphere<T, Sh>, M>,
        cull: bool,
    ) -> Result<Option<Self>, FrameError> {
        let size = camera.size();
        // Clip in i64: no overflow for any offset or target size. A target whose box
        // reaches past `i32::MAX` is clipped at the last coordinate that exists, so no
        // row wraps around and no row's area runs past `i32::MAX`.
        let span = |origin: i32, len: u32, clip_origin: i32, clip_len: u32| {
            let lo = i64::from(origin).max(i64::from(clip_origin));
            let hi = (i64::from(origin) + i64::from(len))
                .min(i64::from(clip_origin) + i64::from(clip_len))
                .min(i64::from(i32::MAX) + 1);
            (lo < hi).then(|| ((lo - i64::from(origin)) as u32, (hi - i64::from(origin)) as u32))
        };
        let Some((i0, i1)) = span(offset.x, size.width, clip.top_left.x, clip.size.width) else {
            return Ok(None);
        };
        let Some((j0, j1)) = span(offset.y, size.height, clip.top_left.y, clip.size.height) else {
            return Ok(None);
        };
        let (scale, culled) = frame_scale::<N, L, P, D, S, T>(scene, camera, options, cull)?;
        // How far the stepping's directions can be from the ideal ones (widens the spans).
        let step_err = S::error_bound(camera);
        let row = RowGeometry {
            du: camera.pixel_step(),
            anchor: options.anchor_interval,
            pixel_width: camera.pixel_width(),
        };
        // Per-sphere constants and silhouettes, once per frame, in the frame's units.
        // A push loop, not `collect()`: heapless' `FromIterator` panics on overflow, and
        // the optimiser cannot see that a `Scene<N>` never holds more than N.
        spheres.clear();
        for s in scene.spheres() {
            // A sphere the scale left out is one no ray of the frame meets: it gets
            // no span, so its constants (outside the frame's range) are never read.
            let unseen = culled && !seen::<T>(s, camera, step_err);
            Self::push_sphere::<M, S>(spheres, s, camera, options, &row, step_err, scale, unseen);
        }
        Ok(Some(Self {
            camera,
            scale,
            spheres,
            background: scene.background(),
            i0,
            i1,
            j0,
            j1,
            offset,
        }))
    }

    /// One sphere's per-frame constants and silhouette, lengths scaled by `scale`.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn push_sphere<const N: usize, S: Stepper>(
        spheres: &mut Vec<FrameSphere<T, Sh>, N>,
        s: &Sphere,
        camera: &Camera,
        options: Options,
        row: &RowGeometry,
        step_err: f32,
        scale: Scale,
        unseen: bool,
    ) {
        let eye = camera.eye();
        {
            let geom = SphereGeom::new(s.center, s.radius, eye, scale);
            let radius = s.radius * scale.0;
            let silhouette = if unseen {
                Silhouette::NONE
            } else if options.span_culling {
                Silhouette::new(geom.l, radius, camera, T::MARGIN, step_err)
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
                    .or_else(|| Silhouette::new(geom.l, radius, camera, T::MARGIN, 0.0).extent())
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

/// The sizes a frame's [`Scale`] must bring into its exact range: the largest and the
/// smallest non-zero one, and whose they are. An object's size is its largest
/// coordinate relative to the eye, or a sphere's radius where that is larger.
#[derive(Clone, Copy)]
struct Sizes {
    hi: f32,
    far: ObjectRef,
    lo: f32,
    near: ObjectRef,
    /// The first object whose size overflowed `f32`.
    not_finite: Option<ObjectRef>,
}

impl Sizes {
    const EMPTY: Self = Self {
        hi: 0.0,
        far: ObjectRef::Sphere(0),
        lo: f32::INFINITY,
        near: ObjectRef::Sphere(0),
        not_finite: None,
    };

    #[inline(always)]
    fn add(&mut self, m: f32, object: ObjectRef) {
        if m == f32::INFINITY {
            if self.not_finite.is_none() {
                self.not_finite = Some(object);
            }
            return;
        }
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
        if let Some(o) = self.not_finite {
            return Err(FrameError::NotFinite(o));
        }
        if !(self.hi > 0.0) {
            return Ok(Scale(1.0));
        }
        Scale::for_range(self.lo, self.hi).ok_or(FrameError::Magnitudes {
            far: self.far,
            near: self.near,
        })
    }
}

/// A sphere's size (see [`Sizes`]).
#[inline(always)]
fn sphere_size(s: &Sphere, eye: Vec3) -> f32 {
    let (l, r) = ((s.center - eye).max_abs(), s.radius.abs());
    if r > l {
        r
    } else {
        l
    }
}

/// Whether a primary ray through a pixel centre of the whole image can meet the
/// sphere: its silhouette, enlarged for the test's rounding and the stepping's error,
/// meets the image, or where it is not a bounded ellipse, the sphere is not outside
/// the image's cone of rays. Computed in the scene's own units (the silhouette is homogeneous
/// in the lengths, and its `f64` arithmetic holds any finite `f32` geometry).
fn seen<T: TestStrategy>(s: &Sphere, camera: &Camera, step_err: f32) -> bool {
    let l = s.center - camera.eye();
    let silhouette = Silhouette::new(l, s.radius, camera, T::MARGIN, step_err);
    if silhouette.is_all() {
        // Not a bounded ellipse (beside or behind the eye): the cone of the image.
        !Silhouette::outside_view(l, s.radius, camera, T::MARGIN, step_err)
    } else {
        silhouette.meets_image(camera.size())
    }
}

/// The frame's [`Scale`], once per frame from the scene, the camera and the method —
/// never from the clip, so a band, a clipped and a whole render share it: the power of
/// two nearest 1 that brings the size of every object the frame's rays can meet into
/// `[2⁻⁴⁰, 2⁵⁰)` ([`Scale::for_range`]), and whether spheres were left out for it.
///
/// Every object counts, except where the frame's rays are primary rays through pixel
/// centres alone (`cull`, a Lab #1 frame of one ray a pixel with span culling): there a
/// sphere outside the view ([`seen`]) is met by no ray, and is left out when the others
/// need a range it cannot share (a sphere 10³⁰ away behind the eye). Where no power of
/// two fits, the frame is refused ([`FrameError::Magnitudes`]): a near object's
/// squares would fall below `f32`'s normal numbers and draw a wrong picture.
#[inline(never)]
pub(crate) fn frame_scale<
    const N: usize,
    const L: usize,
    const P: usize,
    const D: usize,
    S: Stepper,
    T: TestStrategy,
>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    options: Options,
    cull: bool,
) -> Result<(Scale, bool), FrameError> {
    let eye = camera.eye();
    let mut sizes = Sizes::EMPTY;
    for (i, p) in scene.planes().iter().enumerate() {
        sizes.add((p.point - eye).max_abs(), ObjectRef::Plane(i));
    }
    for (i, l) in scene.lights().iter().enumerate() {
        if let Light::Point { position, .. } = *l {
            sizes.add((position - eye).max_abs(), ObjectRef::Light(i));
        }
    }
    let others = sizes;
    for (i, s) in scene.spheres().iter().enumerate() {
        sizes.add(sphere_size(s, eye), ObjectRef::Sphere(i));
    }
    match sizes.scale() {
        Ok(scale) => Ok((scale, false)),
        Err(e) if !(cull && options.span_culling) => Err(e),
        Err(_) => {
            let step_err = S::error_bound(camera);
            let mut seen_sizes = others;
            for (i, s) in scene.spheres().iter().enumerate() {
                if seen::<T>(s, camera, step_err) {
                    seen_sizes.add(sphere_size(s, eye), ObjectRef::Sphere(i));
                }
            }
            seen_sizes.scale().map(|scale| (scale, true))
        }
    }
}
