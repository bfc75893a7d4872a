//! The display models: the colour type of the panel a firmware drives, and whether the
//! kernel's ordered dither sits in front of it.

/// The display the firmware drives: colour type and whether the kernel's dither sits
/// in front of it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Model {
    /// 24-bit colour.
    Rgb888,
    /// 16-bit colour (the kernel's conversion: the top bits of each channel).
    Rgb565,
    /// 256 grey levels.
    Gray8,
    /// 16 grey levels, each pixel the nearest.
    Gray4,
    /// 16 grey levels through the ordered dither.
    Gray4Dither,
    /// 4 grey levels, each pixel the nearest.
    Gray2,
    /// 4 grey levels through the ordered dither.
    Gray2Dither,
    /// 1 bit a pixel (an OLED), each pixel the nearest.
    Binary,
    /// 1 bit a pixel through the ordered dither.
    BinaryDither,
}

impl Model {
    /// Every model, from the deepest colour to one bit (the preview's keys `1`–`9`).
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

    /// The model's name on the command line: `rgb888`, `gray4-dither`, `binary`.
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

    /// The model named `name` ([`Model::name`]), if there is one.
    pub fn from_name(name: &str) -> Option<Model> {
        Model::ALL.into_iter().find(|m| m.name() == name)
    }

    /// Whether the panel has one bit a pixel (its colours are a [`crate::Theme`]'s).
    pub fn is_binary(self) -> bool {
        matches!(self, Model::Binary | Model::BinaryDither)
    }

    /// Whether the kernel's ordered dither sits in front of the panel.
    pub fn is_dithered(self) -> bool {
        matches!(
            self,
            Model::Gray4Dither | Model::Gray2Dither | Model::BinaryDither
        )
    }

    /// The model's place in [`Model::ALL`].
    pub fn index(self) -> usize {
        Model::ALL.iter().position(|&m| m == self).unwrap_or(0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_the_flags_match_them() {
        for (k, model) in Model::ALL.into_iter().enumerate() {
            assert_eq!(Model::from_name(model.name()), Some(model));
            assert_eq!(model.index(), k);
            assert_eq!(model.is_dithered(), model.name().ends_with("-dither"));
            assert_eq!(model.is_binary(), model.name().starts_with("binary"));
        }
        assert_eq!(Model::from_name("cmyk"), None);
    }
}
