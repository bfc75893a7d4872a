//! How a secondary ray (a shadow or a reflected ray) leaves the surface it starts on,
//! chosen once per frame from [`SecondaryOrigin`] as a strategy type.
//!
//! The ray starts at a hit point computed in `f32`. The default,
//! [`SecondaryOrigin::Convex`] ([`ConvexExit`]), needs no epsilon: a sphere or plane is
//! convex, so a ray that leaves its outside cannot meet it again and it is not tested;
//! a ray leaving a sphere's inner surface meets it once more, at
//! `s = 2·(C − p)·r/(r·r)` ([`far_root`]), computed directly (no root near 0 to
//! misjudge). The textbook [`SecondaryOrigin::Epsilon`] ([`EpsilonExit`]) starts the ray
//! at `s = ε` and tests every object: it is kept to show where it fails
//! (`lab/tests/lab/lit_stability.rs`).
//!
//! [`SecondaryOrigin`]: crate::trace::options::SecondaryOrigin
//! [`SecondaryOrigin::Convex`]: crate::trace::options::SecondaryOrigin::Convex
//! [`SecondaryOrigin::Epsilon`]: crate::trace::options::SecondaryOrigin::Epsilon

use crate::math::sqrt_exact;
use crate::math::vec3::Vec3;
use crate::method::intersect::SphereGeom;

/// How a secondary ray leaves its surface, as a strategy type.
pub(crate) trait Exit {
    /// Whether the surface the ray leaves is tested like any other object.
    const TESTS_SELF: bool;
    /// The ray's origin for a ray leaving `p` along `dir`.
    fn start(p: Vec3, dir: Vec3, eps: f32) -> Vec3;
}

/// The exit of [`SecondaryOrigin::Convex`]: the surface left is not tested (a sphere's
/// inner one at its far root).
///
/// [`SecondaryOrigin::Convex`]: crate::trace::options::SecondaryOrigin::Convex
pub(crate) struct ConvexExit;
/// The exit of [`SecondaryOrigin::Epsilon`]: the ray starts `ε` along its direction and
/// every object is tested.
///
/// [`SecondaryOrigin::Epsilon`]: crate::trace::options::SecondaryOrigin::Epsilon
pub(crate) struct EpsilonExit;

impl Exit for ConvexExit {
    const TESTS_SELF: bool = false;
    #[inline(always)]
    fn start(p: Vec3, _dir: Vec3, _eps: f32) -> Vec3 {
        p
    }
}

impl Exit for EpsilonExit {
    const TESTS_SELF: bool = true;
    #[inline(always)]
    fn start(p: Vec3, dir: Vec3, eps: f32) -> Vec3 {
        p + dir * (eps / sqrt_exact(dir.dot(dir)))
    }
}

/// The second root of the sphere `g` along `o + t·dir` (`a = dir·dir`) for an origin `o`
/// on its surface, where the first root is 0.
///
/// `t = 2·(C − o)·dir/a`, positive only when the ray goes into the sphere — computed
/// directly, with no root near 0 to misjudge.
#[inline(always)]
pub(super) fn far_root(g: &SphereGeom, o: Vec3, dir: Vec3, a: f32) -> f32 {
    2.0 * (g.l - o).dot(dir) / a
}
