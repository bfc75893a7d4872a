//! The number of an object a ray meets in the features path: spheres first, then
//! planes.
//!
//! An [`ObjectId`] is made from an index of the frame's objects, so it never stands for
//! "no object": the one value that does is [`LastOccluder::NONE`], the empty cache of a
//! light's last occluder, a type of its own.

/// The object a hit is on: spheres `0 … n − 1`, then planes `n …` (the frame's order).
///
/// The index itself, no wider: comparing, counting and indexing with it cost what they
/// cost with a `usize`.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
#[repr(transparent)]
pub(super) struct ObjectId(usize);

impl ObjectId {
    /// The object at `index` of the frame's numbering (an index of its spheres, or the
    /// sphere count plus an index of its planes).
    #[inline(always)]
    pub(super) const fn new(index: usize) -> Self {
        Self(index)
    }

    /// Its index: a sphere's below the frame's sphere count, else that count plus its
    /// plane's.
    #[inline(always)]
    pub(super) const fn index(self) -> usize {
        self.0
    }
}

/// A light's last occluder on the current row ([`ObjectId`]), or none yet.
///
/// A `usize`, not an `Option<ObjectId>`: the empty value is the one index no slice has
/// (`usize::MAX`), so the cache is one word and its test one comparison.
#[derive(Clone, Copy)]
pub(super) struct LastOccluder(usize);

impl LastOccluder {
    /// No occluder cached.
    pub(super) const NONE: Self = Self(usize::MAX);

    /// The cache holding `k`.
    #[inline(always)]
    pub(super) const fn of(k: ObjectId) -> Self {
        Self(k.0)
    }

    /// The object cached, if any.
    #[inline(always)]
    pub(super) fn get(self) -> Option<ObjectId> {
        (self.0 != Self::NONE.0).then_some(ObjectId(self.0))
    }

    /// Whether `k` is the object cached.
    #[inline(always)]
    pub(super) fn holds(self, k: ObjectId) -> bool {
        self.0 == k.0
    }
}
