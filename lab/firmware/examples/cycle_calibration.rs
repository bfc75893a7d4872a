//! The cycle model's self-test: loops of known cost, in assembly, each between the
//! region markers of `lab/firmware/examples/common/cycle_region.rs`.
//!
//! ```sh
//! bash .ci/cycles --quick    # builds this, traces it in QEMU, checks every loop
//! ```
//!
//! Each loop's cost is derived by hand from ARM's Cortex-M4 Technical Reference Manual
//! (DDI 0439B; Table 3-1 "Cortex-M4 instruction set summary", §3.3.2 "Load/store
//! timings", Table 7-1 "FPU instruction set") with a pipeline refill of `P` = 1 cycle and
//! printed as `region calibration NAME expected CYCLES`; `cycle_model run` fails unless
//! its estimate of that region equals the figure exactly. So a wrong row of the model's
//! timing table, a mis-decoded mnemonic, a missed taken branch or a wrong pipelining
//! rule fails the check.
//!
//! Every loop runs `N` times and ends with `subs r4, r4, #1` (1 cycle) and `bne` (taken
//! `N − 1` times, 1 + P, then not taken, 1); see [`looped`].
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(all(target_os = "none", target_abi = "eabihf", not(armv8m_main)))]
#[path = "common/cycle_region.rs"]
mod cycle_region;

#[cfg(all(target_os = "none", target_abi = "eabihf", not(armv8m_main)))]
mod fw {
    use core::arch::asm;
    use core::ptr::addr_of_mut;

    use cortex_m_rt::entry;
    use cortex_m_semihosting::{debug, hprintln};
    use panic_semihosting as _;
    // The PAC's vector table: cortex-m-rt's `device` feature (turned on by the stm32f4
    // dev-dependency) requires it in every firmware example.
    use stm32f4xx_hal as _;

    use crate::cycle_region::{cycle_region_begin, cycle_region_end};

    /// Iterations of every loop.
    const N: u32 = 100;
    /// Pipeline refill cycles the expected figures assume (the model's `P`).
    const P: u32 = 1;

    /// Cycles of a loop whose body (including its `subs`, excluding its `bne`) costs
    /// `body`: `N` bodies, `N − 1` taken `bne` (1 + P) and one not taken (1).
    const fn looped(body: u32) -> u32 {
        N * body + (N - 1) * (1 + P) + 1
    }

    /// Words the loads and stores use: word 0 holds the array's own address (for the
    /// dependent load), the others are scratch.
    static mut CELLS: [u32; 4] = [0; 4];

    /// Runs the assembly lines between the markers with `r4` = `N` (the loop counter)
    /// and `r5` = `CELLS`, then prints the region's label and expected cycles. The
    /// markers (`nop`s) preserve every register but `lr`; the loops may use r0–r3,
    /// r12, `lr` and s0–s4, declared clobbered.
    macro_rules! calibrate {
        ($name:literal, $expected:expr, $($line:literal),+ $(,)?) => {{
            let cells = addr_of_mut!(CELLS) as u32;
            // SAFETY: the loops only touch `CELLS` (through r5), the stack below SP
            // (balanced push/pop) and registers declared here.
            unsafe {
                asm!(
                    "bl {begin}",
                    $($line,)+
                    "bl {end}",
                    begin = sym cycle_region_begin,
                    end = sym cycle_region_end,
                    inout("r4") N => _,
                    in("r5") cells,
                    out("r0") _,
                    out("r1") _,
                    out("r2") _,
                    out("r3") _,
                    out("r12") _,
                    out("lr") _,
                    out("s0") _,
                    out("s1") _,
                    out("s2") _,
                    out("s3") _,
                    out("s4") _,
                )
            }
            hprintln!("region calibration {} expected {}", $name, $expected);
        }};
    }

    #[entry]
    fn main() -> ! {
        // SAFETY: single-threaded start-up; nothing else touches CELLS.
        unsafe {
            let cells = addr_of_mut!(CELLS);
            core::ptr::write_volatile(cells.cast::<u32>(), cells as u32);
        }
        hprintln!(
            "cycle_calibration: loops of TRM-derived cost, N = {}, P = {}",
            N,
            P
        );

        // Data processing: 1 cycle each (Table 3-1, Add).
        calibrate!(
            "alu",
            looped(4 + 1),
            "2:",
            "adds r0, r0, #1",
            "adds r0, r0, #1",
            "adds r0, r0, #1",
            "adds r0, r0, #1",
            "subs r4, r4, #1",
            "bne 2b",
        );
        // A load after a branch is not pipelined: 2 (Table 3-1, Load word).
        calibrate!(
            "ldr",
            looped(2 + 1 + 1),
            "2:",
            "ldr r0, [r5]",
            "adds r1, r0, #1",
            "subs r4, r4, #1",
            "bne 2b",
        );
        // Independent loads pipeline: 2 + 1 + 1 (§3.3.2, "LDR R0,[R1,R5]; LDR R1,[R2];
        // LDR R2,[R3,#4] - normally four cycles total").
        calibrate!(
            "ldr-pipelined",
            looped(2 + 1 + 1 + 1),
            "2:",
            "ldr r0, [r5]",
            "ldr r1, [r5, #4]",
            "ldr r2, [r5, #8]",
            "subs r4, r4, #1",
            "bne 2b",
        );
        // A load whose address is the previous load's result does not pipeline: 2 + 2.
        calibrate!(
            "ldr-dependent",
            looped(2 + 2 + 1),
            "2:",
            "ldr r0, [r5]",
            "ldr r1, [r0]",
            "subs r4, r4, #1",
            "bne 2b",
        );
        // A store after a load pipelines (1), a load after a store does not (2) (§3.3.2:
        // "STR can only be pipelined when it follows an LDR, but nothing can be
        // pipelined after the store").
        calibrate!(
            "ldr-str-ldr",
            looped(2 + 1 + 2 + 1),
            "2:",
            "ldr r0, [r5, #4]",
            "str r0, [r5, #8]",
            "ldr r1, [r5, #12]",
            "subs r4, r4, #1",
            "bne 2b",
        );
        // VDIV.F32: 14 (Table 7-1).
        calibrate!(
            "vdiv",
            looped(14 + 1),
            "2:",
            "vdiv.f32 s0, s1, s2",
            "subs r4, r4, #1",
            "bne 2b",
        );
        // VSQRT.F32: 14 (Table 7-1).
        calibrate!(
            "vsqrt",
            looped(14 + 1),
            "2:",
            "vsqrt.f32 s0, s1",
            "subs r4, r4, #1",
            "bne 2b",
        );
        // Unconditional B, BL and BX: 1 + P each (Table 3-1, Branch).
        calibrate!(
            "call-bx",
            (1 + P) + looped((1 + P) + (1 + P) + 1),
            "b 3f",
            "4:",
            "bx lr",
            "3:",
            "bl 4b",
            "subs r4, r4, #1",
            "bne 3b",
        );
        // PUSH {LR}: 1 + N = 2; POP {PC}: 1 + N + P = 2 + P (Table 3-1, Push, Pop).
        calibrate!(
            "call-pop-pc",
            (1 + P) + looped((1 + P) + 2 + (2 + P) + 1),
            "b 3f",
            "4:",
            "push {{lr}}",
            "pop {{pc}}",
            "3:",
            "bl 4b",
            "subs r4, r4, #1",
            "bne 3b",
        );
        // CBZ: 1 not taken, 1 + P taken (Table 3-1, note c); B: 1 + P.
        calibrate!(
            "cbz",
            (N - 1) * (1 + 1 + (1 + P)) + 1 + (1 + P),
            "3:",
            "subs r4, r4, #1",
            "cbz r4, 4f",
            "b 3b",
            "4:",
        );
        // IT: 1; each predicated ADD: 1, passed or failed (Table 3-1, If-then, Add).
        calibrate!(
            "it",
            looped(1 + 1 + 1 + 1 + 1),
            "2:",
            "cmp r4, #50",
            "ite hs",
            "addhs r0, r0, #1",
            "addlo r1, r1, #1",
            "subs r4, r4, #1",
            "bne 2b",
        );
        // PUSH/POP of 4 registers: 1 + 4; VPUSH/VPOP of 2 doubles: 1 + 2·2; LDM of 3:
        // 1 + 3 (Table 3-1, Table 7-1).
        calibrate!(
            "multiple",
            looped(5 + 5 + 5 + 5 + 4 + 1),
            "2:",
            "push {{r0, r1, r2, r3}}",
            "pop {{r0, r1, r2, r3}}",
            "vpush {{d0, d1}}",
            "vpop {{d0, d1}}",
            "ldm r5, {{r0, r1, r2}}",
            "subs r4, r4, #1",
            "bne 2b",
        );
        // VLDR.32/VSTR.32: 2; VMOV core↔float: 2; VMLA.F32: 3; VCVT, VADD: 1; MUL,
        // UMULL: 1 (Table 7-1, Table 3-1).
        calibrate!(
            "fp-mixed",
            looped(2 + 2 + 2 + 2 + 3 + 1 + 1 + 1 + 1 + 1),
            "2:",
            "vldr s0, [r5, #4]",
            "vstr s0, [r5, #8]",
            "vmov r0, s0",
            "vmov s1, r0",
            "vmla.f32 s2, s0, s1",
            "vcvt.s32.f32 s3, s2",
            "vadd.f32 s4, s3, s2",
            "mul r1, r0, r0",
            "umull r2, r3, r0, r0",
            "subs r4, r4, #1",
            "bne 2b",
        );
        // UDIV: the model's assumed 12 (Table 3-1: 2 to 12).
        calibrate!(
            "udiv",
            looped(12 + 1),
            "2:",
            "udiv r0, r5, r4",
            "subs r4, r4, #1",
            "bne 2b",
        );

        hprintln!("result ok");
        debug::exit(debug::EXIT_SUCCESS);
        // Not reached: QEMU exits on the semihosting call.
        loop {
            cortex_m::asm::wfi();
        }
    }
}

#[cfg(all(target_os = "none", not(all(target_abi = "eabihf", not(armv8m_main)))))]
#[path = "common/wrong_target.rs"]
mod wrong_target;
#[cfg(all(target_os = "none", not(all(target_abi = "eabihf", not(armv8m_main)))))]
wrong_target::firmware_for!("cycle_calibration", "thumbv7em-none-eabihf");

#[cfg(not(target_os = "none"))]
fn main() {
    println!("cycle_calibration is firmware: bash .ci/cycles --quick builds, traces and checks it");
}
