//! The measurement platform of the RV32 firmware in QEMU (`qemu_rv32` on the `virt`
//! machine): the `minstret` CSR as the instruction counter, semihosting for output and
//! exit status (QEMU needs `-semihosting-config enable=on`).
//!
//! `minstret`/`minstreth` count retired instructions; RV32 reads the 64-bit counter as
//! two CSRs. QEMU (7.2) has no cycle model: under `-icount` both `minstret` and `mcycle`
//! read its instruction count (without `-icount`, host time), so `mcycle` is printed
//! once beside `minstret` to show it, and no cycle figure is derived from it.
//!
//! Included with `#[path]` together with `measure.rs`.

use core::arch::asm;
use core::fmt;

use riscv_semihosting::{debug, hprintln};

use crate::measure::{Platform, PAINT};

extern "C" {
    // riscv-rt's link.x: the start of its `.stack` region (the lowest address the stack
    // may reach, after .bss and the empty heap) and the initial stack pointer.
    static mut __estack: u32;
    static mut _stack_start: u32;
}

/// Reads a 64-bit counter as two 32-bit CSRs: high, low, high again, retried if the
/// low word wrapped in between.
macro_rules! csr64 {
    ($lo:literal, $hi:literal) => {{
        loop {
            let (hi, lo, hi2): (u32, u32, u32);
            // SAFETY: reads of counter CSRs, no side effects.
            unsafe {
                asm!(
                    concat!("csrr {0}, ", $hi),
                    concat!("csrr {1}, ", $lo),
                    concat!("csrr {2}, ", $hi),
                    out(reg) hi,
                    out(reg) lo,
                    out(reg) hi2,
                    options(nomem, nostack, preserves_flags)
                )
            };
            if hi == hi2 {
                break (u64::from(hi) << 32) | u64::from(lo);
            }
        }
    }};
}

/// Instructions retired (`minstret`).
#[inline(always)]
pub fn minstret() -> u64 {
    csr64!("minstret", "minstreth")
}

/// QEMU's `mcycle`: under `-icount`, the instruction count again.
#[inline(always)]
pub fn mcycle() -> u64 {
    csr64!("mcycle", "mcycleh")
}

/// Prints a line and exits with failure.
pub fn abort_with(what: fmt::Arguments) -> ! {
    hprintln!("{}", what);
    debug::exit(debug::EXIT_FAILURE);
    loop {
        riscv::asm::wfi();
    }
}

/// An RV32 hart in QEMU, counting with `minstret`.
pub struct Rv32 {
    name: &'static str,
}

impl Rv32 {
    /// The platform of the firmware called `name`.
    pub fn new(name: &'static str) -> Self {
        Self { name }
    }
}

impl Platform for Rv32 {
    fn name(&self) -> &'static str {
        self.name
    }

    #[inline(always)]
    fn ticks(&self) -> u64 {
        minstret()
    }

    fn instructions(&self, ticks: u64) -> u64 {
        ticks
    }

    fn instructions_per_tick(&self) -> u64 {
        1
    }

    fn describe_counter(&self, overhead_ticks: u64) {
        hprintln!(
            "counter minstret instructions = ticks overhead_ticks {}",
            overhead_ticks
        );
    }

    /// `addi` + `bnez` per iteration.
    #[inline(always)]
    fn spin(&self, n: u32) {
        // SAFETY: register-only loop; touches no memory and not the stack.
        unsafe {
            asm!("2:", "addi {0}, {0}, -1", "bnez {0}, 2b", inout(reg) n => _, options(nomem, nostack))
        };
    }

    #[inline(always)]
    fn sp(&self) -> usize {
        let sp: usize;
        // SAFETY: reads the stack pointer only.
        unsafe { asm!("mv {}, sp", out(reg) sp, options(nomem, nostack, preserves_flags)) };
        sp
    }

    #[inline(always)]
    fn paint_stack(&self) {
        let bottom = core::ptr::addr_of_mut!(__estack) as usize;
        // SAFETY: the words below SP down to `__estack` are unused stack.
        unsafe {
            asm!(
                "mv {top}, sp",
                "2:",
                "bgeu {p}, {top}, 3f",
                "sw {pat}, 0({p})",
                "addi {p}, {p}, 4",
                "j 2b",
                "3:",
                p = inout(reg) bottom => _,
                top = out(reg) _,
                pat = in(reg) PAINT,
                options(nostack),
            );
        }
    }

    fn stack_region(&self) -> (usize, usize) {
        (
            core::ptr::addr_of_mut!(__estack) as usize,
            core::ptr::addr_of_mut!(_stack_start) as usize,
        )
    }

    /// No interrupt is enabled: nothing to silence.
    fn quiet(&mut self, _quiet: bool) {}

    fn print(&self, args: fmt::Arguments) {
        hprintln!("{}", args);
    }

    fn exit(&self, ok: bool) -> ! {
        debug::exit(if ok {
            debug::EXIT_SUCCESS
        } else {
            debug::EXIT_FAILURE
        });
        // Not reached: QEMU exits on the semihosting call.
        loop {
            riscv::asm::wfi();
        }
    }
}
