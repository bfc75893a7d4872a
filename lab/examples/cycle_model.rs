//! Estimated Cortex-M4 cycles of marked regions of a firmware run, from QEMU's
//! execution log and the ARM Technical Reference Manual's instruction timings (the
//! model and every assumption: `lab/src/cycle_model.rs`).
//!
//! ```text
//! cycle_model run --disasm DISASM --trace TRACE|- --labels FIRMWARE-OUTPUT [--profile FILE]
//! cycle_model table [DATA] [--qemu QEMU-OUTPUT]
//! ```
//!
//! `run` streams QEMU's log (a named pipe or stdin, never held in memory) through the
//! model, with `DISASM` the `llvm-objdump -d` of the same ELF. The log is either
//! `-singlestep -d exec,nochain` (one instruction per translation block: one `Trace`
//! line per executed instruction) or, several times faster, `-d in_asm,exec,nochain`
//! (each block's instructions listed once when translated, one `Trace` line per
//! executed block, expanded into its instructions; no interrupt runs inside a region,
//! so every block runs to its end). `.ci/cycles --quick` checks that both give the same
//! estimates. Regions lie between calls of `cycle_region_begin` and `cycle_region_end`;
//! the k-th is labelled by the k-th `region LABEL…` line of the firmware's output.
//! Prints one line per region (keys: `lab/src/cycle_model.rs`'s `Counts`):
//!
//! ```text
//! estimate LABEL… instr N cycles C refills R ldst C1 branch C2 divsqrt C3 fp C4 int C5 cond_extra X it_fold Y store_buffer Z divides D fetch_bytes B code_bytes F code_lines L
//! ```
//!
//! With `--profile FILE`, also writes where each region's cycles go: per executed
//! instruction `LABEL… | ADDRESS COUNT CYCLES TEXT <FUNCTION>`, by address, and per
//! function its share of the region's cycles (sort the file to find the hot loop).
//!
//! A region may leave out work in its middle: the instructions between a call of
//! `cycle_region_pause` and the return of `cycle_region_resume` are not counted.
//!
//! A label holding `expected N` is a calibration loop: its estimate must be exactly `N`
//! or the tool fails. Also fails on an executed instruction the timing table does not
//! know, an address outside the disassembly, or a region count that differs from the
//! labels'.
//!
//! `table` formats a file of such lines (default `lab/data/cycles_cortex_m4.txt`) as
//! the README's Markdown: cycles per pixel beside instructions per pixel, the default
//! method's breakdown on `lab`, and the default's cycles on the scenes with lights, a
//! floor and mirrors with the frame rates they imply beside an ST7789 at 42 MHz, and
//! the first frame of `bounce` in milliseconds at 168 MHz; with `--qemu`, the trace's instruction counts
//! are compared with the SysTick-measured ones of that `qemu_cortex_m4` output (which
//! must come from the same kernel).
//!
//! `.ci/cycles` builds the firmware, runs QEMU and this tool.

use embedded_raytracer_lab::cycle_model;
use embedded_raytracer_lab::qemu_output;
use embedded_raytracer_scenes as standard;

use std::collections::HashMap;
use std::io::{BufRead, BufReader, Read};
use std::process::ExitCode;

use cycle_model::{Counts, Kind, ModelError, Program, Tracer, DIVIDE_CYCLES, P};
use embedded_raytracer::Method;
use standard::{FEATURE_SCENES, SCENES};

/// The STM32F405/407's maximum core clock.
const F_CLK_HZ: f64 = 168e6;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("run") => run(args.get(1..).unwrap_or_default()),
        Some("table") => table(args.get(1..).unwrap_or_default()),
        _ => Err(ModelError(
            "usage: cycle_model run --disasm FILE --trace FILE|- --labels FILE | table [DATA] [--qemu FILE]"
                .into(),
        )),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The value after `--name` in `args`.
fn option<'a>(args: &'a [String], name: &str) -> Option<&'a str> {
    let i = args.iter().position(|a| a == name)?;
    args.get(i + 1).map(String::as_str)
}

fn read(path: &str) -> Result<String, ModelError> {
    std::fs::read_to_string(path).map_err(|e| ModelError(format!("{path}: {e}")))
}

/// The value after `key` in a whitespace-separated `key value` list.
fn field<'a>(words: &[&'a str], key: &str) -> Option<&'a str> {
    let i = words.iter().position(|w| *w == key)?;
    words.get(i + 1).copied()
}

fn number(words: &[&str], key: &str) -> Option<u64> {
    field(words, key)?.parse().ok()
}

fn run(args: &[String]) -> Result<(), ModelError> {
    let need = |name| option(args, name).ok_or_else(|| ModelError(format!("missing {name}")));
    let (disasm, trace, labels) = (need("--disasm")?, need("--trace")?, need("--labels")?);
    let program = Program::from_objdump(&read(disasm)?)?;
    let mut tracer = Tracer::new(&program)?;
    let profile_path = option(args, "--profile");
    if profile_path.is_some() {
        tracer.profile = Some(Vec::new());
    }

    // Stream the log line by line. With `-d in_asm` QEMU prints each translation block's
    // instructions once, when it translates it (`IN:`, one `0x…:` line per instruction,
    // a blank line); every `Trace` line then stands for all of its block's instructions.
    // Without it (one instruction per block), a `Trace` line is one instruction.
    let input: Box<dyn Read> = if trace == "-" {
        Box::new(std::io::stdin().lock())
    } else {
        Box::new(std::fs::File::open(trace).map_err(|e| ModelError(format!("{trace}: {e}")))?)
    };
    let mut reader = BufReader::with_capacity(1 << 20, input);
    let mut line = Vec::with_capacity(128);
    let mut blocks: HashMap<u32, Vec<u32>> = HashMap::new();
    let mut translating: Option<Vec<u32>> = None;
    let mut retranslated = 0u64;
    let mut executed = 0u64;
    loop {
        line.clear();
        let n = reader
            .read_until(b'\n', &mut line)
            .map_err(|e| ModelError(format!("{trace}: {e}")))?;
        if n == 0 {
            break;
        }
        if let Some(pc) = cycle_model::trace_pc(&line) {
            let before = tracer.regions.len();
            match blocks.get(&pc) {
                Some(block) => {
                    for &addr in block {
                        tracer.step(addr);
                    }
                    executed += block.len() as u64;
                }
                None => {
                    tracer.step(pc);
                    executed += 1;
                }
            }
            if let Some(c) = tracer.regions.get(before) {
                eprintln!(
                    "region {}: {} instructions, {} cycles",
                    before + 1,
                    c.instructions,
                    c.cycles
                );
            }
        } else if line.starts_with(b"IN:") {
            translating = Some(Vec::new());
        } else if let Some(block) = &mut translating {
            match cycle_model::in_asm_pc(&line) {
                Some(addr) => block.push(addr),
                None => {
                    // End of the block's listing.
                    if let Some(&start) = block.first() {
                        let block = std::mem::take(block);
                        if blocks.get(&start).is_some_and(|old| *old != block) {
                            retranslated += 1;
                        }
                        blocks.insert(start, block);
                    }
                    translating = None;
                }
            }
        }
    }
    if retranslated > 0 {
        // A start address with two different blocks: which one a `Trace` line means is
        // unknown.
        return Err(ModelError(format!(
            "{retranslated} translation blocks were translated again with other instructions; \
             trace one instruction per block instead"
        )));
    }
    eprintln!("{executed} executed instructions in the log");
    if tracer.unfinished() {
        return Err(ModelError("the log ends inside a region".into()));
    }
    if tracer.unmapped > 0 {
        return Err(ModelError(format!(
            "{} executed addresses inside regions are not in the disassembly",
            tracer.unmapped
        )));
    }

    // The firmware prints one `region LABEL…` line per region, in order.
    let output = read(labels)?;
    let names: Vec<&str> = output
        .lines()
        .filter_map(|l| l.strip_prefix("region "))
        .map(str::trim)
        .collect();
    if names.len() != tracer.regions.len() {
        return Err(ModelError(format!(
            "{} regions in the log, {} `region` lines in {labels}",
            tracer.regions.len(),
            names.len()
        )));
    }
    let mut failures = 0;
    for (name, counts) in names.iter().zip(&tracer.regions) {
        if !counts.unknown.is_empty() {
            for (text, n) in &counts.unknown {
                eprintln!("error: {name}: `{text}` executed {n} times: not in the timing table");
            }
            failures += 1;
        }
        println!("estimate {name} {}", format_counts(counts));
        let words: Vec<&str> = name.split_whitespace().collect();
        if let Some(expected) = number(&words, "expected") {
            let ok = expected == counts.cycles;
            eprintln!(
                "{name}: model {} cycles {}",
                counts.cycles,
                if ok { "ok" } else { "MISMATCH" }
            );
            if !ok {
                failures += 1;
            }
        }
    }
    if failures > 0 {
        return Err(ModelError(format!("{failures} region(s) failed")));
    }
    if let (Some(path), Some(profile)) = (profile_path, &tracer.profile) {
        let text = format_profile(&program, &names, profile);
        std::fs::write(path, text).map_err(|e| ModelError(format!("{path}: {e}")))?;
    }
    Ok(())
}

/// Per region: every executed instruction (address, count, cycles, text, function),
/// then every function's cycles and share of the region's.
fn format_profile(program: &Program, names: &[&str], profile: &[Vec<(u64, u64)>]) -> String {
    use std::fmt::Write;
    // The function holding an address: the last symbol starting at or before it.
    let starts: Vec<(u32, &str)> = program
        .symbols
        .iter()
        .map(|(name, &(start, _))| (start, name.as_str()))
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    let function = |addr: u32| {
        let i = starts.partition_point(|&(start, _)| start <= addr);
        i.checked_sub(1)
            .and_then(|i| starts.get(i))
            .map_or("?", |&(_, name)| name)
    };
    let mut out = String::new();
    for (name, region) in names.iter().zip(profile) {
        let total: u64 = region.iter().map(|&(_, c)| c).sum();
        let mut by_function: HashMap<&str, u64> = HashMap::new();
        for (insn, &(count, cycles)) in program.insns.iter().zip(region) {
            if count == 0 {
                continue;
            }
            let f = function(insn.addr);
            *by_function.entry(f).or_insert(0) += cycles;
            let _ = writeln!(
                out,
                "{name} | {:08x} {count} {cycles} {} <{f}>",
                insn.addr, insn.text
            );
        }
        let mut functions: Vec<_> = by_function.into_iter().collect();
        functions.sort_by_key(|f| std::cmp::Reverse(f.1));
        for (f, cycles) in functions {
            let share = 100.0 * cycles as f64 / total.max(1) as f64;
            let _ = writeln!(out, "{name} | function {cycles} {share:.1} % <{f}>");
        }
    }
    out
}

fn format_counts(c: &Counts) -> String {
    let kinds: Vec<String> = Kind::ALL
        .iter()
        .zip(c.by_kind)
        .map(|(k, v)| format!("{} {v}", k.key()))
        .collect();
    format!(
        "instr {} cycles {} refills {} {} cond_extra {} it_fold {} store_buffer {} divides {} \
         fetch_bytes {} code_bytes {} code_lines {}",
        c.instructions,
        c.cycles,
        c.refills,
        kinds.join(" "),
        c.cond_extra,
        c.it_fold,
        c.store_buffer,
        c.divides,
        c.fetch_bytes,
        c.code_bytes,
        c.code_lines
    )
}

fn table(args: &[String]) -> Result<(), ModelError> {
    let path = args
        .first()
        .filter(|a| !a.starts_with("--"))
        .map_or("lab/data/cycles_cortex_m4.txt", String::as_str);
    let text = read(path)?;
    let estimates = cycle_model::estimates(&text);
    let find = |scene: &str, method: &str| {
        estimates
            .iter()
            .find(|e| e.scene() == scene && e.method() == method)
    };

    println!("Estimated Cortex-M4 cycles per pixel (instructions per pixel) at 240×240, `PixelHash` sink included:\n");
    println!("| method | {} |", SCENES.join(" | "));
    println!("|---|{}", "---:|".repeat(SCENES.len()));
    for method in Method::ALL {
        let name = method.to_string();
        let mark = if method == Method::TARGET_DEFAULT {
            " (default)"
        } else {
            ""
        };
        let cells: Vec<String> = SCENES
            .iter()
            .map(|scene| match find(scene, &name) {
                Some(e) => format!("{:.1} ({:.1})", e.per_pixel("cycles"), e.per_pixel("instr")),
                None => "—".into(),
            })
            .collect();
        println!("| `{name}`{mark} | {} |", cells.join(" | "));
    }

    let default = Method::TARGET_DEFAULT.to_string();
    let Some(e) = find("lab", &default) else {
        return Err(ModelError(format!("{path}: no estimate for lab {default}")));
    };
    let cpp = e.per_pixel("cycles");
    let share = |key: &str| 100.0 * e.get(key) / e.get("cycles");
    println!(
        "\nThe default `{default}` on `lab`: **{cpp:.1} estimated cycles per pixel** for {:.1} instructions \
         (CPI {:.2}), **{:.1} frames/s at 168 MHz** (240×240). Cycles spent on loads and stores {:.0} %, \
         branches {:.0} %, `VDIV`/`VSQRT` {:.0} %, other FPU {:.0} %, integer {:.0} %.",
        e.per_pixel("instr"),
        e.get("cycles") / e.get("instr"),
        F_CLK_HZ / e.get("cycles"),
        share(Kind::LoadStore.key()),
        share(Kind::Branch.key()),
        share(Kind::DivSqrt.key()),
        share(Kind::Fp.key()),
        share(Kind::Integer.key()),
    );
    let refills = e.per_pixel("refills");
    println!(
        "Sensitivity (cycles per pixel): P = 2: {:.1}, P = 3: {:.1} ({refills:.2} refills per pixel at P = {P}); \
         at most {:.1} fewer if every IT-predicated instruction failed its condition, {:.1} fewer if every \
         `IT` after a 16-bit instruction folded, {:.1} fewer if the store buffer hid the second cycle of \
         every store not followed by a load or store; {:.2} `SDIV`/`UDIV` per pixel at {DIVIDE_CYCLES} cycles.",
        cpp + refills * (2 - P) as f64,
        cpp + refills * (3 - P) as f64,
        e.per_pixel("cond_extra"),
        e.per_pixel("it_fold"),
        e.per_pixel("store_buffer"),
        e.per_pixel("divides"),
    );
    println!(
        "Fetch: {:.2} bytes per instruction, so at this CPI {:.1} cycles per 128-bit flash line of \
         straight-line code; the render executes {} distinct bytes of code ({} distinct 16-byte lines). If every \
         refill also waited for a flash line at 5 wait states (P = 6): {:.1} cycles per pixel.",
        e.get("fetch_bytes") / e.get("instr"),
        16.0 * e.get("cycles") / e.get("fetch_bytes"),
        e.get("code_bytes"),
        e.get("code_lines"),
        cpp + refills * (6 - P) as f64,
    );
    let robust = "direct/robust/exact";
    if let Some(r) = find("lab", robust) {
        println!(
            "Against `{robust}` on `lab`: {:+.1} % in estimated cycles, {:+.1} % in instructions.",
            100.0 * (e.get("cycles") / r.get("cycles") - 1.0),
            100.0 * (e.get("instr") / r.get("instr") - 1.0),
        );
    }
    if let Some(sink) = estimates.iter().find(|e| e.scene() == "sink") {
        println!(
            "The `PixelHash` sink alone (240 rows of 240 pixels through `fill_contiguous`): {:.1} estimated \
             cycles per pixel ({:.1} instructions).",
            sink.get("cycles") / sink.get("pixels"),
            sink.get("instr") / sink.get("pixels"),
        );
    }

    if let Some(band) = find("lab-band", &default) {
        println!(
            "The default on `lab` traced into a band buffer instead (`Render::draw_band` into `Rgb888` bands, \
             no `DrawTarget`, no hash: `lab-band` in `lab/firmware/examples/qemu_cycles.rs`): {:.1} estimated cycles per \
             pixel ({:.1} instructions), {:.1} frames/s at 168 MHz.",
            band.per_pixel("cycles"),
            band.per_pixel("instr"),
            F_CLK_HZ / band.get("cycles"),
        );
    }
    // The scenes with lights, a floor and mirrors: the default method, and the frame
    // rate with a 240×240 ST7789 on SPI at 42 MHz (16 bits a pixel, 4 core cycles a bit
    // at 168 MHz): blocking traces then sends, overlapped sends while it traces (the
    // larger of the two, at best).
    let wire = 16.0 * 4.0 * e.get("pixels");
    for scene in FEATURE_SCENES {
        if let Some(f) = find(scene, &default) {
            println!(
                "The default on `{scene}`: **{:.1} estimated cycles per pixel** for {:.1} instructions (CPI {:.2}), \
                 {:.2} frames/s at 168 MHz; with the ST7789 at 42 MHz ({:.1} ms a frame on the wire) {:.2} frames/s \
                 blocking (trace + wire), {:.2} overlapped (the larger of the two, at best). Cycles spent on \
                 `VDIV`/`VSQRT` {:.0} %, other FPU {:.0} %, loads and stores {:.0} %.",
                f.per_pixel("cycles"),
                f.per_pixel("instr"),
                f.get("cycles") / f.get("instr"),
                F_CLK_HZ / f.get("cycles"),
                1e3 * wire / F_CLK_HZ,
                F_CLK_HZ / (f.get("cycles") + wire),
                F_CLK_HZ / f.get("cycles").max(wire),
                100.0 * f.get(Kind::DivSqrt.key()) / f.get("cycles"),
                100.0 * f.get(Kind::Fp.key()) / f.get("cycles"),
                100.0 * f.get(Kind::LoadStore.key()) / f.get("cycles"),
            );
        }
    }
    // The first frame of `bounce`, drawn whole: what every frame costs once the camera
    // or the light moves.
    if let Some(b) = find("bounce", &default) {
        println!(
            "The default on the first frame of `bounce` (drawn whole, as every frame is when the camera or a light \
             moves): **{:.2} M estimated cycles, {:.1} ms at 168 MHz** ({:.1} cycles per pixel for {:.1} \
             instructions), {:.1} frames/s; with the ST7789 at 42 MHz {:.1} frames/s blocking, {:.1} overlapped.",
            b.get("cycles") / 1e6,
            1e3 * b.get("cycles") / F_CLK_HZ,
            b.per_pixel("cycles"),
            b.per_pixel("instr"),
            F_CLK_HZ / b.get("cycles"),
            F_CLK_HZ / (b.get("cycles") + wire),
            F_CLK_HZ / b.get("cycles").max(wire),
        );
    }
    if let Some(qemu_path) = option(args, "--qemu") {
        let qemu =
            qemu_output::QemuOutput::parse(&read(qemu_path)?).map_err(|e| ModelError(e.to_string()))?;
        let mut compared = 0;
        let mut worst: f64 = 0.0;
        for e in &estimates {
            if let Some(q) = qemu.get(e.scene(), e.method()) {
                compared += 1;
                worst = worst.max((e.get("instr") - q.instructions as f64).abs());
            }
        }
        println!(
            "Instructions in the trace against the SysTick count of a `qemu_cortex_m4` run of the same kernel: \
             {compared} renders compared, largest difference {worst} instructions per render."
        );
    }
    Ok(())
}
