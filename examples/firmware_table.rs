//! Formats a QEMU firmware run (`qemu_cortex_m4`, `qemu_cortex_m0`, `qemu_rv32`) as the
//! README's Markdown tables: instructions per pixel for every method on every standard
//! scene at 240×240, the stack of a render, and a frame-rate estimate.
//!
//! ```sh
//! cargo run --example firmware_table -- [QEMU-OUTPUT]   # default: tests/data/qemu_cortex_m4.txt
//! cargo run --example firmware_table -- tests/data/qemu_cortex_m0.txt --estimate "an RP2040" 133
//! ```
//!
//! Without `--estimate CHIP MHZ` the estimate is the STM32F405/407's at 168 MHz.
//! `.ci/firmware` and `.ci/firmware-nofpu` run QEMU and then this on the fresh output.

#[path = "common/qemu_output.rs"]
mod qemu_output;

use std::process::ExitCode;

use embedded_raytracer::Method;
use qemu_output::QemuOutput;
use standard::SCENES;

#[path = "common/standard.rs"]
mod standard;
/// Pixels of a 240×240 frame.
const PIXELS: f64 = 240.0 * 240.0;
/// The STM32F405/407's maximum core clock.
const F_CLK_HZ: f64 = 168e6;

/// `--estimate CHIP MHZ`: a chip to estimate the frame rate of, at its clock.
struct Estimate {
    chip: String,
    mhz: f64,
}

/// `(run path, estimate)` from the command line.
fn args() -> Result<(String, Option<Estimate>), String> {
    let mut path = None;
    let mut estimate = None;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        if arg == "--estimate" {
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
    Ok((
        path.unwrap_or_else(|| "tests/data/qemu_cortex_m4.txt".into()),
        estimate,
    ))
}

fn main() -> ExitCode {
    let (path, estimate) = match args() {
        Ok(args) => args,
        Err(e) => {
            eprintln!("error: {e}\nusage: firmware_table [QEMU-OUTPUT] [--estimate CHIP MHZ]");
            return ExitCode::from(2);
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
    for method in Method::ALL {
        let name = method.to_string();
        let mark = if method == Method::DEFAULT {
            " (default)"
        } else {
            ""
        };
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
        Method::ALL.len()
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

    match (output.get("lab", &Method::DEFAULT.to_string()), &estimate) {
        (Some(e), Some(Estimate { chip, mhz })) => println!(
            "\nEstimate only: {chip} at {mhz} MHz would draw {:.2} frames/s at 240×240 with the default method on `lab` ({:.1} instructions per pixel) if one instruction were one cycle; a real core needs more cycles than instructions (flash wait states, multi-cycle loads and branches).",
            mhz * 1e6 / (e.ipp() * PIXELS),
            e.ipp()
        ),
        (Some(e), None) => println!(
            "\nEstimate only: at 168 MHz and one instruction per cycle, the default method's {:.1} instructions per pixel on `lab` would be {:.1} frames/s at 240×240 (a real Cortex-M4 takes more cycles than instructions: flash wait states, 14-cycle divides and square roots).",
            e.ipp(),
            F_CLK_HZ / (e.ipp() * PIXELS)
        ),
        (None, _) => {}
    }
    if !output.ok {
        eprintln!("error: {path}: the firmware run did not end with `result ok`");
        return ExitCode::FAILURE;
    }
    ExitCode::SUCCESS
}
