//! The smallest firmware of this crate's build: the runtime's reset handler, the vector
//! table (the STM32F407's on thumbv7em, cortex-m-rt's own on the Cortex-M0 and Cortex-M33, riscv-rt's
//! trap entry on RV32) and an idle loop — no kernel. Its section sizes are the baseline
//! subtracted from `no_panic`'s to get the kernel's flash footprint (`.ci/firmware` and
//! `.ci/firmware-nofpu` print both).
//!
//! `cargo build --release --example empty_firmware --target thumbv7em-none-eabihf`
//! (or `thumbv6m-none-eabi`, `riscv32imc-unknown-none-elf`)
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
mod fw {
    #[cfg(target_arch = "arm")]
    use cortex_m::asm::wfi;
    #[cfg(target_arch = "arm")]
    use cortex_m_rt::entry;
    use panic_halt as _;
    #[cfg(target_arch = "riscv32")]
    use riscv::asm::wfi;
    #[cfg(target_arch = "riscv32")]
    use riscv_rt::entry;
    // The PAC's vector table: cortex-m-rt's `device` feature (turned on by the
    // stm32f4 dependency of thumbv7em-none-eabihf) requires it.
    #[cfg(all(target_arch = "arm", target_abi = "eabihf", not(armv8m_main)))]
    use stm32f4xx_hal as _;

    #[entry]
    fn main() -> ! {
        loop {
            wfi();
        }
    }
}

#[cfg(not(target_os = "none"))]
fn main() {
    println!("empty_firmware is firmware: build it with --target thumbv7em-none-eabihf, thumbv6m-none-eabi or riscv32imc-unknown-none-elf");
}
