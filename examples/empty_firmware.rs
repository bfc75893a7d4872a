//! The smallest firmware of this crate's build: cortex-m-rt's reset handler, the
//! STM32F407 vector table and an idle loop — no kernel. Its section sizes are the
//! baseline subtracted from `no_panic`'s to get the kernel's flash footprint
//! (`.ci/firmware` prints both).
//!
//! `cargo build --release --example empty_firmware --target thumbv7em-none-eabihf`
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
mod fw {
    use cortex_m_rt::entry;
    use panic_halt as _;
    // The PAC's vector table: cortex-m-rt's `device` feature (turned on by the
    // stm32f4 dev-dependency) requires it in every firmware example.
    use stm32f4xx_hal as _;

    #[entry]
    fn main() -> ! {
        loop {
            cortex_m::asm::wfi();
        }
    }
}

#[cfg(not(target_os = "none"))]
fn main() {
    println!("empty_firmware is firmware: build it with --target thumbv7em-none-eabihf");
}
