//! A display model's panel: its framebuffer, what draws on it through the model, and
//! the colours it shows.

use alloc::vec::Vec;
use core::convert::Infallible;

use embedded_graphics::{
    pixelcolor::{BinaryColor, Gray2, Gray4, Gray8, Rgb565, Rgb888},
    prelude::*,
    primitives::Rectangle,
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

    /// Draws on `target`: [`Panel::paint`] passes an `Rgb888` view of the panel that
    /// converts to the model's colour type.
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
    ///
    /// The work sees one `Rgb888` view of the panel whatever the model, so it is built
    /// once, not once per colour type; the view converts each call's colours as a
    /// target of the model's own type would (`C::from(Rgb888)`, or the dither).
    pub fn paint<W: Paint>(&mut self, work: W) -> W::Output {
        let dither = self.model.is_dithered().then_some(self.bayer);
        work.paint(&mut View {
            pixels: &mut self.pixels,
            dither,
        })
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

/// The panel as one `Rgb888` target: each call is passed on to the framebuffer in the
/// model's colour type, through the ordered dither when `dither` is set (a dithered
/// model's framebuffer is `Gray4`, `Gray2` or `BinaryColor`).
struct View<'a> {
    pixels: &'a mut Pixels,
    dither: Option<Bayer>,
}

impl OriginDimensions for View<'_> {
    fn size(&self) -> Size {
        match &*self.pixels {
            Pixels::Rgb888(f) => f.size(),
            Pixels::Rgb565(f) => f.size(),
            Pixels::Gray8(f) => f.size(),
            Pixels::Gray4(f) => f.size(),
            Pixels::Gray2(f) => f.size(),
            Pixels::Binary(f) => f.size(),
        }
    }
}

/// One drawing call, made on whichever target the view stands for.
trait Call {
    fn on<T>(self, target: &mut T)
    where
        T: DrawTarget<Error = Infallible>,
        T::Color: From<Rgb888>;
}

impl View<'_> {
    /// Makes `call` on the framebuffer (or the dither in front of it).
    fn pass<K: Call>(&mut self, call: K) {
        match (&mut *self.pixels, self.dither) {
            (Pixels::Rgb888(f), _) => call.on(f),
            (Pixels::Rgb565(f), _) => call.on(f),
            (Pixels::Gray8(f), _) => call.on(f),
            (Pixels::Gray4(f), Some(b)) => call.on(&mut f.dithered_with(b)),
            (Pixels::Gray4(f), None) => call.on(f),
            (Pixels::Gray2(f), Some(b)) => call.on(&mut f.dithered_with(b)),
            (Pixels::Gray2(f), None) => call.on(f),
            (Pixels::Binary(f), Some(b)) => call.on(&mut f.dithered_with(b)),
            (Pixels::Binary(f), None) => call.on(f),
        }
    }
}

/// `draw_iter` of `Rgb888` pixels.
struct DrawIter<I>(I);

impl<I: IntoIterator<Item = Pixel<Rgb888>>> Call for DrawIter<I> {
    fn on<T>(self, target: &mut T)
    where
        T: DrawTarget<Error = Infallible>,
        T::Color: From<Rgb888>,
    {
        let Ok(()) = target.draw_iter(self.0.into_iter().map(|Pixel(p, c)| Pixel(p, c.into())));
    }
}

/// `fill_contiguous` of `Rgb888` colours over an area.
struct FillContiguous<'r, I>(&'r Rectangle, I);

impl<I: IntoIterator<Item = Rgb888>> Call for FillContiguous<'_, I> {
    fn on<T>(self, target: &mut T)
    where
        T: DrawTarget<Error = Infallible>,
        T::Color: From<Rgb888>,
    {
        let Ok(()) = target.fill_contiguous(self.0, self.1.into_iter().map(Into::into));
    }
}

// `fill_solid` and `clear` keep their defaults (a repeated colour through
// `fill_contiguous`), which is what the framebuffer's and the dither's do as well.
impl DrawTarget for View<'_> {
    type Color = Rgb888;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<Rgb888>>,
    {
        self.pass(DrawIter(pixels));
        Ok(())
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Rgb888>,
    {
        self.pass(FillContiguous(area, colors));
        Ok(())
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

    /// The traced colours of `frame`, drawn by the kernel on a simulator display.
    fn traced<const N: usize, const L: usize, const P: usize, const D: usize>(
        frame: Frame<'_, N, L, P, D>,
    ) -> Vec<Rgb888> {
        let mut display = SimulatorDisplay::<Rgb888>::new(frame.camera.size());
        frame.paint(&mut display);
        window(
            &display,
            &OutputSettingsBuilder::new().scale(1).pixel_spacing(0).build(),
        )
    }

    /// `traced` colours drawn on a simulator display of colour `C`, converted by
    /// embedded-graphics, shown in the window.
    fn converted<C>(traced: &[Rgb888], size: Size, settings: &OutputSettings) -> Vec<Rgb888>
    where
        C: PixelColor + From<Rgb888> + Into<Rgb888> + From<BinaryColor>,
    {
        let mut display = SimulatorDisplay::<C>::new(size);
        let area = Rectangle::new(Point::zero(), size);
        let Ok(()) = display.fill_contiguous(&area, traced.iter().map(|&c| C::from(c)));
        window(&display, settings)
    }

    /// `traced` colours drawn on a simulator display of colour `C` (through the
    /// kernel's dither when `dither` is set), shown in the window.
    fn simulated<C>(
        traced: &[Rgb888],
        size: Size,
        dither: Option<Bayer>,
        settings: &OutputSettings,
    ) -> Vec<Rgb888>
    where
        C: DitherColor + From<Rgb888> + Into<Rgb888> + From<BinaryColor>,
    {
        let Some(b) = dither else {
            return converted::<C>(traced, size, settings);
        };
        let mut display = SimulatorDisplay::<C>::new(size);
        let area = Rectangle::new(Point::zero(), size);
        let Ok(()) = display
            .dithered_with(b)
            .fill_contiguous(&area, traced.iter().copied());
        window(&display, settings)
    }

    /// `traced` colours of a frame of `size` on a display of `model` as the simulator
    /// shows them: the model's colour type, the dither in front for a dithered model,
    /// the OLED theme for a binary one.
    fn simulator(
        traced: &[Rgb888],
        size: Size,
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
            Model::Rgb888 => converted::<Rgb888>(traced, size, &s),
            Model::Rgb565 => converted::<Rgb565>(traced, size, &s),
            Model::Gray8 => converted::<Gray8>(traced, size, &s),
            Model::Gray4 | Model::Gray4Dither => simulated::<Gray4>(traced, size, b, &s),
            Model::Gray2 | Model::Gray2Dither => simulated::<Gray2>(traced, size, b, &s),
            Model::Binary | Model::BinaryDither => simulated::<BinaryColor>(traced, size, b, &s),
        }
    }

    /// Every model, matrix and theme shows the simulator's pixels of the same traced
    /// frame, on a spheres-only scene and on one with lights, a floor and mirrors.
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
        let lab_traced = traced(Frame::new(&lab.scene, &lab_camera));
        let shadows_traced = traced(Frame::new(&shadows.scene, &shadows_camera));
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
                    let size = lab_camera.size();
                    let want = simulator(&lab_traced, size, model, bayer, simulator_theme);
                    assert!(panel.shown(theme) == want, "lab {model:?} {bayer:?} {theme:?}");

                    let frame = Frame::new(&shadows.scene, &shadows_camera);
                    let mut panel = Panel::new(model, bayer, shadows_camera.size());
                    panel.paint(frame);
                    let size = shadows_camera.size();
                    let want = simulator(&shadows_traced, size, model, bayer, simulator_theme);
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
