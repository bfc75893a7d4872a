//! The measurement platform of the Cortex-M firmware in QEMU (`qemu_cortex_m4` on
//! `netduinoplus2`, `qemu_cortex_m0` on `microbit`): SysTick as the instruction
//! counter, semihosting for output and exit status.
//!
//! Under QEMU's `-icount shift=0` one instruction advances virtual time by 1 ns and
//! SysTick counts the core clock, so instructions = ticks × 1e9 / f_clk (SysTick's
//! 24-bit wrap is counted by its exception). Emulation figures: QEMU executes every
//! instruction in one "cycle"; a real core has wait states, multi-cycle loads, and on
//! a Cortex-M0 a soft-float library behind every `f32` operation.
//!
//! The assembly is Thumb-1 (ARMv6-M) so that both cores run the same instructions.
//! Included with `#[path]` together with `measure.rs`.

use core::arch::asm;
use core::fmt;
use core::sync::atomic::{AtomicU32, Ordering};

use cortex_m::peripheral::{syst::SystClkSource, SYST};
use cortex_m_rt::exception;
use cortex_m_semihosting::{debug, hprintln};

use crate::measure::{Platform, PAINT};

static WRAPS: AtomicU32 = AtomicU32::new(0);

/// SysTick reload: counts SysTick's 24-bit wraps so that [`CortexM::ticks`] is 64-bit.
/// (A load and a store: ARMv6-M has no atomic read-modify-write, and nothing else
/// writes the count.)
#[exception]
fn SysTick() {
    WRAPS.store(WRAPS.load(Ordering::Relaxed).wrapping_add(1), Ordering::Relaxed);
}

extern "C" {
    // cortex-m-rt's link.x: the lowest address the stack may reach (end of
    // .bss/.uninit) and the initial stack pointer (top of RAM).
    static mut _stack_end: u32;
    static mut _stack_start: u32;
}

/// A Cortex-M core in QEMU whose SysTick counts a core clock of `clock_hz`.
pub struct CortexM {
    syst: SYST,
    name: &'static str,
    clock_hz: u64,
}

impl CortexM {
    /// Starts SysTick on the core clock (`clock_hz`: QEMU's model of the chip) with the
    /// longest reload and its wrap exception on; `name` is the firmware's. `None` if
    /// the core peripherals were already taken.
    pub fn start(name: &'static str, clock_hz: u64) -> Option<Self> {
        let mut cp = cortex_m::Peripherals::take()?;
        cp.SYST.set_clock_source(SystClkSource::Core);
        cp.SYST.set_reload(0xFF_FFFF);
        cp.SYST.clear_current();
        cp.SYST.enable_interrupt();
        cp.SYST.enable_counter();
        // After clear_current() the counter reads 0 until its first reload.
        while SYST::get_current() == 0 {}
        Some(Self {
            syst: cp.SYST,
            name,
            clock_hz,
        })
    }
}

/// Prints a line and exits with failure: for firmware that cannot start.
pub fn abort(what: &str) -> ! {
    hprintln!("{}", what);
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}

impl Platform for CortexM {
    fn name(&self) -> &'static str {
        self.name
    }

    /// Core-clock ticks since SysTick started: wraps × 2²⁴ + (0xFF_FFFF − current).
    /// Reads the wrap count on both sides of the counter and retries if a wrap
    /// happened in between.
    #[inline(always)]
    fn ticks(&self) -> u64 {
        loop {
            let w1 = WRAPS.load(Ordering::SeqCst);
            let current = SYST::get_current();
            let w2 = WRAPS.load(Ordering::SeqCst);
            if w1 == w2 {
                return u64::from(w1) * (1 << 24) + u64::from(0xFF_FFFF - current);
            }
        }
    }

    /// Ticks of the core clock to instructions under `-icount shift=0` (1 ns each).
    fn instructions(&self, ticks: u64) -> u64 {
        (ticks * 1_000_000_000 + self.clock_hz / 2) / self.clock_hz
    }

    fn instructions_per_tick(&self) -> u64 {
        1_000_000_000_u64.div_ceil(self.clock_hz)
    }

    fn describe_counter(&self, overhead_ticks: u64) {
        hprintln!(
            "clock {} Hz instructions = ticks * 1e9 / {} overhead_ticks {}",
            self.clock_hz,
            self.clock_hz,
            overhead_ticks
        );
    }

    /// `subs` + `bne` per iteration.
    #[inline(always)]
    fn spin(&self, n: u32) {
        // SAFETY: register-only loop; touches no memory and not the stack.
        unsafe { asm!("2:", "subs {0}, #1", "bne 2b", inout(reg) n => _, options(nomem, nostack)) };
    }

    #[inline(always)]
    fn sp(&self) -> usize {
        let sp: usize;
        // SAFETY: reads the stack pointer only.
        unsafe { asm!("mov {}, sp", out(reg) sp, options(nomem, nostack, preserves_flags)) };
        sp
    }

    #[inline(always)]
    fn paint_stack(&self) {
        let bottom = core::ptr::addr_of_mut!(_stack_end) as usize;
        // SAFETY: the words below SP down to `_stack_end` are unused stack.
        unsafe {
            asm!(
                "mov {top}, sp",
                "2:",
                "cmp {p}, {top}",
                "bhs 3f",
                "str {pat}, [{p}]",
                "adds {p}, #4",
                "b 2b",
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
            core::ptr::addr_of_mut!(_stack_end) as usize,
            core::ptr::addr_of_mut!(_stack_start) as usize,
        )
    }

    fn quiet(&mut self, quiet: bool) {
        if quiet {
            self.syst.disable_interrupt();
        } else {
            self.syst.enable_interrupt();
        }
    }

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
            cortex_m::asm::wfi();
        }
    }
}
