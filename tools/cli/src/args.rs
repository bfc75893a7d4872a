//! The flags, parsed by clap (derive). The method axes and the sampling list their
//! choices from the kernel's own tables (`Stepping::NAMES`, `Sampling::ALL`, …), so
//! `--help` and the shell completions name exactly what the kernel parses; the kernel's
//! `FromStr` parses them, so its error is the message. Every error is one line naming
//! the flag and the reason ([`message`]), exit code 2.

use std::ffi::OsStr;
use std::path::PathBuf;

use clap::builder::{PossibleValue, TypedValueParser};
use clap::error::{ContextKind, ErrorKind};
use clap::{Arg, Command, Parser};
use clap_complete::Shell;
use embedded_graphics::geometry::Size;
use embedded_raytracer::{
    Arithmetic, Method, Options, Sampling, SecondaryOrigin, SphereTest, Sqrt, Stepping,
};

use crate::cost;
use embedded_raytracer_scenes as standard;

/// The most tracing threads `--threads` takes.
pub const MAX_THREADS: usize = 1024;

/// The usage line; every choice of the method flags is listed from the method's own
/// tables.
fn usage() -> String {
    format!(
        "ertrace SCENE.toml... [--output OUT.png] [--output-frames DIR] [--frames N] [--fps F] [--frame K] [--force] {} \
[--arithmetic {}] [--secondary convex|epsilon:VALUE] [--sampling center|grid:N|adaptive:N] [--size WxH] [--threads N] \
[--quiet] (default method {}, sampling {}, secondary {})",
        standard::method_flags(),
        Arithmetic::NAMES.join("|"),
        Method::TARGET_DEFAULT,
        Sampling::Center,
        Options::DEFAULT.secondary
    )
}

const ABOUT: &str = "\
Renders a TOML scene file (see scenes/*.toml) to an 8-bit RGB PNG. Spheres alone
(scenes/lab.toml) are drawn under the Lab #1 headlight; lights, a checkered floor and
mirrors (scenes/shadows.toml, scenes/mirrors.toml) are drawn when the file has them.
Bands of rows are traced in parallel (--threads) and written in order: the PNG is the
same, byte for byte, for every number of threads.

Sequences: several scene files are consecutive frames of one display, and a scene with
[[motion]] tables (scenes/bounce.toml, scenes/circling.toml) is drawn at the moments
t = (k - 1)/fps of its frames k = 1, 2, ... (--frames N). A sequence is drawn into one
frame in memory, each frame incrementally (only the pixels that can differ from the
frame before are traced), on one thread; --output-frames DIR writes DIR/0001.png,
DIR/0002.png, ... (each the same bytes as the single-frame PNG of that file or moment),
--output OUT.png an animated PNG (APNG) of every frame. One line per frame on stderr:
the frame, the pixels traced and sent, the time (--quiet: none).";

/// The text after the flags: the output rules, the limits and the worst case.
fn after_help() -> String {
    format!(
        "\
Output rules: a regular file is replaced atomically (temporary file beside it, then a
rename) and keeps its permissions; a symbolic link is followed and its target replaced;
a file this user may not write (access(W_OK), as the shell decides) or one with no
write permission for anyone (even as root) is refused unless --force; the scene file itself is refused; a FIFO or character device (/dev/null,
/dev/stdout) is written through, never replaced (the summary line then goes to stderr);
a block device, socket or directory is refused. A missing or unwritable directory, or
a name ending in /, is refused before anything is traced. Nothing is written when the
scene does not load. SIGINT, SIGTERM or SIGHUP remove the unfinished temporary file
(exit 130, 143, 129).

Limits: the scene file is at most 1 MiB, at most 256 spheres, 8 lights and 8 planes,
8 motions, max_depth at most 8, width and height at most 8192, --frames at most
{max_frames}. A sequence holds one frame in memory (3 bytes a pixel) and its APNG
until it is written.
{worst}
Worst case measured (docs/cli_worst_case.toml: 8192x8192, 256 spheres all enclosing
the eye, so none is culled, centre sampling; release build on a shared 2-core AMD EPYC
VM, one thread): 158.6 s of CPU time, peak memory 3,324 KB. A render whose bound
exceeds {warn} s prints that bound first. The image is streamed in bands of rows:
memory grows with the width and the threads, not with the height.

Exit codes: 0 done, 2 bad input or a failed write (one message on stderr), 130/143/129
interrupted by SIGINT/SIGTERM/SIGHUP (nothing left behind).",
        worst = cost::help_text(),
        max_frames = MAX_FRAMES,
        warn = cost::WARN_SECONDS,
    )
}

/// The parsed command line.
#[derive(Parser, Debug)]
#[command(
    name = "ertrace",
    version,
    about = ABOUT,
    override_usage = usage(),
    after_help = after_help(),
    help_template = "usage: {usage}\n\n{about}\n\n{all-args}\n{after-help}",
    disable_help_flag = true,
)]
pub struct Args {
    /// The scene file (TOML); several: the consecutive frames of a sequence
    #[arg(value_name = "SCENE.toml", num_args = 0.., value_hint = clap::ValueHint::FilePath)]
    pub scenes: Vec<PathBuf>,
    /// The PNG (default: the first scene's name with .png, in the current directory); for
    /// a sequence an animated PNG (APNG) of every frame, written unless only
    /// --output-frames is given
    #[arg(short, long, value_name = "OUT.png", value_hint = clap::ValueHint::FilePath)]
    pub output: Option<PathBuf>,
    /// Write every frame of the sequence as DIR/0001.png, DIR/0002.png, ... (DIR is made
    /// if missing, its parent must exist; other files in it are left alone)
    #[arg(long, value_name = "DIR", value_hint = clap::ValueHint::DirPath)]
    pub output_frames: Option<PathBuf>,
    /// Draw N frames of the scene's motion, at t = 0, 1/F, 2/F, ... seconds (one scene
    /// file; with --output-frames alone: the file's [animation] frames)
    #[arg(long, value_name = "N", value_parser = Checked::new(parse_frames, &[]))]
    pub frames: Option<u32>,
    /// Frames a second of the motion (default: the file's [animation] fps, else 25)
    #[arg(long, value_name = "F", value_parser = Checked::new(parse_fps, &[]))]
    pub fps: Option<f32>,
    /// Draw frame K of the scene's motion, at t = (K - 1)/F seconds (default 1: its
    /// start); for several files, each file's frame K
    #[arg(long, value_name = "K", conflicts_with = "frames", value_parser = Checked::new(parse_frame, &[]))]
    pub frame: Option<u32>,
    /// Replace an output this user may not write, where its directory lets us: the new
    /// file is renamed over it, so it belongs to whoever ran ertrace (root keeps the old
    /// owner), with the old file's permission bits
    #[arg(long)]
    pub force: bool,
    /// Ray stepping (default: the crate's Method::TARGET_DEFAULT)
    #[arg(long, value_parser = Checked::<Stepping>::table(Stepping::NAMES))]
    pub stepping: Option<Stepping>,
    /// Ray–sphere test (default: Method::TARGET_DEFAULT's)
    #[arg(long, value_parser = Checked::<SphereTest>::table(SphereTest::NAMES))]
    pub sphere_test: Option<SphereTest>,
    /// Square root (default: Method::TARGET_DEFAULT's)
    #[arg(long, value_parser = Checked::<Sqrt>::table(Sqrt::NAMES))]
    pub sqrt: Option<Sqrt>,
    /// integer: the integer kernel where its per-frame rule takes the frame (spheres
    /// only, square pixels, within its range limits), else the f32 method; without the
    /// flag Method::TARGET_DEFAULT's (f32 on this host). The summary says which one drew
    #[arg(long, value_parser = Checked::<Arithmetic>::table(Arithmetic::NAMES))]
    pub arithmetic: Option<Arithmetic>,
    /// Where shadow and reflection rays start: convex (default; no epsilon) or the
    /// textbook fixed epsilon, VALUE scene units (a positive finite number); only scenes
    /// with lights or mirrors use it
    #[arg(long, value_name = "convex|epsilon:VALUE", value_parser = Checked::new(parse_secondary, &["convex", "epsilon:0.001"]))]
    pub secondary: Option<SecondaryOrigin>,
    /// Rays per pixel: the centre ray (default), an N x N grid in every pixel, or the
    /// grid only where an edge can cross the pixel (N = 2, 3 or 4), averaged in linear
    /// light
    #[arg(long, value_parser = Checked::new(parse_sampling, sampling_names()))]
    pub sampling: Option<Sampling>,
    /// The image's size instead of the scene file's (the camera keeps its vertical field
    /// of view), as the preview's --size
    #[arg(long, value_name = "WxH", value_parser = Checked::new(parse_size, &[]))]
    pub size: Option<Size>,
    /// Tracing threads (default: every core); 1 traces on the calling thread alone. The
    /// PNG is the same for every N
    #[arg(long, value_name = "N", value_parser = Checked::new(parse_threads, &[]))]
    pub threads: Option<usize>,
    /// No progress bar, no time estimate and no per-frame lines on stderr (the summary
    /// line stays)
    #[arg(short, long)]
    pub quiet: bool,
    /// Print the completion script for SHELL to stdout and exit
    #[arg(long, value_name = "SHELL", value_parser = Checked::new(parse_shell, &["bash", "zsh", "fish", "elvish", "powershell"]))]
    pub completions: Option<Shell>,
    /// This text
    #[arg(short, long, action = clap::ArgAction::Help)]
    pub help: Option<bool>,
}

impl Args {
    /// The method the flags select, starting from `Method::default()`.
    pub fn method(&self) -> Method {
        let mut method = Method::default();
        if let Some(s) = self.stepping {
            method.stepping = s;
        }
        if let Some(s) = self.sphere_test {
            method.sphere_test = s;
        }
        if let Some(s) = self.sqrt {
            method.sqrt = s;
        }
        if let Some(a) = self.arithmetic {
            method.arithmetic = a;
        }
        method
    }
}

/// The clap command, for the completion scripts.
pub fn command() -> Command {
    <Args as clap::CommandFactory>::command()
}

/// A value parser: `parse` gives the value or the reason, the error names the flag;
/// `choices` are what `--help` and the completions list.
#[derive(Clone)]
pub struct Checked<T> {
    parse: fn(&str) -> Result<T, String>,
    choices: &'static [&'static str],
}

impl<T> Checked<T> {
    fn new(parse: fn(&str) -> Result<T, String>, choices: &'static [&'static str]) -> Self {
        Self { parse, choices }
    }
}

impl<T: std::str::FromStr> Checked<T>
where
    T::Err: std::fmt::Display,
{
    /// A method axis: the choices are the kernel's own table, parsed by its `FromStr`.
    fn table(names: &'static [&'static str]) -> Self {
        Self {
            parse: |s| s.parse::<T>().map_err(|e| e.to_string()),
            choices: names,
        }
    }
}

impl<T: Clone + Send + Sync + 'static> TypedValueParser for Checked<T> {
    type Value = T;

    fn parse_ref(&self, _cmd: &Command, arg: Option<&Arg>, value: &OsStr) -> Result<T, clap::Error> {
        let flag = arg
            .and_then(Arg::get_long)
            .map_or(String::new(), |l| format!("--{l}"));
        let text = value.to_str().ok_or_else(|| {
            fail(format!(
                "{flag}: `{}` is not a valid choice",
                value.to_string_lossy()
            ))
        })?;
        (self.parse)(text).map_err(|reason| fail(format!("{flag}: {reason}")))
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        if self.choices.is_empty() {
            return None;
        }
        Some(Box::new(self.choices.iter().map(|&c| PossibleValue::new(c))))
    }
}

/// Every sampling's name (`Sampling::ALL` as `Display` writes them), for clap, which
/// keeps `&'static str`s: seven short strings, made once per run.
fn sampling_names() -> &'static [&'static str] {
    let names: Vec<&'static str> = Sampling::ALL
        .iter()
        .map(|s| &*Box::leak(s.to_string().into_boxed_str()))
        .collect();
    Box::leak(names.into_boxed_slice())
}

/// A value parser's complete message (flag and reason) as clap's error.
fn fail(message: String) -> clap::Error {
    clap::Error::raw(ErrorKind::ValueValidation, message)
}

/// `--secondary`'s value: `convex` or `epsilon:VALUE` with a positive finite VALUE.
pub fn parse_secondary(text: &str) -> Result<SecondaryOrigin, String> {
    if text == "convex" {
        return Ok(SecondaryOrigin::Convex);
    }
    let Some(value) = text.strip_prefix("epsilon:") else {
        return Err(format!("expected convex or epsilon:VALUE, got `{text}`"));
    };
    let eps: f32 = value
        .parse()
        .map_err(|_| format!("epsilon `{value}` is not a number"))?;
    if !(eps.is_finite() && eps > 0.0) {
        return Err(format!("epsilon must be a positive finite number, got `{value}`"));
    }
    Ok(SecondaryOrigin::Epsilon(eps))
}

fn parse_sampling(text: &str) -> Result<Sampling, String> {
    text.parse().map_err(|e| format!("{e}, got `{text}`"))
}

fn parse_size(text: &str) -> Result<Size, String> {
    let (w, h) = text
        .split_once('x')
        .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
        .ok_or_else(|| format!("expected WxH, got `{text}`"))?;
    Ok(Size::new(w, h))
}

fn parse_threads(text: &str) -> Result<usize, String> {
    match text.parse::<usize>() {
        Ok(n) if (1..=MAX_THREADS).contains(&n) => Ok(n),
        _ => Err(format!(
            "expected a number of threads from 1 to {MAX_THREADS}, got `{text}`"
        )),
    }
}

/// The most frames `--frames` takes.
pub const MAX_FRAMES: u32 = 100_000;

fn parse_frames(text: &str) -> Result<u32, String> {
    match text.parse::<u32>() {
        Ok(n) if (1..=MAX_FRAMES).contains(&n) => Ok(n),
        _ => Err(format!(
            "expected a number of frames from 1 to {MAX_FRAMES}, got `{text}`"
        )),
    }
}

fn parse_frame(text: &str) -> Result<u32, String> {
    match text.parse::<u32>() {
        Ok(k) if k >= 1 => Ok(k),
        _ => Err(format!("expected a frame number from 1, got `{text}`")),
    }
}

fn parse_fps(text: &str) -> Result<f32, String> {
    match text.parse::<f32>() {
        Ok(f) if f.is_finite() && f > 0.0 => Ok(f),
        _ => Err(format!(
            "expected a positive finite number of frames a second, got `{text}`"
        )),
    }
}

fn parse_shell(text: &str) -> Result<Shell, String> {
    <Shell as clap::ValueEnum>::from_str(text, true)
        .map_err(|_| format!("expected bash, zsh, fish, elvish or powershell, got `{text}`"))
}

/// One line for a clap error: the flag (or argument) and the reason, as the CLI's own
/// errors read.
pub fn message(e: &clap::Error) -> String {
    let context = |kind| e.get(kind).map(|v| v.to_string());
    // `--output <OUT.png>` → `--output`.
    let arg = context(ContextKind::InvalidArg).unwrap_or_default();
    let flag = arg.split([' ', '=']).next().unwrap_or_default().to_string();
    let suggestion = context(ContextKind::SuggestedArg)
        .or_else(|| context(ContextKind::SuggestedValue))
        .map_or(String::new(), |s| format!(" (did you mean `{s}`?)"));
    match e.kind() {
        ErrorKind::UnknownArgument if arg.starts_with('-') => format!("unknown flag `{arg}`{suggestion}"),
        ErrorKind::UnknownArgument => format!("unexpected argument `{arg}`"),
        ErrorKind::ArgumentConflict if context(ContextKind::PriorArg).as_deref() == Some(arg.as_str()) => {
            format!("{flag} is given twice")
        }
        ErrorKind::InvalidValue if context(ContextKind::InvalidValue).unwrap_or_default().is_empty() => {
            format!("{flag} needs a value")
        }
        ErrorKind::TooManyValues => format!("{flag} takes no value"),
        _ => {
            let text = e.render().to_string();
            let first = text.lines().next().unwrap_or_default();
            first.strip_prefix("error: ").unwrap_or(first).to_string()
        }
    }
}
