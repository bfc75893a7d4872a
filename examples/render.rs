//! The host CLI: render a TOML scene file to a PNG.
//!
//! ```text
//! cargo run --release --example render -- scenes/lab.toml --output lab.png \
//!     [--stepping world-space|incremental|direct] \
//!     [--sphere-test algebraic|geometric|robust|forward-diff|auto] [--sqrt exact|fast]
//! ```
//!
//! Prints the resolution, the method and the render time. Any bad input (file, field
//! or flag) is one message on stderr and exit code 2; the output file is then neither
//! created nor touched (the PNG is written to a temporary file and renamed into place
//! only after a successful render).

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use embedded_graphics::{pixelcolor::Rgb888, prelude::*};
use embedded_graphics_simulator::{OutputSettings, SimulatorDisplay};
use embedded_raytracer::{scene_file, Method, Render};

/// Scene-file capacity of the CLI.
const MAX_SPHERES: usize = 256;

const USAGE: &str =
    "usage: render SCENE.toml [--output OUT.png] [--stepping world-space|incremental|direct] \
[--sphere-test algebraic|geometric|robust|forward-diff|auto] [--sqrt exact|fast]";

struct Args {
    scene: PathBuf,
    output: PathBuf,
    method: Method,
}

fn parse_args(mut args: impl Iterator<Item = String>) -> Result<Args, String> {
    let mut scene = None;
    let mut output = None;
    let mut method = Method::default();
    while let Some(arg) = args.next() {
        let mut value = |flag: &str| args.next().ok_or_else(|| format!("{flag} needs a value"));
        match arg.as_str() {
            "--output" | "-o" => output = Some(PathBuf::from(value(&arg)?)),
            "--stepping" => method.stepping = value(&arg)?.parse().map_err(|e| format!("--stepping: {e}"))?,
            "--sphere-test" => {
                method.sphere_test = value(&arg)?.parse().map_err(|e| format!("--sphere-test: {e}"))?
            }
            "--sqrt" => method.sqrt = value(&arg)?.parse().map_err(|e| format!("--sqrt: {e}"))?,
            "--help" | "-h" => return Err(USAGE.to_string()),
            flag if flag.starts_with('-') => return Err(format!("unknown flag `{flag}`")),
            path if scene.is_none() => scene = Some(PathBuf::from(path)),
            extra => return Err(format!("unexpected argument `{extra}`")),
        }
    }
    let scene = scene.ok_or("no scene file given")?;
    let output = output.unwrap_or_else(|| {
        let stem = scene.file_stem().unwrap_or_default();
        PathBuf::from(stem).with_extension("png")
    });
    Ok(Args {
        scene,
        output,
        method,
    })
}

fn run() -> Result<(), String> {
    let args = parse_args(std::env::args().skip(1))?;
    let file = scene_file::load::<MAX_SPHERES>(&args.scene).map_err(|e| e.to_string())?;
    let size = file.camera.size();

    let mut display = SimulatorDisplay::<Rgb888>::new(size);
    let render = Render::new(&file.scene, &file.camera).with_method(args.method);
    let start = Instant::now();
    let Ok(()) = render.draw(&mut display); // the simulator cannot fail
    let elapsed = start.elapsed();

    write_png(&display, &args.output)?;
    let pixels = u64::from(size.width) * u64::from(size.height);
    println!(
        "{}: {}x{} pixels, method {}, {:.3} ms ({:.1} ns/pixel) -> {}",
        args.scene.display(),
        size.width,
        size.height,
        args.method,
        elapsed.as_secs_f64() * 1e3,
        elapsed.as_secs_f64() * 1e9 / pixels as f64,
        args.output.display()
    );
    Ok(())
}

/// One image pixel per scene pixel, 8-bit RGB; written beside the target and renamed
/// so a failure never leaves a half-written or clobbered file.
fn write_png(display: &SimulatorDisplay<Rgb888>, output: &Path) -> Result<(), String> {
    let image = display.to_rgb_output_image(&OutputSettings::default());
    let dir = output
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = output
        .file_name()
        .ok_or_else(|| format!("{}: not a file name", output.display()))?;
    let tmp = dir.join(format!(".{}.{}.tmp", name.to_string_lossy(), std::process::id()));
    let result = image
        .save_png(&tmp)
        .map_err(|e| e.to_string())
        .and_then(|()| std::fs::rename(&tmp, output).map_err(|e| e.to_string()));
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(format!("{}: cannot write the PNG: {e}", output.display()));
    }
    Ok(())
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
