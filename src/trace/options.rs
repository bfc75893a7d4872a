//! What a render is asked for besides the scene, the camera and the method, and what it
//! reports per pixel.
//!
//! Its [`Options`] (span culling, the forward-differenced test's anchor interval, where
//! secondary rays start, any-hit shadow rays) and what
//! [`Render::trace`](crate::Render::trace) reports per pixel, a [`Sample`]. Small shared
//! types: every stage of tracing reads them, none of them reads a stage.

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;

use crate::math::vec3::Vec3;
use crate::method::intersect::FD_ANCHOR_INTERVAL;
use crate::scene::Hit;

/// How a render traces besides the [`Method`](crate::Method) and the
/// [`Sampling`](crate::Sampling): where shadow and reflection rays start
/// ([`SecondaryOrigin`]).
///
/// Nothing here changes what a pixel means beyond that choice.
///
/// The kernel's speed devices — span culling, any-hit shadow rays, the
/// forward-differenced test's anchor interval — are always on at their proven settings;
/// their literal baselines, for measuring them, are behind the `bench-baselines`
/// feature (`with_span_culling`, `with_shadow_any_hit`, `with_anchor_interval`).
///
/// ```
/// use embedded_raytracer::{Options, SecondaryOrigin};
/// let o = Options::DEFAULT;
/// assert_eq!(o.secondary, SecondaryOrigin::Convex);
/// assert_eq!(o.with_secondary(SecondaryOrigin::TEXTBOOK).secondary, SecondaryOrigin::Epsilon(1e-3));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Options {
    /// Where shadow and reflection rays start (default [`SecondaryOrigin::Convex`]: no
    /// epsilon).
    ///
    /// Only scenes with lights or mirrors trace such rays.
    pub secondary: SecondaryOrigin,
    /// Span culling (default on): a sphere is tested only in the columns of each row
    /// that its silhouette can reach.
    ///
    /// The silhouette is enlarged by the test's and the stepping's proven rounding
    /// margins: culling is proven to change no pixel (`tests/api/speed.rs`, bit for bit
    /// against the unculled render). Off, every sphere is tested at every pixel — the
    /// lecture notes' algorithm taken literally, the benchmarks' baseline.
    pub(crate) span_culling: bool,
    /// The anchor interval K of the forward-differenced test (default
    /// `FD_ANCHOR_INTERVAL`; `0` is taken as 1): its differences are re-evaluated
    /// directly every K columns.
    ///
    /// The edge error bound grows with K (see
    /// [`SphereTest::ForwardDiff`](crate::SphereTest::ForwardDiff)); for measuring it.
    pub(crate) anchor_interval: u32,
    /// Shadow rays stop at the first occluder, testing first the one that shadowed the
    /// previous pixel (default on).
    ///
    /// Off, every object is tested for every shadow ray,
    /// as a closest-hit search would — the benchmarks' literal baseline; no pixel
    /// changes.
    pub(crate) shadow_any_hit: bool,
}

impl Options {
    /// Secondary rays from the surface itself ([`SecondaryOrigin::Convex`]), every speed
    /// device on.
    pub const DEFAULT: Options = Options {
        span_culling: true,
        anchor_interval: FD_ANCHOR_INTERVAL,
        secondary: SecondaryOrigin::Convex,
        shadow_any_hit: true,
    };

    /// The same options with secondary rays starting as `secondary` says.
    #[must_use]
    pub const fn with_secondary(mut self, secondary: SecondaryOrigin) -> Self {
        self.secondary = secondary;
        self
    }
}

/// The literal baselines, for measuring the speed devices against them (feature
/// `bench-baselines`).
///
/// None changes a pixel's meaning: culling and any-hit shadow rays
/// change no pixel at all, the anchor interval moves the forward-differenced test's
/// pixels only within its stated error bound.
#[cfg(feature = "bench-baselines")]
impl Options {
    /// The same options with span culling on or off.
    #[must_use]
    pub const fn with_span_culling(mut self, on: bool) -> Self {
        self.span_culling = on;
        self
    }

    /// Whether span culling is on.
    #[must_use]
    pub const fn span_culling(&self) -> bool {
        self.span_culling
    }

    /// The same options with anchor interval `k` (`0` is taken as 1).
    #[must_use]
    pub const fn with_anchor_interval(mut self, k: u32) -> Self {
        self.anchor_interval = k;
        self
    }

    /// The forward-differenced test's anchor interval.
    #[must_use]
    pub const fn anchor_interval(&self) -> u32 {
        self.anchor_interval
    }

    /// The same options with any-hit shadow rays on or off.
    #[must_use]
    pub const fn with_shadow_any_hit(mut self, on: bool) -> Self {
        self.shadow_any_hit = on;
        self
    }

    /// Whether shadow rays stop at the first occluder.
    #[must_use]
    pub const fn shadow_any_hit(&self) -> bool {
        self.shadow_any_hit
    }
}

impl Default for Options {
    fn default() -> Self {
        Options::DEFAULT
    }
}

/// One traced pixel, as [`Render::trace`](crate::Render::trace) reports it.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Sample {
    /// Pixel position in the image (column, row), before the render's offset.
    pub pixel: Point,
    /// The ray direction `p − eye` the stepping produced for this pixel.
    pub direction: Vec3,
    /// The closest hit, if any.
    pub hit: Option<Hit>,
    /// The shaded colour.
    pub color: Rgb888,
    /// The rays averaged into `color`: 1 for the centre ray alone, `n²` where
    /// [`Sampling`](crate::Sampling) traced the pixel's grid (then `hit` is `None`: several rays have
    /// no single hit).
    pub rays: u32,
}

/// Where a shadow or reflection ray starts: the choice of how a secondary ray leaves
/// the surface its origin was computed on.
///
/// A speed/accuracy axis of its own (matched
/// once per frame, like the [`Method`](crate::Method)); only scenes with lights or
/// mirrors use it.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum SecondaryOrigin {
    /// No epsilon (default): the surface the ray leaves is not tested where convexity
    /// proves it cannot be met, and is met at its directly computed far root where it
    /// can.
    ///
    /// Convexity proves it when the ray leaves a plane or a sphere's outside; a ray
    /// leaving a sphere's inner surface meets it at its far root. Every other object is tested from the hit point itself.
    Convex,
    /// The textbook fixed epsilon: the ray starts at `s = ε` (scene units) along its
    /// unit direction and every object, the one it leaves included, is tested.
    ///
    /// It fails both ways: shadow acne where the hit point's rounding error (≈ 2⁻²⁴ of the
    /// coordinates' magnitude) exceeds ε, and light leaking under spheres that touch a
    /// floor where ε exceeds the occluder's chord.
    Epsilon(f32),
}

impl SecondaryOrigin {
    /// The textbook epsilon, `10⁻³` scene units.
    pub const TEXTBOOK: SecondaryOrigin = SecondaryOrigin::Epsilon(1e-3);
}

/// The CLI's name of the choice: `convex`, or `epsilon:` and the epsilon.
///
/// ```
/// use embedded_raytracer::SecondaryOrigin;
/// assert_eq!(SecondaryOrigin::Convex.to_string(), "convex");
/// assert_eq!(SecondaryOrigin::TEXTBOOK.to_string(), "epsilon:0.001");
/// ```
impl core::fmt::Display for SecondaryOrigin {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            SecondaryOrigin::Convex => f.write_str("convex"),
            SecondaryOrigin::Epsilon(eps) => write!(f, "epsilon:{eps}"),
        }
    }
}
