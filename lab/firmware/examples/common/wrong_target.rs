//! A firmware example built for a bare-metal target it was not written for (say,
//! `qemu_rv32` for `thumbv6m-none-eabi`) still builds, as this stub: it prints which
//! target the example is for and exits with failure. Included with `#[path]`:
//!
//! ```ignore
//! wrong_target::firmware_for!("qemu_cortex_m4", "thumbv7em-none-eabihf");
//! ```

/// The stub's `main` and panic handler for the target being built.
macro_rules! firmware_for {
    ($name:literal, $target:literal) => {
        use panic_halt as _;
        // The PAC's vector table: cortex-m-rt's `device` feature (turned on by the
        // stm32f4 dependency of thumbv7em-none-eabihf) requires it.
        #[cfg(all(target_arch = "arm", target_abi = "eabihf", not(armv8m_main)))]
        use stm32f4xx_hal as _;

        #[cfg(target_arch = "arm")]
        #[cortex_m_rt::entry]
        fn main() -> ! {
            cortex_m_semihosting::hprintln!(concat!($name, " is firmware for ", $target));
            cortex_m_semihosting::debug::exit(cortex_m_semihosting::debug::EXIT_FAILURE);
            loop {
                cortex_m::asm::wfi();
            }
        }

        #[cfg(target_arch = "riscv32")]
        #[riscv_rt::entry]
        fn main() -> ! {
            riscv_semihosting::hprintln!(concat!($name, " is firmware for ", $target));
            riscv_semihosting::debug::exit(riscv_semihosting::debug::EXIT_FAILURE);
            loop {
                riscv::asm::wfi();
            }
        }
    };
}
pub(crate) use firmware_for;
