//! The display the page's frames are drawn on, for every display model: what each pixel
//! shows and which pixels the current frame sent.
//!
//! The kernel's pixel is an `Rgb888` turned into the display's colour at the very end
//! (`C::from(Rgb888)` in its sink, or the dither adapter's `dither(colour, position)`),
//! so converting each sent pixel here gives the model's framebuffer bit for bit while
//! the kernel is compiled for one colour type only: one render per scene type in the
//! `.wasm`, not one per model.

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_raytracer::dither::Bayer;

use crate::display::Model;

/// A display model's pixels, as its colour type reads back into `Rgb888`, and the
/// pixels the current frame sent.
pub struct Screen {
    size: Size,
    model: Model,
    bayer: Bayer,
    /// Row-major, one a display pixel.
    shown: Vec<Rgb888>,
    /// Row-major: the pixel was sent since [`Screen::begin_frame`].
    sent: Vec<bool>,
}

impl Screen {
    /// A black display of `size` pixels through `model` (and `bayer`, if dithered).
    pub fn new(size: Size, model: Model, bayer: Bayer) -> Self {
        let pixels = size.width as usize * size.height as usize;
        Self {
            size,
            model,
            bayer,
            shown: vec![Rgb888::BLACK; pixels],
            sent: vec![false; pixels],
        }
    }

    /// Whether this screen is `size` pixels through `model` and `bayer`: what it shows
    /// is then what a frame drawn on such a display leaves.
    pub fn is(&self, size: Size, model: Model, bayer: Bayer) -> bool {
        self.size == size && self.model == model && self.bayer == bayer
    }

    /// Forgets which pixels were sent: a frame starts.
    pub fn begin_frame(&mut self) {
        self.sent.fill(false);
    }

    /// Sends columns `lo..hi` of row `y` of `image` (the kernel's colours, row-major,
    /// the display's size): one window, as a display driver receives it.
    pub fn send(&mut self, y: u32, lo: u32, hi: u32, image: &[Rgb888]) {
        let w = self.size.width as usize;
        for x in lo..hi.min(self.size.width) {
            let k = y as usize * w + x as usize;
            let at = Point::new(x as i32, y as i32);
            if let (Some(px), Some(sent), Some(&c)) =
                (self.shown.get_mut(k), self.sent.get_mut(k), image.get(k))
            {
                *px = self.model.shown(c, at, self.bayer);
                *sent = true;
            }
        }
    }

    /// What each pixel shows, row-major.
    pub fn shown(&self) -> &[Rgb888] {
        &self.shown
    }

    /// Which pixels the frame sent, row-major.
    pub fn sent(&self) -> &[bool] {
        &self.sent
    }

    /// The model the pixels are drawn through.
    pub fn model(&self) -> Model {
        self.model
    }

    /// The display's resolution.
    pub fn size(&self) -> Size {
        self.size
    }
}
