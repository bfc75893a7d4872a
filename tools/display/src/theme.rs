//! The OLED themes of the 1-bit models: the colour a lit pixel shows and the colour of
//! a dark one.

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};

/// The colours of a 1-bit OLED panel (the embedded-graphics simulator's themes of the
/// same names, colour for colour).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Theme {
    /// Light blue on dark blue.
    #[default]
    OledBlue,
    /// White on near black.
    OledWhite,
}

impl Theme {
    /// Every theme (the preview's `T` key cycles them).
    pub const ALL: [Theme; 2] = [Theme::OledBlue, Theme::OledWhite];

    /// The theme's name on the command line: `oled-blue`, `oled-white`.
    pub fn name(self) -> &'static str {
        match self {
            Theme::OledBlue => "oled-blue",
            Theme::OledWhite => "oled-white",
        }
    }

    /// The theme named `name` ([`Theme::name`]), if there is one.
    pub fn from_name(name: &str) -> Option<Theme> {
        Theme::ALL.into_iter().find(|t| t.name() == name)
    }

    /// The next theme of [`Theme::ALL`], after the last the first.
    pub fn next(self) -> Theme {
        match self {
            Theme::OledBlue => Theme::OledWhite,
            Theme::OledWhite => Theme::OledBlue,
        }
    }

    /// The colour of a lit pixel.
    pub fn on(self) -> Rgb888 {
        match self {
            Theme::OledBlue => Rgb888::new(0, 210, 255),
            Theme::OledWhite => Rgb888::WHITE,
        }
    }

    /// The colour of a dark pixel.
    pub fn off(self) -> Rgb888 {
        match self {
            Theme::OledBlue => Rgb888::new(0, 20, 40),
            Theme::OledWhite => Rgb888::new(20, 20, 20),
        }
    }

    /// What a 1-bit pixel of colour `color` (black or white, as `BinaryColor` converts)
    /// shows: black is dark, anything else lit.
    pub fn show(self, color: Rgb888) -> Rgb888 {
        if color == Rgb888::BLACK {
            self.off()
        } else {
            self.on()
        }
    }
}
