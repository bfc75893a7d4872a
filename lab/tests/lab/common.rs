//! What the integration tests share: the standard scenes (`embedded-raytracer-scenes`)
//! and tracing a render into comparable pixels.

#![allow(dead_code)]

use std::convert::Infallible;

use embedded_graphics::prelude::*;
use embedded_raytracer_scenes as standard;

#[allow(unused_imports)]
pub use standard::{load, load_full, path, FEATURE_SCENES, MAX_SPHERES, SCENES};

#[path = "../../../tests/api/helpers.rs"]
mod helpers;
pub use helpers::*;

/// A display on the host: what was drawn where, `None` where nothing was.
///
/// The tests that draw to an `Rgb565` panel share this one type: each scene type and
/// display type a test draws to builds the whole kernel again.
pub struct Panel<C> {
    size: Size,
    pub px: Vec<Option<C>>,
}

impl<C: PixelColor> Panel<C> {
    pub fn new(size: Size) -> Self {
        Self {
            size,
            px: vec![None; (size.width * size.height) as usize],
        }
    }

    /// Every pixel, all drawn.
    pub fn pixels(self) -> Vec<C> {
        self.px
            .into_iter()
            .map(|p| p.expect("every pixel drawn"))
            .collect()
    }
}

impl<C: PixelColor> OriginDimensions for Panel<C> {
    fn size(&self) -> Size {
        self.size
    }
}

impl<C: PixelColor> DrawTarget for Panel<C> {
    type Color = C;
    type Error = Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(&mut self, pixels: I) -> Result<(), Infallible> {
        for Pixel(p, c) in pixels {
            if self.bounding_box().contains(p) {
                self.px[(p.y as u32 * self.size.width + p.x as u32) as usize] = Some(c);
            }
        }
        Ok(())
    }
}
