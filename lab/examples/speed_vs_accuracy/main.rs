//! The chart of speed against accuracy: every method on every standard scene.
//!
//! ```text
//! cargo run --release --features tools --example speed_vs_accuracy            # writes docs/speed_vs_accuracy.{csv,png,md}
//! cargo run --release --features tools --example speed_vs_accuracy -- --quick --out target/chart   # CI: 1 run each
//! ```
//!
//! For each scene and method: the time per pixel (median of several renders in this
//! process, into an in-memory Rgb565 frame buffer) and the error against an `f64`
//! reference render: **coverage errors** (pixels whose hit sphere differs from the
//! reference's, hit/miss included) and the **max shade error** (largest 8-bit channel
//! difference among the pixels that hit the same sphere as the reference, or both miss).
//! Also the growth curve: ns/pixel against the number of spheres (the first 1 … 64 of
//! the `crowd` scene), and the same errors on `lab` against the **estimated Cortex-M4
//! cycles per pixel** of `lab/data/cycles_cortex_m4.txt` (240×240, from `.ci/cycles
//! --update`; a model, see the README) instead of the host's time.
//!
//! And the **sampling axis** (two panels at the bottom right, a section of the md and
//! csv): every `Sampling` choice on every standard scene with the default method, its
//! cost — host ns/pixel timed in the same interleaved way, and rays averaged per pixel —
//! against its mean error over all pixels, in 8-bit levels, from the 16 × 16-ray
//! box-filtered reference in linear light (`reference::aa`; the measurement of
//! `aa_table`, `common/aa.rs`, so the errors are the README's anti-aliasing table's:
//! scenes wider than 256 pixels at 256 wide). `--quick` measures against a 4 × 4-ray
//! reference instead (16 times cheaper; a smoke test, not the README's figures).
//!
//! The reference is the accuracy lab's independent `f64` renderer
//! ([`embedded_raytracer_lab::reference`]: the seed's camera and Lab #1 shading, the robust
//! sphere test, all in `f64`, sharing no code with the kernel), and the metrics are its
//! [`compare`](embedded_raytracer_lab::reference::compare) (pixels the reference cannot
//! decide are not counted).
//!
//! The example's parts: [`measure`] (timing and errors of the methods, the growth
//! curve, the lit scenes), [`sampling`] (the sampling axis: its measurement, panels and
//! table), [`plot`] and [`panels`] (the chart), [`report`] (the md and csv).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use embedded_raytracer::scene_file;
use embedded_raytracer_scenes::{self as standard, MAX_SPHERES, SCENES};

mod measure;
mod panels;
mod plot;
mod report;
mod sampling;

/// The flags: `--quick` (one timed render a point, the 4 × 4-ray reference), `--out
/// DIR` (where the csv, md and png go; `docs/` by default).
struct Args {
    quick: bool,
    out: PathBuf,
}

impl Args {
    /// Timed renders per point (interleaved rounds).
    fn runs(&self) -> usize {
        if self.quick {
            1
        } else {
            15
        }
    }
}

/// The flags after the program's name.
fn parse_args() -> Result<Args, String> {
    let mut args = Args {
        quick: false,
        out: PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../docs")),
    };
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--quick" => args.quick = true,
            "--out" => args.out = PathBuf::from(it.next().ok_or("--out needs a directory")?),
            _ => {
                return Err(format!(
                    "unknown argument `{a}`; usage: speed_vs_accuracy [--quick] [--out DIR]"
                ))
            }
        }
    }
    Ok(args)
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let args = parse_args()?;
    let runs = args.runs();
    std::fs::create_dir_all(&args.out)?;
    // Errors first (one trace per method and scene), then the timing rounds.
    let files = SCENES
        .iter()
        .map(|scene| scene_file::load::<MAX_SPHERES, 0, 0, 0>(standard::path(scene)))
        .collect::<Result<Vec<_>, _>>()?;
    let points = measure::methods(&files, runs);
    let growth = measure::growth(args.quick, runs)?;
    let isolated = measure::isolated(runs)?;
    let lit = measure::lit(runs);
    let sampled = sampling::measure(&files, args.quick, runs);
    let cycles =
        measure::estimated_cycles(&Path::new(env!("CARGO_MANIFEST_DIR")).join("data/cycles_cortex_m4.txt"))?;
    report::write_outputs(&args, &points, &lit, &growth, &cycles, &isolated, &sampled)?;
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
