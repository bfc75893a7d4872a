//! The kernel on a Cortex-M4F, measured in QEMU (`netduinoplus2`, an STM32F405):
//!
//! ```sh
//! cargo run --release --example qemu_cortex_m4 --target thumbv7em-none-eabihf
//! ```
//!
//! The measurement is `lab/firmware/examples/common/measure.rs` (shared with `qemu_cortex_m0` and
//! `qemu_rv32`) on the SysTick platform of `lab/firmware/examples/common/cortex_m.rs`. It renders
//! every standard scene (`lab/src/scenes.rs`, the numbers of
//! `scenes/*.toml`) with every method in `Method::ALL` into a [`PixelHash`] — the board
//! has 128 KiB of RAM and no framebuffer — **at 240×240**: each scene's own camera
//! (eye, look-at, up, vertical field of view) with its size replaced by 240×240, so the
//! horizontal field of view follows from the square aspect. Then the scenes with lights,
//! a floor and mirrors (`shadows`, `mirrors`) with the renders of
//! `scenes::FEATURE_RENDERS`: the default method with the default options, the literal
//! options and the textbook epsilon, and the seed's method with the literal options.
//! Prints, one line per scene and render, in a format `lab/tests/lab/firmware_hashes.rs` parses:
//!
//! ```text
//! hash lab incremental/robust/exact 0x0123456789abcdef pixels 57600 instr 3456789 ipp 60.0 stack 312
//! ```
//!
//! - `instr`: instructions executed by the render. Under QEMU's `-icount shift=0` one
//!   instruction advances virtual time by 1 ns and SysTick counts the 168 MHz core
//!   clock, so instructions = ticks × 1e9 / 168e6 (SysTick's 24-bit wrap is counted by
//!   its exception). The conversion is checked first against `subs`/`bne` loops of known
//!   length (`calibration` lines). Emulation figures: QEMU executes every instruction in
//!   one "cycle"; a real M4 has wait states, multi-cycle loads, divides and square roots.
//! - `stack`: bytes of stack below the caller's stack pointer that the render touched
//!   (the stack is painted before and scanned after), measured in a second, untimed
//!   render with the SysTick interrupt off so no exception frame lands on the stack.
//!
//! Also checks `math::sqrt_exact` (`VSQRT.F32`) bit for bit against `libm::sqrtf`
//! over every 4099th `f32` bit pattern. Exits through semihosting with status 1 on any
//! failure (a wrong pixel count, a calibration off by more than its tolerance, a square
//! root mismatch, an unbuildable camera, differing hashes between the two passes).
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(all(target_os = "none", target_abi = "eabihf"))]
#[path = "common/cortex_m.rs"]
mod cortex_m_platform;
#[cfg(all(target_os = "none", target_abi = "eabihf"))]
#[path = "common/measure.rs"]
mod measure;
#[cfg(all(target_os = "none", target_abi = "eabihf"))]
#[path = "../../src/scenes.rs"]
mod scenes;

#[cfg(all(target_os = "none", target_abi = "eabihf"))]
mod fw {
    use cortex_m_rt::entry;
    use panic_semihosting as _;
    // The PAC's vector table: cortex-m-rt's `device` feature (turned on by the stm32f4
    // dev-dependency) requires it in every firmware example.
    use stm32f4xx_hal as _;

    use crate::cortex_m_platform::{abort, CortexM};
    use crate::measure::Run;

    /// netduinoplus2's core clock (QEMU's STM32F405 model runs SYSCLK at 168 MHz).
    const F_CLK_HZ: u64 = 168_000_000;

    #[entry]
    fn main() -> ! {
        let Some(platform) = CortexM::start("qemu_cortex_m4", F_CLK_HZ) else {
            abort("core peripherals already taken");
        };
        let mut run = Run::start(platform);
        run.calibrate(1_000_000); // 2 M instructions: no SysTick wrap
        run.calibrate(100_000_000); // 200 M instructions: 2 wraps
        run.check_sqrt();
        run.sink();
        run.every_scene();
        run.feature_scenes();
        run.finish()
    }
}

#[cfg(all(target_os = "none", not(target_abi = "eabihf")))]
#[path = "common/wrong_target.rs"]
mod wrong_target;
#[cfg(all(target_os = "none", not(target_abi = "eabihf")))]
wrong_target::firmware_for!("qemu_cortex_m4", "thumbv7em-none-eabihf");

#[cfg(not(target_os = "none"))]
fn main() {
    println!(
        "qemu_cortex_m4 is firmware: cargo run --release --example qemu_cortex_m4 --target thumbv7em-none-eabihf"
    );
}
