//! Proof at link time that the render path cannot panic.
//!
//! ```sh
//! cargo build --release --example no_panic --target thumbv7em-none-eabihf
//! cargo build --release --example no_panic --target thumbv6m-none-eabi          # Cortex-M0
//! cargo build --release --example no_panic --target riscv32imc-unknown-none-elf  # RV32
//! ```
//!
//! The panic handler is `panic-never`'s, which references an undefined symbol: the
//! firmware only links if the optimiser removed every panicking branch from what it
//! runs — building a camera from run-time values (`read_volatile`, so nothing is
//! constant-folded), rendering the lab scene with the default method into a
//! `PixelHash`, and storing the hash (`write_volatile`). A reachable panic fails the
//! build with `error(panic-never): your program contains at least one panicking branch`.
//! Needs optimisation (`--release`; opt-level 0 and 1 keep dead panic branches).
//!
//! It is also the kernel's flash footprint for one method: its sections minus
//! `empty_firmware`'s (`.ci/firmware` and `.ci/firmware-nofpu` print both). Run in QEMU
//! it prints the hash (`cargo run --release --example no_panic --target …`), through the
//! raw semihosting `SYS_WRITE0` call — `hprintln!` has a panic path of its own.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
#[path = "../../src/scenes.rs"]
mod scenes;

#[cfg(target_os = "none")]
mod fw {
    use core::ptr::{addr_of, addr_of_mut, read_volatile, write_volatile};

    #[cfg(target_arch = "arm")]
    use cortex_m::asm::wfi;
    #[cfg(target_arch = "arm")]
    use cortex_m_rt::entry;
    #[cfg(target_arch = "arm")]
    use cortex_m_semihosting::{debug, nr, syscall1};
    use embedded_graphics::prelude::*;
    use embedded_raytracer::{CameraParams, Render, Vec3};
    use embedded_raytracer_lab::hash::PixelHash;
    use panic_never as _;
    #[cfg(target_arch = "riscv32")]
    use riscv::asm::wfi;
    #[cfg(target_arch = "riscv32")]
    use riscv_rt::entry;
    #[cfg(target_arch = "riscv32")]
    use riscv_semihosting::{debug, nr, syscall1};
    // The PAC's vector table: cortex-m-rt's `device` feature (turned on by the stm32f4
    // dependency of thumbv7em-none-eabihf) requires it.
    #[cfg(all(target_arch = "arm", target_abi = "eabihf", not(armv8m_main)))]
    use stm32f4xx_hal as _;

    use crate::scenes;

    /// The camera's inputs, read at run time: eye, look-at, up (x, y, z each), vertical
    /// field of view in radians — `scenes/lab.toml`'s camera, so the hash equals the
    /// lab line of `qemu_cortex_m4` for the default method (`.ci/firmware` checks).
    static INPUTS: [f32; 10] = [
        0.0,
        0.0,
        5.0,
        0.0,
        0.0,
        0.0,
        0.0,
        1.0,
        0.0,
        60.0 * (core::f32::consts::PI / 180.0),
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
        // SAFETY: reads of an immutable static.
        let size = unsafe { Size::new(read_volatile(&SIZE[0]), read_volatile(&SIZE[1])) };
        let params = CameraParams::new(v(0), v(3), v(6), input(9), size);
        let hash = match params.build() {
            Ok(camera) => {
                let mut target = PixelHash::new(size);
                let Ok(()) = Render::new(&scenes::LAB, &camera).draw(&mut target);
                target.hash()
            }
            Err(_) => 0,
        };
        // SAFETY: single-threaded, no interrupt touches RESULT.
        unsafe { write_volatile(addr_of_mut!(RESULT), hash) };

        // Print it: "no_panic hash 0x................\n".
        // SAFETY: as above.
        let stored = unsafe { read_volatile(addr_of!(RESULT)) };
        let mut line = *b"no_panic hash 0x................\n\0";
        for (k, digit) in line.iter_mut().skip(16).take(16).enumerate() {
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

#[cfg(not(target_os = "none"))]
fn main() {
    println!(
        "no_panic is firmware: cargo build --release --example no_panic --target thumbv7em-none-eabihf (or thumbv6m-none-eabi, riscv32imc-unknown-none-elf)"
    );
}
