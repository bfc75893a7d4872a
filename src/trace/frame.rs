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
use crate::method::intersect::{RowGeometry, Scale, SphereGeom, TestStrategy};
use crate::method::stepping::Stepper;
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
    /// sphere beyond `M` would be left out); `None` if nothing is visible. `others` is
    /// the largest eye-relative magnitude of the scene's other primitives (planes,
    /// point lights), which the frame's [`Scale`] must cover too (0 when there are
    /// none).
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
        camera: &'a Camera,
        options: Options,
        clip: Rectangle,
        offset: Point,
        spheres: &'a mut Vec<FrameSphere<T, Sh>, M>,
        others: f32,
    ) -> Option<Self> {
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
        let (i0, i1) = span(offset.x, size.width, clip.top_left.x, clip.size.width)?;
        let (j0, j1) = span(offset.y, size.height, clip.top_left.y, clip.size.height)?;
        // How far the stepping's directions can be from the ideal ones (widens the spans).
        let step_err = S::error_bound(camera);
        let eye = camera.eye();
        let row = RowGeometry {
            du: camera.pixel_step(),
            anchor: options.anchor_interval,
            pixel_width: camera.pixel_width(),
        };
        // Per-sphere constants and silhouettes, once per frame, in the scene's units;
        // only a scene whose magnitudes are outside the scale-1 range is built again in
        // scaled units (see `Scale`), so the usual frame pays one comparison per sphere.
        let mut scale = Scale(1.0);
        loop {
            let mut largest = others;
            // A push loop, not `collect()`: heapless' `FromIterator` panics on overflow,
            // and the optimiser cannot see that a `Scene<N>` never holds more than N.
            spheres.clear();
            for s in scene.spheres() {
                Self::push_sphere::<M, S>(spheres, s, camera, options, &row, step_err, scale);
                for m in [(s.center - eye).max_abs(), s.radius.abs()] {
                    // Comparisons pass NaN over: a NaN sphere never decides the scale.
                    if m > largest {
                        largest = m;
                    }
                }
            }
            // At most twice: the second pass finds the same magnitudes.
            let needed = Scale::for_magnitude(largest);
            if needed == scale {
                break;
            }
            scale = needed;
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

    /// One sphere's per-frame constants and silhouette, lengths scaled by `scale`.
    #[inline(always)]
    fn push_sphere<const N: usize, S: Stepper>(
        spheres: &mut Vec<FrameSphere<T, Sh>, N>,
        s: &Sphere,
        camera: &Camera,
        options: Options,
        row: &RowGeometry,
        step_err: f32,
        scale: Scale,
    ) {
        let eye = camera.eye();
        {
            let geom = SphereGeom::new(s.center, s.radius, eye, scale);
            let radius = s.radius * scale.0;
            let silhouette = if options.span_culling {
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
