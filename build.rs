//! Build glue: the `host_std` cfg (feature `std` on a target with an OS), and for
//! bare-metal ARM the firmware examples' memory map (`memory.x`, read by
//! cortex-m-rt's `link.x`).
use std::env;
use std::path::PathBuf;

fn main() {
    println!("cargo::rustc-check-cfg=cfg(host_std)");
    let std = env::var_os("CARGO_FEATURE_STD").is_some();
    let target_os = env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let target_arch = env::var("CARGO_CFG_TARGET_ARCH").unwrap_or_default();
    let bare_metal = target_os == "none";
    if std && !bare_metal {
        println!("cargo::rustc-cfg=host_std");
    }
    // Firmware examples (thumbv7em-none-eabihf): put memory.x on the linker search
    // path, where `-Tlink.x` (.cargo/config.toml) finds it through `INCLUDE memory.x`.
    if bare_metal && target_arch == "arm" {
        let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
        std::fs::write(out.join("memory.x"), include_bytes!("memory.x")).expect("write memory.x to OUT_DIR");
        println!("cargo::rustc-link-search={}", out.display());
    }
    println!("cargo::rerun-if-changed=memory.x");
    println!("cargo::rerun-if-changed=build.rs");
}
