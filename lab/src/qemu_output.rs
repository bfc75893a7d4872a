//! Parser for the output of the QEMU firmware examples (`qemu_cortex_m4`, also as
//! `qemu_cortex_m33`, `qemu_cortex_m0`, `qemu_rv32`; the line format is `lab/firmware/examples/common/measure.rs`'s).
//! Shared, through `#[path]`, by `lab/tests/lab/firmware_hashes.rs` (which compares the hashes
//! with the host's) and `lab/examples/firmware_table.rs` (which formats the README's
//! tables).

#![allow(dead_code)]

use std::fmt;

/// One `hash` line: a scene rendered at 240×240 with one method.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Entry {
    pub scene: String,
    pub method: String,
    pub hash: u64,
    pub pixels: u64,
    pub instructions: u64,
    pub stack: u64,
}

/// One `calibration` line: a loop of known length measured through SysTick.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Calibration {
    pub expected: u64,
    pub measured: u64,
    pub tolerance: u64,
}

/// Everything the firmware printed.
#[derive(Clone, Debug, Default)]
pub struct QemuOutput {
    /// The firmware's name: the first word of its header line (`qemu_cortex_m0: …`).
    pub name: Option<String>,
    /// The clock SysTick counts (`clock` line); `None` for a counter of instructions
    /// (`counter` line, RV32's `minstret`).
    pub clock_hz: Option<u64>,
    /// `(loop instructions, minstret, mcycle)` of RV32's `counters` line.
    pub counters: Option<(u64, u64, u64)>,
    pub entries: Vec<Entry>,
    pub calibrations: Vec<Calibration>,
    /// `(inputs, mismatches)` of the VSQRT-vs-libm check.
    pub sqrt: Option<(u64, u64)>,
    /// `(pixels, instructions)` of the sink alone.
    pub sink: Option<(u64, u64)>,
    /// The firmware's `Method::TARGET_DEFAULT` (its `default METHOD` line).
    pub default: Option<String>,
    /// The final `result ok` line was printed.
    pub ok: bool,
}

#[derive(Debug)]
pub struct ParseError {
    pub line: usize,
    pub text: String,
    pub reason: &'static str,
}

impl fmt::Display for ParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}: {:?}", self.line, self.reason, self.text)
    }
}

impl std::error::Error for ParseError {}

/// The value after `key` in a whitespace-separated `key value` list.
fn field<'a>(words: &[&'a str], key: &str) -> Option<&'a str> {
    words
        .iter()
        .position(|w| *w == key)
        .and_then(|i| words.get(i + 1))
        .copied()
}

fn number(words: &[&str], key: &str) -> Option<u64> {
    field(words, key)?.parse().ok()
}

impl QemuOutput {
    /// Parses the firmware's output; lines it does not know (headers, QEMU messages)
    /// are skipped, known lines that do not parse are errors.
    pub fn parse(text: &str) -> Result<Self, ParseError> {
        let mut out = QemuOutput::default();
        for (n, line) in text.lines().enumerate() {
            let err = |reason| ParseError {
                line: n + 1,
                text: line.to_string(),
                reason,
            };
            let words: Vec<&str> = line.split_whitespace().collect();
            match words.first().copied() {
                Some("hash") => {
                    let (Some(scene), Some(method), Some(hex)) = (words.get(1), words.get(2), words.get(3))
                    else {
                        return Err(err("expected `hash SCENE METHOD 0xHASH ...`"));
                    };
                    let hash = hex
                        .strip_prefix("0x")
                        .and_then(|h| u64::from_str_radix(h, 16).ok())
                        .ok_or_else(|| err("bad hash"))?;
                    out.entries.push(Entry {
                        scene: scene.to_string(),
                        method: method.to_string(),
                        hash,
                        pixels: number(&words, "pixels").ok_or_else(|| err("bad pixels"))?,
                        instructions: number(&words, "instr").ok_or_else(|| err("bad instr"))?,
                        stack: number(&words, "stack").ok_or_else(|| err("bad stack"))?,
                    });
                }
                Some("calibration") => out.calibrations.push(Calibration {
                    expected: number(&words, "expected").ok_or_else(|| err("bad expected"))?,
                    measured: number(&words, "measured").ok_or_else(|| err("bad measured"))?,
                    tolerance: number(&words, "tolerance").ok_or_else(|| err("bad tolerance"))?,
                }),
                Some("sqrt") => {
                    out.sqrt = Some((
                        number(&words, "inputs").ok_or_else(|| err("bad inputs"))?,
                        number(&words, "mismatches").ok_or_else(|| err("bad mismatches"))?,
                    ))
                }
                Some("sink") => {
                    out.sink = Some((
                        number(&words, "pixels").ok_or_else(|| err("bad pixels"))?,
                        number(&words, "instr").ok_or_else(|| err("bad instr"))?,
                    ))
                }
                Some("clock") => {
                    let hz = words.get(1).and_then(|w| w.parse().ok());
                    out.clock_hz = Some(hz.ok_or_else(|| err("bad clock"))?);
                }
                Some("counters") => {
                    out.counters = Some((
                        number(&words, "loop").ok_or_else(|| err("bad loop"))?,
                        number(&words, "minstret").ok_or_else(|| err("bad minstret"))?,
                        number(&words, "mcycle").ok_or_else(|| err("bad mcycle"))?,
                    ))
                }
                Some("result") => out.ok = words.get(1) == Some(&"ok"),
                Some("default") => out.default = words.get(1).map(|m| m.to_string()),
                Some(first) if out.name.is_none() && first.starts_with("qemu_") && first.ends_with(':') => {
                    out.name = Some(first.trim_end_matches(':').to_string());
                }
                _ => {}
            }
        }
        Ok(out)
    }

    /// Instructions per tick of the counter, rounded up: 1 for an instruction counter.
    pub fn instructions_per_tick(&self) -> u64 {
        self.clock_hz
            .map_or(1, |hz| 1_000_000_000_u64.div_ceil(hz.max(1)))
    }

    /// The entry for `scene` and `method`, if printed.
    pub fn get(&self, scene: &str, method: &str) -> Option<&Entry> {
        self.entries
            .iter()
            .find(|e| e.scene == scene && e.method == method)
    }
}

impl Entry {
    /// Instructions per pixel.
    pub fn ipp(&self) -> f64 {
        self.instructions as f64 / self.pixels.max(1) as f64
    }
}
