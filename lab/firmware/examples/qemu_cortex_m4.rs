//! The kernel on a Cortex-M4F, measured in QEMU (`netduinoplus2`, an STM32F405) — and,
//! built for `thumbv8m.main-none-eabihf`, on a Cortex-M33 with FPU (QEMU `mps2-an505`,
//! the core of the Raspberry Pi Pico 2's RP2350), the same measurement:
//!
//! ```sh
//! cargo run --release --example qemu_cortex_m4 --target thumbv7em-none-eabihf
//! cargo run --release --example qemu_cortex_m4 --target thumbv8m.main-none-eabihf
//! ```
//!
//! One source, so that both chips run the same render sequence; only the machine
//! differs ([`fw::CHIP`]: the run's name, `qemu_cortex_m4` or `qemu_cortex_m33`, its
//! SysTick clock and the length of the calibration loop that spans a SysTick wrap).
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
//!   clock (the Cortex-M33: AN505's 20 MHz system clock), so instructions = ticks ×
//!   1e9 / 168e6 (1e9 / 20e6 = 50 per tick; SysTick's 24-bit wrap is counted by its
//!   exception). The conversion is checked first against `subs`/`bne` loops of known
//!   length (`calibration` lines). Emulation figures: QEMU executes every instruction in
//!   one "cycle"; a real M4 has wait states, multi-cycle loads, divides and square roots.
//! - `stack`: bytes of stack below the caller's stack pointer that the render touched
//!   (the stack is painted before and scanned after), measured in a second, untimed
//!   render with the SysTick interrupt off so no exception frame lands on the stack.
//!
//! Also checks `math::sqrt_exact` (`VSQRT.F32` on both cores) bit for bit against `libm::sqrtf`
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
    // dependency of thumbv7em-none-eabihf) requires it. The Cortex-M33 build has
    // cortex-m-rt's own table.
    #[cfg(not(armv8m_main))]
    use stm32f4xx_hal as _;

    use crate::cortex_m_platform::{abort, CortexM};
    use crate::measure::Run;

    /// The machine the firmware runs on: the run's name (the first word of its output,
    /// by which `lab/tests/lab/firmware_hashes.rs` tells the runs apart), the clock
    /// SysTick counts, and a calibration loop (`2n` instructions) that spans a SysTick
    /// wrap (2²⁴ ticks).
    pub struct Chip {
        name: &'static str,
        clock_hz: u64,
        wrap_calibration: u32,
    }

    /// netduinoplus2: QEMU's STM32F405 model runs SYSCLK at 168 MHz; a wrap is 99.9 M
    /// instructions, the loop of 200 M spans two.
    #[cfg(not(armv8m_main))]
    pub const CHIP: Chip = Chip {
        name: "qemu_cortex_m4",
        clock_hz: 168_000_000,
        wrap_calibration: 100_000_000,
    };

    /// mps2-an505: QEMU clocks the AN505's Cortex-M33 (and its SysTick, on the core
    /// clock) at the 20 MHz system clock; a wrap is 839 M instructions, the loop of
    /// 1.2 G spans one.
    #[cfg(armv8m_main)]
    pub const CHIP: Chip = Chip {
        name: "qemu_cortex_m33",
        clock_hz: 20_000_000,
        wrap_calibration: 600_000_000,
    };

    #[entry]
    fn main() -> ! {
        let Some(platform) = CortexM::start(CHIP.name, CHIP.clock_hz) else {
            abort("core peripherals already taken");
        };
        let mut run = Run::start(platform);
        run.calibrate(1_000_000); // 2 M instructions: no SysTick wrap
        run.calibrate(CHIP.wrap_calibration); // across a SysTick wrap
        run.check_sqrt();
        run.sink();
        run.every_scene();
        run.feature_scenes();
        // The kernel's incremental (animated) sequences go here, after the still
        // renders, so that the lines above stay as committed: e.g. `run.bounce()`, a
        // `Run` method in `common/measure.rs` that prints one line per sequence (a
        // new first word, which `lab/src/qemu_output.rs` and the host test learn).
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
