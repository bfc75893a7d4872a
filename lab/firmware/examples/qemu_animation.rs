//! Measurement firmware for animated scenes drawn with incremental frames: one cycle of
//! `scenes/bounce.toml` (lit, shadowed, the default method), of
//! `scenes/circling.toml` (Lab #1 spheres, the integer kernel) and of `bounce` seen by a
//! camera that orbits it (`orbit`: every frame whole), each frame drawn through
//! `Incremental` onto a 240×240 `Rgb565` frame buffer (115,200 B: it fits the
//! emulated STM32F405's 128 KiB and the AN505's), which stands for the display's own
//! memory. Runs on the Cortex-M4F (QEMU `netduinoplus2`) and the Cortex-M33
//! (`mps2-an505`).
//!
//! One line per frame:
//!
//! ```text
//! anim bounce frame 3 traced 5120 sent 4210 windows 96 bytes 9476 instr 3456789 full_instr 39000000 first 0
//! ```
//!
//! - `traced`, `sent`, `windows`: `FrameStats` (pixels in the strips the render traced,
//!   pixels sent, runs they were sent in);
//! - `bytes`: what an ST7789 on SPI would be sent: 2 bytes a pixel and 11 a window
//!   (column and row address commands, memory write);
//! - `instr`: instructions of the incremental frame, the frame buffer's stores included;
//! - `full_instr`: instructions of the same frame drawn whole (`Render::draw`) into the
//!   same frame buffer, the baseline of the same run.
//!
//! Then per sequence a `setup` line (an incremental frame whose only change is one
//! pixel: the comparison of scenes, the plan and one strip's frame set-up), a `stack`
//! line (the most stack an incremental frame of the sequence used, each frame drawn a
//! second time from a copy of the `Incremental` under the stack paint, and the stack of
//! the last frame drawn whole, as `Render::draw`; bytes below the caller) and a
//! `check` line: the frame buffer's hash after the sequence and the hash of the last
//! frame's full render (`PixelHash` over the `Rgb565` colours in row order), which must
//! be equal, and equal to the host's (`lab/tests/lab/firmware_hashes.rs`).
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(all(target_os = "none", target_abi = "eabihf"))]
#[path = "common/cortex_m.rs"]
mod cortex_m_platform;
#[cfg(all(target_os = "none", target_abi = "eabihf"))]
#[path = "common/measure.rs"]
mod measure;
#[cfg(all(target_os = "none", target_abi = "eabihf"))]
#[path = "../../src/scenes.rs"]
mod scenes;

#[cfg(all(target_os = "none", target_abi = "eabihf"))]
mod fw {
    use core::convert::Infallible;

    use cortex_m_rt::entry;
    use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
    use embedded_graphics::prelude::*;
    use embedded_graphics::primitives::Rectangle;
    use embedded_raytracer::motion::Animation;
    use embedded_raytracer::{CameraParams, Incremental, Method, Render, Scene};
    use embedded_raytracer_lab::hash::PixelHash;
    use panic_semihosting as _;
    #[cfg(not(armv8m_main))]
    use stm32f4xx_hal as _;

    use crate::cortex_m_platform::{abort, CortexM};
    use crate::measure::{Platform, Run};
    use crate::scenes;

    #[cfg(not(armv8m_main))]
    const CHIP: (&str, u64) = ("qemu_cortex_m4", 168_000_000);
    #[cfg(armv8m_main)]
    const CHIP: (&str, u64) = ("qemu_cortex_m33", 20_000_000);

    const W: u32 = 240;
    const H: u32 = 240;

    /// The display's memory (its first `px.len() / W` rows: one row stands for a
    /// display whose contents are not kept, at the same cost a pixel), and what an SPI
    /// link to it would carry.
    struct Display<'a> {
        px: &'a mut [Rgb565],
        bytes: u64,
    }

    impl Display<'_> {
        fn start(&self, p: Point) -> usize {
            let rows = (self.px.len() as u32 / W).max(1);
            ((p.y as u32 % rows) * W + p.x as u32) as usize
        }
    }

    impl OriginDimensions for Display<'_> {
        fn size(&self) -> Size {
            Size::new(W, H)
        }
    }

    impl DrawTarget for Display<'_> {
        type Color = Rgb565;
        type Error = Infallible;
        fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, pixels: I) -> Result<(), Infallible> {
            for Pixel(p, c) in pixels {
                let i = self.start(p);
                if let Some(slot) = self.px.get_mut(i) {
                    *slot = c;
                }
            }
            Ok(())
        }
        /// One window: its commands, then its pixels stored in row order (every area
        /// the kernel sends lies within the display: a run of a row, or a strip of
        /// rows).
        fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
            &mut self,
            area: &Rectangle,
            colors: I,
        ) -> Result<(), Infallible> {
            let (w, h) = (area.size.width as usize, area.size.height as usize);
            self.bytes += 11 + 2 * (w * h) as u64;
            if h == 1 {
                // A row or a run of one: its pixels straight in.
                let start = self.start(area.top_left);
                if let Some(out) = self.px.get_mut(start..start + w) {
                    for (slot, c) in out.iter_mut().zip(colors) {
                        *slot = c;
                    }
                }
                return Ok(());
            }
            let mut colors = colors.into_iter();
            for r in 0..h {
                let start = self.start(area.top_left + Point::new(0, r as i32));
                match self.px.get_mut(start..start + w) {
                    Some(out) => out
                        .iter_mut()
                        .zip(colors.by_ref())
                        .for_each(|(slot, c)| *slot = c),
                    None => colors.by_ref().take(w).for_each(drop),
                }
            }
            Ok(())
        }
    }

    /// `Rgb565` colours hashed as the host hashes them: widened to `Rgb888`.
    struct Hash565(PixelHash);

    impl OriginDimensions for Hash565 {
        fn size(&self) -> Size {
            Size::new(W, H)
        }
    }

    impl DrawTarget for Hash565 {
        type Color = Rgb565;
        type Error = Infallible;
        fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, pixels: I) -> Result<(), Infallible> {
            self.0
                .draw_iter(pixels.into_iter().map(|Pixel(p, c)| Pixel(p, Rgb888::from(c))))
        }
    }

    /// One cycle of `animation` drawn incrementally, one line a frame. Inlined: the
    /// method is a constant of each call, so only its code is linked. `WHOLE`: a
    /// sequence whose every frame is drawn whole (the camera moves): no stack probe and
    /// no baseline a frame (`full_instr 0`), no `stack` line.
    #[inline(always)]
    fn sequence<
        P: Platform,
        const N: usize,
        const L: usize,
        const PL: usize,
        const D: usize,
        const M: usize,
        const INTEGER: bool,
        const WHOLE: bool,
    >(
        run: &mut Run<P>,
        fb: &mut [Rgb565],
        name: &str,
        base: &Scene<N, L, PL, D>,
        params: CameraParams,
        animation: &Animation<M>,
    ) -> bool {
        // A constant in each instantiation, named inside each timed closure (a captured
        // local would be read through the closure's environment, a run-time value that
        // links every method): the measured code dispatches on a known method, as a
        // firmware's does.
        let method = || {
            if INTEGER {
                Method::INTEGER
            } else {
                Method::TARGET_DEFAULT
            }
        };
        let mut scene = base.clone();
        let mut at = params;
        let mut shown: Incremental<N, L, PL, D> = Incremental::new();
        let mut row = [Rgb565::BLACK; W as usize];
        let mut ok = true;
        // The most stack an incremental frame used; `None` once one overran the region.
        let mut stack = Some(0);
        for frame in 0..=animation.frames() {
            if animation
                .apply_frame(base, &params, frame, &mut scene, &mut at)
                .is_err()
            {
                return false;
            }
            let Ok(camera) = at.build() else { return false };
            // The same frame from a copy of what the display shows, under the stack
            // paint (the same pixels again; not timed: painting costs instructions).
            if !WHOLE {
                let mut probe = shown.clone();
                let mut scratch = Display {
                    px: &mut *fb,
                    bytes: 0,
                };
                let probed = run.stack(|| {
                    let render = Render::new(&scene, &camera).with_method(method());
                    let _ = probe.draw(&render, &mut scratch);
                });
                stack = stack.zip(probed).map(|(a, b)| a.max(b));
            }
            let mut display = Display {
                px: &mut *fb,
                bytes: 0,
            };
            let mut stats = None;
            let instr = run.timed(|| {
                let render = Render::new(&scene, &camera).with_method(method());
                stats = shown.draw(&render, &mut display).ok();
            });
            let Some(stats) = stats else { return false };
            let bytes = display.bytes;
            ok &= stats.refused.is_none();
            // The same frame drawn whole, each row stored as the display stores it: the
            // baseline.
            let mut whole = Display {
                px: &mut row[..],
                bytes: 0,
            };
            let full_instr = if WHOLE {
                0
            } else {
                run.timed(|| {
                    let _ = Render::new(&scene, &camera)
                        .with_method(method())
                        .draw(&mut whole);
                })
            };
            run.platform.print(format_args!(
                "anim {} frame {} traced {} sent {} windows {} bytes {} instr {} full_instr {} first {} strips {}",
                name,
                frame,
                stats.traced,
                stats.sent,
                stats.windows,
                bytes,
                instr,
                full_instr,
                u8::from(stats.full),
                stats.strips
            ));
        }
        // The plan and one strip's set-up: a frame whose only change is one pixel.
        shown.invalidate_area(Rectangle::new(Point::new(0, 0), Size::new(1, 1)));
        let Ok(camera) = at.build() else { return false };
        let render = Render::new(&scene, &camera).with_method(method());
        let mut display = Display {
            px: &mut *fb,
            bytes: 0,
        };
        let setup = run.timed(|| {
            let _ = shown.draw(&Render::new(&scene, &camera).with_method(method()), &mut display);
        });
        run.platform.print(format_args!("setup {} instr {}", name, setup));
        let mut whole = Display {
            px: &mut row[..],
            bytes: 0,
        };
        if !WHOLE {
            let full_stack = run.stack(|| {
                let _ = Render::new(&scene, &camera)
                    .with_method(method())
                    .draw(&mut whole);
            });
            match (stack, full_stack) {
                (Some(incremental), Some(full)) => run.platform.print(format_args!(
                    "stack {} incremental {} full {}",
                    name, incremental, full
                )),
                _ => {
                    run.platform
                        .print(format_args!("FAIL {} overran the stack region", name));
                    ok = false;
                }
            }
        }
        // The display against the last frame's full render.
        let mut shown_hash = Hash565(PixelHash::new(Size::new(W, H)));
        let _ = shown_hash.fill_contiguous(
            &Rectangle::new(Point::zero(), Size::new(W, H)),
            fb.iter().copied(),
        );
        let mut full_hash = Hash565(PixelHash::new(Size::new(W, H)));
        let _ = render.draw(&mut full_hash);
        let equal = shown_hash.0.hash() == full_hash.0.hash();
        run.platform.print(format_args!(
            "check {} display {:#018x} full {:#018x} {}",
            name,
            shown_hash.0.hash(),
            full_hash.0.hash(),
            if equal { "equal" } else { "DIFFER" }
        ));
        ok && equal
    }

    #[entry]
    fn main() -> ! {
        let Some(platform) = CortexM::start(CHIP.0, CHIP.1) else {
            abort("core peripherals already taken");
        };
        let mut run = Run::start(platform);
        let Some(fb) = cortex_m::singleton!(: [Rgb565; (W * H) as usize] = [Rgb565::BLACK; (W * H) as usize])
        else {
            abort("frame buffer already taken");
        };
        let bounce = sequence::<_, 3, 1, 1, 0, 1, false, false>(
            &mut run,
            fb,
            "bounce",
            &scenes::BOUNCE,
            scenes::BOUNCE_CAMERA.with_size(Size::new(W, H)),
            &scenes::BOUNCE_ANIMATION,
        );
        fb.fill(Rgb565::BLACK);
        let circling = sequence::<_, 3, 0, 0, 0, 3, true, false>(
            &mut run,
            fb,
            "circling",
            &scenes::CIRCLING,
            scenes::CIRCLING_CAMERA.with_size(Size::new(W, H)),
            &scenes::CIRCLING_ANIMATION,
        );
        fb.fill(Rgb565::BLACK);
        let orbit = sequence::<_, 3, 1, 1, 0, 2, false, true>(
            &mut run,
            fb,
            "orbit",
            &scenes::BOUNCE,
            scenes::BOUNCE_CAMERA.with_size(Size::new(W, H)),
            &scenes::BOUNCE_ORBIT_ANIMATION,
        );
        if !(bounce && circling && orbit) {
            run.platform.print(format_args!("FAIL an animated sequence"));
            run.platform.exit(false);
        }
        run.finish()
    }
}

#[cfg(all(target_os = "none", not(target_abi = "eabihf")))]
#[path = "common/wrong_target.rs"]
mod wrong_target;
#[cfg(all(target_os = "none", not(target_abi = "eabihf")))]
wrong_target::firmware_for!("qemu_animation", "thumbv7em-none-eabihf");

#[cfg(not(target_os = "none"))]
fn main() {
    println!("qemu_animation is firmware: cargo run --release --example qemu_animation --target thumbv7em-none-eabihf");
}
