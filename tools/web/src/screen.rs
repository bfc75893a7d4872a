//! The display the page's frames are drawn on, for every display model: what each pixel
//! shows and which pixels the current frame sent.
//!
//! The kernel's pixel is an `Rgb888` turned into the display's colour at the very end
//! (`C::from(Rgb888)` in its sink, or the dither adapter's `dither(colour, position)`),
//! so converting each sent pixel here gives the model's framebuffer bit for bit while
//! the kernel is compiled for one colour type only: one render per scene type in the
//! `.wasm`, not one per model.

use embedded_graphics::pixelcolor::{BinaryColor, Gray2, Gray4, Gray8, Rgb565, Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_raytracer::dither::{dither, Bayer};

use embedded_raytracer_display::Model;

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
                *px = show(self.model, c, at, self.bayer);
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

/// The colour a display of `model` shows for the kernel's `color` at `at`, read back as
/// `Rgb888` (before any OLED theme): what the firmware's `C::from(Rgb888)`, or the
/// dither in front of a low-depth panel, writes, as embedded-graphics converts it back.
///
/// The shared display crate's `Panel` draws through a target of each model's colour
/// type instead; the page converts pixel by pixel so that the kernel is compiled once.
pub fn show(model: Model, color: Rgb888, at: Point, bayer: Bayer) -> Rgb888 {
    match model {
        Model::Rgb888 => color,
        Model::Rgb565 => Rgb565::from(color).into(),
        Model::Gray8 => Gray8::from(color).into(),
        Model::Gray4 => Gray4::from(color).into(),
        Model::Gray2 => Gray2::from(color).into(),
        Model::Binary => BinaryColor::from(color).into(),
        Model::Gray4Dither => dither::<Gray4>(color, at, bayer).into(),
        Model::Gray2Dither => dither::<Gray2>(color, at, bayer).into(),
        Model::BinaryDither => dither::<BinaryColor>(color, at, bayer).into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_raytracer_display::{Frame, Panel, Theme};
    use embedded_raytracer_scenes as standard;

    /// Converting the kernel's `Rgb888` frame pixel by pixel shows what the display
    /// crate's panel of each model shows (drawn through the model's colour type and
    /// dither), for both matrices and both themes.
    #[test]
    fn each_pixel_converted_is_the_panels() {
        let lab = standard::load("lab");
        let camera = lab.camera.params().with_size(Size::new(40, 30)).build().unwrap();
        let frame = Frame::new(&lab.scene, &camera);
        let mut rgb = Panel::new(Model::Rgb888, Bayer::Eight, camera.size());
        rgb.paint(frame);
        let image = rgb.shown(Theme::OledBlue);
        for model in Model::ALL {
            for bayer in [Bayer::Four, Bayer::Eight] {
                let mut screen = Screen::new(camera.size(), model, bayer);
                for y in 0..camera.size().height {
                    screen.send(y, 0, camera.size().width, &image);
                }
                let mut panel = Panel::new(model, bayer, camera.size());
                panel.paint(frame);
                for theme in Theme::ALL {
                    let shown: Vec<Rgb888> = screen
                        .shown()
                        .iter()
                        .map(|&c| if model.is_binary() { theme.show(c) } else { c })
                        .collect();
                    assert!(shown == panel.shown(theme), "{model:?} {bayer:?} {theme:?}");
                }
            }
        }
    }
}
