//! The integer kernel alone on a chip without an FPU: `no_panic` through
//! [`Render::draw_integer`](embedded_raytracer::Render::draw_integer), which links no
//! `f32` render (same camera from run-time values, lab scene, `PixelHash`,
//! `panic-never`: links only without a reachable panic).
//!
//! ```sh
//! cargo build --release --example no_panic_integer --target thumbv6m-none-eabi
//! bash .ci/integer-loop   # no soft-float call reachable from its pixel loop; its flash
//! ```
//!
//! `.ci/integer-loop` disassembles it: no soft-float routine may be reachable from the
//! integer row loop (what `fixed::draw_rows` calls besides the per-row `activate`), and
//! it prints the flash of the integer kernel's own functions. Run in QEMU it prints
//! `no_panic_integer hash 0x…`, the `lab integer/direct/auto/exact` line of
//! `lab/data/qemu_cortex_m0.txt`.
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
    /// lab line of the measurement runs for `integer/direct/auto/exact`.
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
    /// Where the result goes: the hash, or 0 if the camera or the frame was refused.
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
                // The integer kernel alone: no f32 render linked, 0 where the rule
                // refuses the frame.
                match Render::new(&scenes::LAB, &camera).draw_integer(&mut target) {
                    Ok(()) => target.hash(),
                    Err(_) => 0,
                }
            }
            Err(_) => 0,
        };
        // SAFETY: single-threaded, no interrupt touches RESULT.
        unsafe { write_volatile(addr_of_mut!(RESULT), hash) };

        // Print it: "no_panic_integer hash 0x................\n".
        // SAFETY: as above.
        let stored = unsafe { read_volatile(addr_of!(RESULT)) };
        let mut line = *b"no_panic_integer hash 0x................\n\0";
        for (k, digit) in line.iter_mut().skip(24).take(16).enumerate() {
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
        "no_panic_integer is firmware: cargo build --release --example no_panic_integer --target thumbv6m-none-eabi (or riscv32imc-unknown-none-elf)"
    );
}
