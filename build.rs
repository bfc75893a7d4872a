//! Build glue: the `host_std` cfg (feature `std` on a target with an OS), the
//! anti-aliasing's sRGB tables, and `-Tlink.x` for the root firmware example.
//!
//! Nothing here reaches a crate that depends on this library: no linker search path and
//! no library-wide link argument. `-Tlink.x` (cortex-m-rt's script, which includes the
//! root `memory.x`) is passed to this package's own examples only, and only on
//! bare-metal ARM.
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
    if bare_metal && target_arch == "arm" {
        println!("cargo::rustc-link-arg-examples=-Tlink.x");
    }
    srgb_tables();
    println!("cargo::rerun-if-changed=build.rs");
}

/// The anti-aliasing's sRGB tables (IEC 61966-2-1), written to `OUT_DIR/srgb_tables.rs`
/// for `src/sampling/average.rs`: 8-bit level to linear light (`round(65535·L)`), and the 255
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
