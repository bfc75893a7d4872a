//! The measurement firmware's memory map, written to `OUT_DIR` as `memory.x` and put on
//! the linker search path, where the runtime's `link.x` includes it:
//!
//! | target | memory map | machine |
//! |---|---|---|
//! | ARMv8-M mainline (`thumbv8m.main-none-eabihf`) | `memory-mps2-an505.x` | Cortex-M33, QEMU `mps2-an505` |
//! | other hard-float ARM (`thumbv7em-none-eabihf`) | `memory-stm32f4.x` | STM32F405/407, QEMU `netduinoplus2` |
//! | other ARM (`thumbv6m-none-eabi`) | `memory-nrf51.x` | nRF51, QEMU `microbit` |
//! | RV32 (`riscv32imc-unknown-none-elf`) | `memory-rv32-virt.x` | QEMU `virt` |
//!
//! No file in this folder may be called `memory.x`: the linker runs here and looks for an
//! `INCLUDE`d script in its working directory before the search path, so one would be
//! every target's map.
//!
//! It also sets the cfg `armv8m_main` on `thumbv8m.main` targets: there the examples leave
//! out the STM32F4 HAL (a dependency of `thumbv7em-none-eabihf` only, `Cargo.toml`), and
//! `qemu_cortex_m4` measures the Cortex-M33 of `mps2-an505` instead of the Cortex-M4F.
//! Cargo's `cfg(…)` cannot tell the two hard-float targets apart (stable rustc sets the
//! same `target_*` values for both), so the target's name decides.
use std::env;
use std::path::PathBuf;

fn main() {
    let target_arch = env::var("CARGO_CFG_TARGET_ARCH").unwrap_or_default();
    let target_abi = env::var("CARGO_CFG_TARGET_ABI").unwrap_or_default();
    let armv8m_main = env::var("TARGET")
        .unwrap_or_default()
        .starts_with("thumbv8m.main");
    println!("cargo::rustc-check-cfg=cfg(armv8m_main)");
    if armv8m_main {
        println!("cargo::rustc-cfg=armv8m_main");
    }
    let memory: Option<&[u8]> = match (target_arch.as_str(), target_abi.as_str()) {
        ("arm", _) if armv8m_main => Some(include_bytes!("memory-mps2-an505.x")),
        ("arm", "eabihf") => Some(include_bytes!("memory-stm32f4.x")),
        ("arm", _) => Some(include_bytes!("memory-nrf51.x")),
        ("riscv32", _) => Some(include_bytes!("memory-rv32-virt.x")),
        _ => None,
    };
    if let Some(memory) = memory {
        let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
        std::fs::write(out.join("memory.x"), memory).expect("write memory.x to OUT_DIR");
        println!("cargo::rustc-link-search={}", out.display());
    }
    for file in [
        "memory-stm32f4.x",
        "memory-mps2-an505.x",
        "memory-nrf51.x",
        "memory-rv32-virt.x",
        "build.rs",
    ] {
        println!("cargo::rerun-if-changed={file}");
    }
}
