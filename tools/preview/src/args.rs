//! The command line: the flags, as clap parses them, turned into [`Args`].

use std::path::PathBuf;

use clap::builder::{PossibleValuesParser, TypedValueParser};
use embedded_graphics::prelude::Size;
use embedded_raytracer::{dither::Bayer, Method, Sampling, SphereTest, Sqrt, Stepping};
use embedded_raytracer_display::{bayer, Model, Theme};
use embedded_raytracer_scenes as standard;

/// The usage line: every flag, the method flags' choices from the kernel's tables.
pub fn usage() -> String {
    format!(
        "usage: ertrace-preview [SCENE.toml] [--display MODEL] [--size WxH] [--scale N] \
[--bayer 4|8] [--theme oled-blue|oled-white] {} [--sampling center|grid:N|adaptive:N] [--diff] [--no-overlay] \
[--frame K] [--screenshot OUT.png [--frames N]]\n  MODEL: rgb888 rgb565 gray8 gray4 gray4-dither gray2 \
gray2-dither binary binary-dither",
        standard::method_flags()
    )
}

/// Command-line options.
pub struct Args {
    pub scene: PathBuf,
    pub model: Model,
    pub size: Option<Size>,
    pub scale: Option<u32>,
    pub method: Method,
    pub sampling: Sampling,
    pub bayer: Bayer,
    pub theme: Theme,
    pub diff: bool,
    pub overlay: bool,
    pub screenshot: Option<PathBuf>,
    pub frames: Option<u32>,
    /// The frame of the scene's motion to start paused on (1: its start).
    pub frame: Option<u32>,
}

/// The flags as clap parses them; [`parse_args`] turns them into [`Args`]. Every
/// choice is listed in `--help`: the display models from [`Model::ALL`], the method
/// axes from the kernel's own tables (`Stepping::NAMES`, …), the samplings from
/// `Sampling::ALL`.
#[derive(clap::Parser)]
#[command(
    name = "ertrace-preview",
    version,
    about = "A scene file in the embedded-graphics simulator's window, through a display model \
(keys: see docs/cli.md); --screenshot renders one frame without a display server.",
    override_usage = usage_line(),
)]
struct Cli {
    /// The scene file (TOML)
    #[arg(value_name = "SCENE.toml", default_value = "scenes/lab.toml")]
    scene: PathBuf,
    /// The display model
    #[arg(long, value_name = "MODEL", value_parser = PossibleValuesParser::new(Model::ALL.map(Model::name))
        .try_map(|s| Model::from_name(&s).ok_or_else(|| format!("--display: unknown model `{s}`"))))]
    display: Option<Model>,
    /// The display's resolution, instead of the scene file's
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<Size>,
    /// Window pixels per display pixel (1 to 16)
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=16))]
    scale: Option<u32>,
    /// Rays per pixel
    #[arg(long, value_parser = PossibleValuesParser::new(sampling_names()).try_map(|s| s.parse::<Sampling>()))]
    sampling: Option<Sampling>,
    /// Bayer matrix of the dithered models
    #[arg(long, value_parser = PossibleValuesParser::new(bayer::NAMES)
        .try_map(|s| bayer::from_name(&s).ok_or_else(|| format!("--bayer: unknown matrix `{s}`"))))]
    bayer: Option<Bayer>,
    /// OLED theme of the binary models
    #[arg(long, value_parser = PossibleValuesParser::new(Theme::ALL.map(Theme::name))
        .try_map(|s| Theme::from_name(&s).ok_or_else(|| format!("--theme: unknown theme `{s}`"))))]
    theme: Option<Theme>,
    /// The starting method's stepping
    #[arg(long, value_parser = PossibleValuesParser::new(Stepping::NAMES).try_map(|s| s.parse::<Stepping>()))]
    stepping: Option<Stepping>,
    /// The starting method's ray–sphere test
    #[arg(long, value_parser = PossibleValuesParser::new(SphereTest::NAMES).try_map(|s| s.parse::<SphereTest>()))]
    sphere_test: Option<SphereTest>,
    /// The starting method's square root
    #[arg(long, value_parser = PossibleValuesParser::new(Sqrt::NAMES).try_map(|s| s.parse::<Sqrt>()))]
    sqrt: Option<Sqrt>,
    /// Start in the difference view
    #[arg(long)]
    diff: bool,
    /// No status bar: the window shows exactly the display
    #[arg(long)]
    no_overlay: bool,
    /// Write what the window shows to OUT.png and exit
    #[arg(long, value_name = "OUT.png")]
    screenshot: Option<PathBuf>,
    /// With --screenshot: open the window, show N frames, write the last
    #[arg(long, value_name = "N", requires = "screenshot", value_parser = clap::value_parser!(u32))]
    frames: Option<u32>,
    /// Start paused on frame K of the scene's motion, at t = (K - 1)/fps seconds (the
    /// render CLI's --frame K); Space plays
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(1..))]
    frame: Option<u32>,
}

/// Every sampling's name (`Sampling::ALL` as `Display` writes them), for clap, which
/// keeps `&'static str`s: seven short strings, made once per run.
fn sampling_names() -> Vec<&'static str> {
    Sampling::ALL
        .iter()
        .map(|s| &*Box::leak(s.to_string().into_boxed_str()))
        .collect()
}

/// `--size`'s value.
fn parse_size(v: &str) -> Result<Size, String> {
    v.split_once('x')
        .and_then(|(w, h)| Some(Size::new(w.parse().ok()?, h.parse().ok()?)))
        .ok_or_else(|| format!("expected WxH, got `{v}`"))
}

/// The usage line for clap (without the leading `usage: `).
fn usage_line() -> String {
    usage().trim_start_matches("usage: ").to_string()
}

/// The flags after the program's name.
pub fn parse_args<T: Into<std::ffi::OsString> + Clone>(
    args: impl IntoIterator<Item = T>,
) -> Result<Args, clap::Error> {
    use clap::Parser;
    let cli = Cli::try_parse_from(
        std::iter::once(std::ffi::OsString::from("ertrace-preview")).chain(args.into_iter().map(Into::into)),
    )?;
    let mut method = Method::default();
    if let Some(s) = cli.stepping {
        method.stepping = s;
    }
    if let Some(s) = cli.sphere_test {
        method.sphere_test = s;
    }
    if let Some(s) = cli.sqrt {
        method.sqrt = s;
    }
    Ok(Args {
        scene: cli.scene,
        model: cli.display.unwrap_or(Model::Rgb888),
        size: cli.size,
        scale: cli.scale,
        method,
        sampling: cli.sampling.unwrap_or(Sampling::Center),
        bayer: cli.bayer.unwrap_or(Bayer::Eight),
        theme: cli.theme.unwrap_or(Theme::OledBlue),
        diff: cli.diff,
        overlay: !cli.no_overlay,
        screenshot: cli.screenshot,
        frames: cli.frames.map(|n| n.max(1)),
        frame: cli.frame,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_flags_are_errors() {
        for bad in [
            &["--display", "cmyk"][..],
            &["--size", "12"],
            &["--scale", "0"],
            &["--bayer", "3"],
            &["--sampling", "grid:5"],
            &["--sampling", "box"],
            &["--frames", "2"],
            &["--frame", "0"],
            &["--frame", "x"],
            &["--frobnicate"],
        ] {
            let all = bad.iter().map(|s| s.to_string());
            assert!(parse_args(all).is_err(), "{bad:?}");
        }
    }
}
