//! Formats a QEMU firmware run (`qemu_cortex_m4`, `qemu_cortex_m33`, `qemu_cortex_m0`,
//! `qemu_rv32`) as the README's Markdown tables: instructions per pixel for every method
//! on every standard scene at 240×240, the stack of a render, and a frame-rate estimate.
//!
//! ```sh
//! cargo run --features tools --example firmware_table -- [QEMU-OUTPUT]   # default: lab/data/qemu_cortex_m4.txt
//! cargo run --features tools --example firmware_table -- lab/data/qemu_cortex_m0.txt --estimate "an RP2040" 133
//! cargo run --features tools --example firmware_table -- QEMU-OUTPUT --cycles lab/data/cycles_cortex_m4.txt
//! ```
//!
//! Without `--estimate CHIP MHZ` the estimate is the STM32F405/407's at 168 MHz.
//! If the run measured the scenes with lights, a floor and mirrors (`shadows`,
//! `mirrors`: the Cortex-M4F's and Cortex-M33's), also their table: instructions per
//! pixel and stack of each render, and with `--cycles FILE` (the Cortex-M4 estimates
//! `.ci/cycles --update` stores) the default method's estimated cycles per pixel and
//! the frame rates they imply at
//! 168 MHz with an ST7789 on SPI at 42 MHz, blocking and overlapped. An estimate is
//! used only if its hash equals the run's (the same pixels, so the same kernel).
//! `.ci/firmware`, `.ci/firmware-m33` and `.ci/firmware-nofpu` run QEMU and then this on
//! the fresh output.

use embedded_raytracer_lab::qemu_output;

use std::process::ExitCode;

use embedded_raytracer::Method;
use qemu_output::QemuOutput;
use standard::{FEATURE_SCENES, SCENES};

use embedded_raytracer_lab::scenes;
use embedded_raytracer_scenes as standard;
/// Pixels of a 240×240 frame.
const PIXELS: f64 = 240.0 * 240.0;
/// The STM32F405/407's maximum core clock.
const F_CLK_HZ: f64 = 168e6;
/// Core cycles one pixel spends on the wire: 16 bits (Rgb565) at SPI1's fastest clock,
/// 42 MHz (APB2 84 MHz / 2), is 4 core cycles a bit at 168 MHz.
const WIRE_CYCLES_PER_PIXEL: f64 = 16.0 * 4.0;

/// One line of `.ci/cycles`' estimates: `estimate SCENE METHOD hash 0x… pixels P instr
/// I cycles C …`.
struct CycleEstimate {
    scene: String,
    method: String,
    hash: u64,
    pixels: f64,
    cycles: f64,
}

/// The estimates of renders (lines with a hash) in `text`.
fn cycle_estimates(text: &str) -> Result<Vec<CycleEstimate>, String> {
    let mut out = Vec::new();
    for line in text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.first() != Some(&"estimate") || words.get(3) != Some(&"hash") {
            continue;
        }
        let value = |key: &str| {
            words
                .iter()
                .position(|w| *w == key)
                .and_then(|i| words.get(i + 1))
                .copied()
                .ok_or_else(|| format!("no `{key}` in {line:?}"))
        };
        let number = |key: &str| {
            value(key)?
                .parse::<f64>()
                .map_err(|e| format!("`{key}` in {line:?}: {e}"))
        };
        let hash = value("hash")?;
        out.push(CycleEstimate {
            scene: words[1].to_string(),
            method: words[2].to_string(),
            hash: hash
                .strip_prefix("0x")
                .and_then(|h| u64::from_str_radix(h, 16).ok())
                .ok_or_else(|| format!("bad hash in {line:?}"))?,
            pixels: number("pixels")?,
            cycles: number("cycles")?,
        });
    }
    Ok(out)
}

/// `--estimate CHIP MHZ`: a chip to estimate the frame rate of, at its clock.
struct Estimate {
    chip: String,
    mhz: f64,
}

/// The command line.
struct Args {
    path: String,
    estimate: Option<Estimate>,
    /// `--cycles FILE`: `.ci/cycles`' estimates.
    cycles: Option<String>,
}

/// The command line, parsed.
fn args() -> Result<Args, String> {
    let mut path = None;
    let mut estimate = None;
    let mut cycles = None;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        if arg == "--cycles" {
            cycles = Some(args.next().ok_or("--cycles needs FILE")?);
        } else if arg == "--estimate" {
            let (Some(chip), Some(mhz)) = (args.next(), args.next()) else {
                return Err("--estimate needs CHIP and MHZ".into());
            };
            let mhz = mhz
                .parse::<f64>()
                .ok()
                .filter(|m| *m > 0.0)
                .ok_or_else(|| format!("--estimate: bad MHZ {mhz:?}"))?;
            estimate = Some(Estimate { chip, mhz });
        } else if path.is_none() {
            path = Some(arg);
        } else {
            return Err(format!("unexpected argument {arg:?}"));
        }
    }
    Ok(Args {
        path: path.unwrap_or_else(|| "lab/data/qemu_cortex_m4.txt".into()),
        estimate,
        cycles,
    })
}

fn main() -> ExitCode {
    let Args {
        path,
        estimate,
        cycles,
    } = match args() {
        Ok(args) => args,
        Err(e) => {
            eprintln!(
                "error: {e}\nusage: firmware_table [QEMU-OUTPUT] [--estimate CHIP MHZ] [--cycles FILE]"
            );
            return ExitCode::from(2);
        }
    };
    let cycles = match cycles.map(|c| {
        std::fs::read_to_string(&c)
            .map_err(|e| e.to_string())
            .and_then(|text| cycle_estimates(&text))
            .map_err(|e| format!("{c}: {e}"))
    }) {
        None => Vec::new(),
        Some(Ok(cycles)) => cycles,
        Some(Err(e)) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let output = match std::fs::read_to_string(&path)
        .map_err(|e| e.to_string())
        .and_then(|text| QemuOutput::parse(&text).map_err(|e| e.to_string()))
    {
        Ok(output) => output,
        Err(e) => {
            eprintln!("error: {path}: {e}");
            return ExitCode::FAILURE;
        }
    };

    println!("Instructions per pixel at 240×240, rendered into `PixelHash` (sink included):\n");
    println!("| method | {} |", SCENES.join(" | "));
    println!("|---|{}", "---:|".repeat(SCENES.len()));
    // The firmware's own default (the integer kernel on a chip without an FPU).
    let default = output
        .default
        .clone()
        .unwrap_or_else(|| Method::TARGET_DEFAULT.to_string());
    let integer_measured = output
        .entries
        .iter()
        .any(|e| e.method == Method::INTEGER.to_string());
    for method in Method::ALL
        .into_iter()
        .chain(integer_measured.then_some(Method::INTEGER))
    {
        let name = method.to_string();
        let mark = if name == default { " (default)" } else { "" };
        let cells: Vec<String> = SCENES
            .iter()
            .map(|scene| match output.get(scene, &name) {
                Some(e) => format!("{:.1}", e.ipp()),
                None => "—".into(),
            })
            .collect();
        println!("| `{name}`{mark} | {} |", cells.join(" | "));
    }
    if let Some((pixels, instructions)) = output.sink {
        println!(
            "\nOf these, the `PixelHash` sink itself (FNV-1a over 3 bytes, fed row by row) costs {:.1} instructions per pixel.",
            instructions as f64 / pixels.max(1) as f64
        );
    }

    // Only SysTick (a `clock` line) needs an interrupt; RV32's minstret has none.
    let interrupt = if output.clock_hz.is_some() {
        " with the SysTick interrupt off"
    } else {
        ""
    };
    println!(
        "\nStack bytes of a render (high-water mark below the caller: stack painted before, scanned after, in an untimed second render{interrupt}), lowest–highest over the {} methods:\n",
        Method::ALL.len() + usize::from(integer_measured)
    );
    println!("| {} |", SCENES.join(" | "));
    println!("|{}", "---:|".repeat(SCENES.len()));
    let cells: Vec<String> = SCENES
        .iter()
        .map(|scene| {
            let stacks: Vec<u64> = output
                .entries
                .iter()
                .filter(|e| e.scene == *scene)
                .map(|e| e.stack)
                .collect();
            match (stacks.iter().min(), stacks.iter().max()) {
                (Some(lo), Some(hi)) => format!("{lo}–{hi}"),
                _ => "—".into(),
            }
        })
        .collect();
    println!("| {} |", cells.join(" | "));

    match (output.get("lab", &default), &estimate) {
        (Some(e), Some(Estimate { chip, mhz })) => {
            // The kernel alone: the sink's own cost taken off.
            let sink = output.sink.map_or(0.0, |(p, i)| i as f64 / p.max(1) as f64);
            println!(
                "\nThe default method (`{default}`) on `lab`: {:.1} instructions per pixel, {:.1} without the sink. Estimate only: {chip} at {mhz} MHz would draw {:.2} frames/s at 240×240 ({:.2} without the sink) if one instruction were one cycle; a real core needs more cycles than instructions (flash wait states, multi-cycle loads and branches).",
                e.ipp(),
                e.ipp() - sink,
                mhz * 1e6 / (e.ipp() * PIXELS),
                mhz * 1e6 / ((e.ipp() - sink) * PIXELS)
            )
        }
        (Some(e), None) => println!(
            "\nEstimate only: at 168 MHz and one instruction per cycle, the default method's {:.1} instructions per pixel on `lab` would be {:.1} frames/s at 240×240 (a real Cortex-M4 takes more cycles than instructions: flash wait states, 14-cycle divides and square roots).",
            e.ipp(),
            F_CLK_HZ / (e.ipp() * PIXELS)
        ),
        (None, _) => {}
    }
    if output
        .entries
        .iter()
        .any(|e| FEATURE_SCENES.contains(&e.scene.as_str()))
    {
        feature_table(&output, &cycles);
    }
    if !output.ok {
        eprintln!("error: {path}: the firmware run did not end with `result ok`");
        return ExitCode::FAILURE;
    }
    ExitCode::SUCCESS
}

/// The scenes with lights, a floor and mirrors: every render of
/// `scenes::FEATURE_RENDERS`, with `lab`'s default for scale; the default method's
/// estimated cycles per pixel and frame rates where `cycles` has its estimate.
fn feature_table(output: &QemuOutput, cycles: &[CycleEstimate]) {
    let default = Method::TARGET_DEFAULT.to_string();
    if cycles.is_empty() {
        // No cycle estimates (a chip the cycle model does not cover): the measured
        // instructions and stack only.
        println!(
            "\nThe scenes with lights, a floor and mirrors at 240×240 (`PixelHash` sink included), \
             `lab` for scale:\n"
        );
        println!("| scene | render | instructions/pixel | stack (B) |");
        println!("|---|---|---:|---:|");
        for (scene, label) in feature_rows(&default) {
            if let Some(e) = output.get(scene, &label) {
                let mark = if label == default { " (default)" } else { "" };
                println!("| {scene} | `{label}`{mark} | {:.1} | {} |", e.ipp(), e.stack);
            }
        }
        return;
    }
    println!(
        "\nThe scenes with lights, a floor and mirrors at 240×240 (`PixelHash` sink included), \
         `lab` for scale. Estimated cycles (`bash .ci/cycles --update`, the default method only) and \
         the frame rates they imply at 168 MHz with a 240×240 ST7789 on SPI at 42 MHz (64 core cycles \
         a pixel on the wire, 21.9 ms a frame): blocking traces, then sends (trace + wire); \
         overlapped sends one part of the frame while it traces the next (the larger of the two, \
         at best: see the DMA example below). **Estimates of a model, not measurements.**\n"
    );
    println!(
        "| scene | render | instructions/pixel | stack (B) | est. cycles/pixel | frames/s blocking | frames/s overlapped |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|");
    let mut stale = Vec::new();
    for (scene, label) in feature_rows(&default) {
        let Some(e) = output.get(scene, &label) else {
            continue;
        };
        let estimate = cycles
            .iter()
            .find(|c| c.scene == scene && c.method == label && c.pixels > 0.0);
        let figures = match estimate {
            Some(c) if c.hash == e.hash => {
                let per_pixel = c.cycles / c.pixels;
                format!(
                    "{per_pixel:.1} | {:.2} | {:.2}",
                    F_CLK_HZ / ((per_pixel + WIRE_CYCLES_PER_PIXEL) * PIXELS),
                    F_CLK_HZ / (per_pixel.max(WIRE_CYCLES_PER_PIXEL) * PIXELS)
                )
            }
            Some(_) => {
                stale.push(format!("{scene} {label}"));
                "— | — | —".into()
            }
            None => "— | — | —".into(),
        };
        let mark = if label == default { " (default)" } else { "" };
        println!(
            "| {scene} | `{label}`{mark} | {:.1} | {} | {figures} |",
            e.ipp(),
            e.stack
        );
    }
    if !stale.is_empty() {
        println!(
            "\n(No estimate shown for {}: the cycle estimates are of other pixels, an older kernel; \
             `bash .ci/cycles --update` re-makes them.)",
            stale.join(", ")
        );
    }
}

/// The rows of the feature table: `lab`'s default for scale, then every render of
/// `scenes::FEATURE_RENDERS` on each scene with features, as `(scene, label)`.
fn feature_rows(default: &str) -> impl Iterator<Item = (&'static str, String)> {
    std::iter::once(("lab", default.to_string())).chain(FEATURE_SCENES.iter().flat_map(|&scene| {
        scenes::FEATURE_RENDERS
            .iter()
            .map(move |(method, suffix, _)| (scene, format!("{method}{suffix}")))
    }))
}
