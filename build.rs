//! Build glue: the `host_std` cfg (feature `std` on a target with an OS), and for
//! bare-metal targets the firmware examples' memory map, written to `OUT_DIR` as
//! `memory.x` (the runtime's `link.x` includes it):
//!
//! | target | memory map | machine |
//! |---|---|---|
//! | hard-float ARM (`thumbv7em-none-eabihf`) | `memory-stm32f4.x` | STM32F405/407, QEMU `netduinoplus2` |
//! | other ARM (`thumbv6m-none-eabi`) | `memory-nrf51.x` | nRF51, QEMU `microbit` |
//! | RV32 (`riscv32imc-unknown-none-elf`) | `memory-rv32-virt.x` | QEMU `virt` |
//!
//! No file in the package root may be called `memory.x`: the linker runs there and
//! looks for an `INCLUDE`d script in its working directory before the search path, so
//! a root `memory.x` would be every target's map.
use std::env;
use std::path::PathBuf;

fn main() {
    println!("cargo::rustc-check-cfg=cfg(host_std)");
    let std = env::var_os("CARGO_FEATURE_STD").is_some();
    let target_os = env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let target_arch = env::var("CARGO_CFG_TARGET_ARCH").unwrap_or_default();
    let target_abi = env::var("CARGO_CFG_TARGET_ABI").unwrap_or_default();
    let bare_metal = target_os == "none";
    if std && !bare_metal {
        println!("cargo::rustc-cfg=host_std");
    }
    // The same split as the firmware dev-dependencies in Cargo.toml.
    let memory: Option<&[u8]> = match (bare_metal, target_arch.as_str(), target_abi.as_str()) {
        (true, "arm", "eabihf") => Some(include_bytes!("memory-stm32f4.x")),
        (true, "arm", _) => Some(include_bytes!("memory-nrf51.x")),
        (true, "riscv32", _) => Some(include_bytes!("memory-rv32-virt.x")),
        _ => None,
    };
    // On the linker search path, where `-Tlink.x` (.cargo/config.toml) finds it through
    // `INCLUDE memory.x`.
    if let Some(memory) = memory {
        let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
        std::fs::write(out.join("memory.x"), memory).expect("write memory.x to OUT_DIR");
        println!("cargo::rustc-link-search={}", out.display());
    }
    srgb_tables();
    for file in [
        "memory-stm32f4.x",
        "memory-nrf51.x",
        "memory-rv32-virt.x",
        "build.rs",
    ] {
        println!("cargo::rerun-if-changed={file}");
    }
}

/// The anti-aliasing's sRGB tables (IEC 61966-2-1), written to `OUT_DIR/srgb_tables.rs`
/// for `src/sampling.rs`: 8-bit level to linear light (`round(65535·L)`), and the 255
/// linear thresholds between neighbouring levels (`round(16·65535·L((k + ½)/255))`),
/// where the encoded value is exactly `k + ½` (rounding to nearest once).
fn srgb_tables() {
    fn linear(c: f64) -> f64 {
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    }
    let decode: Vec<String> = (0..256)
        .map(|k| format!("{}", (linear(f64::from(k) / 255.0) * 65535.0).round() as u32))
        .collect();
    let thresholds: Vec<u32> = (0..255)
        .map(|k| (linear((f64::from(k) + 0.5) / 255.0) * 16.0 * 65535.0).round() as u32)
        .collect();
    // Where the search for a linear value x starts: the number of thresholds below
    // x's bucket, buckets of 2⁸ below 2¹⁶ (where the levels are densest) and of 2¹⁰
    // above.
    let below = |v: u32| thresholds.iter().filter(|&&t| t < v).count().to_string();
    let low: Vec<String> = (0..256u32).map(|b| below(b << 8)).collect();
    let high: Vec<String> = (0..1024u32).map(|b| below(b << 10)).collect();
    let list = |v: &[u32]| v.iter().map(u32::to_string).collect::<Vec<_>>().join(", ");
    let text = format!(
        "/// 8-bit sRGB level to linear light, `round(65535·L)`.\n\
         pub(crate) const SRGB_TO_LINEAR: [u16; 256] = [{}];\n\
         /// Linear light (×16·65535) where the sRGB encoding is `k + ½` levels.\n\
         pub(crate) const LINEAR_THRESHOLDS: [u32; 255] = [{}];\n\
         /// The thresholds below `b·2⁸`, for `b·2⁸ < 2¹⁶`.\n\
         pub(crate) const LEVELS_BELOW_LOW: [u8; 256] = [{}];\n\
         /// The thresholds below `b·2¹⁰`, for `b·2¹⁰ < 2²⁰`.\n\
         pub(crate) const LEVELS_BELOW_HIGH: [u8; 1024] = [{}];\n",
        decode.join(", "),
        list(&thresholds),
        low.join(", "),
        high.join(", ")
    );
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    std::fs::write(out.join("srgb_tables.rs"), text).expect("write srgb_tables.rs to OUT_DIR");
}
