//! A Cortex-M4 cycle model driven by an execution trace: every executed instruction,
//! looked up in `llvm-objdump -d` of the same ELF, is charged the cycles of ARM's
//! Cortex-M4 Technical Reference Manual (DDI 0439B), with taken branches found from the
//! next executed address and load/store pipelining from the previous instruction.
//!
//! Shared, through `#[path]`, by `lab/examples/cycle_model.rs` (the command-line tool that
//! streams QEMU's `-d exec` log through it) and `lab/tests/lab/cycle_model.rs` (the model on
//! hand-written instruction sequences).
//!
//! Assumptions (the README's "Cycles, estimated" states them for readers):
//! - zero-wait-state memory for code and data (no flash wait states, no bus contention);
//! - pipeline refill `P` = [`P`] cycles per taken branch or other write to the PC
//!   (the TRM gives 1…3); the refills are counted, so any other `P` follows exactly;
//! - `SDIV`/`UDIV` take [`DIVIDE_CYCLES`], the top of the TRM's 2…12 (their early
//!   termination depends on the operands, which a trace of addresses does not show);
//! - an instruction in an IT block costs the same whether or not its condition passes
//!   (the trace cannot tell, except for writes to the PC); the most this can overcount
//!   is reported as `cond_extra`;
//! - `IT` costs 1 cycle (folding onto a preceding 16-bit instruction, which can make it
//!   free, is not modelled; the count of such `IT`s is reported as `it_fold`);
//! - a single store costs 2 cycles unless pipelined behind a load; if the store buffer
//!   hides its second cycle whenever no load or store follows, the saving is reported
//!   as `store_buffer`;
//! - no other stalls: no register dependency stalls beyond the table, no FPU
//!   overlap of `VDIV`/`VSQRT` with integer instructions, no interrupts.

#![allow(dead_code)]

use std::collections::BTreeMap;
use std::fmt;

/// The firmware calls this (an `#[inline(never)]` function) right before a region.
pub const BEGIN_SYMBOL: &str = "cycle_region_begin";
/// The firmware calls this right after a region.
pub const END_SYMBOL: &str = "cycle_region_end";
/// Optional: inside a region, the firmware calls this before work that is not the
/// region's (e.g. checking a band buffer between two band renders)…
pub const PAUSE_SYMBOL: &str = "cycle_region_pause";
/// …and this after it; the instructions in between are not counted.
pub const RESUME_SYMBOL: &str = "cycle_region_resume";

/// Pipeline refill cycles assumed per taken branch (DDI 0439B §3.3.1, "P: the number of
/// cycles required for a pipeline refill. This ranges from 1 to 3 depending on the
/// alignment and width of the target instruction, and whether the processor manages to
/// speculate the address early").
pub const P: u64 = 1;

/// Cycles assumed for `SDIV`/`UDIV` (DDI 0439B Table 3-1: "2 to 12", early termination
/// on the operands' leading zeros and ones): the upper bound.
pub const DIVIDE_CYCLES: u32 = 12;

/// How an instruction's cycles depend on its operands and what follows it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// `base` cycles (`base + P` if it writes the PC).
    Fixed,
    /// A single load: `base`, or 1 when pipelined behind a single load whose loaded
    /// register the address does not use; `base + P` into the PC.
    Load,
    /// A single store: `base`, or 1 when pipelined behind a single load.
    Store,
    /// `base + N` for N core registers in the list (`+ P` when the list holds the PC).
    Multiple,
    /// `base + N` for N single-precision registers (`+ 2N` for double registers).
    FpMultiple,
    /// `VLDR`/`VSTR`: `base` for a single register, `base + 1` for a double.
    FpSingleDouble,
    /// `VMOV`: `base` between FPU registers or from an immediate; 2 to or from core
    /// registers (one float or two); 1 for half of a double.
    FpMove,
    /// A branch: `base` if not taken, `base + P` if taken.
    Branch,
    /// Always refills the pipeline: `base + P`.
    Refill,
}

/// What a cycle is spent on, for the breakdown of a region.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Kind {
    /// Integer loads and stores, single and multiple, `PUSH`/`POP`, and the FPU's.
    LoadStore,
    /// Branches and other writes to the PC (refills included).
    Branch,
    /// `VDIV.F32` and `VSQRT.F32`.
    DivSqrt,
    /// Every other FPU instruction.
    Fp,
    /// Integer data processing, multiplies, divides, `IT`.
    Integer,
}

impl Kind {
    pub const ALL: [Kind; 5] = [
        Kind::LoadStore,
        Kind::Branch,
        Kind::DivSqrt,
        Kind::Fp,
        Kind::Integer,
    ];

    /// The key of this kind's cycles in the tool's output.
    pub fn key(self) -> &'static str {
        match self {
            Kind::LoadStore => "ldst",
            Kind::Branch => "branch",
            Kind::DivSqrt => "divsqrt",
            Kind::Fp => "fp",
            Kind::Integer => "int",
        }
    }
}

/// One row of the timing table: the mnemonics (base names: no condition, no `S`, no
/// `.W`/`.N`, no data type) that cost `base` cycles shaped by `shape`, and where the
/// figure comes from.
pub struct Timing {
    pub mnemonics: &'static [&'static str],
    pub base: u32,
    pub shape: Shape,
    pub kind: Kind,
    pub source: &'static str,
}

/// The timing table: every instruction the model knows, from DDI 0439B ("Cortex-M4
/// Technical Reference Manual", r0p1). An executed instruction that matches no row is
/// an error, never a guess.
pub const TIMINGS: &[Timing] = &[
    Timing {
        mnemonics: &[
            "mov", "movw", "movt", "mvn", "add", "addw", "adc", "sub", "subw", "sbc", "rsb", "adr", "cmp",
            "cmn", "and", "eor", "orr", "orn", "bic", "tst", "teq", "lsl", "lsr", "asr", "ror", "rrx", "clz",
            "sxtb", "sxth", "uxtb", "uxth", "sxtab", "sxtah", "uxtab", "uxtah", "sxtb16", "uxtb16",
            "sxtab16", "uxtab16", "ubfx", "sbfx", "bfc", "bfi", "rev", "rev16", "revsh", "rbit", "ssat",
            "usat", "nop", "sel", "uadd8", "usub8", "qadd", "qsub",
        ],
        base: 1,
        shape: Shape::Fixed,
        kind: Kind::Integer,
        source: "Table 3-1: Move, Add, Subtract, Compare, Logical, Shift, Rotate, Count, Extend, \
                 Bit field, Reverse, Saturate, NOP: 1 (MOV/ADD to the PC: 1 + P)",
    },
    Timing {
        mnemonics: &[
            "mul", "mla", "mls", "smull", "umull", "smlal", "umlal", "smulbb", "smlabb",
        ],
        base: 1,
        shape: Shape::Fixed,
        kind: Kind::Integer,
        source: "Table 3-1: Multiply (MUL, MLA, MLS, SMULL, UMULL, SMLAL, UMLAL): 1",
    },
    Timing {
        mnemonics: &["sdiv", "udiv"],
        base: DIVIDE_CYCLES,
        shape: Shape::Fixed,
        kind: Kind::Integer,
        source: "Table 3-1: Divide: 2 to 12 (early termination); the model takes 12",
    },
    Timing {
        mnemonics: &[
            "ldr", "ldrb", "ldrh", "ldrsb", "ldrsh", "ldrex", "ldrexb", "ldrexh",
        ],
        base: 2,
        shape: Shape::Load,
        kind: Kind::LoadStore,
        source: "Table 3-1: Load word/halfword/byte: 2 (to the PC: 2 + P); note b and §3.3.2: \
                 a load or store after a load whose result its address does not use takes 1",
    },
    Timing {
        mnemonics: &["str", "strb", "strh", "strex", "strexb", "strexh"],
        base: 2,
        shape: Shape::Store,
        kind: Kind::LoadStore,
        source: "Table 3-1: Store word/halfword/byte: 2; §3.3.2: pipelined (1) only after a load",
    },
    Timing {
        mnemonics: &["ldrd", "strd"],
        base: 1,
        shape: Shape::Multiple,
        kind: Kind::LoadStore,
        source: "Table 3-1: Load/Store doubleword: 1 + N (N = 2)",
    },
    Timing {
        mnemonics: &[
            "ldm", "ldmia", "ldmfd", "ldmdb", "pop", "stm", "stmia", "stmea", "stmdb", "stmfd", "push",
        ],
        base: 1,
        shape: Shape::Multiple,
        kind: Kind::LoadStore,
        source: "Table 3-1: LDM/STM/PUSH/POP: 1 + N (with the PC: 1 + N + P)",
    },
    Timing {
        mnemonics: &["b", "bl", "bx", "blx", "cbz", "cbnz"],
        base: 1,
        shape: Shape::Branch,
        kind: Kind::Branch,
        source: "Table 3-1: Branch B, BL, BX, BLX: 1 + P; conditional B, CBZ, CBNZ: 1 not taken, \
                 1 + P taken (note c)",
    },
    Timing {
        mnemonics: &["tbb", "tbh"],
        base: 2,
        shape: Shape::Refill,
        kind: Kind::Branch,
        source: "Table 3-1: Table branch TBB/TBH: 2 + P",
    },
    Timing {
        mnemonics: &["mrs", "msr"],
        base: 2,
        shape: Shape::Fixed,
        kind: Kind::Integer,
        source: "Table 3-1: Move to register from special register MRS, to special register from \
                 register MSR: 1 or 2; the model takes 2 (compiled code saves and restores the flags \
                 with them around FPU compares, once per frame in the plane set-up)",
    },
    Timing {
        mnemonics: &["it"],
        base: 1,
        shape: Shape::Fixed,
        kind: Kind::Integer,
        source:
            "Table 3-1: If-then IT: 1 (note d: can fold onto a preceding 16-bit instruction; not modelled)",
    },
    Timing {
        mnemonics: &[
            "vadd", "vsub", "vmul", "vnmul", "vabs", "vneg", "vcmp", "vcmpe", "vcvt", "vcvtr", "vmrs", "vmsr",
        ],
        base: 1,
        shape: Shape::Fixed,
        kind: Kind::Fp,
        source: "Table 7-1: VADD, VSUB, VMUL, VNMUL, VABS, VNEG, VCMP(E), VCVT, VMRS, VMSR: 1",
    },
    Timing {
        mnemonics: &["vmla", "vmls", "vnmla", "vnmls", "vfma", "vfms", "vfnma", "vfnms"],
        base: 3,
        shape: Shape::Fixed,
        kind: Kind::Fp,
        source:
            "Table 7-1: multiply-accumulate VMLA, VMLS, VNMLA, VNMLS and fused VFMA, VFMS, VFNMA, VFNMS: 3",
    },
    Timing {
        mnemonics: &["vdiv", "vsqrt"],
        base: 14,
        shape: Shape::Fixed,
        kind: Kind::DivSqrt,
        source: "Table 7-1: VDIV.F32, VSQRT.F32: 14",
    },
    Timing {
        mnemonics: &["vmov"],
        base: 1,
        shape: Shape::FpMove,
        kind: Kind::Fp,
        source: "Table 7-1: VMOV immediate or float to float register: 1; half of a double to/from a \
                 core register: 1; one float or two floats/one double to/from core registers: 2",
    },
    Timing {
        mnemonics: &["vldr", "vstr"],
        base: 2,
        shape: Shape::FpSingleDouble,
        kind: Kind::LoadStore,
        source: "Table 7-1: VLDR.32/VSTR.32: 2, VLDR.64/VSTR.64: 3",
    },
    Timing {
        mnemonics: &[
            "vpush", "vpop", "vldm", "vldmia", "vldmdb", "vstm", "vstmia", "vstmdb",
        ],
        base: 1,
        shape: Shape::FpMultiple,
        kind: Kind::LoadStore,
        source: "Table 7-1: VPUSH/VPOP/VLDM/VSTM: 1 + N floats, 1 + 2N doubles",
    },
];

/// Condition-code suffixes (ARMv7-M ARM §A7.3).
const CONDITIONS: [&str; 16] = [
    "eq", "ne", "cs", "hs", "cc", "lo", "mi", "pl", "vs", "vc", "hi", "ls", "ge", "lt", "gt", "le",
];

/// A decoded instruction's timing-relevant facts.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Decoded {
    /// Index of its row in [`TIMINGS`].
    pub row: usize,
    pub base: u32,
    pub shape: Shape,
    pub kind: Kind,
    /// Has a condition suffix outside the branch row (so it sits in an IT block).
    pub predicated: bool,
    /// Writes the PC (other than the branch rows): a taken one refills the pipeline.
    pub writes_pc: bool,
    /// Core registers (bit n = rn, 13 sp, 14 lr, 15 pc) a single load writes.
    pub load_dest: u16,
    /// Core registers inside the address brackets.
    pub address_regs: u16,
    /// Registers in the list of a multiple load/store (doubles count 2 for the FPU).
    pub list_cost: u32,
    /// `IT`.
    pub is_it: bool,
    /// `SDIV`/`UDIV`.
    pub is_divide: bool,
}

/// One instruction of the disassembly.
#[derive(Clone, Debug)]
pub struct Insn {
    pub addr: u32,
    /// Bytes: 2 or 4.
    pub size: u32,
    /// `mnemonic operands`, for messages.
    pub text: String,
    /// `None`: a mnemonic the table does not know (an error if executed).
    pub decoded: Option<Decoded>,
}

/// The core register number of an operand (`r0`…`r12`, `sp`, `lr`, `pc`).
fn core_reg(name: &str) -> Option<u32> {
    match name {
        "sp" => Some(13),
        "lr" => Some(14),
        "pc" => Some(15),
        "sb" => Some(9),
        "sl" => Some(10),
        "fp" => Some(11),
        "ip" => Some(12),
        _ => name.strip_prefix('r')?.parse().ok().filter(|&n: &u32| n <= 15),
    }
}

/// Core registers named anywhere in `text` (a bit mask).
fn core_regs(text: &str) -> u16 {
    text.split(|c: char| !c.is_ascii_alphanumeric())
        .filter_map(core_reg)
        .fold(0, |mask, r| mask | 1 << r)
}

/// Registers in a `{…}` list, ranges (`d8-d11`) expanded: `(count, doubles, has_pc)`.
fn register_list(operands: &str) -> Option<(u32, bool, bool)> {
    let inner = operands.split_once('{')?.1.split_once('}')?.0;
    let mut count = 0;
    let mut doubles = false;
    let mut pc = false;
    for item in inner.split(',').map(str::trim) {
        let (first, last) = item.split_once('-').unwrap_or((item, item));
        doubles |= first.starts_with('d');
        pc |= first == "pc";
        let number = |r: &str| {
            r.trim_start_matches(|c: char| c.is_ascii_alphabetic())
                .parse::<u32>()
                .ok()
        };
        count += match (number(first), number(last)) {
            (Some(a), Some(b)) if b >= a => b - a + 1,
            _ => 1,
        };
    }
    Some((count, doubles, pc))
}

/// Splits a mnemonic (`addseq.w`, `vadd.f32`, `bls`) into its table row and whether it
/// carries a condition suffix.
fn lookup(mnemonic: &str) -> Option<(usize, bool)> {
    let stem = mnemonic.split('.').next().unwrap_or(mnemonic);
    // IT, ITT, ITE, ITTE, …: the row "it".
    if stem
        .strip_prefix("it")
        .is_some_and(|mask| mask.len() <= 3 && mask.chars().all(|c| c == 't' || c == 'e'))
    {
        let row = TIMINGS.iter().position(|t| t.mnemonics.contains(&"it"))?;
        return Some((row, false));
    }
    let mut best: Option<(usize, usize, bool)> = None;
    for (row, timing) in TIMINGS.iter().enumerate() {
        for base in timing.mnemonics {
            let Some(rest) = stem.strip_prefix(base) else {
                continue;
            };
            // What may follow a base name: `S` (flags, data processing only) and/or a
            // condition.
            let flags = timing.kind == Kind::Integer && timing.shape == Shape::Fixed;
            let rest = rest.strip_prefix('s').filter(|_| flags).unwrap_or(rest);
            let conditional = if rest.is_empty() {
                false
            } else if CONDITIONS.contains(&rest) {
                true
            } else {
                continue;
            };
            // The longest base name wins (`bl` + `s` is not a flag-setting BL, `b` + `ls` is).
            if best.is_none_or(|(len, _, _)| base.len() > len) {
                best = Some((base.len(), row, conditional));
            }
        }
    }
    best.map(|(_, row, conditional)| (row, conditional))
}

/// Decodes one instruction's mnemonic and operands.
pub fn decode(mnemonic: &str, operands: &str) -> Option<Decoded> {
    let (row, conditional) = lookup(mnemonic)?;
    let timing = TIMINGS.get(row)?;
    let operands = operands.split('@').next().unwrap_or("").trim();
    let first = operands.split(',').next().unwrap_or("").trim();
    let mut d = Decoded {
        row,
        base: timing.base,
        shape: timing.shape,
        kind: timing.kind,
        predicated: conditional && timing.shape != Shape::Branch,
        writes_pc: false,
        load_dest: 0,
        address_regs: 0,
        list_cost: 0,
        is_it: timing.mnemonics.contains(&"it"),
        is_divide: timing.mnemonics.contains(&"udiv"),
    };
    let brackets = operands
        .split_once('[')
        .map(|(_, r)| r.split(']').next().unwrap_or(""));
    match timing.shape {
        Shape::Fixed => d.writes_pc = first == "pc" && timing.kind == Kind::Integer,
        Shape::Load => {
            d.load_dest = core_regs(first);
            d.writes_pc = first == "pc";
            d.address_regs = brackets.map_or(0, core_regs);
        }
        Shape::Store => d.address_regs = brackets.map_or(0, core_regs),
        Shape::Multiple => {
            if let Some((count, _, pc)) = register_list(operands) {
                d.list_cost = count;
                d.writes_pc = pc && mnemonic.starts_with(['l', 'p']);
            } else {
                // LDRD/STRD: two registers.
                d.list_cost = 2;
            }
        }
        Shape::FpMultiple => {
            let (count, doubles, _) = register_list(operands)?;
            d.list_cost = if doubles { 2 * count } else { count };
        }
        Shape::FpSingleDouble => {
            if first.starts_with('d') {
                d.base += 1;
            }
        }
        Shape::FpMove => {
            let core = operands.split(',').any(|o| core_reg(o.trim()).is_some());
            let lane = operands.contains('[');
            if core && !lane {
                d.base = 2;
            }
        }
        Shape::Branch | Shape::Refill => {}
    }
    Some(d)
}

/// The program: every instruction of the disassembly, by address, and its symbols.
pub struct Program {
    /// Lowest instruction address.
    start: u32,
    /// `(address − start) / 2` → index into `insns` + 1 (0: no instruction there).
    index: Vec<u32>,
    pub insns: Vec<Insn>,
    /// Symbol → `(start, end)`: its label's address to the next label's.
    pub symbols: BTreeMap<String, (u32, u32)>,
}

/// Why a disassembly or trace cannot be used.
#[derive(Debug)]
pub struct ModelError(pub String);

impl fmt::Display for ModelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ModelError {}

impl Program {
    /// Parses `llvm-objdump -d` output: `08000188 <name>:` symbol lines and
    /// ` 8000188: f000 f831  \tbl\t0x80001ee <…>` instruction lines (data words such as
    /// `.word` are kept as instructions without a timing).
    pub fn from_objdump(text: &str) -> Result<Self, ModelError> {
        let mut insns = Vec::new();
        let mut labels: Vec<(u32, String)> = Vec::new();
        for line in text.lines() {
            if let Some(name) = line.strip_suffix(">:") {
                let Some((addr, name)) = name.split_once(" <") else {
                    continue;
                };
                if let Ok(addr) = u32::from_str_radix(addr.trim(), 16) {
                    labels.push((addr, name.to_string()));
                }
                continue;
            }
            let Some((addr, rest)) = line.split_once(':') else {
                continue;
            };
            let Ok(addr) = u32::from_str_radix(addr.trim(), 16) else {
                continue;
            };
            let mut fields = rest.split('\t');
            let raw = fields.next().unwrap_or("");
            let mnemonic = fields.next().unwrap_or("").trim();
            let operands = fields.next().unwrap_or("").trim();
            let hex: usize = raw
                .split_whitespace()
                .map(|w| {
                    if w.chars().all(|c| c.is_ascii_hexdigit()) {
                        w.len()
                    } else {
                        0
                    }
                })
                .sum();
            let size = (hex / 2) as u32;
            if mnemonic.is_empty() || !(size == 2 || size == 4) {
                continue;
            }
            let decoded = if mnemonic.starts_with('.') {
                None
            } else {
                decode(mnemonic, operands)
            };
            let text = format!("{mnemonic} {}", operands.split('@').next().unwrap_or("").trim());
            insns.push(Insn {
                addr,
                size,
                text: text.trim().to_string(),
                decoded,
            });
        }
        insns.sort_by_key(|i| i.addr);
        let (Some(first), Some(last)) = (insns.first(), insns.last()) else {
            return Err(ModelError("no instructions in the disassembly".into()));
        };
        let start = first.addr;
        let mut index = vec![0u32; ((last.addr - start) / 2 + 1) as usize];
        for (i, insn) in insns.iter().enumerate() {
            if let Some(slot) = index.get_mut(((insn.addr - start) / 2) as usize) {
                *slot = i as u32 + 1;
            }
        }
        labels.sort();
        let mut symbols = BTreeMap::new();
        for (i, (addr, name)) in labels.iter().enumerate() {
            let end = labels.get(i + 1).map_or(last.addr + last.size, |(a, _)| *a);
            symbols.entry(name.clone()).or_insert((*addr, end));
        }
        Ok(Program {
            start,
            index,
            insns,
            symbols,
        })
    }

    /// The instruction at `addr`.
    pub fn at(&self, addr: u32) -> Option<usize> {
        let slot = addr.checked_sub(self.start)? / 2;
        match self.index.get(slot as usize) {
            Some(&i) if i > 0 => Some(i as usize - 1),
            _ => None,
        }
    }

    fn symbol(&self, name: &str) -> Result<(u32, u32), ModelError> {
        self.symbols
            .get(name)
            .copied()
            .ok_or_else(|| ModelError(format!("symbol `{name}` not in the disassembly")))
    }
}

/// Cycles of one region and their breakdown.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    pub instructions: u64,
    /// Estimated cycles at `P` = [`P`].
    pub cycles: u64,
    /// Pipeline refills charged (each costs `P`).
    pub refills: u64,
    /// Cycles per [`Kind`], in [`Kind::ALL`] order.
    pub by_kind: [u64; 5],
    /// Cycles above 1 of IT-predicated instructions (at most this many are overcounted
    /// if their conditions failed).
    pub cond_extra: u64,
    /// `IT`s after a 16-bit instruction (free if folded).
    pub it_fold: u64,
    /// Single stores charged 2 with no load or store after them.
    pub store_buffer: u64,
    /// `SDIV`/`UDIV` executed (each charged [`DIVIDE_CYCLES`]).
    pub divides: u64,
    /// Bytes of instructions executed (the fetch stream's length).
    pub fetch_bytes: u64,
    /// Bytes of the distinct instructions executed (the code's footprint).
    pub code_bytes: u64,
    /// Distinct 16-byte-aligned lines of code executed (a flash line of the STM32F4's
    /// ART accelerator is 128 bits).
    pub code_lines: u64,
    /// Executed instructions the table does not know, with how often.
    pub unknown: BTreeMap<String, u64>,
}

impl Counts {
    /// Cycles for another refill cost `p`.
    pub fn cycles_at(&self, p: u64) -> u64 {
        self.cycles + self.refills * p - self.refills * P
    }
}

/// Cycles of `insn`, executed after `prev` and followed by the instruction at `next`,
/// added to `counts`.
pub fn charge(program: &Program, insn: &Insn, prev: Option<&Insn>, next: u32, counts: &mut Counts) {
    counts.instructions += 1;
    counts.fetch_bytes += u64::from(insn.size);
    let Some(d) = &insn.decoded else {
        *counts.unknown.entry(insn.text.clone()).or_insert(0) += 1;
        return;
    };
    let fallthrough = next == insn.addr + insn.size;
    let prev_load = prev
        .and_then(|p| p.decoded.as_ref())
        .filter(|p| p.shape == Shape::Load && !p.writes_pc);
    let mut cycles = u64::from(d.base);
    let mut refill = false;
    match d.shape {
        Shape::Fixed | Shape::FpSingleDouble | Shape::FpMove => {}
        Shape::Load | Shape::Store => {
            // §3.3.2: a load or store right after a load whose loaded register its
            // address does not use overlaps that load's data phase: 1 cycle.
            let pipelined = prev_load.is_some_and(|p| p.load_dest & d.address_regs == 0);
            if pipelined && !d.writes_pc {
                cycles = 1;
            }
        }
        Shape::Multiple | Shape::FpMultiple => cycles += u64::from(d.list_cost),
        Shape::Branch => refill = !fallthrough,
        Shape::Refill => refill = true,
    }
    if d.writes_pc {
        if fallthrough && d.predicated {
            // Condition failed: like a branch not taken, one cycle.
            cycles = 1;
        } else {
            refill = true;
        }
    }
    if refill {
        cycles += P;
        counts.refills += 1;
    }
    if d.predicated && !d.writes_pc {
        counts.cond_extra += cycles - 1;
    }
    if d.is_it && prev.is_some_and(|p| p.size == 2) {
        counts.it_fold += 1;
    }
    if d.shape == Shape::Store && cycles == 2 {
        let next_is_memory = program
            .at(next)
            .and_then(|i| program.insns.get(i))
            .and_then(|i| i.decoded.as_ref())
            .is_some_and(|n| matches!(n.kind, Kind::LoadStore));
        if !next_is_memory {
            counts.store_buffer += 1;
        }
    }
    if d.is_divide {
        counts.divides += 1;
    }
    counts.cycles += cycles;
    if let Some(slot) = Kind::ALL
        .iter()
        .position(|&k| k == d.kind)
        .and_then(|i| counts.by_kind.get_mut(i))
    {
        *slot += cycles;
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum State {
    /// Outside every region.
    Idle,
    /// Inside the begin marker's own instructions.
    InBegin,
    /// Counting.
    Counting,
    /// Inside a region, between the pause marker's call and the resume marker.
    Paused,
    /// Inside the resume marker's own instructions.
    InResume,
}

/// Streams executed addresses through the model and collects one [`Counts`] per region:
/// the instructions after the begin marker returns up to, not including, the call of
/// the end marker.
pub struct Tracer<'a> {
    program: &'a Program,
    begin: (u32, u32),
    end: u32,
    /// The pause and resume markers, if the program has them.
    pause: Option<u32>,
    resume: Option<(u32, u32)>,
    state: State,
    prev: Option<usize>,
    pending: Option<usize>,
    counts: Counts,
    /// Per instruction, and per 16-byte line of code: the number of the last region
    /// that executed it (for the footprint).
    insn_seen: Vec<usize>,
    line_seen: Vec<usize>,
    pub regions: Vec<Counts>,
    /// If asked for (`cycle_model run --profile`): per region, per instruction (as
    /// the program's `insns`), how often it executed and the cycles charged to it.
    pub profile: Option<Vec<Vec<(u64, u64)>>>,
    /// Executed addresses inside a region that are not in the disassembly.
    pub unmapped: u64,
}

impl<'a> Tracer<'a> {
    pub fn new(program: &'a Program) -> Result<Self, ModelError> {
        let begin = program.symbol(BEGIN_SYMBOL)?;
        let end = program.symbol(END_SYMBOL)?.0;
        if begin.0 == end {
            return Err(ModelError("the begin and end markers share an address".into()));
        }
        let pause = program.symbol(PAUSE_SYMBOL).ok().map(|s| s.0);
        let resume = program.symbol(RESUME_SYMBOL).ok();
        Ok(Tracer {
            program,
            begin,
            end,
            pause,
            resume,
            state: State::Idle,
            prev: None,
            pending: None,
            counts: Counts::default(),
            insn_seen: vec![0; program.insns.len()],
            line_seen: vec![0; program.index.len() / 8 + 2],
            regions: Vec::new(),
            profile: None,
            unmapped: 0,
        })
    }

    /// One executed instruction's address.
    pub fn step(&mut self, pc: u32) {
        match self.state {
            State::Idle => {
                if pc == self.begin.0 {
                    self.state = State::InBegin;
                }
            }
            State::InBegin => {
                if !(self.begin.0..self.begin.1).contains(&pc) {
                    self.state = State::Counting;
                    self.counts = Counts::default();
                    if let Some(profile) = &mut self.profile {
                        profile.push(vec![(0, 0); self.program.insns.len()]);
                    }
                    self.prev = None;
                    self.pending = None;
                    self.count(pc);
                }
            }
            State::Counting => {
                if pc == self.end {
                    // The pending instruction is the call of the end marker: not counted.
                    self.regions.push(std::mem::take(&mut self.counts));
                    self.state = State::Idle;
                } else if Some(pc) == self.pause {
                    // Likewise the call of the pause marker.
                    self.state = State::Paused;
                } else {
                    self.count(pc);
                }
            }
            State::Paused => {
                if self.resume.is_some_and(|r| r.0 == pc) {
                    self.state = State::InResume;
                }
            }
            State::InResume => {
                if self.resume.is_some_and(|r| !(r.0..r.1).contains(&pc)) {
                    // As after the begin marker: nothing before it pipelines.
                    self.state = State::Counting;
                    self.prev = None;
                    self.pending = None;
                    self.count(pc);
                }
            }
        }
    }

    fn count(&mut self, pc: u32) {
        let program = self.program;
        if let Some((i, pending)) = self.pending.and_then(|i| Some((i, program.insns.get(i)?))) {
            let prev = self.prev.and_then(|i| program.insns.get(i));
            let before = self.counts.cycles;
            charge(program, pending, prev, pc, &mut self.counts);
            if let Some(entry) = self.profile.as_mut().and_then(|p| p.last_mut()?.get_mut(i)) {
                entry.0 += 1;
                entry.1 += self.counts.cycles - before;
            }
        }
        self.prev = self.pending;
        self.pending = program.at(pc);
        let region = self.regions.len() + 1;
        match self
            .pending
            .and_then(|i| Some((program.insns.get(i)?, self.insn_seen.get_mut(i)?)))
        {
            Some((insn, seen)) => {
                if *seen != region {
                    *seen = region;
                    self.counts.code_bytes += u64::from(insn.size);
                }
                // A 32-bit instruction may straddle two lines.
                for addr in [insn.addr, insn.addr + insn.size - 1] {
                    let line = ((addr - program.start) / 16) as usize;
                    if let Some(seen) = self.line_seen.get_mut(line) {
                        if *seen != region {
                            *seen = region;
                            self.counts.code_lines += 1;
                        }
                    }
                }
            }
            None => self.unmapped += 1,
        }
    }

    /// A region began but did not end.
    pub fn unfinished(&self) -> bool {
        self.state != State::Idle
    }
}

/// The executed address of one line of QEMU's `-d exec` log:
/// `Trace 0: 0x7f… [00800408/08000188/00000110/ff000201] symbol` (the second field in
/// brackets is the guest PC). Other lines: `None`.
pub fn trace_pc(line: &[u8]) -> Option<u32> {
    if !line.starts_with(b"Trace ") {
        return None;
    }
    let open = line.iter().position(|&b| b == b'[')?;
    let rest = line.get(open + 1..)?;
    let slash = rest.iter().position(|&b| b == b'/')?;
    let field = rest.get(slash + 1..)?;
    let mut pc = 0u32;
    for &b in field.iter().take_while(|&&b| b != b'/') {
        pc = pc.checked_mul(16)? + char::from(b).to_digit(16)?;
    }
    Some(pc)
}

/// One line of the tool's output (and of `lab/data/cycles_cortex_m4.txt`):
/// `estimate SCENE METHOD … KEY VALUE …`.
pub struct Estimate<'a> {
    pub words: Vec<&'a str>,
}

impl Estimate<'_> {
    /// The second word: the scene (or `sink`, `calibration`).
    pub fn scene(&self) -> &str {
        self.words.get(1).copied().unwrap_or("")
    }

    /// The third word: the method.
    pub fn method(&self) -> &str {
        self.words.get(2).copied().unwrap_or("")
    }

    /// The word after `key` (searched after scene and method), as written.
    pub fn field(&self, key: &str) -> Option<&str> {
        let words = self.words.get(3..).unwrap_or_default();
        let i = words.iter().position(|w| *w == key)?;
        words.get(i + 1).copied()
    }

    /// The number after `key` (searched after scene and method); NaN if absent.
    pub fn get(&self, key: &str) -> f64 {
        self.field(key).and_then(|w| w.parse().ok()).unwrap_or(f64::NAN)
    }

    /// `key` per pixel.
    pub fn per_pixel(&self, key: &str) -> f64 {
        self.get(key) / self.get("pixels")
    }
}

/// The `estimate` lines of `text`.
pub fn estimates(text: &str) -> Vec<Estimate<'_>> {
    text.lines()
        .filter(|l| l.starts_with("estimate "))
        .map(|l| Estimate {
            words: l.split_whitespace().collect(),
        })
        .collect()
}

/// The address of one instruction line of QEMU's `-d in_asm` listing:
/// `0x08000188:  f000 f831  bl       #0x80016ac`. Other lines: `None`.
pub fn in_asm_pc(line: &[u8]) -> Option<u32> {
    let rest = line.strip_prefix(b"0x")?;
    let colon = rest.iter().position(|&b| b == b':')?;
    let mut pc = 0u32;
    for &b in rest.get(..colon)? {
        pc = pc.checked_mul(16)? + char::from(b).to_digit(16)?;
    }
    Some(pc)
}
