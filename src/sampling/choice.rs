//! The public choice of sampling: [`Sampling`], its grid size, its errors and its text
//! form.

use core::fmt;
use core::str::FromStr;

/// Rays per pixel: one at the centre, a grid, or a grid only where an edge can cross
/// the pixel (the files of `src/sampling/` document how the edges are found and each
/// rule's error bound).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Sampling {
    /// One ray through the pixel centre.
    #[default]
    Center,
    /// `n × n` rays in every pixel, averaged in linear light.
    Grid(SubSamples),
    /// `n × n` rays where an edge can cross the pixel, the centre ray elsewhere.
    Adaptive(SubSamples),
}

/// The `n` of an `n × n` grid: 2, 3 or 4 (checked by [`SubSamples::new`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SubSamples(u8);

impl SubSamples {
    /// `n × n` sub-samples.
    ///
    /// # Errors
    ///
    /// [`SamplingError::SubSamples`] unless `n` is 2, 3 or 4.
    pub const fn new(n: u32) -> Result<Self, SamplingError> {
        if n >= 2 && n <= 4 {
            Ok(Self(n as u8))
        } else {
            Err(SamplingError::SubSamples(n))
        }
    }

    /// `n`.
    #[must_use]
    pub const fn get(self) -> u32 {
        self.0 as u32
    }
}

impl Sampling {
    /// [`Sampling::Grid`] with `n × n` rays.
    ///
    /// # Errors
    ///
    /// [`SamplingError::SubSamples`] unless `n` is 2, 3 or 4.
    pub const fn grid(n: u32) -> Result<Self, SamplingError> {
        match SubSamples::new(n) {
            Ok(n) => Ok(Sampling::Grid(n)),
            Err(e) => Err(e),
        }
    }

    /// [`Sampling::Adaptive`] with `n × n` rays in edge pixels.
    ///
    /// # Errors
    ///
    /// [`SamplingError::SubSamples`] unless `n` is 2, 3 or 4.
    pub const fn adaptive(n: u32) -> Result<Self, SamplingError> {
        match SubSamples::new(n) {
            Ok(n) => Ok(Sampling::Adaptive(n)),
            Err(e) => Err(e),
        }
    }

    /// Every choice the renderer offers, for tests and tables.
    pub const ALL: [Sampling; 7] = [
        Sampling::Center,
        Sampling::Grid(SubSamples(2)),
        Sampling::Grid(SubSamples(3)),
        Sampling::Grid(SubSamples(4)),
        Sampling::Adaptive(SubSamples(2)),
        Sampling::Adaptive(SubSamples(3)),
        Sampling::Adaptive(SubSamples(4)),
    ];
}

/// Why a sampling choice was refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum SamplingError {
    /// The grid is `n × n` with `n` = 2…4; this `n` is outside.
    SubSamples(u32),
    /// Not `center`, `grid:N` or `adaptive:N`.
    Syntax,
}

impl fmt::Display for SamplingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SamplingError::SubSamples(n) => write!(f, "sub-samples per axis must be 2, 3 or 4, not {n}"),
            SamplingError::Syntax => f.write_str("expected center, grid:N or adaptive:N (N = 2, 3, 4)"),
        }
    }
}

impl core::error::Error for SamplingError {}

impl fmt::Display for Sampling {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Sampling::Center => f.write_str("center"),
            Sampling::Grid(n) => write!(f, "grid:{}", n.get()),
            Sampling::Adaptive(n) => write!(f, "adaptive:{}", n.get()),
        }
    }
}

impl FromStr for Sampling {
    type Err = SamplingError;

    /// `center`, `grid:N` or `adaptive:N`, as [`Display`](fmt::Display) writes them.
    fn from_str(s: &str) -> Result<Self, SamplingError> {
        if s == "center" {
            return Ok(Sampling::Center);
        }
        let (kind, n) = s.split_once(':').ok_or(SamplingError::Syntax)?;
        let n: u32 = n.parse().map_err(|_| SamplingError::Syntax)?;
        match kind {
            "grid" => Sampling::grid(n),
            "adaptive" => Sampling::adaptive(n),
            _ => Err(SamplingError::Syntax),
        }
    }
}
