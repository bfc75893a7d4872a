//! Proof at link time that the render path of a scene with every feature — lights
//! (directional and point), shadows, a checkered plane, mirrors — cannot panic, and
//! that path's flash footprint.
//!
//! ```sh
//! cargo build --release --example no_panic_features --target thumbv7em-none-eabihf
//! ```
//!
//! As `no_panic` (whose notes apply: `panic-never`'s handler references an undefined
//! symbol, so the firmware links only if the optimiser removed every panicking branch;
//! `--release` is needed), for the scene type of `scenes/mirrors.toml`,
//! `Scene<5, 1, 1, 3>`: the camera is built from run-time values, and the scene is
//! reached through a pointer read with `read_volatile`, so the optimiser cannot see
//! which scene it draws — the light may be either kind, shadows on or off, any
//! material — and links the whole scene-features path of that type. It draws the
//! `mirrors` scene with the default method into a `PixelHash` and prints the hash
//! (`cargo run --release --example no_panic_features --target thumbv7em-none-eabihf`),
//! which `.ci/firmware` compares with `qemu_cortex_m4`'s `mirrors` line of the default
//! method; its sections minus `empty_firmware`'s are the flash of a firmware using
//! every feature.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(all(target_os = "none", target_abi = "eabihf"))]
#[path = "../../src/scenes.rs"]
mod scenes;

#[cfg(all(target_os = "none", target_abi = "eabihf"))]
mod fw {
    use core::ptr::{addr_of, addr_of_mut, read_volatile, write_volatile};

    use cortex_m::asm::wfi;
    use cortex_m_rt::entry;
    use cortex_m_semihosting::{debug, nr, syscall1};
    use embedded_graphics::prelude::*;
    use embedded_raytracer::{CameraParams, Render, Scene, Vec3};
    use embedded_raytracer_lab::hash::PixelHash;
    use panic_never as _;
    // The PAC's vector table: cortex-m-rt's `device` feature (turned on by the stm32f4
    // dependency of thumbv7em-none-eabihf) requires it.
    #[cfg(not(armv8m_main))]
    use stm32f4xx_hal as _;

    use crate::scenes;

    /// The scene type of every feature: `scenes/mirrors.toml`'s capacities.
    type FullScene = Scene<5, 1, 1, 3>;

    /// The scene drawn, behind a pointer the optimiser cannot follow (read volatile).
    static SCENE: &FullScene = &scenes::MIRRORS;

    /// The camera's inputs, read at run time: eye, look-at, up (x, y, z each), vertical
    /// field of view in radians — `scenes/mirrors.toml`'s camera, so the hash equals the
    /// mirrors line of `qemu_cortex_m4` for the default method (`.ci/firmware` checks).
    static INPUTS: [f32; 10] = [
        0.0,
        3.2,
        6.5,
        0.0,
        0.7,
        0.2,
        0.0,
        1.0,
        0.0,
        45.0 * (core::f32::consts::PI / 180.0),
    ];
    static SIZE: [u32; 2] = [240, 240];
    /// Where the result goes: the hash, or 0 if the camera was rejected.
    static mut RESULT: u64 = 0;

    fn input(i: usize) -> f32 {
        // SAFETY: a read of an immutable static; volatile so the value is unknown to
        // the optimiser. `get` keeps the index check out of the proof.
        INPUTS.get(i).map_or(f32::NAN, |x| unsafe { read_volatile(x) })
    }

    fn write0(s: &[u8]) {
        // SAFETY: SYS_WRITE0 reads a NUL-terminated string; every caller passes one.
        unsafe { syscall1(nr::WRITE0, s.as_ptr() as usize) };
    }

    #[entry]
    fn main() -> ! {
        let v = |i: usize| Vec3::new(input(i), input(i + 1), input(i + 2));
        // SAFETY: reads of immutable statics.
        let size = unsafe { Size::new(read_volatile(&SIZE[0]), read_volatile(&SIZE[1])) };
        // SAFETY: as above; the pointer read is a valid `&'static FullScene`.
        let scene: &FullScene = unsafe { read_volatile(addr_of!(SCENE)) };
        let params = CameraParams::new(v(0), v(3), v(6), input(9), size);
        let hash = match params.build() {
            Ok(camera) => {
                let mut target = PixelHash::new(size);
                let Ok(()) = Render::new(scene, &camera).draw(&mut target);
                target.hash()
            }
            Err(_) => 0,
        };
        // SAFETY: single-threaded, no interrupt touches RESULT.
        unsafe { write_volatile(addr_of_mut!(RESULT), hash) };

        // Print it: "no_panic_features hash 0x................\n".
        // SAFETY: as above.
        let stored = unsafe { read_volatile(addr_of!(RESULT)) };
        let mut line = *b"no_panic_features hash 0x................\n\0";
        for (k, digit) in line.iter_mut().skip(25).take(16).enumerate() {
            let nibble = (stored >> (60 - 4 * k)) & 0xf;
            *digit = b"0123456789abcdef".get(nibble as usize).copied().unwrap_or(b'?');
        }
        write0(&line);
        debug::exit(if stored != 0 {
            debug::EXIT_SUCCESS
        } else {
            debug::EXIT_FAILURE
        });
        loop {
            wfi();
        }
    }
}

#[cfg(all(target_os = "none", not(target_abi = "eabihf")))]
#[path = "common/wrong_target.rs"]
mod wrong_target;
#[cfg(all(target_os = "none", not(target_abi = "eabihf")))]
wrong_target::firmware_for!("no_panic_features", "thumbv7em-none-eabihf");

#[cfg(not(target_os = "none"))]
fn main() {
    println!(
        "no_panic_features is firmware: cargo build --release --example no_panic_features --target thumbv7em-none-eabihf"
    );
}
