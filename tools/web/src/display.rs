//! The desktop preview's display models and OLED themes by name, as the page picks
//! them: the names and colours of the shared display crate's `Model` and `Theme`.
//!
//! Stop-gap until that crate (`tools/display`, `embedded-raytracer-display`) is in the
//! workspace: the same names and signatures, so that the page then imports them from
//! it and this module goes.

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};

/// The display the firmware drives: colour type and whether the kernel's dither sits
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

    /// The model named `name`, if there is one.
    pub fn from_name(name: &str) -> Option<Model> {
        Model::ALL.into_iter().find(|m| m.name() == name)
    }

    /// Whether the panel has one bit a pixel (an OLED theme colours it).
    pub fn is_binary(self) -> bool {
        matches!(self, Model::Binary | Model::BinaryDither)
    }
}

/// The colours of a 1-bit OLED panel (the embedded-graphics simulator's themes of the
/// same names, colour for colour).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Theme {
    OledBlue,
    OledWhite,
}

impl Theme {
    /// Every theme.
    pub const ALL: [Theme; 2] = [Theme::OledBlue, Theme::OledWhite];

    /// The preview's `--theme` name.
    pub fn name(self) -> &'static str {
        match self {
            Theme::OledBlue => "oled-blue",
            Theme::OledWhite => "oled-white",
        }
    }

    /// The theme named `name`, if there is one.
    pub fn from_name(name: &str) -> Option<Theme> {
        Theme::ALL.into_iter().find(|t| t.name() == name)
    }

    /// What a 1-bit pixel of colour `color` (black or white, as `BinaryColor` converts)
    /// shows: black is dark, anything else lit.
    pub fn show(self, color: Rgb888) -> Rgb888 {
        let (off, on) = match self {
            Theme::OledBlue => (Rgb888::new(0, 20, 40), Rgb888::new(0, 210, 255)),
            Theme::OledWhite => (Rgb888::new(20, 20, 20), Rgb888::WHITE),
        };
        if color == Rgb888::BLACK {
            off
        } else {
            on
        }
    }
}
