//! Region markers for the cycle model (`lab/examples/cycle_model.rs`): a firmware calls
//! [`cycle_region_begin`] right before and [`cycle_region_end`] right after the code
//! whose cycles are estimated. The tool finds them by these symbol names in the ELF's
//! disassembly and counts the instructions executed after the begin marker returns, up
//! to (not including) the call of the end marker.
//!
//! Included with `#[path]` by the firmware examples `qemu_cycles` and
//! `cycle_calibration`.

use core::arch::asm;

/// Start of a region. Never inlined (the tool needs its address); its body differs from
/// [`cycle_region_end`]'s so the two cannot be merged into one address. The `asm!`
/// without `nomem` is a compiler barrier: no memory access moves across the call.
#[no_mangle]
#[inline(never)]
pub extern "C" fn cycle_region_begin() {
    // SAFETY: a no-op instruction.
    unsafe { asm!("nop", options(nostack, preserves_flags)) };
}

/// End of a region (see [`cycle_region_begin`]).
#[no_mangle]
#[inline(never)]
pub extern "C" fn cycle_region_end() {
    // SAFETY: no-op instructions.
    unsafe { asm!("nop", "nop", options(nostack, preserves_flags)) };
}

/// Inside a region, before work that is not the region's: the tool stops counting at
/// its call…
#[no_mangle]
#[inline(never)]
pub extern "C" fn cycle_region_pause() {
    // SAFETY: no-op instructions.
    unsafe { asm!("nop", "nop", "nop", options(nostack, preserves_flags)) };
}

/// …and counts again after it returns (see [`cycle_region_pause`]).
#[no_mangle]
#[inline(never)]
pub extern "C" fn cycle_region_resume() {
    // SAFETY: no-op instructions.
    unsafe { asm!("nop", "nop", "nop", "nop", options(nostack, preserves_flags)) };
}
