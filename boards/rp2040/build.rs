//! Link setup for the RP2040 firmware:
//!
//! - this board's `memory.x` (with the RP2040's BOOT2 section) on the linker search path
//!   for cortex-m-rt's `link.x`. The linker also finds it in the package directory, its
//!   working directory, which it searches first. Both matter: the kernel's own build
//!   script puts the nRF51 map of the QEMU Cortex-M0 examples on the search path of
//!   every thumbv6m build, and that one must not be used here;
//! - `-Tlink.x`, unless the rustflags already have it: cargo merges this package's
//!   `.cargo/config.toml` with the repository root's, whose thumbv6m rustflags pass it
//!   for the QEMU examples, and a second copy of the script fails the link (every
//!   memory region defined twice);
//! - `--nmagic`: no page alignment of the sections, which would pad the flash image.
use std::env;
use std::path::PathBuf;

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    std::fs::write(out.join("memory.x"), include_bytes!("memory.x")).expect("write memory.x to OUT_DIR");
    println!("cargo::rustc-link-search={}", out.display());

    let rustflags = env::var("CARGO_ENCODED_RUSTFLAGS").unwrap_or_default();
    if !rustflags.split('\x1f').any(|flag| flag.ends_with("-Tlink.x")) {
        println!("cargo::rustc-link-arg-bins=-Tlink.x");
    }
    println!("cargo::rustc-link-arg-bins=--nmagic");

    println!("cargo::rerun-if-changed=memory.x");
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-env-changed=CARGO_ENCODED_RUSTFLAGS");
}
