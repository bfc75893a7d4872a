//! Ordered (Bayer) dithering for low-depth displays, as a [`DrawTarget`] adapter.
//!
//! The adapter takes the shaded [`Rgb888`] stream and writes [`BinaryColor`], [`Gray2`]
//! or [`Gray4`] to the display, so a 1-bit SSD1306 shows the spheres' shading as a dot
//! density instead of a hard threshold.
//!
//! The adapter sits between the render and the driver and keeps no state between
//! pixels: every pixel's output depends only on its colour and its position on the
//! target, so rows stream straight through (`fill_contiguous` in, `fill_contiguous`
//! out), with no buffer and no allocation, and clipping or
//! [`Render::with_offset`](crate::Render::with_offset) cannot shift the pattern.
//!
//! ## The quantisation
//!
//! 1. **Luma.** `L = Gray8::from(rgb).luma()`, the ITU-R BT.601 integer luma
//!    embedded-graphics itself uses for `Rgb888 → Gray8`:
//!    `L = (77·R + 150·G + 29·B + 128) / 256`, `0 ≤ L ≤ 255`.
//! 2. **Scale to the output's levels.** With `M` the output's maximum level (1 for
//!    `BinaryColor`, 3 for `Gray2`, 15 for `Gray4`), `L·M = 255·q + r` with
//!    `0 ≤ r < 255`: the ideal level is `q + r/255`, between the two representable
//!    levels `q` and `q + 1`.
//! 3. **Threshold by position.** For the `n × n` Bayer index matrix `B` (`n` = 4 or 8,
//!    `c = n²` cells, each index `0 … c−1` once) and the pixel at target position
//!    `(x, y)`, with `b = B[y mod n][x mod n]`, the output is `q + 1` when
//!    `r/255 > (b + ½)/c`, otherwise `q`. This is evaluated exactly in integers:
//!    `r > ⌊255·(2b + 1)/(2c)⌋`, with the right-hand side tabulated per position at
//!    compile time, so there is no rounding anywhere in the stage and the per-pixel
//!    work is the luma, one multiply, a division by the constant 255, one table
//!    lookup and one compare.
//!
//! ## Error behaviour
//!
//! - Each pixel is `q` or `q + 1`: never more than one output level from the input
//!   (a hard threshold is within ½ level; dithering trades that for the right mean).
//! - Black (`L = 0`) gives level 0 and white (`L = 255`) gives level `M` at every
//!   position (then `r = 0`, and `r/255 > (b + ½)/c` is never true).
//! - Over any `n × n` window of a flat field (aligned or not: the window holds every
//!   index `b` once) the number of `q + 1` pixels is `k = #{b : b + ½ < c·r/255}`,
//!   i.e. `c·r/255` rounded to the nearest integer (halves down), so the window's mean level is
//!   `q + k/c` and differs from the ideal `L·M/255` by at most `1/(2c)` of one output
//!   level — `≤ 1/(2·M·c)` of full scale: 1/32 of a level (4×4) and 1/128 (8×8).
//!   Between two output levels the 4×4 matrix can show 17 distinct window means and
//!   the 8×8 matrix 65, so on a 1-bit display lumas closer than 255/16 (4×4) or
//!   255/64 (8×8) may dither to the same pattern.
//!
//! ```
//! use embedded_graphics::{mock_display::MockDisplay, pixelcolor::{BinaryColor, Rgb888}, prelude::*};
//! use embedded_raytracer::dither::{Bayer, DitherExt};
//!
//! let mut display = MockDisplay::<BinaryColor>::new();
//! // A 50 % grey field (luma 128) through the 4×4 matrix is a checkerboard.
//! display
//!     .dithered_with(Bayer::Four)
//!     .fill_solid(&embedded_graphics::primitives::Rectangle::new(Point::zero(), Size::new(4, 2)), Rgb888::new(128, 128, 128))?;
//! display.assert_pattern(&["#.#.", ".#.#"]);
//! # Ok::<(), core::convert::Infallible>(())
//! ```
//!
//! Rendering through it: the render's colour type is inferred as `Rgb888` from the
//! adapter.
//!
//! ```
//! use embedded_graphics::{mock_display::MockDisplay, pixelcolor::{BinaryColor, Rgb888}, prelude::*};
//! use embedded_raytracer::{dither::DitherExt, Camera, Render, Scene, Sphere, Vec3};
//!
//! static SCENE: Scene<1> = Scene::from_array(
//!     [Sphere::new(Vec3::new(0.0, 0.0, 0.0), 1.0, Rgb888::new(255, 255, 255))],
//!     Rgb888::BLACK,
//! );
//! let camera = Camera::new(
//!     Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0),
//!     0.5, Size::new(32, 32),
//! )?;
//! let mut display = MockDisplay::<BinaryColor>::new();
//! Render::new(&SCENE, &camera).draw(&mut display.dithered())?;
//! assert_eq!(display.get_pixel(Point::new(16, 16)), Some(BinaryColor::On)); // lit centre
//! assert_eq!(display.get_pixel(Point::new(0, 0)), Some(BinaryColor::Off)); // background
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use embedded_graphics::pixelcolor::{BinaryColor, Gray2, Gray4, Gray8, GrayColor, PixelColor, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

/// The Bayer index matrix of the ordered dither.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Bayer {
    /// 4×4, 16 thresholds: a coarser, more visible pattern; the mean of a flat field is
    /// within 1/32 of an output level.
    Four,
    /// 8×8, 64 thresholds (default): the mean of a flat field is within 1/128 of an
    /// output level.
    #[default]
    Eight,
}

impl Bayer {
    /// The matrix side `n`.
    #[must_use]
    pub const fn side(self) -> u32 {
        match self {
            Bayer::Four => 4,
            Bayer::Eight => 8,
        }
    }

    /// The number of cells `c = n²` (distinct thresholds).
    #[must_use]
    pub const fn cells(self) -> u32 {
        self.side() * self.side()
    }

    /// The Bayer index `b ∈ 0 … n²−1` at target position `(x, y)`, periodic with period
    /// `n` in both directions (negative coordinates included).
    ///
    /// The recursive construction `M₂ₙ = [[4Mₙ, 4Mₙ+2], [4Mₙ+3, 4Mₙ+1]]` read bit by
    /// bit: the lowest bit pair of `(x, y)` picks the most significant base-4 digit,
    /// with digit `2·(x⊕y) + y` (0 ↖, 2 ↗, 3 ↙, 1 ↘).
    ///
    /// ```
    /// use embedded_raytracer::dither::Bayer;
    /// let row0: Vec<u32> = (0..4).map(|x| Bayer::Four.index(x, 0)).collect();
    /// assert_eq!(row0, [0, 8, 2, 10]);
    /// assert_eq!(Bayer::Four.index(-1, -1), Bayer::Four.index(3, 3));
    /// ```
    #[must_use]
    pub const fn index(self, x: i32, y: i32) -> u32 {
        let bits = match self {
            Bayer::Four => 2,
            Bayer::Eight => 3,
        };
        // Two's complement: `& 1` of each bit is the Euclidean remainder's bit, so the
        // pattern continues across negative coordinates without a seam.
        let (x, y) = (x as u32, y as u32);
        let mut b = 0;
        let mut k = 0;
        while k < bits {
            let xb = (x >> k) & 1;
            let yb = (y >> k) & 1;
            b = (b << 2) | (2 * (xb ^ yb) + yb);
            k += 1;
        }
        b
    }

    /// The output level (`0 ..= max`) for luma `luma` at target position `(x, y)`:
    /// steps 2 and 3 of the [module docs](self), exact in integers (see
    /// [`threshold`](Self::threshold)).
    ///
    /// ```
    /// use embedded_raytracer::dither::Bayer;
    /// // Luma 128 on a 1-bit display: on where the 8×8 index is below 32.
    /// assert_eq!(Bayer::Eight.level(128, 1, 0, 0), 1);
    /// assert_eq!(Bayer::Eight.level(128, 1, 1, 0), 0);
    /// ```
    #[must_use]
    #[inline]
    pub fn level(self, luma: u8, max: u8, x: i32, y: i32) -> u8 {
        let scaled = u32::from(luma) * u32::from(max); // ≤ 255·255
        let q = scaled / 255;
        let r = scaled % 255;
        // r/255 > (b + ½)/c, through the per-position threshold table.
        let up = r > u32::from(self.threshold(x, y));
        (q + u32::from(up)) as u8
    }

    /// The integer threshold at target position `(x, y)`: level `q + 1` when
    /// `r > threshold`.
    ///
    /// It is `⌊255·(2b + 1) / (2c)⌋`, exact because `r` is an integer
    /// (`r > X/(2c) ⇔ r > ⌊X/(2c)⌋`), so the table lookup is the rule of step 3.
    ///
    /// ```
    /// use embedded_raytracer::dither::Bayer;
    /// assert_eq!(Bayer::Four.threshold(0, 0), 7); // b = 0: ⌊255/32⌋
    /// assert_eq!(Bayer::Four.threshold(0, 3), 247); // b = 15: ⌊255·31/32⌋
    /// ```
    #[must_use]
    #[inline]
    pub fn threshold(self, x: i32, y: i32) -> u8 {
        match self {
            Bayer::Four => lookup(&THRESHOLDS_4, x, y),
            Bayer::Eight => lookup(&THRESHOLDS_8, x, y),
        }
    }
}

/// Per-position thresholds of the 4×4 matrix, built once at compile time.
const THRESHOLDS_4: [[u8; 4]; 4] = thresholds(Bayer::Four);
/// Per-position thresholds of the 8×8 matrix.
const THRESHOLDS_8: [[u8; 8]; 8] = thresholds(Bayer::Eight);

/// `⌊255·(2b + 1) / (2c)⌋` for every position of the matrix (≤ 253, fits a `u8`).
// Compile-time indexing within the array's own bounds.
#[allow(clippy::indexing_slicing)]
const fn thresholds<const N: usize>(m: Bayer) -> [[u8; N]; N] {
    let mut t = [[0u8; N]; N];
    let c = m.cells();
    let mut y = 0;
    while y < N {
        let mut x = 0;
        while x < N {
            let b = m.index(x as i32, y as i32);
            t[y][x] = (255 * (2 * b + 1) / (2 * c)) as u8;
            x += 1;
        }
        y += 1;
    }
    t
}

/// The table entry at `(x mod N, y mod N)`; `N` is a power of two, so masking the
/// two's-complement coordinate is the Euclidean remainder (negative positions included)
/// and the lookup cannot miss.
#[inline(always)]
fn lookup<const N: usize>(table: &[[u8; N]; N], x: i32, y: i32) -> u8 {
    let mask = N - 1;
    table
        .get(y as usize & mask)
        .and_then(|row| row.get(x as usize & mask))
        .copied()
        .unwrap_or(0)
}

/// A display colour the dither can produce: `MAX` + 1 evenly spaced levels.
pub trait DitherColor: PixelColor {
    /// The maximum level `M` (the number of levels is `M + 1`).
    const MAX: u8;
    /// The colour of level `0 ..= MAX` (larger values are clamped to `MAX`).
    fn from_level(level: u8) -> Self;
}

impl DitherColor for BinaryColor {
    const MAX: u8 = 1;
    fn from_level(level: u8) -> Self {
        BinaryColor::from(level != 0)
    }
}

impl DitherColor for Gray2 {
    const MAX: u8 = 3;
    fn from_level(level: u8) -> Self {
        Gray2::new(level.min(Self::MAX))
    }
}

impl DitherColor for Gray4 {
    const MAX: u8 = 15;
    fn from_level(level: u8) -> Self {
        Gray4::new(level.min(Self::MAX))
    }
}

/// The dithered colour of `color` at target position `point` (the whole stage for one
/// pixel: luma, scale, threshold).
///
/// ```
/// use embedded_graphics::{pixelcolor::{Gray2, Rgb888}, prelude::*};
/// use embedded_raytracer::dither::{dither, Bayer};
/// assert_eq!(dither::<Gray2>(Rgb888::WHITE, Point::new(5, 7), Bayer::Eight), Gray2::WHITE);
/// assert_eq!(dither::<Gray2>(Rgb888::BLACK, Point::new(5, 7), Bayer::Eight), Gray2::BLACK);
/// ```
#[inline]
#[must_use]
pub fn dither<C: DitherColor>(color: Rgb888, point: Point, matrix: Bayer) -> C {
    let luma = Gray8::from(color).luma();
    C::from_level(matrix.level(luma, C::MAX, point.x, point.y))
}

/// A [`DrawTarget`] with `Rgb888` colour that dithers every pixel into the wrapped
/// low-depth target.
///
/// Made by [`DitherExt::dithered`]; see the [module docs](self) for the quantisation and
/// its error bound.
///
/// Every call is forwarded one to one (`fill_contiguous` → `fill_contiguous`,
/// `draw_iter` → `draw_iter`) with the same area and the same number of pixels, so each
/// pixel reaches the inner target exactly once and the inner target's clipping and
/// fast paths apply unchanged.
#[derive(Debug)]
pub struct Dithered<'a, D> {
    target: &'a mut D,
    matrix: Bayer,
}

impl<'a, D> Dithered<'a, D>
where
    D: DrawTarget,
    D::Color: DitherColor,
{
    /// Wraps `target`, dithering with `matrix`.
    pub fn new(target: &'a mut D, matrix: Bayer) -> Self {
        Self { target, matrix }
    }

    /// The matrix in use.
    #[must_use]
    pub const fn matrix(&self) -> Bayer {
        self.matrix
    }
}

impl<D> Dimensions for Dithered<'_, D>
where
    D: DrawTarget,
{
    fn bounding_box(&self) -> Rectangle {
        self.target.bounding_box()
    }
}

impl<D> DrawTarget for Dithered<'_, D>
where
    D: DrawTarget,
    D::Color: DitherColor,
{
    type Color = Rgb888;
    type Error = D::Error;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Rgb888>>,
    {
        let matrix = self.matrix;
        self.target.draw_iter(
            pixels
                .into_iter()
                .map(move |Pixel(p, c)| Pixel(p, dither(c, p, matrix))),
        )
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Rgb888>,
    {
        // The colours come in row-major order over `area` (the DrawTarget contract), so
        // pairing them with `area.points()` gives each one its target position.
        let matrix = self.matrix;
        self.target.fill_contiguous(
            area,
            area.points().zip(colors).map(move |(p, c)| dither(c, p, matrix)),
        )
    }

    fn fill_solid(&mut self, area: &Rectangle, color: Rgb888) -> Result<(), Self::Error> {
        // A flat colour is not flat after dithering: stream the pattern.
        self.fill_contiguous(area, core::iter::repeat(color))
    }

    fn clear(&mut self, color: Rgb888) -> Result<(), Self::Error> {
        let area = self.target.bounding_box();
        self.fill_solid(&area, color)
    }
}

/// `display.dithered()`: an `Rgb888` view of a `BinaryColor`, `Gray2` or `Gray4`
/// target through the ordered dither.
pub trait DitherExt: DrawTarget + Sized
where
    Self::Color: DitherColor,
{
    /// The dithering view with the 8×8 matrix.
    fn dithered(&mut self) -> Dithered<'_, Self> {
        Dithered::new(self, Bayer::Eight)
    }

    /// The dithering view with a chosen matrix.
    fn dithered_with(&mut self, matrix: Bayer) -> Dithered<'_, Self> {
        Dithered::new(self, matrix)
    }
}

impl<D> DitherExt for D
where
    D: DrawTarget,
    D::Color: DitherColor,
{
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::mock_display::MockDisplay;

    fn grey(v: u8) -> Rgb888 {
        Rgb888::new(v, v, v)
    }

    fn rect(x: i32, y: i32, w: u32, h: u32) -> Rectangle {
        Rectangle::new(Point::new(x, y), Size::new(w, h))
    }

    #[test]
    fn bayer_matrices_are_the_standard_ones() {
        // The textbook 4×4 Bayer matrix.
        let expected4 = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];
        for (y, row) in expected4.iter().enumerate() {
            for (x, &b) in row.iter().enumerate() {
                assert_eq!(Bayer::Four.index(x as i32, y as i32), b, "({x}, {y})");
            }
        }
        // The textbook 8×8 matrix's first two rows.
        let row0 = [0, 32, 8, 40, 2, 34, 10, 42];
        let row1 = [48, 16, 56, 24, 50, 18, 58, 26];
        for x in 0..8 {
            assert_eq!(Bayer::Eight.index(x, 0), row0[x as usize]);
            assert_eq!(Bayer::Eight.index(x, 1), row1[x as usize]);
        }
        // Each index exactly once, and periodic (negative coordinates included).
        for m in [Bayer::Four, Bayer::Eight] {
            let n = m.side() as i32;
            let mut seen = [false; 64];
            for y in 0..n {
                for x in 0..n {
                    let b = m.index(x, y) as usize;
                    assert!(!seen[b], "{m:?} index {b} twice");
                    seen[b] = true;
                    assert_eq!(m.index(x - n, y - 3 * n), m.index(x, y));
                    assert_eq!(m.index(x + 5 * n, y + n), m.index(x, y));
                }
            }
            assert_eq!(seen.iter().filter(|&&s| s).count(), m.cells() as usize);
        }
    }

    #[test]
    fn threshold_tables_are_the_exact_rule() {
        // r > T[b]  ⇔  r/255 > (b + ½)/c, i.e. 2·r·c > 255·(2b + 1), for every r.
        for m in [Bayer::Four, Bayer::Eight] {
            let c = m.cells();
            for y in 0..m.side() as i32 {
                for x in 0..m.side() as i32 {
                    let b = m.index(x, y);
                    let t = u32::from(m.threshold(x, y));
                    for r in 0..255u32 {
                        assert_eq!(r > t, 2 * r * c > 255 * (2 * b + 1), "{m:?} b {b} r {r}");
                    }
                }
            }
        }
    }

    #[test]
    fn binary_flat_fields_give_the_bayer_patterns() {
        // Luma 128 (r/255 = 0.502): on where b < 8 — the 4×4 checkerboard.
        let mut d = MockDisplay::<BinaryColor>::new();
        d.dithered_with(Bayer::Four)
            .fill_solid(&rect(0, 0, 8, 4), grey(128))
            .unwrap();
        d.assert_pattern(&["#.#.#.#.", ".#.#.#.#", "#.#.#.#.", ".#.#.#.#"]);

        // Luma 64 (0.251): on where b < 4 → b ∈ {0, 1, 2, 3} at (0,0), (2,2), (2,0), (0,2).
        let mut d = MockDisplay::<BinaryColor>::new();
        d.dithered_with(Bayer::Four)
            .fill_solid(&rect(0, 0, 4, 4), grey(64))
            .unwrap();
        d.assert_pattern(&["#.#.", "....", "#.#.", "...."]);

        // Luma 16 (0.0627 > 1/32 = (0 + ½)/16, < 3/32): only b = 0.
        let mut d = MockDisplay::<BinaryColor>::new();
        d.dithered_with(Bayer::Four)
            .fill_solid(&rect(0, 0, 8, 4), grey(16))
            .unwrap();
        d.assert_pattern(&["#...#...", "........", "........", "........"]);

        // Luma 192 (0.753): off only where b ≥ 12 → (0,1), (2,1), (0,3), (2,3).
        let mut d = MockDisplay::<BinaryColor>::new();
        d.dithered_with(Bayer::Four)
            .fill_solid(&rect(0, 0, 4, 4), grey(192))
            .unwrap();
        d.assert_pattern(&["####", ".#.#", "####", ".#.#"]);

        // 8×8 at luma 32 (0.1255·64 = 8.03 → 8 cells on: b ∈ 0..8).
        let mut d = MockDisplay::<BinaryColor>::new();
        d.dithered().fill_solid(&rect(0, 0, 8, 8), grey(32)).unwrap();
        d.assert_pattern(&[
            "#...#...", //
            "........", "..#...#.", "........", "#...#...", "........", "..#...#.", "........",
        ]);
    }

    #[test]
    fn gray_flat_fields_give_the_bayer_patterns() {
        // Gray2, luma 128: 128·3 = 384 = 255 + 129 → between levels 1 and 2, r/255 =
        // 0.506 → level 2 where b < 8.
        let mut d = MockDisplay::<Gray2>::new();
        d.dithered_with(Bayer::Four)
            .fill_solid(&rect(0, 0, 4, 4), grey(128))
            .unwrap();
        d.assert_pattern(&["2121", "1212", "2121", "1212"]);

        // Gray4, luma 100: 100·15 = 1500 = 5·255 + 225 → levels 5 and 6, r/255 = 0.882
        // → 6 where b < 14.6, i.e. b ≤ 13: 5 only at b = 14 (2,1) and b = 15 (0,3).
        let mut d = MockDisplay::<Gray4>::new();
        d.dithered_with(Bayer::Four)
            .fill_solid(&rect(0, 0, 4, 4), grey(100))
            .unwrap();
        d.assert_pattern(&["6666", "6656", "6666", "5666"]);

        // Gray4 levels that are exact (luma 17·k) are flat.
        let mut d = MockDisplay::<Gray4>::new();
        d.dithered().fill_solid(&rect(0, 0, 8, 8), grey(17 * 10)).unwrap();
        d.assert_pattern(&["AAAAAAAA"; 8]);
    }

    #[test]
    fn black_stays_black_and_white_stays_white() {
        fn check<C: DitherColor + core::fmt::Debug>(black: C, white: C) {
            for m in [Bayer::Four, Bayer::Eight] {
                for y in -9..9 {
                    for x in -9..9 {
                        let p = Point::new(x, y);
                        assert_eq!(dither::<C>(Rgb888::BLACK, p, m), black);
                        assert_eq!(dither::<C>(Rgb888::WHITE, p, m), white);
                    }
                }
            }
        }
        check(BinaryColor::Off, BinaryColor::On);
        check(Gray2::BLACK, Gray2::WHITE);
        check(Gray4::BLACK, Gray4::WHITE);
        // Saturated colours go by their luma, not a channel: pure blue is dark (29/256).
        assert_eq!(Gray8::from(Rgb888::BLUE).luma(), 29);
    }

    #[test]
    fn window_mean_equals_the_input_level_within_the_bound() {
        // Every luma, every output depth, both matrices, aligned and unaligned windows:
        // each pixel is q or q+1, and the window's mean is within 1/(2c) of a level.
        fn check(max: u8) {
            for m in [Bayer::Four, Bayer::Eight] {
                let n = m.side() as i32;
                let c = m.cells() as f64;
                for luma in 0..=255u8 {
                    let ideal = f64::from(luma) * f64::from(max) / 255.0;
                    let q = (u32::from(luma) * u32::from(max) / 255) as u8;
                    for (ox, oy) in [(0, 0), (3, -5)] {
                        let mut sum = 0u32;
                        for y in oy..oy + n {
                            for x in ox..ox + n {
                                let l = m.level(luma, max, x, y);
                                assert!(l == q || l == q + 1, "luma {luma} max {max}: level {l}");
                                sum += u32::from(l);
                            }
                        }
                        let mean = f64::from(sum) / c;
                        assert!(
                            (mean - ideal).abs() <= 0.5 / c + 1e-12,
                            "luma {luma}, max {max}, {m:?}: mean {mean} vs {ideal}"
                        );
                    }
                }
            }
        }
        check(1);
        check(3);
        check(15);
    }

    #[test]
    fn the_bound_is_tight() {
        // Where the bound is nearly reached: 1-bit, 4×4. Luma 7 (7/255 = 0.0275 < 1/32)
        // lights nothing; luma 8 (0.0314 > 1/32) lights exactly one cell of 16, so the
        // mean 1/16 is off by 1/16 − 8/255 = 0.03113, within 1/8160 of the bound 1/32.
        let lit = |luma: u8| -> u32 {
            (0..4)
                .flat_map(|y| (0..4).map(move |x| (x, y)))
                .map(|(x, y)| u32::from(Bayer::Four.level(luma, 1, x, y)))
                .sum()
        };
        assert_eq!(lit(7), 0);
        assert_eq!(lit(8), 1);
        let err = 1.0 / 16.0 - 8.0 / 255.0;
        assert!(err <= 1.0 / 32.0 && 1.0 / 32.0 - err < 1.0 / 8000.0);
    }

    #[test]
    fn fill_contiguous_and_draw_iter_agree_and_key_by_target_position() {
        // A gradient drawn at an odd offset: fill_contiguous positions come from the
        // area, draw_iter positions from each pixel; both must match the per-pixel
        // function at the *target* position.
        let area = rect(3, 5, 13, 7);
        let color_at = |p: Point| grey((p.x * 17 + p.y * 5) as u8);
        let mut a = MockDisplay::<Gray2>::new();
        a.dithered()
            .fill_contiguous(&area, area.points().map(color_at))
            .unwrap();
        let mut b = MockDisplay::<Gray2>::new();
        b.dithered()
            .draw_iter(area.points().map(|p| Pixel(p, color_at(p))))
            .unwrap();
        a.assert_eq(&b);
        for p in area.points() {
            assert_eq!(
                a.get_pixel(p),
                Some(dither::<Gray2>(color_at(p), p, Bayer::Eight))
            );
        }
        assert_eq!(a.affected_area(), area);
    }

    #[test]
    fn render_with_offset_is_keyed_by_target_position_every_pixel_once() {
        use crate::{Camera, Render, Scene, Sphere, Vec3};
        static SCENE: Scene<2> = Scene::from_array(
            [
                Sphere::new(Vec3::new(0.0, 0.0, 0.0), 1.0, Rgb888::new(255, 200, 100)),
                Sphere::new(Vec3::new(0.9, 0.6, -1.0), 0.8, Rgb888::new(60, 255, 60)),
            ],
            Rgb888::new(40, 40, 40),
        );
        let camera = Camera::new(
            Vec3::new(0.0, 0.0, 5.0),
            Vec3::ZERO,
            Vec3::new(0.0, 1.0, 0.0),
            0.6,
            Size::new(40, 30),
        )
        .unwrap();
        let offset = Point::new(7, 11);
        // Reference: the Rgb888 render, then the per-pixel dither at target positions.
        let mut reference = MockDisplay::<Rgb888>::new();
        Render::new(&SCENE, &camera).draw(&mut reference).unwrap();
        // MockDisplay panics on overdraw: the dithered render writes every pixel once.
        let mut d = MockDisplay::<BinaryColor>::new();
        Render::new(&SCENE, &camera)
            .with_offset(offset)
            .draw(&mut d.dithered())
            .unwrap();
        assert_eq!(d.affected_area(), Rectangle::new(offset, Size::new(40, 30)));
        let mut lit = 0;
        for p in Rectangle::new(Point::zero(), Size::new(40, 30)).points() {
            let src = reference.get_pixel(p).unwrap();
            let got = d.get_pixel(p + offset).unwrap();
            assert_eq!(got, dither::<BinaryColor>(src, p + offset, Bayer::Eight), "{p:?}");
            lit += u32::from(got.is_on());
        }
        // The shading shows as dot density: some but not all pixels are lit.
        assert!(lit > 0 && lit < 40 * 30);
    }

    #[test]
    fn clipped_render_passes_each_visible_pixel_once() {
        // Counts what reaches the inner target: a render partly off the 64×64 mock
        // display must deliver exactly the visible pixels.
        struct Count(MockDisplay<Gray4>, u32);
        impl Dimensions for Count {
            fn bounding_box(&self) -> Rectangle {
                self.0.bounding_box()
            }
        }
        impl DrawTarget for Count {
            type Color = Gray4;
            type Error = core::convert::Infallible;
            fn draw_iter<I: IntoIterator<Item = Pixel<Gray4>>>(&mut self, it: I) -> Result<(), Self::Error> {
                for Pixel(p, c) in it {
                    self.1 += 1;
                    self.0.draw_pixel(p, c); // panics on overdraw or out of bounds
                }
                Ok(())
            }
        }
        use crate::{Camera, Render, Scene, Sphere, Vec3};
        static SCENE: Scene<1> = Scene::from_array(
            [Sphere::new(
                Vec3::new(0.0, 0.0, 0.0),
                1.0,
                Rgb888::new(200, 120, 90),
            )],
            Rgb888::BLACK,
        );
        let camera = Camera::new(
            Vec3::new(0.0, 0.0, 4.0),
            Vec3::ZERO,
            Vec3::new(0.0, 1.0, 0.0),
            0.7,
            Size::new(50, 40),
        )
        .unwrap();
        let mut t = Count(MockDisplay::new(), 0);
        Render::new(&SCENE, &camera)
            .with_offset(Point::new(30, -10))
            .draw(&mut t.dithered_with(Bayer::Four))
            .unwrap();
        assert_eq!(t.1, 34 * 30);
        assert_eq!(t.0.affected_area(), rect(30, 0, 34, 30));
    }
}
