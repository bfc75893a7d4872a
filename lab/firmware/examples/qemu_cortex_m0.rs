//! The kernel on a Cortex-M0 without FPU, measured in QEMU (`microbit`, an nRF51822:
//! 256 KiB flash, 16 KiB RAM, 16 MHz):
//!
//! ```sh
//! cargo run --release --example qemu_cortex_m0 --target thumbv6m-none-eabi
//! ```
//!
//! The same measurement as `qemu_cortex_m4` (`lab/firmware/examples/common/measure.rs` on the
//! SysTick platform of `lab/firmware/examples/common/cortex_m.rs`): every standard scene at 240×240
//! with every method of `Method::ALL` into a `PixelHash`, one `hash` line each with the
//! instructions and the stack of the render, the `PixelHash` sink's own cost on its
//! `sink` line. Every `f32` operation here is a call into compiler-builtins' soft
//! float, and `math::sqrt_exact` is libm's `sqrtf`.
//!
//! Instructions: SysTick counts the 16 MHz core clock and QEMU runs with
//! `-icount shift=0` (1 ns per instruction), so instructions = ticks × 1e9 / 16e6 —
//! 62.5 instructions per tick, checked on `subs`/`bne` loops of known length, one of
//! them long enough for a SysTick wrap (2²⁴ ticks = 1.05 G instructions). Exits through
//! semihosting with status 1 on any failure.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(all(target_arch = "arm", target_os = "none", not(target_abi = "eabihf")))]
#[path = "common/cortex_m.rs"]
mod cortex_m_platform;
#[cfg(all(target_arch = "arm", target_os = "none", not(target_abi = "eabihf")))]
#[path = "common/measure.rs"]
mod measure;
#[cfg(all(target_arch = "arm", target_os = "none", not(target_abi = "eabihf")))]
#[path = "../../src/scenes.rs"]
mod scenes;

#[cfg(all(target_arch = "arm", target_os = "none", not(target_abi = "eabihf")))]
mod fw {
    use cortex_m_rt::entry;
    use panic_semihosting as _;

    use crate::cortex_m_platform::{abort, CortexM};
    use crate::measure::Run;

    /// microbit's core clock (QEMU's nRF51 model: HCLK 16 MHz).
    const F_CLK_HZ: u64 = 16_000_000;

    #[entry]
    fn main() -> ! {
        let Some(platform) = CortexM::start("qemu_cortex_m0", F_CLK_HZ) else {
            abort("core peripherals already taken");
        };
        let mut run = Run::start(platform);
        run.calibrate(1_000_000); // 2 M instructions: no SysTick wrap
        run.calibrate(600_000_000); // 1.2 G instructions: one wrap
        run.sink();
        run.every_scene();
        run.finish()
    }
}

#[cfg(all(target_os = "none", not(all(target_arch = "arm", not(target_abi = "eabihf")))))]
#[path = "common/wrong_target.rs"]
mod wrong_target;
#[cfg(all(target_os = "none", not(all(target_arch = "arm", not(target_abi = "eabihf")))))]
wrong_target::firmware_for!("qemu_cortex_m0", "thumbv6m-none-eabi");

#[cfg(not(target_os = "none"))]
fn main() {
    println!("qemu_cortex_m0 is firmware: cargo run --release --example qemu_cortex_m0 --target thumbv6m-none-eabi");
}
