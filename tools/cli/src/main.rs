//! `ertrace`, the host CLI: render a TOML scene file to a PNG.
//!
//! ```text
//! cargo run --release -p embedded-raytracer-cli -- scenes/lab.toml --output lab.png \
//!     [--stepping …] [--sphere-test …] [--sqrt …] [--arithmetic f32|integer] \
//!     [--secondary convex|epsilon:VALUE] [--sampling center|grid:N|adaptive:N] \
//!     [--force]   # --help lists the choices
//! ```
//!
//! A scene file without lights, planes or mirrors is drawn through the spheres-only type
//! `Scene<N>`, the Lab #1 loop (its PNG is the one it always was); one with them through
//! the full type `Scene<N, L, P, D>` with the host's capacities.
//!
//! Prints the resolution, the method, the arithmetic the frame was drawn in (the integer
//! kernel's per-frame rule decides where `--arithmetic integer` or the default asks for
//! it), the render and PNG times and the peak memory.
//! Any bad input (file, field or flag) is one message on stderr and exit code 2. The
//! rules for the output (`--help` and the README say the same):
//!
//! - A regular file is written to a temporary file created exclusively (random name,
//!   no link followed) beside it, and renamed over it only after the whole PNG is
//!   written: a failure never leaves a half-written or clobbered output. A replaced
//!   file keeps its permissions (and, as root, its owner).
//! - A symbolic link is followed: the PNG replaces the link's target, the link stays
//!   (what `cp` does); a link to nothing is refused.
//! - A read-only output is refused unless `--force` is given.
//! - The scene file itself (same device and inode, after following links) is refused.
//! - A FIFO or character device (`/dev/null`, a terminal, `/dev/stdout`) is written
//!   through, opened without creating or truncating anything; it is never replaced (and
//!   the summary line goes to stderr). A block device, a socket or a directory is
//!   refused.
//!
//! The PNG is streamed: the render hands over one row at a time and only that row is
//! buffered, so memory is O(width), not O(width × height).

use std::ffi::{OsStr, OsString};
use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use embedded_graphics::{pixelcolor::Rgb888, prelude::*, primitives::Rectangle};
use embedded_raytracer::{scene_file, Arithmetic, Method, Options, Render, Sampling, SecondaryOrigin};

mod standard;
use standard::FullSceneFile;

/// The usage line; the method flags list every choice from the method's own tables.
fn usage() -> String {
    format!(
        "usage: ertrace SCENE.toml [--output OUT.png] [--force] {} [--arithmetic {}] [--secondary convex|epsilon:VALUE] \
[--sampling center|grid:N|adaptive:N] (default method {}, sampling {}, secondary {})",
        standard::method_flags(),
        Arithmetic::NAMES.join("|"),
        Method::TARGET_DEFAULT,
        Sampling::Center,
        secondary_name(Options::DEFAULT.secondary)
    )
}

/// `--secondary`'s value: `convex` or `epsilon:VALUE` with a positive finite VALUE.
fn parse_secondary(text: &str) -> Result<SecondaryOrigin, String> {
    if text == "convex" {
        return Ok(SecondaryOrigin::Convex);
    }
    let Some(value) = text.strip_prefix("epsilon:") else {
        return Err(format!(
            "--secondary: expected convex or epsilon:VALUE, got `{text}`"
        ));
    };
    let eps: f32 = value
        .parse()
        .map_err(|_| format!("--secondary: epsilon `{value}` is not a number"))?;
    if !(eps.is_finite() && eps > 0.0) {
        return Err(format!(
            "--secondary: epsilon must be a positive finite number, got `{value}`"
        ));
    }
    Ok(SecondaryOrigin::Epsilon(eps))
}

/// The `--secondary` value that selects `secondary` (`convex`, `epsilon:0.001`).
fn secondary_name(secondary: SecondaryOrigin) -> String {
    secondary.to_string()
}

/// The rest of `--help` after the usage line. The worst case was measured with
/// `/usr/bin/time -v target/release/ertrace docs/cli_worst_case.toml --output worst.png`.
const HELP: &str = "
Renders a TOML scene file (see scenes/*.toml) to an 8-bit RGB PNG. Spheres alone
(scenes/lab.toml) are drawn under the Lab #1 headlight; lights, a checkered floor and
mirrors (scenes/shadows.toml, scenes/mirrors.toml) are drawn when the file has them.

  --output, -o OUT   the PNG (default: the scene's name with .png, in the current directory)
  --force            replace a read-only output
  --stepping, --sphere-test, --sqrt
                     the render method (default: the crate's Method::TARGET_DEFAULT)
  --arithmetic f32|integer
                     integer: the integer kernel where its per-frame rule takes the
                     frame (spheres only, square pixels, within its range limits),
                     else the f32 method above; without the flag Method::TARGET_DEFAULT's
                     (f32 on this host). The summary says which one drew the frame
  --secondary convex|epsilon:VALUE
                     where shadow and reflection rays start: convex (default; no
                     epsilon) or the textbook fixed epsilon, VALUE scene units (a
                     positive finite number); only scenes with lights or mirrors use it
  --sampling center|grid:N|adaptive:N
                     rays per pixel: the centre ray (default), an N x N grid in every
                     pixel, or the grid only where an edge can cross the pixel (N = 2,
                     3 or 4), averaged in linear light
  --help, -h         this text

Flags take their value as the next argument or after `=` (--output=out.png); a value
that starts with `-` must use the `=` form. `--` ends the flags.

Output rules: a regular file is replaced atomically (temporary file beside it, then a
rename) and keeps its permissions; a symbolic link is followed and its target replaced;
a read-only output is refused unless --force; the scene file itself is refused; a FIFO
or character device (/dev/null, /dev/stdout) is written through, never replaced (the
summary line then goes to stderr); a block device, socket or directory is refused.
Nothing is written when the scene does not load.

Limits: the scene file is at most 1 MiB, at most 256 spheres, 8 lights and 8 planes,
max_depth at most 8, width and height at most 8192. Worst case measured
(docs/cli_worst_case.toml: 8192x8192, 256 spheres all enclosing the eye, so none is
culled; release build on a shared 2-core AMD EPYC VM):
158.6 s of CPU time (10.5 min wall under a load average of 8 to 10), peak memory 3,324 KB.
The image is streamed row by row: memory grows with the width, not with the height.
Exit codes: 0 done, 2 bad input or a failed write (one message on stderr).";

struct Args {
    scene: PathBuf,
    output: PathBuf,
    method: Method,
    secondary: SecondaryOrigin,
    sampling: Sampling,
    force: bool,
}

enum Command {
    Render(Args),
    Help,
}

/// A flag's name and its value when written as `--flag=value`.
fn split_flag(arg: &OsStr) -> Result<(String, Option<OsString>), String> {
    let bytes = arg.as_encoded_bytes();
    let (name, value) = match bytes.iter().position(|&b| b == b'=') {
        Some(eq) if bytes.starts_with(b"--") => (bytes.get(..eq), bytes.get(eq + 1..)),
        _ => (Some(bytes), None),
    };
    let name = name
        .and_then(|n| std::str::from_utf8(n).ok())
        .ok_or_else(|| format!("unknown flag `{}`", arg.to_string_lossy()))?;
    let value = value.map(os_string_from_bytes).transpose()?;
    Ok((name.to_string(), value))
}

/// The `value` part of `--flag=value`, which is split off at an ASCII `=`.
#[cfg(unix)]
fn os_string_from_bytes(bytes: &[u8]) -> Result<OsString, String> {
    use std::os::unix::ffi::OsStrExt;
    Ok(OsStr::from_bytes(bytes).to_os_string())
}

#[cfg(not(unix))]
fn os_string_from_bytes(bytes: &[u8]) -> Result<OsString, String> {
    String::from_utf8(bytes.to_vec())
        .map(OsString::from)
        .map_err(|_| "a `--flag=value` argument must be valid Unicode here".to_string())
}

/// An argument that reads as a flag: `-x` or `--x`, but not `-` alone.
fn is_flag(arg: &OsStr) -> bool {
    let bytes = arg.as_encoded_bytes();
    bytes.len() > 1 && bytes.starts_with(b"-")
}

fn parse_args(args: impl IntoIterator<Item = OsString>) -> Result<Command, String> {
    let mut args = args.into_iter();
    let mut scene = None;
    let mut output = None;
    let mut method = Method::default();
    let mut secondary = Options::DEFAULT.secondary;
    let mut sampling = Sampling::Center;
    let mut force = false;
    let mut seen: Vec<&'static str> = Vec::new();
    let mut flags_ended = false;
    while let Some(arg) = args.next() {
        if flags_ended || !is_flag(&arg) {
            if scene.is_some() {
                return Err(format!("unexpected argument `{}`", arg.to_string_lossy()));
            }
            scene = Some(PathBuf::from(arg));
            continue;
        }
        let (name, inline) = split_flag(&arg)?;
        let flag: &'static str = match name.as_str() {
            "--" if inline.is_none() => {
                flags_ended = true;
                continue;
            }
            "--help" | "-h" => return Ok(Command::Help),
            "--output" | "-o" => "--output",
            "--stepping" => "--stepping",
            "--sphere-test" => "--sphere-test",
            "--sqrt" => "--sqrt",
            "--arithmetic" => "--arithmetic",
            "--secondary" => "--secondary",
            "--sampling" => "--sampling",
            "--force" => "--force",
            _ => return Err(format!("unknown flag `{}`", arg.to_string_lossy())),
        };
        if seen.contains(&flag) {
            return Err(format!("{flag} is given twice"));
        }
        seen.push(flag);
        if flag == "--force" {
            if inline.is_some() {
                return Err("--force takes no value".to_string());
            }
            force = true;
            continue;
        }
        // The value: after `=`, or the next argument unless that is itself a flag.
        let value = match inline {
            Some(value) => value,
            None => match args.next() {
                Some(next) if is_flag(&next) => {
                    return Err(format!(
                        "{flag} needs a value, found the flag `{}` (write {flag}=VALUE for a value that starts with `-`)",
                        next.to_string_lossy()
                    ))
                }
                Some(next) => next,
                None => return Err(format!("{flag} needs a value")),
            },
        };
        if flag == "--output" {
            output = Some(PathBuf::from(value));
            continue;
        }
        let text = value
            .to_str()
            .ok_or_else(|| format!("{flag}: `{}` is not a valid choice", value.to_string_lossy()))?;
        match flag {
            "--secondary" => secondary = parse_secondary(text)?,
            "--sampling" => {
                sampling = text
                    .parse()
                    .map_err(|e| format!("--sampling: {e}, got `{text}`"))?
            }
            "--stepping" => method.stepping = text.parse().map_err(|e| format!("--stepping: {e}"))?,
            "--sphere-test" => {
                method.sphere_test = text.parse().map_err(|e| format!("--sphere-test: {e}"))?
            }
            "--arithmetic" => method.arithmetic = text.parse().map_err(|e| format!("--arithmetic: {e}"))?,
            _ => method.sqrt = text.parse().map_err(|e| format!("--sqrt: {e}"))?,
        }
    }
    let scene: PathBuf = scene.ok_or("no scene file given")?;
    let output = match output {
        Some(output) => output,
        None => {
            let stem = scene
                .file_stem()
                .ok_or_else(|| format!("{}: not a file name", scene.display()))?;
            PathBuf::from(stem).with_extension("png")
        }
    };
    Ok(Command::Render(Args {
        scene,
        output,
        method,
        secondary,
        sampling,
        force,
    }))
}

fn run() -> Result<(), String> {
    let args = match parse_args(std::env::args_os().skip(1))? {
        Command::Render(args) => args,
        Command::Help => {
            let _ = writeln!(io::stdout(), "{}\n{HELP}", usage());
            return Ok(());
        }
    };
    let file: Box<FullSceneFile> = Box::new(scene_file::load(&args.scene).map_err(|e| e.to_string())?);
    let size = file.camera.size();
    let destination = destination(&args.output, &args.scene, args.force)?;

    // A stream may be this process's own standard output (`--output /dev/stdout`): the
    // summary then goes to standard error, after the PNG.
    let summary_to_stderr = matches!(destination, Destination::Stream { .. });
    let (rendering, encoding, arithmetic) = match file.spheres_only() {
        // No light, plane or mirror: the spheres-only type, whose loop is Lab #1's.
        Some(spheres) => {
            let render = Render::new(&spheres.scene, &spheres.camera)
                .with_method(args.method)
                .with_sampling(args.sampling);
            let (r, e) = output(&render, size, destination, &args.output)?;
            (r, e, render.arithmetic())
        }
        None => {
            let render = Render::new(&file.scene, &file.camera)
                .with_method(args.method)
                .with_options(Options::DEFAULT.with_secondary(args.secondary))
                .with_sampling(args.sampling);
            let (r, e) = output(&render, size, destination, &args.output)?;
            (r, e, render.arithmetic())
        }
    };

    let pixels = u64::from(size.width) * u64::from(size.height);
    let memory = peak_memory().map_or(String::new(), |kib| {
        format!(", peak memory {:.1} MB", kib as f64 * 1024.0 / 1e6)
    });
    let sampling = match args.sampling {
        Sampling::Center => String::new(),
        other => format!(", sampling {other}"),
    };
    let summary = format!(
        "{}: {}x{} pixels{}, method {}, arithmetic {arithmetic}{sampling}, {:.3} ms ({:.1} ns/pixel), PNG {:.3} ms{memory} -> {}",
        args.scene.display(),
        size.width,
        size.height,
        features(&file, args.secondary),
        args.method,
        rendering.as_secs_f64() * 1e3,
        rendering.as_secs_f64() * 1e9 / pixels as f64,
        encoding.as_secs_f64() * 1e3,
        args.output.display()
    );
    // The PNG is written: a closed stdout or stderr (`| head`) is no failure any more.
    let _ = if summary_to_stderr {
        writeln!(io::stderr(), "{summary}")
    } else {
        writeln!(io::stdout(), "{summary}")
    };
    Ok(())
}

/// Writes the PNG of `render` to `destination` (the output rules of the module docs);
/// returns the time spent tracing and the time spent encoding and writing.
fn output<const N: usize, const L: usize, const P: usize, const D: usize>(
    render: &Render<'_, N, Rgb888, L, P, D>,
    size: Size,
    destination: Destination,
    name: &Path,
) -> Result<(Duration, Duration), String> {
    let fail = |e: io::Error| format!("{}: cannot write the PNG: {e}", name.display());
    match destination {
        Destination::File { path, existing } => {
            let temp = temporary_beside(&path, existing.as_ref()).map_err(fail)?;
            let times = write_png(render, size, temp.as_file()).map_err(fail)?;
            temp.as_file().sync_all().map_err(fail)?;
            // Rename over the file that was there; a new name must still be free, so a
            // file or link placed there since the checks above is not replaced either.
            let persisted = match existing {
                Some(_) => temp.persist(&path),
                None => temp.persist_noclobber(&path),
            };
            persisted.map_err(|e| fail(e.error))?;
            Ok(times)
        }
        Destination::Stream { path } => {
            let stream = OpenOptions::new().write(true).open(&path).map_err(fail)?;
            write_png(render, size, &stream).map_err(fail)
        }
    }
}

/// The summary's note of what a scene has beyond spheres and where its secondary rays
/// start (` (2 lights, 1 plane, max_depth 3, secondary convex)`); empty for one drawn
/// through the spheres-only type, which traces no secondary ray.
fn features(file: &FullSceneFile, secondary: SecondaryOrigin) -> String {
    if !file.has_features() {
        return String::new();
    }
    let count = |n: usize, noun: &str| format!("{n} {noun}{}", if n == 1 { "" } else { "s" });
    let scene = &file.scene;
    format!(
        " ({}, {}, max_depth {}, secondary {})",
        count(scene.lights().len(), "light"),
        count(scene.planes().len(), "plane"),
        scene.max_depth(),
        secondary_name(secondary)
    )
}

/// Where the PNG goes, decided before anything is written.
enum Destination {
    /// A regular file, new or replaced (`existing`): written beside it, then renamed.
    File {
        path: PathBuf,
        existing: Option<fs::Metadata>,
    },
    /// A FIFO or character device: written through, never replaced.
    Stream { path: PathBuf },
}

/// Applies the output rules (module docs) to `output`.
fn destination(output: &Path, scene: &Path, force: bool) -> Result<Destination, String> {
    let name = output.display();
    // `metadata` follows links, so this is what the PNG would land in.
    let meta = match fs::metadata(output) {
        Ok(meta) => meta,
        Err(e) if e.kind() == io::ErrorKind::NotFound => {
            if fs::symlink_metadata(output).is_ok() {
                return Err(format!(
                    "{name} is a symbolic link to a file that does not exist: refusing to create it"
                ));
            }
            if output.file_name().is_none() {
                return Err(format!("{name}: not a file name"));
            }
            return Ok(Destination::File {
                path: output.to_path_buf(),
                existing: None,
            });
        }
        Err(e) => return Err(format!("{name}: {e}")),
    };
    let scene_meta = fs::metadata(scene).map_err(|e| format!("{}: {e}", scene.display()))?;
    if same_file(&meta, &scene_meta, output, scene) {
        return Err(format!(
            "{name} is the scene file {}: refusing to write the PNG over its input",
            scene.display()
        ));
    }
    let kind = meta.file_type();
    if kind.is_file() {
        if meta.permissions().readonly() && !force {
            return Err(format!(
                "{name} is read-only: refusing to replace it (--force replaces it, keeping its permissions)"
            ));
        }
        // Replace the file the links lead to, not the link.
        let path = fs::canonicalize(output).map_err(|e| format!("{name}: {e}"))?;
        return Ok(Destination::File {
            path,
            existing: Some(meta),
        });
    }
    if kind.is_dir() {
        return Err(format!("{name} is a directory"));
    }
    if is_stream(&kind) {
        return Ok(Destination::Stream {
            path: output.to_path_buf(),
        });
    }
    Err(format!(
        "{name} is a block device, socket or other special file: refusing to write to it"
    ))
}

#[cfg(unix)]
fn same_file(a: &fs::Metadata, b: &fs::Metadata, _: &Path, _: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    a.dev() == b.dev() && a.ino() == b.ino()
}

#[cfg(not(unix))]
fn same_file(_: &fs::Metadata, _: &fs::Metadata, a: &Path, b: &Path) -> bool {
    matches!((fs::canonicalize(a), fs::canonicalize(b)), (Ok(a), Ok(b)) if a == b)
}

#[cfg(unix)]
fn is_stream(kind: &fs::FileType) -> bool {
    use std::os::unix::fs::FileTypeExt;
    kind.is_fifo() || kind.is_char_device()
}

#[cfg(not(unix))]
fn is_stream(_: &fs::FileType) -> bool {
    false
}

/// The temporary file for `path`: created exclusively under a random name in the same
/// directory (so the rename stays on one file system and no pre-placed link is
/// followed), with the replaced file's permissions and owner, or the usual ones.
fn temporary_beside(path: &Path, existing: Option<&fs::Metadata>) -> io::Result<tempfile::NamedTempFile> {
    let dir = match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".render-").suffix(".png.tmp");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        // A new file gets 0666 less the umask, like any file the shell creates.
        builder.permissions(fs::Permissions::from_mode(0o666));
    }
    let temp = builder.tempfile_in(dir)?;
    if let Some(meta) = existing {
        temp.as_file().set_permissions(meta.permissions())?;
        #[cfg(unix)]
        {
            use std::os::unix::fs::MetadataExt;
            // Only root can give a file away; for anyone else the owner is theirs already.
            let _ = std::os::unix::fs::fchown(temp.as_file(), Some(meta.uid()), Some(meta.gid()));
        }
    }
    Ok(temp)
}

/// Renders straight into a PNG stream on `out`, one row buffered at a time; returns the
/// time spent tracing and the time spent encoding and writing.
fn write_png<const N: usize, const L: usize, const P: usize, const D: usize>(
    render: &Render<'_, N, Rgb888, L, P, D>,
    size: Size,
    out: &File,
) -> io::Result<(Duration, Duration)> {
    let start = Instant::now();
    let mut out = BufWriter::new(out);
    let mut encoder = png::Encoder::new(&mut out, size.width, size.height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header()?;
    let mut encoding = {
        let mut rows = PngRows {
            stream: writer.stream_writer()?,
            size,
            row: Vec::with_capacity(size.width as usize * 3),
            next_row: 0,
            encoding: Duration::ZERO,
        };
        render.draw(&mut rows)?;
        if rows.next_row != size.height {
            return Err(io::Error::other(format!(
                "the render drew {} of {} rows",
                rows.next_row, size.height
            )));
        }
        let finish = Instant::now();
        rows.stream.finish()?;
        rows.encoding + finish.elapsed()
    };
    let finish = Instant::now();
    writer.finish()?;
    out.flush()?;
    encoding += finish.elapsed();
    // The rows are traced while the encoder consumes them: tracing is the whole minus
    // the encoder's and the writes' share.
    Ok((start.elapsed().saturating_sub(encoding), encoding))
}

/// A `DrawTarget` that encodes the rows it is given, in order, into a PNG stream. The
/// render fills each row with one `fill_contiguous` call, top to bottom; anything else
/// (a pixel out of row order) is an error rather than a silently wrong image.
struct PngRows<'w, W: Write> {
    stream: png::StreamWriter<'w, W>,
    size: Size,
    /// The RGB bytes of the row being filled.
    row: Vec<u8>,
    next_row: u32,
    /// Time spent in the encoder and the writes.
    encoding: Duration,
}

impl<W: Write> Dimensions for PngRows<'_, W> {
    fn bounding_box(&self) -> Rectangle {
        Rectangle::new(Point::zero(), self.size)
    }
}

impl<W: Write> DrawTarget for PngRows<'_, W> {
    type Color = Rgb888;
    type Error = io::Error;

    fn draw_iter<I>(&mut self, _pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        Err(io::Error::other("the PNG stream takes whole rows in order"))
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Self::Color>,
    {
        let whole_rows = area.top_left == Point::new(0, self.next_row as i32)
            && area.size.width == self.size.width
            && area.size.height <= self.size.height - self.next_row;
        if !whole_rows {
            return Err(io::Error::other("the PNG stream takes whole rows in order"));
        }
        let row_bytes = self.size.width as usize * 3;
        for color in colors
            .into_iter()
            .take(area.size.width as usize * area.size.height as usize)
        {
            self.row.extend_from_slice(&[color.r(), color.g(), color.b()]);
            if self.row.len() == row_bytes {
                let start = Instant::now();
                self.stream.write_all(&self.row)?;
                self.encoding += start.elapsed();
                self.row.clear();
                self.next_row += 1;
            }
        }
        Ok(())
    }
}

/// The process's peak resident memory in KiB (`VmHWM`), where the OS reports it.
fn peak_memory() -> Option<u64> {
    let status = fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}
