//! The kernel on a Cortex-M4F, measured in QEMU (`netduinoplus2`, an STM32F405):
//!
//! ```sh
//! cargo run --release --example qemu_cortex_m4 --target thumbv7em-none-eabihf
//! ```
//!
//! Renders every standard scene (`examples/common/scenes.rs`, the numbers of
//! `scenes/*.toml`) with every method in `Method::ALL` into a [`PixelHash`] — the board
//! has 128 KiB of RAM and no framebuffer — **at 240×240**: each scene's own camera
//! (eye, look-at, up, vertical field of view) with its size replaced by 240×240, so the
//! horizontal field of view follows from the square aspect. Prints, one line per scene
//! and method, in a format `tests/firmware_hashes.rs` parses:
//!
//! ```text
//! hash lab incremental/robust/exact 0x0123456789abcdef pixels 57600 instr 3456789 ipp 60.0 stack 312
//! ```
//!
//! - `instr`: instructions executed by the render. Under QEMU's `-icount shift=0` one
//!   instruction advances virtual time by 1 ns and SysTick counts the 168 MHz core
//!   clock, so instructions = ticks × 1e9 / 168e6 (SysTick's 24-bit wrap is counted by
//!   its exception). The conversion is checked first against `subs`/`bne` loops of known
//!   length (`calibration` lines). Emulation figures: QEMU executes every instruction in
//!   one "cycle"; a real M4 has wait states, multi-cycle loads, divides and square roots.
//! - `stack`: bytes of stack below the caller's stack pointer that the render touched
//!   (the stack is painted before and scanned after), measured in a second, untimed
//!   render with the SysTick interrupt off so no exception frame lands on the stack.
//!
//! Also checks `math::sqrt_exact` (`VSQRT.F32`) bit for bit against `libm::sqrtf`
//! over every 4099th `f32` bit pattern. Exits through semihosting with status 1 on any
//! failure (a wrong pixel count, a calibration off by more than its tolerance, a square
//! root mismatch, an unbuildable camera, differing hashes between the two passes).
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
#[path = "common/scenes.rs"]
mod scenes;

#[cfg(target_os = "none")]
mod fw {
    use core::arch::asm;
    use core::sync::atomic::{AtomicU32, Ordering};

    use cortex_m::peripheral::{syst::SystClkSource, SYST};
    use cortex_m_rt::{entry, exception};
    use cortex_m_semihosting::{debug, hprintln};
    use embedded_graphics::pixelcolor::Rgb888;
    use embedded_graphics::prelude::*;
    use embedded_graphics::primitives::Rectangle;
    use embedded_raytracer::{hash::PixelHash, math, Camera, CameraParams, Method, Render, Scene};
    use panic_semihosting as _;
    // The PAC's vector table: cortex-m-rt's `device` feature (turned on by the stm32f4
    // dev-dependency) requires it in every firmware example.
    use stm32f4xx_hal as _;

    use crate::scenes;

    /// netduinoplus2's core clock (QEMU's STM32F405 model runs SYSCLK at 168 MHz).
    const F_CLK_HZ: u64 = 168_000_000;
    /// Every scene is rendered at this size (its own camera otherwise).
    const SIZE: Size = Size::new(240, 240);
    /// Stack paint pattern.
    const PAINT: u32 = 0xDEAD_BEEF;

    static WRAPS: AtomicU32 = AtomicU32::new(0);

    /// SysTick reload: counts SysTick's 24-bit wraps so `ticks` is 64-bit.
    #[exception]
    fn SysTick() {
        WRAPS.fetch_add(1, Ordering::Relaxed);
    }

    /// Core-clock ticks since SysTick started: wraps × 2²⁴ + (0xFF_FFFF − current).
    /// Reads the wrap count on both sides of the counter and retries if a wrap
    /// happened in between.
    #[inline(always)]
    fn ticks() -> u64 {
        loop {
            let w1 = WRAPS.load(Ordering::SeqCst);
            let current = SYST::get_current();
            let w2 = WRAPS.load(Ordering::SeqCst);
            if w1 == w2 {
                return u64::from(w1) * (1 << 24) + u64::from(0xFF_FFFF - current);
            }
        }
    }

    /// Ticks of the 168 MHz clock to instructions under `-icount shift=0` (1 ns each),
    /// rounded to nearest.
    fn instructions(ticks: u64) -> u64 {
        (ticks * 1_000_000_000 + F_CLK_HZ / 2) / F_CLK_HZ
    }

    /// Exactly `2n` instructions (`subs` + `bne` per iteration), `n ≥ 1`.
    #[inline(always)]
    fn spin(n: u32) {
        // SAFETY: register-only loop; touches no memory and not the stack.
        unsafe { asm!("2:", "subs {0}, #1", "bne 2b", inout(reg) n => _, options(nomem, nostack)) };
    }

    extern "C" {
        // cortex-m-rt's link.x: the lowest address the stack may reach (end of
        // .bss/.uninit) and the initial stack pointer (top of RAM).
        static mut _stack_end: u32;
        static mut _stack_start: u32;
    }

    #[inline(always)]
    fn sp() -> usize {
        let sp: usize;
        // SAFETY: reads the stack pointer only.
        unsafe { asm!("mov {}, sp", out(reg) sp, options(nomem, nostack, preserves_flags)) };
        sp
    }

    /// Paints every word in `[_stack_end, SP)` with `PAINT`, in assembly so that it
    /// writes nothing at or above the stack pointer and needs no stack itself.
    #[inline(always)]
    fn paint_stack() {
        let bottom = core::ptr::addr_of_mut!(_stack_end) as usize;
        // SAFETY: the words below SP down to `_stack_end` are unused stack.
        unsafe {
            asm!(
                "mov {top}, sp",
                "2:",
                "cmp {p}, {top}",
                "bhs 3f",
                "str {pat}, [{p}], #4",
                "b 2b",
                "3:",
                p = inout(reg) bottom => _,
                top = out(reg) _,
                pat = in(reg) PAINT,
                options(nostack),
            );
        }
    }

    /// Bytes of stack ever touched, counted down from the initial stack pointer: the
    /// first word above `_stack_end` that no longer holds the paint.
    fn stack_touched() -> usize {
        let bottom = core::ptr::addr_of_mut!(_stack_end) as usize;
        let top = core::ptr::addr_of_mut!(_stack_start) as usize;
        let mut p = bottom;
        // SAFETY: reads words of the stack region, all below the initial SP.
        while p < top && unsafe { core::ptr::read_volatile(p as *const u32) } == PAINT {
            p += 4;
        }
        top - p
    }

    /// The render under test, never inlined so that its whole frame lies below the
    /// measuring function's stack pointer.
    #[inline(never)]
    fn render<const N: usize>(scene: &Scene<N>, camera: &Camera, method: Method, target: &mut PixelHash) {
        let Ok(()) = Render::new(scene, camera).with_method(method).draw(target);
    }

    /// The sink alone, for scale: the same `PixelHash` fed 240 rows of 240 pixels
    /// through `fill_contiguous`, one call per row as a render makes them, with colours
    /// that cost one add each. A render's instructions minus these are the kernel's.
    #[inline(never)]
    fn sink_only(target: &mut PixelHash) {
        for y in 0..SIZE.height {
            let row = Rectangle::new(Point::new(0, y as i32), Size::new(SIZE.width, 1));
            let colors = (0..SIZE.width).map(|x| Rgb888::new(x as u8, y as u8, (x ^ y) as u8));
            let Ok(()) = target.fill_contiguous(&row, colors);
        }
    }

    /// Instructions executed by `f` (minus the measurement's own `overhead` ticks).
    #[inline(never)]
    fn timed(overhead: u64, f: impl FnOnce()) -> u64 {
        let t0 = ticks();
        f();
        let t1 = ticks();
        instructions((t1 - t0).saturating_sub(overhead))
    }

    /// Peak stack bytes `f` uses below this function's stack pointer.
    #[inline(never)]
    fn stack_of(f: impl FnOnce()) -> usize {
        let base = core::ptr::addr_of_mut!(_stack_start) as usize - sp();
        paint_stack();
        f();
        stack_touched().saturating_sub(base)
    }

    struct Run {
        syst: SYST,
        /// Ticks of an empty `timed` measurement.
        overhead: u64,
        failures: u32,
    }

    impl scenes::EachScene for Run {
        fn scene<const N: usize>(
            &mut self,
            name: &'static str,
            scene: &'static Scene<N>,
            camera: CameraParams,
        ) {
            self.measure_scene(name, scene, camera);
        }
    }

    impl Run {
        fn fail(&mut self, what: &str) {
            hprintln!("FAIL {}", what);
            self.failures += 1;
        }

        /// Checks the tick-to-instruction conversion on a loop of `2n` instructions:
        /// within 0.001 % + 20 instructions (one tick is 5.95 instructions; each
        /// SysTick wrap costs its exception, ~12).
        fn calibrate(&mut self, n: u32) {
            // SAFETY: a plain read, to keep the loop count opaque to the optimiser.
            let n = unsafe { core::ptr::read_volatile(&n) };
            let expected = 2 * u64::from(n);
            let measured = timed(self.overhead, || spin(n));
            let tolerance = expected / 100_000 + 20;
            let ok = measured.abs_diff(expected) <= tolerance;
            hprintln!(
                "calibration expected {} measured {} tolerance {} {}",
                expected,
                measured,
                tolerance,
                if ok { "ok" } else { "FAILED" }
            );
            if !ok {
                self.fail("calibration");
            }
        }

        /// `VSQRT.F32` against libm's `sqrtf`, bit for bit (any NaN equals any NaN).
        fn check_sqrt(&mut self) {
            let mut inputs = 0u32;
            let mut mismatches = 0u32;
            let mut check = |x: f32| {
                let (hw, sw) = (math::sqrt_exact(x), libm::sqrtf(x));
                if hw.to_bits() != sw.to_bits() && !(hw.is_nan() && sw.is_nan()) {
                    if mismatches < 5 {
                        hprintln!(
                            "sqrt mismatch {:#010x}: vsqrt {:#010x} libm {:#010x}",
                            x.to_bits(),
                            hw.to_bits(),
                            sw.to_bits()
                        );
                    }
                    mismatches += 1;
                }
                inputs += 1;
            };
            for x in [
                0.0,
                -0.0,
                1.0,
                2.0,
                4.0,
                f32::MIN_POSITIVE,
                f32::MAX,
                f32::INFINITY,
                f32::NAN,
                -1.0,
            ] {
                check(x);
            }
            let mut bits = 0u32;
            while let Some(next) = bits.checked_add(4099) {
                check(f32::from_bits(bits));
                bits = next;
            }
            hprintln!("sqrt inputs {} mismatches {}", inputs, mismatches);
            if mismatches != 0 {
                self.fail("sqrt");
            }
        }

        /// What the `PixelHash` sink alone costs per pixel.
        fn sink(&mut self) {
            let mut hash = PixelHash::new(SIZE);
            let instr = timed(self.overhead, || sink_only(&mut hash));
            let pixels = hash.pixels();
            let ipp10 = (instr * 10 + pixels / 2) / pixels.max(1);
            hprintln!(
                "sink pixelhash pixels {} instr {} ipp {}.{}",
                pixels,
                instr,
                ipp10 / 10,
                ipp10 % 10
            );
        }

        /// Every method on one scene at 240×240: hash, pixels, instructions, stack.
        fn measure_scene<const N: usize>(&mut self, name: &str, scene: &Scene<N>, params: CameraParams) {
            let camera = match (CameraParams { size: SIZE, ..params }).build() {
                Ok(camera) => camera,
                Err(e) => {
                    hprintln!("camera {}: {:?}", name, e);
                    return self.fail("camera");
                }
            };
            let expected_pixels = u64::from(SIZE.width) * u64::from(SIZE.height);
            for method in Method::ALL {
                // Timed pass (SysTick exception on, counting wraps).
                let mut hash = PixelHash::new(SIZE);
                let instr = timed(self.overhead, || render(scene, &camera, method, &mut hash));
                // Stack pass: the SysTick exception off (it would push its frame onto the
                // render's stack), the counter keeps running.
                self.syst.disable_interrupt();
                let mut again = PixelHash::new(SIZE);
                let stack = stack_of(|| render(scene, &camera, method, &mut again));
                // Wraps during the stack pass go uncounted: harmless, only differences
                // of `ticks` within one timed pass are used.
                self.syst.enable_interrupt();
                let pixels = hash.pixels();
                let ipp10 = (instr * 10 + pixels / 2) / pixels.max(1);
                hprintln!(
                    "hash {} {} {:#018x} pixels {} instr {} ipp {}.{} stack {}",
                    name,
                    method,
                    hash.hash(),
                    pixels,
                    instr,
                    ipp10 / 10,
                    ipp10 % 10,
                    stack
                );
                if pixels != expected_pixels {
                    self.fail("pixel count");
                }
                if again != hash {
                    self.fail("the two passes differ");
                }
            }
        }
    }

    #[entry]
    fn main() -> ! {
        let Some(mut cp) = cortex_m::Peripherals::take() else {
            debug::exit(debug::EXIT_FAILURE);
            loop {
                cortex_m::asm::wfi();
            }
        };
        cp.SYST.set_clock_source(SystClkSource::Core);
        cp.SYST.set_reload(0xFF_FFFF);
        cp.SYST.clear_current();
        cp.SYST.enable_interrupt();
        cp.SYST.enable_counter();
        // After clear_current() the counter reads 0 until its first reload.
        while SYST::get_current() == 0 {}

        let overhead = {
            let t0 = ticks();
            let t1 = ticks();
            t1 - t0
        };
        let mut run = Run {
            syst: cp.SYST,
            overhead,
            failures: 0,
        };
        hprintln!(
            "qemu_cortex_m4: every standard scene at {}x{} (its own camera, size replaced), every method",
            SIZE.width,
            SIZE.height
        );
        hprintln!(
            "clock {} Hz instructions = ticks * 1e9 / {} overhead_ticks {}",
            F_CLK_HZ,
            F_CLK_HZ,
            overhead
        );
        // The default method's name, so tools can pick its lines (e.g. no_panic's hash).
        hprintln!("default {}", embedded_raytracer::Method::DEFAULT);
        run.calibrate(1_000_000); // 2 M instructions: no SysTick wrap
        run.calibrate(100_000_000); // 200 M instructions: 2 wraps
        run.check_sqrt();
        run.sink();
        scenes::for_each(&mut run);
        if run.failures == 0 {
            hprintln!("result ok");
            debug::exit(debug::EXIT_SUCCESS);
        } else {
            hprintln!("result FAILED {}", run.failures);
            debug::exit(debug::EXIT_FAILURE);
        }
        // Not reached: QEMU exits on the semihosting call.
        loop {
            cortex_m::asm::wfi();
        }
    }
}

#[cfg(not(target_os = "none"))]
fn main() {
    println!(
        "qemu_cortex_m4 is firmware: cargo run --release --example qemu_cortex_m4 --target thumbv7em-none-eabihf"
    );
}
