//! Link setup for the RP2350 firmware: this board's `memory.x` (with the RP2350's boot
//! block sections) on the linker search path for cortex-m-rt's `link.x`, `-Tlink.x` for
//! the binary, and `--nmagic`: no page alignment of the sections, which would pad the
//! flash image.
use std::env;
use std::path::PathBuf;

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    std::fs::write(out.join("memory.x"), include_bytes!("memory.x")).expect("write memory.x to OUT_DIR");
    println!("cargo::rustc-link-search={}", out.display());
    println!("cargo::rustc-link-arg-bins=-Tlink.x");
    println!("cargo::rustc-link-arg-bins=--nmagic");
    println!("cargo::rerun-if-changed=memory.x");
    println!("cargo::rerun-if-changed=build.rs");
}
