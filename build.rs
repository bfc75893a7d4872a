//! Build glue: the `host_std` cfg (feature `std` on a target with an OS).
use std::env;

fn main() {
    println!("cargo::rustc-check-cfg=cfg(host_std)");
    let std = env::var_os("CARGO_FEATURE_STD").is_some();
    let bare_metal = env::var("CARGO_CFG_TARGET_OS")
        .map(|os| os == "none")
        .unwrap_or(false);
    if std && !bare_metal {
        println!("cargo::rustc-cfg=host_std");
    }
    println!("cargo::rerun-if-changed=build.rs");
}
