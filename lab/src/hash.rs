//! A `DrawTarget` that hashes what is drawn into it instead of storing it: proof that
//! two renders (say, on the host and on a microcontroller) produced the same pixels,
//! without a framebuffer.

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::*;

/// FNV-1a (64-bit) over the R, G, B bytes of every pixel in draw order, plus a pixel
/// count. Its bounding box is `size` at the origin; pixels drawn outside it are
/// hashed too (a render clips itself, so there are none).
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb888, prelude::*};
/// use embedded_raytracer_lab::hash::PixelHash;
///
/// let mut a = PixelHash::new(Size::new(2, 1));
/// a.draw_iter([Pixel(Point::new(0, 0), Rgb888::RED), Pixel(Point::new(1, 0), Rgb888::BLUE)]).unwrap();
/// let mut b = PixelHash::new(Size::new(2, 1));
/// b.fill_contiguous(&a.bounding_box(), [Rgb888::RED, Rgb888::BLUE]).unwrap();
/// assert_eq!((a.hash(), a.pixels()), (b.hash(), 2));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelHash {
    size: Size,
    hash: u64,
    pixels: u64,
}

const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

impl PixelHash {
    /// An empty hash for a display of `size`.
    #[must_use]
    pub const fn new(size: Size) -> Self {
        Self {
            size,
            hash: FNV_OFFSET,
            pixels: 0,
        }
    }

    /// The FNV-1a hash of everything drawn so far.
    #[must_use]
    pub const fn hash(&self) -> u64 {
        self.hash
    }

    /// How many pixels were drawn.
    #[must_use]
    pub const fn pixels(&self) -> u64 {
        self.pixels
    }

    #[inline]
    fn add(&mut self, c: Rgb888) {
        self.hash = fnv(self.hash, c);
        self.pixels += 1;
    }
}

/// One pixel's R, G, B bytes into the FNV-1a state `hash`.
#[inline(always)]
fn fnv(mut hash: u64, c: Rgb888) -> u64 {
    for byte in [c.r(), c.g(), c.b()] {
        hash = (hash ^ u64::from(byte)).wrapping_mul(FNV_PRIME);
    }
    hash
}

impl OriginDimensions for PixelHash {
    fn size(&self) -> Size {
        self.size
    }
}

impl DrawTarget for PixelHash {
    type Color = Rgb888;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb888>>>(&mut self, pixels: I) -> Result<(), Self::Error> {
        pixels.into_iter().for_each(|Pixel(_, c)| self.add(c));
        Ok(())
    }

    /// Hashes every colour the iterator yields. A render yields exactly the area's
    /// pixels; the trait would let a sink ignore any excess, but bounding the loop here
    /// (with `take` or a counter) made the QEMU-measured cost of a render ~15
    /// instructions per pixel higher by breaking up the render's row loop, and this
    /// target exists to measure that loop.
    fn fill_contiguous<I: IntoIterator<Item = Rgb888>>(
        &mut self,
        _area: &embedded_graphics::primitives::Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        // The state in locals, not behind `&mut self`: inside a render's row loop the
        // compiler would otherwise load and store it around every pixel. The count is a
        // `usize`, like `Iterator::count`'s (a `u64` costs a second register per pixel
        // on a 32-bit core).
        let (hash, pixels) = colors.into_iter().fold((self.hash, 0usize), |(hash, n), c| {
            (fnv(hash, c), n.wrapping_add(1))
        });
        self.hash = hash;
        self.pixels += pixels as u64;
        Ok(())
    }

    /// The trait's default passes an endless `repeat(color)` to `fill_contiguous`,
    /// which would never return here: hash the area's pixels directly (`clear` comes
    /// through here too).
    fn fill_solid(
        &mut self,
        area: &embedded_graphics::primitives::Rectangle,
        color: Rgb888,
    ) -> Result<(), Self::Error> {
        let n = u64::from(area.size.width) * u64::from(area.size.height);
        for _ in 0..n {
            self.add(color);
        }
        Ok(())
    }
}
