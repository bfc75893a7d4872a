//! The desktop preview's display models, as the page shows them: a model's colour
//! conversion (with the kernel's ordered dither for the dithered ones) and the OLED
//! themes of the 1-bit models, in the window colours of embedded-graphics-simulator.
//!
//! Stop-gap until the shared display crate (`tools/display`) is in the workspace; this
//! module then goes and the page uses that crate's models.

use embedded_graphics::pixelcolor::{BinaryColor, Gray2, Gray4, Gray8, Rgb565, Rgb888, RgbColor};
use embedded_graphics::prelude::Point;
use embedded_raytracer::dither::{dither, Bayer};

/// The display a firmware drives: a colour type, with or without the kernel's dither
/// in front of it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Model {
    Rgb888,
    Rgb565,
    Gray8,
    Gray4,
    Gray4Dither,
    Gray2,
    Gray2Dither,
    Binary,
    BinaryDither,
}

impl Model {
    /// Every model, in the preview's order (its `1`–`9` keys).
    pub const ALL: [Model; 9] = [
        Model::Rgb888,
        Model::Rgb565,
        Model::Gray8,
        Model::Gray4,
        Model::Gray4Dither,
        Model::Gray2,
        Model::Gray2Dither,
        Model::Binary,
        Model::BinaryDither,
    ];

    /// The preview's `--display` name.
    pub fn name(self) -> &'static str {
        match self {
            Model::Rgb888 => "rgb888",
            Model::Rgb565 => "rgb565",
            Model::Gray8 => "gray8",
            Model::Gray4 => "gray4",
            Model::Gray4Dither => "gray4-dither",
            Model::Gray2 => "gray2",
            Model::Gray2Dither => "gray2-dither",
            Model::Binary => "binary",
            Model::BinaryDither => "binary-dither",
        }
    }

    /// The model named `name`.
    pub fn parse(name: &str) -> Option<Model> {
        Model::ALL.into_iter().find(|m| m.name() == name)
    }

    /// Whether the display is 1-bit: an OLED theme colours it.
    pub fn is_binary(self) -> bool {
        matches!(self, Model::Binary | Model::BinaryDither)
    }

    /// The colour the display shows for the kernel's `color` at `point`, as an `Rgb888`
    /// (the colour type's own conversion back, before any theme): what the firmware's
    /// `C::from(Rgb888)` or the dither writes, read back as embedded-graphics does.
    pub fn shown(self, color: Rgb888, point: Point, bayer: Bayer) -> Rgb888 {
        match self {
            Model::Rgb888 => color,
            Model::Rgb565 => Rgb565::from(color).into(),
            Model::Gray8 => Gray8::from(color).into(),
            Model::Gray4 => Gray4::from(color).into(),
            Model::Gray2 => Gray2::from(color).into(),
            Model::Binary => BinaryColor::from(color).into(),
            Model::Gray4Dither => dither::<Gray4>(color, point, bayer).into(),
            Model::Gray2Dither => dither::<Gray2>(color, point, bayer).into(),
            Model::BinaryDither => dither::<BinaryColor>(color, point, bayer).into(),
        }
    }
}

/// The OLED themes of the 1-bit models (embedded-graphics-simulator's `OledBlue` and
/// `OledWhite`): the window colours of an unlit and a lit pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Theme {
    OledBlue,
    OledWhite,
}

impl Theme {
    /// The preview's `--theme` name.
    pub fn name(self) -> &'static str {
        match self {
            Theme::OledBlue => "oled-blue",
            Theme::OledWhite => "oled-white",
        }
    }

    /// The theme named `name`.
    pub fn parse(name: &str) -> Option<Theme> {
        [Theme::OledBlue, Theme::OledWhite]
            .into_iter()
            .find(|t| t.name() == name)
    }

    /// The window colour of a 1-bit display's pixel read back as `shown` (black: off).
    pub fn window(self, shown: Rgb888) -> Rgb888 {
        let (off, on) = match self {
            Theme::OledBlue => (Rgb888::new(0, 20, 40), Rgb888::new(0, 210, 255)),
            Theme::OledWhite => (Rgb888::new(20, 20, 20), Rgb888::WHITE),
        };
        if shown == Rgb888::BLACK {
            off
        } else {
            on
        }
    }
}
