//! The kernel on RV32IMC (no FPU), measured in QEMU (`virt` machine, no BIOS):
//!
//! ```sh
//! cargo run --release --example qemu_rv32 --target riscv32imc-unknown-none-elf
//! ```
//!
//! The same measurement as `qemu_cortex_m4` and `qemu_cortex_m0`
//! (`lab/firmware/examples/common/measure.rs`) on the platform of `lab/firmware/examples/common/rv32.rs`: every
//! standard scene at 240×240 with every method of `Method::ALL` into a `PixelHash`, one
//! `hash` line each with the instructions and the stack of the render, the sink's own
//! cost on its `sink` line. Every `f32` operation is a call into compiler-builtins'
//! soft float; `math::sqrt_exact` is libm's `sqrtf`.
//!
//! Instructions: the `minstret` CSR (64-bit, read as two halves), checked on
//! `addi`/`bnez` loops of known length. QEMU runs with `-icount shift=0`; its `mcycle`
//! then reads the same instruction count — QEMU has no cycle model — which the
//! `counters` line shows over one loop. Exits through semihosting with status 1 on any
//! failure.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(all(target_arch = "riscv32", target_os = "none"))]
#[path = "common/measure.rs"]
mod measure;
#[cfg(all(target_arch = "riscv32", target_os = "none"))]
#[path = "common/rv32.rs"]
mod rv32;
#[cfg(all(target_arch = "riscv32", target_os = "none"))]
#[path = "../../src/scenes.rs"]
mod scenes;

#[cfg(all(target_arch = "riscv32", target_os = "none"))]
mod fw {
    use riscv_rt::entry;

    use crate::measure::{Platform, Run};
    use crate::rv32::{self, Rv32};

    /// Panics print their message and end the run with a failure status.
    #[panic_handler]
    fn panic(info: &core::panic::PanicInfo) -> ! {
        rv32::abort_with(format_args!("panicked: {}", info))
    }

    #[entry]
    fn main() -> ! {
        let mut run = Run::start(Rv32::new("qemu_rv32"));
        run.calibrate(1_000_000); // 2 M instructions
        run.calibrate(100_000_000); // 200 M instructions
                                    // minstret and mcycle over the same loop: equal under QEMU's -icount.
        let (i0, c0) = (rv32::minstret(), rv32::mcycle());
        run.platform.spin(1_000_000);
        let (i1, c1) = (rv32::minstret(), rv32::mcycle());
        run.platform.print(format_args!(
            "counters loop 2000000 minstret {} mcycle {}",
            i1 - i0,
            c1 - c0
        ));
        run.sink();
        run.every_scene();
        run.finish()
    }
}

#[cfg(all(target_os = "none", not(target_arch = "riscv32")))]
#[path = "common/wrong_target.rs"]
mod wrong_target;
#[cfg(all(target_os = "none", not(target_arch = "riscv32")))]
wrong_target::firmware_for!("qemu_rv32", "riscv32imc-unknown-none-elf");

#[cfg(not(target_os = "none"))]
fn main() {
    println!(
        "qemu_rv32 is firmware: cargo run --release --example qemu_rv32 --target riscv32imc-unknown-none-elf"
    );
}
