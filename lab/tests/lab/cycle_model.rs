//! The Cortex-M4 cycle model (`lab/src/cycle_model.rs`) on hand-written
//! disassembly and address sequences: decoding of the mnemonics the compiler emits,
//! taken-branch detection, load pipelining, regions. The same model is checked end to
//! end on real loops in QEMU by `lab/firmware/examples/cycle_calibration.rs` (`.ci/cycles`).

use embedded_raytracer_lab::cycle_model;

use cycle_model::{decode, Counts, Kind, Program, Shape, Tracer, DIVIDE_CYCLES, P, TIMINGS};

#[test]
fn every_mnemonic_has_one_row_and_a_source() {
    let mut seen = std::collections::BTreeSet::new();
    for row in TIMINGS {
        assert!(
            row.source.contains("Table 3-1") || row.source.contains("Table 7-1"),
            "{}",
            row.source
        );
        for m in row.mnemonics {
            assert!(seen.insert(*m), "`{m}` in two rows");
        }
    }
}

#[test]
fn decodes_condition_and_flag_suffixes() {
    // `bls` is B + LS (not BL + S): a branch, not predicated.
    let bls = decode("bls", "0x8000100").unwrap();
    assert_eq!((bls.shape, bls.predicated), (Shape::Branch, false));
    let bl = decode("bl", "0x8000100 <f>").unwrap();
    assert_eq!(bl.shape, Shape::Branch);
    // Flag-setting and predicated data processing.
    for (m, predicated) in [
        ("bics", false),
        ("adds.w", false),
        ("addeq", true),
        ("movne", true),
    ] {
        let d = decode(m, "r0, r1").unwrap();
        assert_eq!(
            (d.kind, d.base, d.predicated),
            (Kind::Integer, 1, predicated),
            "{m}"
        );
    }
    assert!(decode("itte", "ne").unwrap().is_it);
    assert!(decode("it", "eq").unwrap().is_it);
    // Loads with a condition suffix and byte/halfword forms.
    assert!(decode("ldrsb.w", "r0, [r1, #2]").unwrap().shape == Shape::Load);
    assert!(decode("ldrbeq", "r0, [r1]").unwrap().predicated);
    // Unknown instructions are not guessed.
    assert!(decode("wfi", "").is_none());
    assert!(decode("vselgt.f32", "s0, s1, s2").is_none());
}

#[test]
fn fpu_costs_follow_table_7_1() {
    let cost = |m: &str, ops: &str| decode(m, ops).unwrap().base;
    assert_eq!(cost("vdiv.f32", "s0, s1, s2"), 14);
    assert_eq!(cost("vsqrt.f32", "s0, s1"), 14);
    assert_eq!(cost("vmla.f32", "s0, s1, s2"), 3);
    assert_eq!(cost("vfma.f32", "s0, s1, s2"), 3);
    assert_eq!(cost("vmul.f32", "s0, s1, s2"), 1);
    assert_eq!(cost("vmov", "r0, s0"), 2);
    assert_eq!(cost("vmov", "s0, r0"), 2);
    assert_eq!(cost("vmov", "r0, r1, d0"), 2);
    assert_eq!(cost("vmov.f32", "s0, #1.000000e+00"), 1);
    assert_eq!(cost("vmov.f32", "s0, s1"), 1);
    assert_eq!(cost("vmov.32", "r0, d0[1]"), 1);
    assert_eq!(cost("vldr", "s0, [r0, #4]"), 2);
    assert_eq!(cost("vldr", "d0, [r0]"), 3);
    assert_eq!(cost("vstr", "s0, [sp, #8]"), 2);
    let vpush = decode("vpush", "{d8, d9, d10}").unwrap();
    assert_eq!((vpush.base, vpush.list_cost), (1, 6));
    let vpop = decode("vpop", "{s16-s19}").unwrap();
    assert_eq!(vpop.list_cost, 4);
    assert_eq!(cost("udiv", "r0, r1, r2"), DIVIDE_CYCLES);
}

#[test]
fn multiple_loads_count_registers_and_the_pc() {
    let pop = decode("pop", "{r4, r5, r7, pc}").unwrap();
    assert_eq!((pop.list_cost, pop.writes_pc), (4, true));
    let push = decode("push.w", "{r4, r5, r6, r7, r8, lr}").unwrap();
    assert_eq!((push.list_cost, push.writes_pc), (6, false));
    assert_eq!(decode("ldrd", "r0, r1, [sp, #8]").unwrap().list_cost, 2);
    let ldr = decode("ldr.w", "r3, [r1, r2, lsl #2]").unwrap();
    assert_eq!((ldr.load_dest, ldr.address_regs), (1 << 3, 1 << 1 | 1 << 2));
}

/// A program in `llvm-objdump -d` format: the markers, a loop with pipelined and
/// dependent loads, a call, and a predicated return.
const DISASM: &str = "
08000100 <cycle_region_begin>:
 8000100: b580         \tpush\t{r7, lr}
 8000102: bd80         \tpop\t{r7, pc}

08000104 <cycle_region_end>:
 8000104: bf00         \tnop
 8000106: 4770         \tbx\tlr

08000108 <main>:
 8000108: 6801         \tldr\tr1, [r0]
 800010a: 6842         \tldr\tr2, [r0, #0x4]
 800010c: 6813         \tldr\tr3, [r2]
 800010e: 3c01         \tsubs\tr4, #0x1
 8000110: d1fa         \tbne\t0x8000108 <main> @ imm = #-0xc
 8000112: f000 f803    \tbl\t0x800011c <leaf> @ imm = #0x6
 8000116: 2800         \tcmp\tr0, #0x0
 8000118: bf08         \tit\teq
 800011a: bd10         \tpopeq\t{r4, pc}

0800011c <leaf>:
 800011c: ee80 0a81    \tvdiv.f32\ts0, s1, s2
 8000120: 4770         \tbx\tlr
 8000122: 0000         \t.short\t0x0000
";

fn run(pcs: &[u32]) -> Vec<Counts> {
    let program = Program::from_objdump(DISASM).unwrap();
    let mut tracer = Tracer::new(&program).unwrap();
    for &pc in pcs {
        tracer.step(pc);
    }
    assert!(!tracer.unfinished());
    assert_eq!(tracer.unmapped, 0);
    tracer.regions
}

#[test]
fn a_region_charges_the_trm_cycles() {
    let begin = [0x0800_0100, 0x0800_0102];
    let iteration = [0x0800_0108, 0x0800_010a, 0x0800_010c, 0x0800_010e, 0x0800_0110];
    let mut pcs = vec![0x0800_0108]; // before the region: not counted
    pcs.extend(begin);
    pcs.extend(iteration); // bne taken
    pcs.extend(iteration); // bne not taken
    pcs.extend([0x0800_0112, 0x0800_011c, 0x0800_0120]); // bl, vdiv, bx lr
    pcs.extend([0x0800_0116, 0x0800_0118, 0x0800_011a]); // cmp, it, popeq (fails)
    pcs.extend([0x0800_011c, 0x0800_0120]); // the call of the end marker (stand-in)
    pcs.push(0x0800_0104);
    pcs.push(0x0800_0106);
    let regions = run(&pcs);
    assert_eq!(regions.len(), 1);
    let r = &regions[0];
    // Per iteration: ldr 2, ldr pipelined 1, ldr on the previous load's result 2, subs 1;
    // bne taken 1 + P, then 1. Then bl 1 + P, vdiv 14, bx 1 + P, cmp 1, it 1, popeq
    // failing its condition 1; the instruction before the end marker is not counted,
    // the one before it (vdiv) is.
    let expected = 2 * (2 + 1 + 2 + 1) + (1 + P) + 1 + (1 + P) + 14 + (1 + P) + 1 + 1 + 1 + 14;
    assert_eq!(r.cycles, expected);
    assert_eq!(r.instructions, 2 * 5 + 3 + 3 + 1);
    assert_eq!(r.refills, 3);
    assert_eq!(r.cycles_at(3), expected + 3 * (3 - P));
    assert_eq!(r.it_fold, 1, "the IT follows a 16-bit CMP");
    assert_eq!(r.by_kind.iter().sum::<u64>(), r.cycles);
}

#[test]
fn a_taken_predicated_pop_refills() {
    let pcs = [
        0x0800_0100,
        0x0800_0102,
        0x0800_0116,
        0x0800_0118,
        0x0800_011a,
        0x0800_0108, // popeq taken: returns somewhere else
        0x0800_010a,
        0x0800_0104,
    ];
    let regions = run(&pcs);
    // cmp 1, it 1, pop {r4, pc} 1 + 2 + P, ldr 2 (the ldr before the marker call is not counted).
    assert_eq!(regions[0].cycles, 1 + 1 + (1 + 2 + P) + 2);
    assert_eq!(regions[0].refills, 1);
}

#[test]
fn unknown_instructions_are_reported() {
    let program = Program::from_objdump(&DISASM.replace("\tvdiv.f32\ts0, s1, s2", "\twfi\t")).unwrap();
    let mut tracer = Tracer::new(&program).unwrap();
    for pc in [
        0x0800_0100,
        0x0800_0102,
        0x0800_011c,
        0x0800_0120,
        0x0800_0116,
        0x0800_0104,
    ] {
        tracer.step(pc);
    }
    assert_eq!(tracer.regions[0].unknown.get("wfi"), Some(&1));
}

#[test]
fn parses_qemu_log_lines() {
    let exec = b"Trace 0: 0x7f4f24000100 [00800408/08000188/00000110/ff000201] \n";
    assert_eq!(cycle_model::trace_pc(exec), Some(0x0800_0188));
    assert_eq!(cycle_model::trace_pc(b"IN: \n"), None);
    let insn = b"0x080016ae:  466f       mov      r7, sp\n";
    assert_eq!(cycle_model::in_asm_pc(insn), Some(0x0800_16ae));
    assert_eq!(cycle_model::in_asm_pc(b"\n"), None);
}

#[test]
fn a_paused_stretch_is_not_counted() {
    // The leaf function stands in for the pause marker, `main`'s first instruction for
    // the resume marker.
    let disasm = DISASM
        .replace("<leaf>:", "<cycle_region_pause>:")
        .replace(
            "08000108 <main>:",
            "08000108 <cycle_region_resume>:\n 8000108: 6801         \tldr\tr1, [r0]\n\n0800010a <main>:",
        )
        .replacen(" 8000108: 6801         \tldr\tr1, [r0]\n", "", 1);
    let program = Program::from_objdump(&disasm).unwrap();
    let count = |pcs: &[u32]| {
        let mut tracer = Tracer::new(&program).unwrap();
        for &pc in pcs {
            tracer.step(pc);
        }
        assert!(!tracer.unfinished());
        tracer.regions[0].clone()
    };
    // begin; cmp, it; popeq as the call of the end marker (not counted).
    let plain = [
        0x0800_0100,
        0x0800_0102,
        0x0800_0116,
        0x0800_0118,
        0x0800_011a,
        0x0800_0104,
    ];
    // The same with a paused stretch between cmp and it: the call of the pause marker
    // (not counted), the marker, work in the pause, the resume marker.
    let paused = [
        0x0800_0100,
        0x0800_0102,
        0x0800_0116, // cmp
        0x0800_0118, // the call of the pause marker
        0x0800_011c, // pause marker: counting stops
        0x0800_0120,
        0x0800_010a, // paused work: two loads
        0x0800_010c,
        0x0800_0108, // resume marker
        0x0800_0118, // it: counted again
        0x0800_011a, // the call of the end marker
        0x0800_0104,
    ];
    let (a, b) = (count(&plain), count(&paused));
    // Both count cmp 1 and it 1; the paused loads are not counted.
    assert_eq!((a.instructions, a.cycles), (2, 2));
    assert_eq!((b.instructions, b.cycles), (2, 2));
    assert_eq!(b.by_kind, a.by_kind);
}
