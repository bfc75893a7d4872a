//! The exact paths of a frame with ties ([`Ties`]).
//!
//! The closest hit of a reflected ray among coincident objects ([`closest_twins`]) and
//! the shadow test of a light that needs the ties ([`occluded_exact`]).
//!
//! Free functions over slices ([`Objects`]), one per sphere test and root rather than
//! one per scene type and exit, so that these rare paths keep the firmware that links
//! every method within its flash.
//!
//! [`Ties`]: crate::trace::lit::ties::Ties

use crate::math::vec3::Vec3;
use crate::math::SqrtFn;
use crate::method::intersect::TestStrategy;
use crate::trace::frame::FrameSphere;
use crate::trace::lit::consts::{FramePlane, LitSphere};
use crate::trace::lit::exit::far_root;
use crate::trace::lit::object::ObjectId;
use crate::trace::lit::shadow::ShadowRay;
use crate::trace::lit::ties::Near;

/// The frame's objects and their coincident twins, for the exact paths
/// ([`closest_twins`], [`occluded_exact`]).
///
/// Slices and a flag, so that these rare paths are one function per sphere test and
/// root, not one per scene type and exit.
pub(super) struct Objects<'a, T: TestStrategy> {
    pub(super) spheres: &'a [FrameSphere<T, LitSphere>],
    pub(super) planes: &'a [FramePlane],
    /// Per sphere and plane: the lowest-numbered identical object ([`Ties`]).
    ///
    /// [`Ties`]: crate::trace::lit::ties::Ties
    pub(super) sphere_twin: &'a [ObjectId],
    pub(super) plane_twin: &'a [ObjectId],
    /// [`Exit::TESTS_SELF`].
    ///
    /// [`Exit::TESTS_SELF`]: crate::trace::lit::exit::Exit::TESTS_SELF
    pub(super) tests_self: bool,
    /// The lamp of a shadow segment beyond the light's far limit ([`FAR_FACTOR`]): its
    /// spheres are tested from this end, its planes by the signs at both ends.
    ///
    /// [`FAR_FACTOR`]: crate::trace::lit::consts::FAR_FACTOR
    pub(super) far: Option<Vec3>,
}

impl<T: TestStrategy> Objects<'_, T> {
    /// The lowest-numbered object identical to `k` (`k` itself if none).
    #[inline(always)]
    fn twin(&self, k: ObjectId) -> ObjectId {
        let n = self.spheres.len();
        let twin = if k.index() < n {
            self.sphere_twin.get(k.index())
        } else {
            self.plane_twin.get(k.index() - n)
        };
        twin.copied().unwrap_or(k)
    }

    /// [`LitRow::blocks`], the exit's flag read at run time; from the lamp's end for a
    /// segment beyond the far limit ([`Self::far`]).
    ///
    /// [`LitRow::blocks`]: crate::trace::lit::row::LitRow::blocks
    #[inline(always)]
    fn blocks<Q: SqrtFn>(&self, k: ObjectId, ray: ShadowRay) -> bool {
        let ShadowRay {
            o,
            l,
            dist,
            from,
            inside,
        } = ray;
        if let Some(s) = self.spheres.get(k.index()) {
            if !self.tests_self && k == from {
                if !inside {
                    return false;
                }
                let t = far_root(&s.geom, o, l, l.dot(l));
                return t > 0.0 && t < dist;
            }
            match self.far {
                // The same open segment, from the lamp toward `o`.
                Some(at) => T::ray::<Q>(&s.geom.seen_from(at), -l, l.dot(l), dist).is_some(),
                None => T::ray::<Q>(&s.geom.seen_from(o), l, l.dot(l), dist).is_some(),
            }
        } else if let Some(plane) = k
            .index()
            .checked_sub(self.spheres.len())
            .and_then(|p| self.planes.get(p))
        {
            if !self.tests_self && k == from {
                return false;
            }
            match self.far {
                Some(at) => plane.separates(o, at),
                None => {
                    let t = plane.t_from(o, l);
                    t > 0.0 && t < dist
                }
            }
        } else {
            false
        }
    }
}

/// [`LitRow::closest`] in a frame with coincident objects ([`Ties`]): an object with
/// a lower-numbered twin is left out, and the twin of the surface the ray leaves is
/// that surface.
///
/// The twin left out computes the same bits as the lower-numbered one, which wins the
/// tie.
///
/// [`LitRow::closest`]: crate::trace::lit::row::LitRow::closest
/// [`Ties`]: crate::trace::lit::ties::Ties
#[cold]
#[inline(never)]
pub(super) fn closest_twins<T: TestStrategy, Q: SqrtFn>(
    objects: &Objects<'_, T>,
    o: Vec3,
    dir: Vec3,
    from: ObjectId,
    inside: bool,
) -> Option<(ObjectId, f32)> {
    let from = objects.twin(from);
    let a = dir.dot(dir);
    let mut best = None;
    let mut t_max = f32::INFINITY;
    let n = objects.spheres.len();
    for k in (0..n + objects.planes.len()).map(ObjectId::new) {
        if objects.twin(k) != k {
            continue;
        }
        let leaves = !objects.tests_self && k == from;
        let t = match objects.spheres.get(k.index()) {
            Some(s) if leaves => {
                if !inside {
                    continue;
                }
                Some(far_root(&s.geom, o, dir, a)).filter(|&t| t > 0.0 && t < t_max)
            }
            Some(s) => T::ray::<Q>(&s.geom.seen_from(o), dir, a, t_max),
            None if leaves => continue,
            None => objects
                .planes
                .get(k.index() - n)
                .map(|plane| plane.t_from(o, dir))
                .filter(|&t| t > 0.0 && t < t_max),
        };
        if let Some(t) = t {
            t_max = t;
            best = Some((k, t));
        }
    }
    best
}

/// A light's lamp as [`occluded_exact`] reads it: which objects it lies on, and where
/// it is.
#[derive(Clone, Copy)]
pub(super) struct Lamp<'a> {
    /// Per sphere: whether, and on which side, the lamp lies on it ([`Ties`]).
    ///
    /// [`Ties`]: crate::trace::lit::ties::Ties
    pub(super) on_sphere: &'a [Near],
    /// Per sphere: `g = |P − C|² − r²` for a lamp within the bound outside it ([`Ties`]).
    ///
    /// [`Ties`]: crate::trace::lit::ties::Ties
    pub(super) sphere_g: &'a [f32],
    /// Per plane: the same as `on_sphere`.
    pub(super) on_plane: &'a [Near],
    /// The lamp's position (eye-relative, scaled).
    pub(super) at: Vec3,
}

/// [`LitRow::occluded`] for a light whose shadow rays need the frame's ties: every
/// object is tested, with the ties decided exactly.
///
/// No shadow span and no cached occluder: an object with a lower-numbered twin is left
/// out, the twin of the surface the ray leaves is that surface, and an object the lamp
/// lies on is decided by the side the segment reaches the lamp from ([`Ties`]).
///
/// [`LitRow::occluded`]: crate::trace::lit::row::LitRow::occluded
/// [`Ties`]: crate::trace::lit::ties::Ties
#[cold]
#[inline(never)]
pub(super) fn occluded_exact<T: TestStrategy, Q: SqrtFn>(
    objects: &Objects<'_, T>,
    lamp: Lamp<'_>,
    ray: ShadowRay,
) -> bool {
    let from = objects.twin(ray.from);
    let ray = ShadowRay { from, ..ray };
    let n = objects.spheres.len();
    for k in (0..n + objects.planes.len()).map(ObjectId::new) {
        if objects.twin(k) != k {
            continue;
        }
        let on = if k.index() < n {
            lamp.on_sphere.get(k.index())
        } else {
            lamp.on_plane.get(k.index() - n)
        };
        let near = on.copied().unwrap_or(Near::Off);
        let blocked = match (near, objects.spheres.get(k.index())) {
            (Near::Off, _) => objects.blocks::<Q>(k, ray),
            // The surface the ray leaves is never met again before the lamp on it.
            (_, _) if !objects.tests_self && k == from => false,
            // A plane the lamp lies on (within the bound): the signs at the two ends; a
            // plane through the lamp meets the segment only at its open end.
            (side, None) => {
                let h = objects.planes.get(k.index() - n).map_or(0.0, |p| p.height(ray.o));
                (side == Near::Neg && h > 0.0) || (side == Near::Pos && h < 0.0)
            }
            // A lamp inside the sphere: the segment crosses it iff it starts outside.
            (Near::Neg, Some(s)) => s.geom.seen_from(ray.o).c > 0.0,
            // A lamp outside: walked back from the lamp, the line meets the sphere at
            // s = σ ± √(σ² − g); blocked iff the near root g/(σ + √(σ² − g)) < dist.
            (Near::Pos, Some(s)) => {
                let sigma = (lamp.at - s.geom.l).dot(ray.l);
                let g = lamp.sphere_g.get(k.index()).copied().unwrap_or(0.0);
                let disc = sigma * sigma - g;
                sigma > 0.0 && disc >= 0.0 && g < ray.dist * (sigma + Q::sqrt(disc))
            }
            // The lamp on the sphere: the line meets it at the lamp and 2σ before.
            (_, Some(s)) => {
                let two_sigma = 2.0 * (lamp.at - s.geom.l).dot(ray.l);
                two_sigma > 0.0 && two_sigma < ray.dist
            }
        };
        if blocked {
            return true;
        }
    }
    false
}
