//! The method vocabulary: the axes of the speed/accuracy chart ([`Stepping`],
//! [`SphereTest`], [`Sqrt`]), their names, parsing and display, and [`Method`], one
//! point on the chart.
//!
//! Each axis is generated from one table by the `axis!` macro below: the enum, its
//! kebab-case names (CLI flags, scene tooling, the chart's legend), `ALL` in chart
//! order, `Display` and `FromStr`. Adding a choice is one row here plus its strategy
//! type (see `ARCHITECTURE.md`); every list of names in the CLI usage, the simulator's
//! key help, the tables and the chart is read from `NAMES`/`ALL`.

pub(crate) mod dispatch;
pub mod intersect;
mod query;
pub(crate) mod stepping;

use core::fmt;
use core::str::FromStr;

pub use crate::error::ParseMethodError;

/// One axis of the method from its table: `Variant => "kebab-name"` rows, each with
/// its doc comment.
macro_rules! axis {
    (
        $(#[$meta:meta])*
        $ty:ident, $what:literal {
            $( $(#[$vmeta:meta])* $variant:ident => $name:literal, )+
        }
    ) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        #[cfg_attr(feature = "defmt", derive(defmt::Format))]
        #[non_exhaustive]
        pub enum $ty {
            $( $(#[$vmeta])* $variant, )+
        }

        impl $ty {
            /// Every choice, in the order of the chart and the tables.
            pub const ALL: [$ty; [$($name),+].len()] = [$($ty::$variant),+];

            /// The kebab-case names, in the order of [`Self::ALL`].
            pub const NAMES: &'static [&'static str] = &[$($name),+];

            /// The kebab-case name used by the CLI.
            #[must_use]
            pub const fn name(self) -> &'static str {
                match self { $($ty::$variant => $name),+ }
            }
        }

        impl fmt::Display for $ty {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(self.name())
            }
        }

        impl FromStr for $ty {
            type Err = ParseMethodError;
            fn from_str(s: &str) -> Result<Self, Self::Err> {
                match s {
                    $($name => Ok($ty::$variant),)+
                    _ => Err(ParseMethodError { what: $what, expected: Self::NAMES }),
                }
            }
        }
    };
}

axis! {
    /// How the ray direction `p − eye` advances from pixel to pixel (strategy types in
    /// `stepping.rs`).
    Stepping, "stepping" {
        /// The slides' stepping (see the crate docs' terms): the pixel centre `p` is
        /// stepped in world space and the ray is `p − eye`.
        ///
        /// The steps are `p += pw·u` and `scanlineStart −= ph·v`. It drifts: each add
        /// rounds relative to `|p| ≈ |eye|`, so far from the origin whole pixels are
        /// lost across a wide image (how far, measured by the accuracy lab:
        /// `docs/accuracy.md`, "Failure points", Stepping drift).
        WorldSpace => "world-space",
        /// Camera-relative: each scanline's first direction is computed directly
        /// (`p(0,j) − eye`, once per row), then the direction is stepped by `pw·u` per
        /// pixel.
        ///
        /// Rounding is relative to `|p − eye| ≈ 1`, independent of where the eye is.
        Incremental => "incremental",
        /// Every pixel's direction evaluated directly, `first + j·dv + i·du`: no
        /// accumulation at all, three multiplies more per pixel.
        Direct => "direct",
    }
}

axis! {
    /// Which ray–sphere intersection formula the pixel loop uses (strategy types in
    /// `method/intersect.rs`).
    SphereTest, "sphere test" {
        /// The slides' quadratic (see [`Sphere::intersect_algebraic`](crate::Sphere::intersect_algebraic)).
        Algebraic => "algebraic",
        /// The slides' `t_ca`/`d²` construction (see [`Sphere::intersect_geometric`](crate::Sphere::intersect_geometric)).
        Geometric => "geometric",
        /// Haines et al.'s robust discriminant and stable roots (see [`Sphere::intersect_robust`](crate::Sphere::intersect_robust)).
        Robust => "robust",
        /// The robust test's discriminant `a·r² − |L × d|²` and `b = L·d`
        /// forward-differenced along each scanline (three additions per sphere and
        /// pixel).
        ///
        /// Re-anchored by direct evaluation at each span start and every
        /// [`FD_ANCHOR_INTERVAL`](crate::method::intersect::FD_ANCHOR_INTERVAL) columns.
        /// Error bound: a silhouette edge moves by at most `2⁻²⁴·K·(R + 2K)` pixels (`R` the
        /// sphere's radius on screen in pixels, `K` the anchor interval), on top of the
        /// robust test's own error. A single-ray query
        /// ([`Sphere::intersect`](crate::Sphere::intersect)) is an anchor, i.e.
        /// evaluated directly.
        ForwardDiff => "forward-diff",
        /// Adaptive: per sphere and frame, `ForwardDiff` where its error bound moves an
        /// edge by at most [`EDGE_TOLERANCE`](crate::math::EDGE_TOLERANCE), `Robust`
        /// otherwise.
        ///
        /// The rule is `2⁻²⁴·K·(R + 2K) ≤ 1/16` pixel, the eye outside the sphere. The
        /// slides' algebraic and geometric tests are never chosen: they are dearer
        /// per pixel than forward differences and fail from distance/radius ≈ 100.
        /// A scene holding more than
        /// [`AUTO_FD_CAPACITY`](crate::method::intersect::AUTO_FD_CAPACITY) (32) spheres is
        /// drawn with `Robust` for every sphere, as its render's stack would otherwise
        /// keep the forward differences' constants for each (the stack this saves:
        /// `docs/firmware.md`, "On a Cortex-M4F", Stack). Single-ray queries behave as
        /// `ForwardDiff`.
        Auto => "auto",
    }
}

axis! {
    /// Which square root the pixel loop uses (strategy types in [`math`](crate::math)).
    Sqrt, "sqrt" {
        /// Correctly rounded ([`math::sqrt_exact`](crate::math::sqrt_exact)).
        Exact => "exact",
        /// micromath's approximation, ≤ +6.07 % ([`math::sqrt_fast`](crate::math::sqrt_fast)).
        Fast => "fast",
    }
}

axis! {
    /// Which arithmetic the pixel loop uses for a scene without lights, planes or
    /// mirrors (the integer kernel in `integer/`).
    Arithmetic, "arithmetic" {
        /// IEEE `f32` with the method's stepping, sphere test and square root.
        F32 => "f32",
        /// The integer kernel: exact integer stepping, the discriminant
        /// forward-differenced exactly in `i128`, an integer square root and the Lab #1
        /// shade in Q16 — no floating point in the pixel loop.
        ///
        /// Taken per frame where
        /// its bounds keep every silhouette within
        /// [`EDGE_TOLERANCE`](crate::math::EDGE_TOLERANCE) (1/16 pixel) and every shade
        /// factor within 2⁻⁹ (under one level) of the exact one; otherwise (and for
        /// scenes with lights, planes or mirrors) the frame is drawn in `f32` with the
        /// method's other three choices.
        Integer => "integer",
    }
}

/// Whether the target has no hardware floating point, as far as `cfg` tells.
///
/// That is ARM without the hard-float ABI (`thumbv6m-none-eabi`, `thumbv7m-none-eabi`;
/// a Cortex-M4F built for the soft-float ABI counts too, every `f32` operation being a
/// call there) and RISC-V without the `F` extension (`riscv32imc-unknown-none-elf`).
/// [`Method::TARGET_DEFAULT`] takes the integer kernel there.
pub const FPU_LESS: bool = cfg!(any(
    all(target_arch = "arm", not(target_abi = "eabihf")),
    all(
        any(target_arch = "riscv32", target_arch = "riscv64"),
        not(target_feature = "f")
    )
));

/// A point on the speed/accuracy chart: stepping × sphere test × square root.
///
/// The default is `Direct` + `Auto` + `Exact`, chosen from the speed/accuracy chart
/// (`docs/speed_vs_accuracy.md`): direct evaluation of each direction has no
/// accumulated rounding (zero coverage errors against the f64 reference on every
/// standard scene, where incremental stepping loses 14 edge pixels on the 1920-wide
/// `drift` scene) and, with span culling, costs its three multiplies only where a
/// sphere can be hit; `Auto` takes the forward-differenced test where its error bound
/// allows (every sphere of the 5-sphere standard scenes, where it is on the Pareto
/// front; `crowd`'s 64 spheres take the robust test, for the stack); the
/// exact root keeps shading within one level of the reference. On a target without an
/// FPU ([`FPU_LESS`]) the default adds the integer kernel ([`Arithmetic::Integer`]),
/// which draws with this `f32` method where its rule does not take a frame.
///
/// ```
/// use embedded_raytracer::{Method, SphereTest, Stepping, Sqrt};
/// let m = Method::default();
/// assert_eq!((m.stepping, m.sphere_test, m.sqrt), (Stepping::Direct, SphereTest::Auto, Sqrt::Exact));
/// assert_eq!("world-space".parse::<Stepping>(), Ok(Stepping::WorldSpace));
/// assert_eq!("forward-diff".parse::<SphereTest>(), Ok(SphereTest::ForwardDiff));
/// assert_eq!(m.to_string(), "direct/auto/exact");
/// assert_eq!("direct/auto/exact".parse::<Method>(), Ok(m));
/// assert_eq!(Method::ALL.len(), 30);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub struct Method {
    /// Ray stepping.
    pub stepping: Stepping,
    /// Ray–sphere test.
    pub sphere_test: SphereTest,
    /// Square root.
    pub sqrt: Sqrt,
    /// Arithmetic: `F32`, or the integer kernel where its bounds hold (the other three
    /// choices then draw the frames it does not take).
    pub arithmetic: Arithmetic,
}

/// How many methods there are: the product of the axes' sizes.
const METHOD_COUNT: usize = Stepping::ALL.len() * SphereTest::ALL.len() * Sqrt::ALL.len();

impl Method {
    /// The default on this target, said at the call site: [`Method::F32`] on a target
    /// with an FPU, [`Method::INTEGER`] on one without ([`FPU_LESS`]).
    ///
    /// Without an FPU the integer kernel draws the lab scene in a fraction of the `f32`
    /// method's instructions, as exactly (measured in QEMU: `docs/firmware.md`, "The
    /// integer kernel: the default without an FPU"). `Method::default()` is this.
    pub const TARGET_DEFAULT: Method = if FPU_LESS { Method::INTEGER } else { Method::F32 };

    /// The default `f32` method (see the type's docs): `direct/auto/exact`.
    pub const F32: Method = Method::new(Stepping::Direct, SphereTest::Auto, Sqrt::Exact);

    /// The integer kernel, `direct/auto/exact` in `f32` where its bounds do not hold.
    pub const INTEGER: Method = Method::F32.with_arithmetic(Arithmetic::Integer);

    /// The lecture notes taken literally: world-space stepping, the quadratic, exact
    /// root.
    pub const LITERAL: Method = Method::new(Stepping::WorldSpace, SphereTest::Algebraic, Sqrt::Exact);

    /// A method from its three choices.
    #[must_use]
    pub const fn new(stepping: Stepping, sphere_test: SphereTest, sqrt: Sqrt) -> Self {
        Self {
            stepping,
            sphere_test,
            sqrt,
            arithmetic: Arithmetic::F32,
        }
    }

    /// The same method with another arithmetic.
    #[must_use]
    pub const fn with_arithmetic(mut self, arithmetic: Arithmetic) -> Self {
        self.arithmetic = arithmetic;
        self
    }

    /// Every `f32` combination, for charts and sweeps: stepping-major, then sphere
    /// test, then square root, each in its axis' `ALL` order.
    ///
    /// The integer kernel is
    /// [`Method::INTEGER`], not in this list: it is one point (its own stepping, test
    /// and root), and the `f32` list keeps its names, order and measured runs.
    // Indexing in a const initialiser is checked at compile time.
    #[allow(clippy::indexing_slicing)]
    pub const ALL: [Method; METHOD_COUNT] = {
        let (nt, nq) = (SphereTest::ALL.len(), Sqrt::ALL.len());
        let mut all = [Method::F32; METHOD_COUNT];
        let mut k = 0;
        while k < METHOD_COUNT {
            all[k] = Method::new(
                Stepping::ALL[k / (nt * nq)],
                SphereTest::ALL[(k / nq) % nt],
                Sqrt::ALL[k % nq],
            );
            k += 1;
        }
        all
    };
}

impl Default for Method {
    fn default() -> Self {
        Method::TARGET_DEFAULT
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.arithmetic != Arithmetic::F32 {
            write!(f, "{}/", self.arithmetic)?;
        }
        write!(f, "{}/{}/{}", self.stepping, self.sphere_test, self.sqrt)
    }
}

/// `stepping/sphere-test/sqrt` (`f32`) or `integer/stepping/sphere-test/sqrt`, as
/// `Display` writes it.
impl FromStr for Method {
    type Err = ParseMethodError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let (arithmetic, s) = match s.split_once('/') {
            Some((a, rest)) if a.parse::<Arithmetic>().is_ok() => (a.parse::<Arithmetic>()?, rest),
            _ => (Arithmetic::F32, s),
        };
        let mut parts = s.split('/');
        let (Some(stepping), Some(test), Some(sqrt), None) =
            (parts.next(), parts.next(), parts.next(), parts.next())
        else {
            return Err(ParseMethodError {
                what: "method (stepping/sphere-test/sqrt)",
                expected: &["e.g. direct/auto/exact"],
            });
        };
        Ok(Method::new(stepping.parse()?, test.parse()?, sqrt.parse()?).with_arithmetic(arithmetic))
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::string::ToString;

    /// `ALL` is the full product, every method once, and names round-trip.
    #[test]
    fn all_methods_once_and_names_round_trip() {
        for (k, a) in Method::ALL.iter().enumerate() {
            for b in &Method::ALL[k + 1..] {
                assert_ne!(a, b);
            }
        }
        for m in Method::ALL {
            assert_eq!(m.to_string().parse::<Method>(), Ok(m));
        }
        assert_eq!(Method::INTEGER.to_string(), "integer/direct/auto/exact");
        assert_eq!("integer/direct/auto/exact".parse::<Method>(), Ok(Method::INTEGER));
        assert_eq!(
            "f32/direct/auto/exact".parse::<Method>(),
            Ok(Method::new(Stepping::Direct, SphereTest::Auto, Sqrt::Exact))
        );
        for (s, name) in Stepping::ALL.iter().zip(Stepping::NAMES) {
            assert_eq!(s.name(), *name);
        }
        assert_eq!(
            "direct/auto".parse::<Method>().unwrap_err().what,
            "method (stepping/sphere-test/sqrt)"
        );
        assert_eq!(
            "direct/nope/exact".parse::<Method>(),
            Err(ParseMethodError {
                what: "sphere test",
                expected: SphereTest::NAMES
            })
        );
    }
}
