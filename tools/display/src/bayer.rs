//! The Bayer matrices of the kernel's ordered dither, by name: the side on the command
//! line (`4`, `8`), `4x4`/`8x8` on a status line.

pub use embedded_raytracer::dither::Bayer;

/// The matrices' names, as [`from_name`] reads them.
pub const NAMES: [&str; 2] = ["4", "8"];

/// The matrix named by its side `name` (`4` or `8`), if there is one.
pub fn from_name(name: &str) -> Option<Bayer> {
    match name {
        "4" => Some(Bayer::Four),
        "8" => Some(Bayer::Eight),
        _ => None,
    }
}

/// The matrix's size on a status line: `4x4`, `8x8`.
pub fn label(matrix: Bayer) -> &'static str {
    match matrix {
        Bayer::Four => "4x4",
        Bayer::Eight => "8x8",
    }
}

/// The other matrix (the preview's `B` key).
pub fn other(matrix: Bayer) -> Bayer {
    match matrix {
        Bayer::Four => Bayer::Eight,
        Bayer::Eight => Bayer::Four,
    }
}
