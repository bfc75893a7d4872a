//! The chip's memory map, chosen by target, written to `OUT_DIR/memory.x`. The sizes are
//! deliberately unlike any map of the embedded-raytracer repository (STM32F4: 1 MiB /
//! 128 KiB, nRF51: 256 KiB / 16 KiB, RP2040: 2 MiB / 256 KiB), so a wrong map shows.
use std::env;
use std::path::PathBuf;

fn main() {
    let abi = env::var("CARGO_CFG_TARGET_ABI").unwrap_or_default();
    let map = if abi == "eabihf" {
        // An STM32F4 with 64 KiB of RAM (e.g. STM32F401xB/C): stack top 0x2001_0000.
        "MEMORY\n{\n  FLASH : ORIGIN = 0x08000000, LENGTH = 256K\n  RAM : ORIGIN = 0x20000000, LENGTH = 64K\n}\n"
    } else {
        // A Cortex-M0 with 24 KiB of RAM and flash at 0x0001_0000: stack top 0x2000_6000.
        "MEMORY\n{\n  FLASH : ORIGIN = 0x00010000, LENGTH = 192K\n  RAM : ORIGIN = 0x20000000, LENGTH = 24K\n}\n"
    };
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    std::fs::write(out.join("memory.x"), map).expect("write memory.x");
    println!("cargo::rustc-link-search={}", out.display());
    println!("cargo::rerun-if-changed=build.rs");
}
