//! Link setup for the ESP32-C3: esp-hal's own linker scripts (`linkall.x`, which
//! includes the chip's memory map: no `memory.x` here).
fn main() {
    println!("cargo::rustc-link-arg-bins=-Tlinkall.x");
    println!("cargo::rerun-if-changed=build.rs");
}
