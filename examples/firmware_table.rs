//! Formats a `qemu_cortex_m4` run as the README's Markdown tables: instructions per
//! pixel for every method on every standard scene at 240×240, the stack of a render,
//! and a frame-rate estimate.
//!
//! ```sh
//! cargo run --example firmware_table -- [QEMU-OUTPUT]   # default: tests/data/qemu_cortex_m4.txt
//! ```
//!
//! `.ci/firmware` runs QEMU and then this on the fresh output.

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

fn main() -> ExitCode {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "tests/data/qemu_cortex_m4.txt".into());
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

    println!(
        "\nStack bytes of a render (high-water mark below the caller: stack painted before, scanned after, in an untimed second render with the SysTick interrupt off), lowest–highest over the {} methods:\n",
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

    if let Some(e) = output.get("lab", &Method::DEFAULT.to_string()) {
        println!(
            "\nEstimate only: at 168 MHz and one instruction per cycle, the default method's {:.1} instructions per pixel on `lab` would be {:.1} frames/s at 240×240 (a real Cortex-M4 takes more cycles than instructions: flash wait states, 14-cycle divides and square roots).",
            e.ipp(),
            F_CLK_HZ / (e.ipp() * PIXELS)
        );
    }
    if !output.ok {
        eprintln!("error: {path}: the firmware run did not end with `result ok`");
        return ExitCode::FAILURE;
    }
    ExitCode::SUCCESS
}
