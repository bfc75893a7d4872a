//! Anti-aliasing on a Cortex-M4F, measured in QEMU (`netduinoplus2`) like
//! `qemu_cortex_m4` (`lab/firmware/examples/common/measure.rs`):
//!
//! ```sh
//! cargo run --release --example qemu_sampling --target thumbv7em-none-eabihf
//! ```
//!
//! `lab` (the Lab #1 loop) and `shadows` (the features path) at 240×240 with
//! `measure::SAMPLINGS` (`Center`, `Grid(4)`, `Adaptive(4)`, default method), one line
//! each: `aa SCENE SAMPLING HASH pixels P instr I ipp X stack S`
//! (`lab/tests/lab/sampling.rs` compares the hashes of the committed run,
//! `lab/data/qemu_sampling.txt`, with the host's). A firmware of its own: linking the
//! sampled paths for a scene type changes how the compiler inlines that type's shared
//! shading functions, so `qemu_cortex_m4`'s figures are measured without them, as a
//! firmware that does not use anti-aliasing is built.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(all(target_os = "none", target_abi = "eabihf", not(armv8m_main)))]
#[path = "common/cortex_m.rs"]
mod cortex_m_platform;
#[cfg(all(target_os = "none", target_abi = "eabihf", not(armv8m_main)))]
#[path = "common/measure.rs"]
mod measure;
#[cfg(all(target_os = "none", target_abi = "eabihf", not(armv8m_main)))]
#[path = "../../src/scenes.rs"]
mod scenes;

#[cfg(all(target_os = "none", target_abi = "eabihf", not(armv8m_main)))]
mod fw {
    use cortex_m_rt::entry;
    use panic_semihosting as _;
    // The PAC's vector table (cortex-m-rt's `device` feature).
    use stm32f4xx_hal as _;

    use crate::cortex_m_platform::{abort, CortexM};
    use crate::measure::Run;

    /// netduinoplus2's core clock (QEMU's STM32F405 model runs SYSCLK at 168 MHz).
    const F_CLK_HZ: u64 = 168_000_000;

    #[entry]
    fn main() -> ! {
        let Some(platform) = CortexM::start("qemu_sampling", F_CLK_HZ) else {
            abort("core peripherals already taken");
        };
        let mut run = Run::start(platform);
        run.calibrate(1_000_000);
        run.sampling_scenes();
        run.finish()
    }
}

#[cfg(all(target_os = "none", not(all(target_abi = "eabihf", not(armv8m_main)))))]
#[path = "common/wrong_target.rs"]
mod wrong_target;
#[cfg(all(target_os = "none", not(all(target_abi = "eabihf", not(armv8m_main)))))]
wrong_target::firmware_for!("qemu_sampling", "thumbv7em-none-eabihf");

#[cfg(not(target_os = "none"))]
fn main() {
    println!("qemu_sampling is firmware: cargo run --release --example qemu_sampling --target thumbv7em-none-eabihf");
}
