//! A display model's panel: its framebuffer, what draws on it through the model, and
//! the colours it shows.

use alloc::vec::Vec;
use core::convert::Infallible;

use embedded_graphics::{
    pixelcolor::{BinaryColor, Gray2, Gray4, Gray8, Rgb565, Rgb888},
    prelude::*,
};
use embedded_raytracer::{
    dither::{Bayer, DitherExt},
    Camera, Method, Options, Render, Sampling, Scene,
};

use crate::framebuffer::Framebuffer;
use crate::{Model, Theme};

/// Work that draws on a panel: called once with the target the model puts in front of
/// the framebuffer (the framebuffer itself, or the kernel's dither in front of it).
pub trait Paint {
    /// What the work returns (statistics of the frame, or nothing).
    type Output;

    /// Draws on `target`, whose colour type is the model's (or the dither's `Rgb888`).
    fn paint<T>(self, target: &mut T) -> Self::Output
    where
        T: DrawTarget<Error = Infallible>,
        T::Color: From<Rgb888>;
}

/// A whole frame of the kernel: a scene through a camera with a method, options and
/// sampling, for any colour type.
#[derive(Clone, Copy)]
pub struct Frame<'a, const N: usize, const L: usize = 0, const P: usize = 0, const D: usize = 0> {
    /// The scene.
    pub scene: &'a Scene<N, L, P, D>,
    /// The camera; its size should be the panel's.
    pub camera: &'a Camera,
    /// The method of every ray.
    pub method: Method,
    /// The options (the secondary rays' origin, …).
    pub options: Options,
    /// Rays per pixel.
    pub sampling: Sampling,
}

impl<'a, const N: usize, const L: usize, const P: usize, const D: usize> Frame<'a, N, L, P, D> {
    /// `scene` through `camera` with the default method, options and sampling.
    pub fn new(scene: &'a Scene<N, L, P, D>, camera: &'a Camera) -> Self {
        Self {
            scene,
            camera,
            method: Method::default(),
            options: Options::DEFAULT,
            sampling: Sampling::Center,
        }
    }
}

impl<const N: usize, const L: usize, const P: usize, const D: usize> Paint for Frame<'_, N, L, P, D> {
    type Output = ();

    fn paint<T>(self, target: &mut T)
    where
        T: DrawTarget<Error = Infallible>,
        T::Color: From<Rgb888>,
    {
        let render = Render::new(self.scene, self.camera)
            .with_method(self.method)
            .with_options(self.options)
            .with_sampling(self.sampling);
        let Ok(()) = render.draw(target);
    }
}

/// The framebuffer of a display model: its own colour type, as the firmware's display
/// holds it (a dithered model's is the undithered model's type).
enum Pixels {
    Rgb888(Framebuffer<Rgb888>),
    Rgb565(Framebuffer<Rgb565>),
    Gray8(Framebuffer<Gray8>),
    Gray4(Framebuffer<Gray4>),
    Gray2(Framebuffer<Gray2>),
    Binary(Framebuffer<BinaryColor>),
}

/// A panel of a display model: its framebuffer (dark at first), kept from frame to
/// frame, and the Bayer matrix of a dithered model.
pub struct Panel {
    model: Model,
    bayer: Bayer,
    pixels: Pixels,
}

impl Panel {
    /// A dark panel of `model` of `size` pixels; `bayer` is the dither's matrix (unused
    /// by a model without dither).
    pub fn new(model: Model, bayer: Bayer, size: Size) -> Self {
        let pixels = match model {
            Model::Rgb888 => Pixels::Rgb888(Framebuffer::new(size)),
            Model::Rgb565 => Pixels::Rgb565(Framebuffer::new(size)),
            Model::Gray8 => Pixels::Gray8(Framebuffer::new(size)),
            Model::Gray4 | Model::Gray4Dither => Pixels::Gray4(Framebuffer::new(size)),
            Model::Gray2 | Model::Gray2Dither => Pixels::Gray2(Framebuffer::new(size)),
            Model::Binary | Model::BinaryDither => Pixels::Binary(Framebuffer::new(size)),
        };
        Self { model, bayer, pixels }
    }

    /// The panel's model.
    pub fn model(&self) -> Model {
        self.model
    }

    /// The dither's matrix.
    pub fn bayer(&self) -> Bayer {
        self.bayer
    }

    /// Whether frames drawn through `model` and `bayer` land on this panel as they
    /// would on a new one: the same model, and for a dithered one the same matrix.
    pub fn shows(&self, model: Model, bayer: Bayer) -> bool {
        model == self.model && (!model.is_dithered() || bayer == self.bayer)
    }

    /// Runs `work` on the panel through its model: on the framebuffer, or on the
    /// kernel's ordered dither in front of it.
    pub fn paint<W: Paint>(&mut self, work: W) -> W::Output {
        let dithered = self.model.is_dithered();
        let b = self.bayer;
        match &mut self.pixels {
            Pixels::Rgb888(f) => work.paint(f),
            Pixels::Rgb565(f) => work.paint(f),
            Pixels::Gray8(f) => work.paint(f),
            Pixels::Gray4(f) if dithered => work.paint(&mut f.dithered_with(b)),
            Pixels::Gray4(f) => work.paint(f),
            Pixels::Gray2(f) if dithered => work.paint(&mut f.dithered_with(b)),
            Pixels::Gray2(f) => work.paint(f),
            Pixels::Binary(f) if dithered => work.paint(&mut f.dithered_with(b)),
            Pixels::Binary(f) => work.paint(f),
        }
    }

    /// The colours the panel shows, one a pixel, row-major: each pixel's colour as
    /// embedded-graphics converts it to `Rgb888`, through `theme` on a 1-bit panel.
    pub fn shown(&self, theme: Theme) -> Vec<Rgb888> {
        match &self.pixels {
            Pixels::Rgb888(f) => plain(f),
            Pixels::Rgb565(f) => plain(f),
            Pixels::Gray8(f) => plain(f),
            Pixels::Gray4(f) => plain(f),
            Pixels::Gray2(f) => plain(f),
            Pixels::Binary(f) => f.pixels().iter().map(|&c| theme.show(c.into())).collect(),
        }
    }
}

/// A framebuffer's colours as `Rgb888`.
fn plain<C: PixelColor + Into<Rgb888>>(framebuffer: &Framebuffer<C>) -> Vec<Rgb888> {
    framebuffer.pixels().iter().map(|&c| c.into()).collect()
}

#[cfg(test)]
mod tests {
    extern crate std;

    use super::*;
    use embedded_graphics_simulator::{
        BinaryColorTheme, OutputSettings, OutputSettingsBuilder, SimulatorDisplay,
    };
    use embedded_raytracer::dither::DitherColor;
    use embedded_raytracer_scenes as standard;

    /// What the simulator's window shows of a `C` display (its own conversion and theme).
    fn window<C: PixelColor + Into<Rgb888>>(
        display: &SimulatorDisplay<C>,
        settings: &OutputSettings,
    ) -> Vec<Rgb888> {
        let image = display.to_rgb_output_image(settings);
        image
            .as_image_buffer()
            .as_raw()
            .chunks_exact(3)
            .map(|p| Rgb888::new(p[0], p[1], p[2]))
            .collect()
    }

    /// `frame` drawn on a simulator display of colour `C`, shown in the window.
    fn simulated<C, const N: usize, const L: usize, const P: usize, const D: usize>(
        frame: Frame<'_, N, L, P, D>,
        dither: Option<Bayer>,
        settings: &OutputSettings,
    ) -> Vec<Rgb888>
    where
        C: DitherColor + From<Rgb888> + Into<Rgb888> + From<BinaryColor>,
    {
        let mut display = SimulatorDisplay::<C>::new(frame.camera.size());
        match dither {
            Some(b) => frame.paint(&mut display.dithered_with(b)),
            None => frame.paint(&mut display),
        }
        window(&display, settings)
    }

    /// `frame` through `model` as the simulator shows it: the model's colour type, the
    /// dither in front for a dithered model, the OLED theme for a binary one.
    fn simulator<const N: usize, const L: usize, const P: usize, const D: usize>(
        frame: Frame<'_, N, L, P, D>,
        model: Model,
        bayer: Bayer,
        theme: BinaryColorTheme,
    ) -> Vec<Rgb888> {
        let theme = if model.is_binary() {
            theme
        } else {
            BinaryColorTheme::Default
        };
        let s = OutputSettingsBuilder::new()
            .scale(1)
            .pixel_spacing(0)
            .theme(theme)
            .build();
        let b = model.is_dithered().then_some(bayer);
        match model {
            Model::Rgb888 => {
                let mut display = SimulatorDisplay::<Rgb888>::new(frame.camera.size());
                frame.paint(&mut display);
                window(&display, &s)
            }
            Model::Rgb565 => {
                let mut display = SimulatorDisplay::<Rgb565>::new(frame.camera.size());
                frame.paint(&mut display);
                window(&display, &s)
            }
            Model::Gray8 => {
                let mut display = SimulatorDisplay::<Gray8>::new(frame.camera.size());
                frame.paint(&mut display);
                window(&display, &s)
            }
            Model::Gray4 | Model::Gray4Dither => simulated::<Gray4, N, L, P, D>(frame, b, &s),
            Model::Gray2 | Model::Gray2Dither => simulated::<Gray2, N, L, P, D>(frame, b, &s),
            Model::Binary | Model::BinaryDither => simulated::<BinaryColor, N, L, P, D>(frame, b, &s),
        }
    }

    /// Every model, matrix and theme shows the simulator's pixels of the same frame, on
    /// a spheres-only scene and on one with lights, a floor and mirrors.
    #[test]
    fn the_panel_shows_what_the_simulator_shows() {
        let lab = standard::load("lab");
        let shadows = standard::load_full("shadows");
        let lab_camera = lab.camera.params().with_size(Size::new(48, 36)).build().unwrap();
        let shadows_camera = shadows
            .camera
            .params()
            .with_size(Size::new(40, 40))
            .build()
            .unwrap();
        let themes = [
            (Theme::OledBlue, BinaryColorTheme::OledBlue),
            (Theme::OledWhite, BinaryColorTheme::OledWhite),
        ];
        for model in Model::ALL {
            for bayer in [Bayer::Four, Bayer::Eight] {
                for (theme, simulator_theme) in themes {
                    let frame = Frame::new(&lab.scene, &lab_camera);
                    let mut panel = Panel::new(model, bayer, lab_camera.size());
                    panel.paint(frame);
                    let want = simulator(frame, model, bayer, simulator_theme);
                    assert!(panel.shown(theme) == want, "lab {model:?} {bayer:?} {theme:?}");

                    let frame = Frame::new(&shadows.scene, &shadows_camera);
                    let mut panel = Panel::new(model, bayer, shadows_camera.size());
                    panel.paint(frame);
                    let want = simulator(frame, model, bayer, simulator_theme);
                    assert!(
                        panel.shown(theme) == want,
                        "shadows {model:?} {bayer:?} {theme:?}"
                    );
                }
            }
        }
    }

    /// A panel starts dark, and a frame painted again over itself changes nothing.
    #[test]
    fn a_new_panel_is_dark_and_painting_is_idempotent() {
        let size = Size::new(8, 4);
        for model in Model::ALL {
            let panel = Panel::new(model, Bayer::Eight, size);
            let dark = if model.is_binary() {
                Theme::OledBlue.off()
            } else {
                Rgb888::BLACK
            };
            assert!(
                panel.shown(Theme::OledBlue).iter().all(|&c| c == dark),
                "{model:?}"
            );
            assert_eq!(panel.shown(Theme::OledBlue).len(), 32);
        }
        let lab = standard::load("lab");
        let camera = lab.camera.params().with_size(Size::new(24, 18)).build().unwrap();
        let mut panel = Panel::new(Model::Gray2Dither, Bayer::Four, camera.size());
        panel.paint(Frame::new(&lab.scene, &camera));
        let once = panel.shown(Theme::OledBlue);
        panel.paint(Frame::new(&lab.scene, &camera));
        assert!(panel.shown(Theme::OledBlue) == once);
        assert!(panel.shows(Model::Gray2Dither, Bayer::Four));
        assert!(!panel.shows(Model::Gray2Dither, Bayer::Eight));
        assert!(!panel.shows(Model::Gray2, Bayer::Four));
        assert!(Panel::new(Model::Gray2, Bayer::Four, size).shows(Model::Gray2, Bayer::Eight));
    }
}
