//! `-Tlink.x` for the binary: cortex-m-rt's script, which includes `memory.x`.
fn main() {
    println!("cargo::rustc-link-arg-bins=-Tlink.x");
}
