//! The one `match` on the method: a [`Method`] value becomes the three strategy types
//! (stepping, sphere test, square root) that everything below is monomorphised over.
//!
//! The scanline renderer and the single-ray queries ([`Sphere::intersect`],
//! [`Scene::closest_hit`]) are [`Visit`]ors: each says what to do for *given* strategy
//! types, and [`dispatch`] picks them once. A new choice on an axis is one arm here;
//! nothing else matches on the method.
//!
//! [`Sphere::intersect`]: crate::Sphere::intersect
//! [`Scene::closest_hit`]: crate::Scene::closest_hit

use crate::math::{ExactSqrt, FastSqrt, SqrtFn};
use crate::method::intersect::{Algebraic, Auto, ForwardDiff, Geometric, Robust, TestStrategy};
use crate::method::stepping::{DirectStep, IncrementalStep, Stepper, WorldSpaceStep};
use crate::method::{Method, SphereTest, Sqrt, Stepping};

/// Work that is generic over the method's strategy types.
pub(crate) trait Visit {
    /// What the work returns.
    type Output;
    /// Do the work with stepping `S`, sphere test `T` and square root `Q`.
    fn visit<S: Stepper, T: TestStrategy, Q: SqrtFn>(self) -> Self::Output;
}

/// Runs `v` with the strategy types `method` names.
///
/// Always inlined: where the method is a constant (firmware's usual `Render::new` or
/// `with_method(CONST)`, and every single-ray query, whose stepping is fixed) only that
/// method's monomorphised code is linked; without it the `match` keeps every
/// combination alive (the flash each takes, measured on
/// `lab/firmware/examples/no_panic.rs`: `docs/firmware.md`, "On a Cortex-M4F",
/// Flash).
#[inline(always)]
pub(crate) fn dispatch<V: Visit>(method: Method, v: V) -> V::Output {
    #[inline(always)]
    fn with_test<V: Visit, S: Stepper>(method: Method, v: V) -> V::Output {
        match method.sphere_test {
            SphereTest::Algebraic => with_sqrt::<V, S, Algebraic>(method, v),
            SphereTest::Geometric => with_sqrt::<V, S, Geometric>(method, v),
            SphereTest::Robust => with_sqrt::<V, S, Robust>(method, v),
            SphereTest::ForwardDiff => with_sqrt::<V, S, ForwardDiff>(method, v),
            SphereTest::Auto => with_sqrt::<V, S, Auto>(method, v),
        }
    }
    #[inline(always)]
    fn with_sqrt<V: Visit, S: Stepper, T: TestStrategy>(method: Method, v: V) -> V::Output {
        match method.sqrt {
            Sqrt::Exact => v.visit::<S, T, ExactSqrt>(),
            Sqrt::Fast => v.visit::<S, T, FastSqrt>(),
        }
    }
    match method.stepping {
        Stepping::WorldSpace => with_test::<V, WorldSpaceStep>(method, v),
        Stepping::Incremental => with_test::<V, IncrementalStep>(method, v),
        Stepping::Direct => with_test::<V, DirectStep>(method, v),
    }
}

/// Runs a single-ray query `v` with the strategy types of `test` and `sqrt` (a single
/// ray has no stepping; the stepping type it is given is never used).
#[inline(always)]
pub(crate) fn dispatch_ray<V: Visit>(test: SphereTest, sqrt: Sqrt, v: V) -> V::Output {
    dispatch(Method::new(Stepping::Direct, test, sqrt), v)
}
