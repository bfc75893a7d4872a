//! The features path's per-frame state ([`LitFrame`]): what every row of the frame
//! reads, built once by [`render`](crate::trace::lit::render).

use embedded_graphics::pixelcolor::Rgb888;

use crate::camera::span::Silhouette;
use crate::camera::Camera;
use crate::math::vec3::Vec3;
use crate::method::intersect::TestStrategy;
use crate::trace::frame::FrameSphere;
use crate::trace::lit::consts::{Floor, FrameLight, FramePlane, LitSphere};
use crate::trace::lit::shadow::ShadowRow;
use crate::trace::lit::ties::Ties;

/// Per-frame state of the scene-features path.
pub(super) struct LitFrame<'a, T: TestStrategy, const N: usize, const L: usize, const P: usize> {
    pub(super) spheres: &'a [FrameSphere<T, LitSphere>],
    /// Lamps on surfaces and coincident objects.
    pub(super) ties: &'a Ties<N, L, P>,
    /// [`Ties::exact_mask`]: 0 in a frame without ties, one test per shadow ray.
    pub(super) exact_lights: u32,
    /// [`Ties::twins`], where the reflected ray's loop reads it.
    pub(super) twins: bool,
    /// Per light and sphere: where on the image the sphere's shadow on the first plane
    /// can be (see [`shadow_silhouette`]).
    ///
    /// [`shadow_silhouette`]: crate::trace::lit::shadow::shadow_silhouette
    pub(super) shadow: &'a [[Silhouette; N]; L],
    /// Per light, the current row's cut of those silhouettes: one buffer for the
    /// frame, rewritten per row (a per-row array of `N × L` spans would be zeroed and
    /// moved for every row).
    pub(super) shadow_rows: &'a [ShadowRow<N>; L],
    pub(super) planes: &'a [FramePlane],
    /// The first plane's shading constants, in a scene type without reflections and
    /// where its pixels need no highlight (`floor.rs`).
    pub(super) floor: Option<&'a Floor<L>>,
    pub(super) lights: &'a [FrameLight],
    pub(super) camera: &'a Camera,
    pub(super) w: Vec3,
    pub(super) background: Rgb888,
    pub(super) bg: [f32; 3],
    pub(super) ambient: f32,
    pub(super) max_depth: u8,
    pub(super) shadows: bool,
    pub(super) any_hit: bool,
    pub(super) span_culling: bool,
    /// The epsilon of [`SecondaryOrigin::Epsilon`], scaled.
    ///
    /// [`SecondaryOrigin::Epsilon`]: crate::trace::options::SecondaryOrigin::Epsilon
    pub(super) eps: f32,
    /// The stepping's direction error bound plus the dot product's rounding: how far a
    /// computed `d·n` can be from the ideal one (planes' span margin).
    pub(super) dn_margin: f64,
    /// Visible columns.
    pub(super) i0: u32,
    pub(super) i1: u32,
}
