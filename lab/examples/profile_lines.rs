//! Where a firmware's cycles go, by source line: a per-instruction profile — the
//! Cortex-M4 cycle model's estimates (`cycle_model run --profile`) or the Cortex-M0+
//! cycles rp2040js counts (`lab/emulator/src/run.mjs --pc-part`) — resolved through the
//! firmware's line tables.
//!
//! ```text
//! profile_lines --profile FILE --elf ELF --region PREFIX [--top N]
//! ```
//!
//! `ELF` is the profiled firmware, built with line tables (`bash .ci/cycles --lines`
//! and `bash .ci/pico-emu --lines` build it so, apart from the measured builds:
//! `CARGO_PROFILE_RELEASE_DEBUG=line-tables-only` adds sections, not code). `PREFIX`
//! picks the profile's regions whose label starts with it (`shadows`: the default method
//! on `scenes/shadows.toml`); the label's `pixels N` turns cycles into cycles per pixel,
//! or its `frames N` (the Pico's profile from `lab/emulator/src/run.mjs --pc-part P`)
//! into cycles per frame, with milliseconds at the label's `clk HZ`. Each executed
//! instruction is
//! resolved by `llvm-addr2line -i` (Debian's `llvm` package) into the chain of source
//! lines it was inlined through, innermost first, and its cycles are summed four ways:
//!
//! - by the file of its innermost line (the kernel's own, `core`'s iterators, …), the
//!   `N` largest;
//! - by its **step**: the innermost line in the library's own `src/` outside
//!   `src/math/` (vectors, roots), so that a dot product's, an iterator's or a slice's
//!   code is charged to the kernel's line that runs it — the step of the algorithm a
//!   cycle belongs to; where no line of the library is in the chain, the innermost line
//!   outside `core`, so that `core`'s code inlined into a driver or a HAL is charged to
//!   it;
//! - by the crate of its step (the library, a driver, the HAL, compiler-builtins' calls,
//!   …), every one;
//! - by its innermost line, the `N` largest (default 30).
//!
//! Paths are printed relative to the repository (the working directory), `core`'s as
//! `core/src/…`, a registry crate's as `NAME-VERSION/…`. Line 0 is code the compiler
//! made without a source line (register spills and reloads, mostly).

use std::collections::HashMap;
use std::io::Write;
use std::process::{Command, ExitCode, Stdio};

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
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

/// One executed instruction of the chosen regions: its address, executions and cycles.
#[derive(Debug)]
struct Executed {
    addr: u32,
    count: u64,
    cycles: u64,
}

fn run(args: &[String]) -> Result<(), String> {
    let need =
        |name| option(args, name).ok_or_else(|| format!("missing {name} (usage: see the file's docs)"));
    let (profile, elf, prefix) = (need("--profile")?, need("--elf")?, need("--region")?);
    let top: usize = match option(args, "--top") {
        Some(n) => n.parse().map_err(|_| format!("--top {n}: not a count"))?,
        None => 30,
    };
    let text = std::fs::read_to_string(profile).map_err(|e| format!("{profile}: {e}"))?;
    let (executed, per, labels) = parse_profile(&text, prefix)?;
    let chains = resolve(elf, &executed)?;
    let root = std::env::current_dir().map_err(|e| e.to_string())?;
    let root = format!("{}/", root.display());

    let (mut by_file, mut by_step, mut by_line) = (Sums::default(), Sums::default(), Sums::default());
    let mut by_crate = Sums::default();
    let (mut total, mut instructions) = (0u64, 0u64);
    for (x, chain) in executed.iter().zip(&chains) {
        let chain: Vec<String> = chain.iter().map(|loc| shorten(loc, &root)).collect();
        let inner = chain.first().map_or("?", String::as_str);
        by_line.add(inner, x);
        by_file.add(file_of(inner), x);
        let own = |loc: &&String| loc.starts_with("src/") && !loc.starts_with("src/math/");
        let step = chain
            .iter()
            .find(own)
            .or_else(|| chain.iter().find(|loc| loc.starts_with("src/")))
            .or_else(|| chain.iter().find(|loc| !loc.starts_with("core/")))
            .map_or(inner, String::as_str);
        by_step.add(step, x);
        by_crate.add(crate_of(step), x);
        total += x.cycles;
        instructions += x.count;
    }
    println!("regions: {}", labels.join("; "));
    let ms = match (per.ms(total), per.clk) {
        (Some(ms), Some(hz)) => format!(" ({ms:.2} ms at {} MHz)", hz / 1e6),
        _ => String::new(),
    };
    let unit = per.unit.name();
    println!(
        "{:.1} cycles{ms} and {:.1} instructions per {unit} ({} {unit}s)",
        per.each(total),
        per.each(instructions),
        per.n
    );
    by_file.print("by the file of the innermost line", &per, total, top);
    by_step.print(
        "by step: the innermost line in the library's src/, src/math/ aside",
        &per,
        total,
        top,
    );
    by_crate.print("by the crate of the step", &per, total, usize::MAX);
    by_line.print("by the innermost line", &per, total, top);
    Ok(())
}

/// What the sums are divided by: the regions' pixels (`pixels N` in their labels, summed)
/// or the later frames of the Pico's profile (`frames N`), and the clock (`clk HZ`).
#[derive(Debug)]
struct Per {
    unit: Unit,
    n: u64,
    clk: Option<f64>,
}

/// What a profile's label counts.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Unit {
    Pixel,
    Frame,
}

impl Unit {
    fn name(self) -> &'static str {
        match self {
            Unit::Pixel => "pixel",
            Unit::Frame => "frame",
        }
    }
}

impl Per {
    /// `x` per pixel or per frame.
    fn each(&self, x: u64) -> f64 {
        x as f64 / self.n as f64
    }

    /// `cycles` per frame in milliseconds at the clock, if the label gave one.
    fn ms(&self, cycles: u64) -> Option<f64> {
        self.clk.map(|hz| self.each(cycles) / hz * 1e3)
    }
}

/// The executed instructions of the regions whose label starts with `prefix`, the
/// divisor of their sums ([`Per`]) and the labels.
fn parse_profile(text: &str, prefix: &str) -> Result<(Vec<Executed>, Per, Vec<String>), String> {
    let mut executed = Vec::new();
    let mut labels: Vec<String> = Vec::new();
    let mut per = Per {
        unit: Unit::Pixel,
        n: 0,
        clk: None,
    };
    for line in text.lines() {
        let Some((label, rest)) = line.split_once(" | ") else {
            continue;
        };
        if !label.starts_with(prefix) {
            continue;
        }
        if labels.last().is_none_or(|l| l != label) {
            let words: Vec<&str> = label.split_whitespace().collect();
            // The word after `key`.
            let after = |key: &str| {
                let i = words.iter().position(|w| *w == key)?;
                words.get(i + 1).copied()
            };
            let count = |key| after(key).and_then(|n| n.parse::<u64>().ok());
            let (unit, n) = match (count("pixels"), count("frames")) {
                (Some(n), None) => (Unit::Pixel, n),
                (None, Some(n)) => (Unit::Frame, n),
                _ => return Err(format!("region '{label}': no 'pixels N' or 'frames N'")),
            };
            if per.n > 0 && per.unit != unit {
                return Err(format!(
                    "region '{label}': counts {}s, the ones before {}s",
                    unit.name(),
                    per.unit.name()
                ));
            }
            // Pixels add up over regions; frames are the same frames, whatever the part.
            if unit == Unit::Frame && per.n > 0 && per.n != n {
                return Err(format!("region '{label}': {n} frames, the ones before {}", per.n));
            }
            per.unit = unit;
            per.n = if unit == Unit::Frame { n } else { per.n + n };
            per.clk = per.clk.or(after("clk").and_then(|hz| hz.parse::<f64>().ok()));
            labels.push(label.to_string());
        }
        let mut words = rest.split_whitespace();
        let (Some(addr), Some(count), Some(cycles)) = (words.next(), words.next(), words.next()) else {
            continue;
        };
        if addr == "function" {
            continue; // the per-function summary lines
        }
        let bad = || format!("profile line not understood: {line}");
        executed.push(Executed {
            addr: u32::from_str_radix(addr, 16).map_err(|_| bad())?,
            count: count.parse().map_err(|_| bad())?,
            cycles: cycles.parse().map_err(|_| bad())?,
        });
    }
    if executed.is_empty() || per.n == 0 {
        return Err(format!("no region of the profile starts with '{prefix}'"));
    }
    Ok((executed, per, labels))
}

/// Each address's chain of `file:line`, innermost first, by one run of
/// `llvm-addr2line -i -a` over them all.
fn resolve(elf: &str, executed: &[Executed]) -> Result<Vec<Vec<String>>, String> {
    let mut child = Command::new("llvm-addr2line")
        .args(["-i", "-a", "-e", elf])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .map_err(|e| format!("llvm-addr2line: {e} (Debian: apt-get install llvm)"))?;
    let input: String = executed.iter().map(|x| format!("0x{:x}\n", x.addr)).collect();
    // Written from a thread: the tool's output fills its pipe while it reads.
    let mut stdin = child.stdin.take().ok_or("llvm-addr2line: no stdin")?;
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()));
    let out = child
        .wait_with_output()
        .map_err(|e| format!("llvm-addr2line: {e}"))?;
    writer
        .join()
        .map_err(|_| "llvm-addr2line: the writer panicked".to_string())?
        .map_err(|e| format!("llvm-addr2line: {e}"))?;
    if !out.status.success() {
        return Err(format!("llvm-addr2line failed ({})", out.status));
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let mut chains: Vec<Vec<String>> = Vec::new();
    for line in text.lines() {
        if line.starts_with("0x") {
            chains.push(Vec::new());
        } else if let Some(chain) = chains.last_mut() {
            // `file:line`, maybe with ` (discriminator N)`.
            let loc = line.split(" (").next().unwrap_or(line);
            chain.push(loc.to_string());
        }
    }
    if chains.len() != executed.len() {
        return Err(format!(
            "llvm-addr2line answered {} addresses of {}",
            chains.len(),
            executed.len()
        ));
    }
    Ok(chains)
}

/// A path as this tool prints it: relative to the repository, `core/src/…` for the
/// standard library, `NAME-VERSION/…` for a registry crate, else as given.
fn shorten(loc: &str, root: &str) -> String {
    if let Some(rest) = loc.strip_prefix(root) {
        return rest.to_string();
    }
    if let Some((_, rest)) = loc.split_once("/library/") {
        return rest.to_string();
    }
    if let Some((_, rest)) = loc.split_once("/registry/src/") {
        // index.crates.io-HASH/NAME-VERSION/…
        return rest.split_once('/').map_or(rest, |(_, r)| r).to_string();
    }
    loc.to_string()
}

/// The crate of a path as [`shorten`] prints it: `src/…` the library, `core/…` the
/// standard library, else its first component (`NAME-VERSION`, `compiler-builtins`,
/// `lab`, `boards`).
fn crate_of(loc: &str) -> &str {
    if loc.starts_with("src/") {
        "the library (src/)"
    } else {
        loc.split_once('/').map_or(loc, |(first, _)| first)
    }
}

/// `file` of `file:line`.
fn file_of(loc: &str) -> &str {
    loc.rsplit_once(':').map_or(loc, |(file, _)| file)
}

/// Cycles and executions summed by a key.
#[derive(Default)]
struct Sums(HashMap<String, (u64, u64)>);

impl Sums {
    fn add(&mut self, key: &str, x: &Executed) {
        let e = self.0.entry(key.to_string()).or_insert((0, 0));
        e.0 += x.cycles;
        e.1 += x.count;
    }

    /// The `top` largest, as cycles and instructions per pixel or frame (and
    /// milliseconds per frame at the clock) and share of `total`.
    fn print(&self, title: &str, per: &Per, total: u64, top: usize) {
        let mut rows: Vec<(&String, &(u64, u64))> = self.0.iter().collect();
        rows.sort_by(|a, b| b.1 .0.cmp(&a.1 .0).then(a.0.cmp(b.0)));
        let ms_head = if per.clk.is_some() { "      ms" } else { "" };
        let unit = match per.unit {
            Unit::Pixel => "px",
            Unit::Frame => "frame",
        };
        println!("\n{title}:\n  cycles/{unit}  instr/{unit}{ms_head}  share  where");
        for (key, &(cycles, count)) in rows.into_iter().take(top) {
            let ms = per.ms(cycles).map_or(String::new(), |ms| format!("  {ms:6.2}"));
            println!(
                "  {:9.1}  {:8.1}{ms}  {:4.1} %  {key}",
                per.each(cycles),
                per.each(count),
                100.0 * cycles as f64 / total.max(1) as f64
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{crate_of, parse_profile, Unit};

    /// A step's crate: the library, the standard library, a registry crate or a folder
    /// of the repository.
    #[test]
    fn steps_belong_to_their_crates() {
        assert_eq!(crate_of("src/integer/row.rs:253"), "the library (src/)");
        assert_eq!(crate_of("core/src/slice/mod.rs:2193"), "core");
        assert_eq!(
            crate_of("mipidsi-0.10.0/src/interface/spi.rs:77"),
            "mipidsi-0.10.0"
        );
        assert_eq!(crate_of("boards/rp2040/src/bin/simple/dma_spi.rs:90"), "boards");
        assert_eq!(crate_of("??:0"), "??:0");
    }

    /// The cycle model's regions: per pixel, summed over the regions the prefix picks,
    /// the per-function summary lines skipped.
    #[test]
    fn cycle_model_regions_divide_by_their_pixels() {
        let text = "shadows a pixels 100 | 80001e0 240 1440 push {r4} <f>\n\
                    shadows a pixels 100 | function 1440 <f>\n\
                    shadows b pixels 50 | 80001e2 10 10 add r7 <f>\n\
                    mirrors pixels 7 | 80001e4 1 1 nop <g>\n";
        let (executed, per, labels) = parse_profile(text, "shadows").unwrap();
        assert_eq!(executed.len(), 2);
        assert_eq!(
            (executed[0].addr, executed[0].count, executed[0].cycles),
            (0x0800_01e0, 240, 1440)
        );
        assert_eq!((per.unit, per.n, per.clk), (Unit::Pixel, 150, None));
        assert_eq!(labels, ["shadows a pixels 100", "shadows b pixels 50"]);
    }

    /// The Pico's profile (`run.mjs --pc-part`): per frame, with its clock.
    #[test]
    fn the_picos_profile_divides_by_its_frames() {
        let text = "simple part 1 frames 11 clk 125000000 | 10000584 76131 152262\n";
        let (executed, per, _) = parse_profile(text, "simple").unwrap();
        assert_eq!(
            (executed[0].addr, executed[0].count, executed[0].cycles),
            (0x1000_0584, 76131, 152262)
        );
        assert_eq!((per.unit, per.n, per.clk), (Unit::Frame, 11, Some(125e6)));
        // Two parts of the same frames: divided by the frames once.
        let parts =
            "simple part 0 frames 11 clk 1.25e8 | 10 1 1\nsimple part 1 frames 11 clk 1.25e8 | 12 1 1\n";
        let (_, per, _) = parse_profile(parts, "simple").unwrap();
        assert_eq!((per.n, per.clk), (11, Some(125e6)));
        let unequal = "simple part 0 frames 11 | 10 1 1\nsimple part 1 frames 5 | 12 1 1\n";
        assert!(parse_profile(unequal, "simple").unwrap_err().contains("5 frames"));
    }

    /// A label without its divisor, or regions that count different things, are refused.
    #[test]
    fn a_label_without_a_count_or_mixed_units_is_refused() {
        assert!(parse_profile("x part 1 | 10 1 1\n", "x")
            .unwrap_err()
            .contains("no 'pixels N'"));
        let mixed = "x pixels 5 | 10 1 1\nx frames 2 | 12 1 1\n";
        assert!(parse_profile(mixed, "x").unwrap_err().contains("counts frames"));
        assert!(parse_profile("y pixels 5 | 10 1 1\n", "x")
            .unwrap_err()
            .contains("no region"));
    }
}
