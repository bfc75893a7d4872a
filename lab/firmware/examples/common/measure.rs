//! The measurement every QEMU firmware example runs (`qemu_cortex_m4`, `qemu_cortex_m0`,
//! `qemu_rv32`): a platform supplies an instruction counter, a stack painter and an
//! output channel ([`Platform`]); this module renders every standard Lab #1 scene with
//! every method of `Method::ALL` (and, on chips without an FPU, `Method::INTEGER`) into
//! a [`PixelHash`] at 240×240 and prints one line per scene and method in the format `lab/src/qemu_output.rs` parses:
//!
//! ```text
//! hash lab incremental/robust/exact 0x0123456789abcdef pixels 57600 instr 3456789 ipp 60.0 stack 312
//! ```
//!
//! [`Run::feature_scenes`] (the Cortex-M4F only) measures the scenes with lights, a
//! floor and mirrors the same way, with the methods and options of
//! `scenes::FEATURE_RENDERS`, the options' suffix appended to the method
//! (`hash shadows direct/auto/exact+literal …`).
//!
//! - `instr`: instructions executed by the render, from the platform's counter minus
//!   what an empty measurement counts. Each run first checks the counter on loops of
//!   known length (`calibration` lines).
//! - `stack`: bytes of stack below the caller's stack pointer that the render touched
//!   (the stack is painted before and scanned after), measured in a second, untimed
//!   render with the counter's interrupt (if any) off, so no exception frame lands on
//!   the stack. Reaching the bottom of the stack region is a failure (an overflow).
//!
//! Included with `#[path]`; `crate::scenes` must be `lab/src/scenes.rs`.

#![allow(dead_code)]

use core::fmt;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raytracer::{math, Camera, CameraParams, Method, Options, Render, Sampling, Scene, SubSamples};
use embedded_raytracer_lab::hash::PixelHash;

use crate::scenes;

/// Whether the Lab #1 scenes are measured with the integer kernel
/// ([`Method::INTEGER`]) after `Method::ALL`: on the chips without an FPU (Cortex-M0,
/// RV32IMC), for which it is made, and on the Cortex-M4F when built with the
/// environment variable `MEASURE_INTEGER` set (not in its committed run, whose lines
/// `.ci/firmware` compares one for one):
/// `MEASURE_INTEGER=1 cargo run --release --example qemu_cortex_m4 --target thumbv7em-none-eabihf`.
pub const INTEGER_TOO: bool = cfg!(any(
    all(target_arch = "arm", not(target_abi = "eabihf")),
    target_arch = "riscv32"
)) || option_env!("MEASURE_INTEGER").is_some();

/// Every scene is rendered at this size (its own camera otherwise).
pub const SIZE: Size = Size::new(240, 240);
/// Stack paint pattern.
pub const PAINT: u32 = 0xDEAD_BEEF;

/// What a chip (or its emulator) provides for the measurement.
pub trait Platform {
    /// The firmware's name, the first word of its output.
    fn name(&self) -> &'static str;
    /// The instruction counter's current value, in its own ticks.
    fn ticks(&self) -> u64;
    /// Ticks to instructions, rounded to nearest.
    fn instructions(&self, ticks: u64) -> u64;
    /// Instructions per tick, rounded up: the counter's resolution.
    fn instructions_per_tick(&self) -> u64;
    /// Prints how the counter becomes instructions (the `clock` or `counter` line).
    fn describe_counter(&self, overhead_ticks: u64);
    /// Executes exactly `2n` instructions, `n ≥ 1`, touching no memory.
    fn spin(&self, n: u32);
    /// The stack pointer.
    fn sp(&self) -> usize;
    /// Paints every word in `[stack bottom, SP)` with [`PAINT`], writing nothing at or
    /// above the stack pointer and using no stack itself.
    fn paint_stack(&self);
    /// The stack region: `(lowest address it may reach, initial stack pointer)`.
    fn stack_region(&self) -> (usize, usize);
    /// Turns the counter's interrupt off (`true`) or back on (`false`).
    fn quiet(&mut self, quiet: bool);
    /// Prints one line.
    fn print(&self, args: fmt::Arguments);
    /// Ends the run with QEMU's exit status 0 (`ok`) or 1.
    fn exit(&self, ok: bool) -> !;
}

/// The render under test, never inlined so that its whole frame lies below the
/// measuring function's stack pointer. An `f32` method (`Method::ALL`) is passed at
/// run time; the integer kernel has its own function, [`render_integer`], with its
/// method a constant, as a firmware would write it (a run-time method that may ask for
/// either arithmetic links both for every method: twice the flash).
#[inline(never)]
fn render<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    method: Method,
    target: &mut PixelHash,
) {
    // The f32 fields only: the arithmetic is then a constant and the integer path is
    // not linked here.
    let f32_method = Method::new(method.stepping, method.sphere_test, method.sqrt);
    let Ok(()) = Render::new(scene, camera).with_method(f32_method).draw(target);
}

/// [`render`] with [`Method::INTEGER`].
#[inline(never)]
fn render_integer<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    target: &mut PixelHash,
) {
    let Ok(()) = Render::new(scene, camera)
        .with_method(Method::INTEGER)
        .draw(target);
}

/// The render of a scene with lights, planes or mirrors under test, with its options;
/// never inlined, like [`render`].
///
/// The methods of `scenes::FEATURE_RENDERS` only, each a constant: a run-time method
/// would link the features' row loop of every method in `Method::ALL` for each scene
/// type, more than the flash holds. Any other method draws nothing (its pixel count
/// fails the run).
#[inline(never)]
fn render_features<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    method: Method,
    options: Options,
    target: &mut PixelHash,
) {
    let render = Render::new(scene, camera).with_options(options);
    let Ok(()) = if method == Method::TARGET_DEFAULT {
        render.with_method(Method::TARGET_DEFAULT).draw(target)
    } else if method == Method::LITERAL {
        render.with_method(Method::LITERAL).draw(target)
    } else {
        Ok(())
    };
}

/// The render of one [`Sampling`] (default method and options) under test; never
/// inlined, like [`render`].
#[inline(never)]
fn render_sampled<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    sampling: Sampling,
    target: &mut PixelHash,
) {
    let Ok(()) = Render::new(scene, camera).with_sampling(sampling).draw(target);
}

/// The samplings [`Run::sampling_scenes`] measures: the centre ray, the 4 × 4 grid
/// everywhere and where an edge can cross the pixel.
pub const SAMPLINGS: [Sampling; 3] = [
    Sampling::Center,
    match SubSamples::new(4) {
        Ok(n) => Sampling::Grid(n),
        Err(_) => Sampling::Center,
    },
    match SubSamples::new(4) {
        Ok(n) => Sampling::Adaptive(n),
        Err(_) => Sampling::Center,
    },
];

/// The scenes anti-aliasing is measured on: `lab` (the Lab #1 loop) and `shadows`
/// (the features path).
const SAMPLED_SCENES: [&str; 2] = ["lab", "shadows"];

/// The sink alone, for scale: the same `PixelHash` fed 240 rows of 240 pixels through
/// `fill_contiguous`, one call per row as a render makes them, with colours that cost
/// one add each. A render's instructions minus these are the kernel's.
#[inline(never)]
fn sink_only(target: &mut PixelHash) {
    for y in 0..SIZE.height {
        let row = Rectangle::new(Point::new(0, y as i32), Size::new(SIZE.width, 1));
        let colors = (0..SIZE.width).map(|x| Rgb888::new(x as u8, y as u8, (x ^ y) as u8));
        let Ok(()) = target.fill_contiguous(&row, colors);
    }
}

/// Counter ticks across `f`, never inlined so that every measurement (the empty one
/// that gives the overhead included) reads the counter through the same code.
#[inline(never)]
fn elapsed<P: Platform>(platform: &P, f: impl FnOnce()) -> u64 {
    let t0 = platform.ticks();
    f();
    let t1 = platform.ticks();
    t1 - t0
}

/// Peak stack bytes `f` uses below this function's stack pointer, or `None` if it
/// reached the bottom of the stack region.
#[inline(never)]
fn stack_of<P: Platform>(platform: &P, f: impl FnOnce()) -> Option<usize> {
    let (bottom, top) = platform.stack_region();
    let base = top - platform.sp();
    platform.paint_stack();
    f();
    // The first word above the bottom that no longer holds the paint.
    let mut p = bottom;
    // SAFETY: reads words of the stack region, all below the initial SP.
    while p < top && unsafe { core::ptr::read_volatile(p as *const u32) } == PAINT {
        p += 4;
    }
    (p > bottom).then(|| (top - p).saturating_sub(base))
}

/// Instructions per pixel, tenths rounded to nearest.
fn ipp10(instructions: u64, pixels: u64) -> u64 {
    (instructions * 10 + pixels / 2) / pixels.max(1)
}

/// One firmware run: its platform, the counter's own cost and the failures so far.
pub struct Run<P: Platform> {
    pub platform: P,
    /// Ticks of an empty measurement.
    overhead: u64,
    failures: u32,
}

/// The Lab #1 scenes ([`Run::every_scene`]): every method.
struct Lab1<'r, P: Platform>(&'r mut Run<P>);

impl<P: Platform> scenes::EachScene for Lab1<'_, P> {
    fn scene<const N: usize, const L: usize, const PL: usize, const D: usize>(
        &mut self,
        name: &'static str,
        scene: &'static Scene<N, L, PL, D>,
        camera: CameraParams,
    ) {
        self.0.measure_scene(name, scene, camera);
    }
}

/// The scenes with lights, a floor and mirrors ([`Run::feature_scenes`]).
struct Features<'r, P: Platform>(&'r mut Run<P>);

impl<P: Platform> scenes::EachScene for Features<'_, P> {
    fn scene<const N: usize, const L: usize, const PL: usize, const D: usize>(
        &mut self,
        name: &'static str,
        scene: &'static Scene<N, L, PL, D>,
        camera: CameraParams,
    ) {
        self.0.measure_feature_scene(name, scene, camera);
    }
}

/// The anti-aliasing renders ([`Run::sampling_scenes`]).
struct Sampled<'r, P: Platform>(&'r mut Run<P>);

impl<P: Platform> scenes::EachScene for Sampled<'_, P> {
    fn scene<const N: usize, const L: usize, const PL: usize, const D: usize>(
        &mut self,
        name: &'static str,
        scene: &'static Scene<N, L, PL, D>,
        camera: CameraParams,
    ) {
        if SAMPLED_SCENES.contains(&name) {
            self.0.measure_sampling(name, scene, camera);
        }
    }
}

impl<P: Platform> Run<P> {
    /// Measures the counter's overhead and prints the run's header lines.
    pub fn start(platform: P) -> Self {
        // The counter's own cost: an empty measurement.
        let overhead = elapsed(&platform, || {});
        platform.print(format_args!(
            "{}: every standard scene at {}x{} (its own camera, size replaced), every method",
            platform.name(),
            SIZE.width,
            SIZE.height
        ));
        platform.describe_counter(overhead);
        // The default method's name, so tools can pick its lines (e.g. no_panic's hash).
        platform.print(format_args!("default {}", Method::TARGET_DEFAULT));
        Run {
            platform,
            overhead,
            failures: 0,
        }
    }

    fn fail(&mut self, what: &str) {
        self.platform.print(format_args!("FAIL {}", what));
        self.failures += 1;
    }

    /// Instructions executed by `f`, measured like a render.
    pub fn timed(&self, f: impl FnOnce()) -> u64 {
        let ticks = elapsed(&self.platform, f);
        self.platform.instructions(ticks.saturating_sub(self.overhead))
    }

    /// The stack `f` uses below the caller's frame (bytes; `None` if it reached the
    /// bottom of the stack region), measured like a render's.
    pub fn stack(&self, f: impl FnOnce()) -> Option<usize> {
        stack_of(&self.platform, f)
    }

    /// Checks the tick-to-instruction conversion on a loop of `2n` instructions:
    /// within 0.001 % + 20 instructions, or two ticks where a tick is coarser than 10
    /// instructions (each wrap of a 24-bit SysTick also costs its exception, ~12).
    pub fn calibrate(&mut self, n: u32) {
        // SAFETY: a plain read, to keep the loop count opaque to the optimiser.
        let n = unsafe { core::ptr::read_volatile(&n) };
        let expected = 2 * u64::from(n);
        let measured = self.timed(|| self.platform.spin(n));
        let tolerance = expected / 100_000 + (2 * self.platform.instructions_per_tick()).max(20);
        let ok = measured.abs_diff(expected) <= tolerance;
        self.platform.print(format_args!(
            "calibration expected {} measured {} tolerance {} {}",
            expected,
            measured,
            tolerance,
            if ok { "ok" } else { "FAILED" }
        ));
        if !ok {
            self.fail("calibration");
        }
    }

    /// `math::sqrt_exact` against `libm::sqrtf`, bit for bit (any NaN equals any NaN):
    /// on hard-float ARM the former is the FPU's `VSQRT.F32`.
    pub fn check_sqrt(&mut self) {
        let mut inputs = 0u32;
        let mut mismatches = 0u32;
        let platform = &self.platform;
        let mut check = |x: f32| {
            let (hw, sw) = (math::sqrt_exact(x), libm::sqrtf(x));
            if hw.to_bits() != sw.to_bits() && !(hw.is_nan() && sw.is_nan()) {
                if mismatches < 5 {
                    platform.print(format_args!(
                        "sqrt mismatch {:#010x}: vsqrt {:#010x} libm {:#010x}",
                        x.to_bits(),
                        hw.to_bits(),
                        sw.to_bits()
                    ));
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
        self.platform
            .print(format_args!("sqrt inputs {} mismatches {}", inputs, mismatches));
        if mismatches != 0 {
            self.fail("sqrt");
        }
    }

    /// What the `PixelHash` sink alone costs per pixel.
    pub fn sink(&mut self) {
        let mut hash = PixelHash::new(SIZE);
        let instr = self.timed(|| sink_only(&mut hash));
        let pixels = hash.pixels();
        let ipp10 = ipp10(instr, pixels);
        self.platform.print(format_args!(
            "sink pixelhash pixels {} instr {} ipp {}.{}",
            pixels,
            instr,
            ipp10 / 10,
            ipp10 % 10
        ));
    }

    /// The scene's camera at 240×240, or `None` (after a failure line) if it cannot be
    /// built.
    fn camera(&mut self, name: &str, params: CameraParams) -> Option<Camera> {
        match (CameraParams { size: SIZE, ..params }).build() {
            Ok(camera) => Some(camera),
            Err(e) => {
                self.platform.print(format_args!("camera {}: {:?}", name, e));
                self.fail("camera");
                None
            }
        }
    }

    /// Prints one render's line, `hash NAME METHODSUFFIX …`, and fails the run on a
    /// wrong pixel count, two passes that differ, or a stack overflow.
    #[allow(clippy::too_many_arguments)]
    fn report(
        &mut self,
        name: &str,
        method: Method,
        suffix: &str,
        hash: &PixelHash,
        again: &PixelHash,
        instr: u64,
        stack: Option<usize>,
    ) {
        let expected_pixels = u64::from(SIZE.width) * u64::from(SIZE.height);
        let pixels = hash.pixels();
        let ipp10 = ipp10(instr, pixels);
        self.platform.print(format_args!(
            "hash {} {}{} {:#018x} pixels {} instr {} ipp {}.{} stack {}",
            name,
            method,
            suffix,
            hash.hash(),
            pixels,
            instr,
            ipp10 / 10,
            ipp10 % 10,
            stack.unwrap_or(0)
        ));
        if pixels != expected_pixels {
            self.fail("pixel count");
        }
        if again != hash {
            self.fail("the two passes differ");
        }
        if stack.is_none() {
            self.fail("stack overflow: the render reached the bottom of the stack region");
        }
    }

    /// Every method on one Lab #1 scene at 240×240: hash, pixels, instructions, stack.
    pub fn measure_scene<const N: usize, const L: usize, const PL: usize, const D: usize>(
        &mut self,
        name: &str,
        scene: &Scene<N, L, PL, D>,
        params: CameraParams,
    ) {
        let Some(camera) = self.camera(name, params) else {
            return;
        };
        for method in Method::ALL
            .into_iter()
            .chain(INTEGER_TOO.then_some(Method::INTEGER))
        {
            let draw = |target: &mut PixelHash| {
                if method == Method::INTEGER {
                    render_integer(scene, &camera, target);
                } else {
                    render(scene, &camera, method, target);
                }
            };
            // Timed pass (the counter's interrupt on).
            let mut hash = PixelHash::new(SIZE);
            let instr = self.timed(|| draw(&mut hash));
            // Stack pass: the counter's interrupt off (it would push its frame onto the
            // render's stack), the counter keeps running. Ticks lost meanwhile are
            // harmless: only differences within one timed pass are used.
            self.platform.quiet(true);
            let mut again = PixelHash::new(SIZE);
            let stack = stack_of(&self.platform, || draw(&mut again));
            self.platform.quiet(false);
            self.report(name, method, "", &hash, &again, instr, stack);
        }
    }

    /// The renders of `scenes::FEATURE_RENDERS` (method and options) on one scene with
    /// lights, planes or mirrors, measured as [`Run::measure_scene`] measures. The two
    /// passes call the render directly, as there: the stack figure is counted from
    /// inside `stack_of`, whose frame holds the closure.
    pub fn measure_feature_scene<const N: usize, const L: usize, const PL: usize, const D: usize>(
        &mut self,
        name: &str,
        scene: &Scene<N, L, PL, D>,
        params: CameraParams,
    ) {
        let Some(camera) = self.camera(name, params) else {
            return;
        };
        for (method, suffix, options) in scenes::FEATURE_RENDERS {
            let mut hash = PixelHash::new(SIZE);
            let instr = self.timed(|| render_features(scene, &camera, method, options, &mut hash));
            self.platform.quiet(true);
            let mut again = PixelHash::new(SIZE);
            let stack = stack_of(&self.platform, || {
                render_features(scene, &camera, method, options, &mut again)
            });
            self.platform.quiet(false);
            self.report(name, method, suffix, &hash, &again, instr, stack);
        }
    }

    /// [`SAMPLINGS`] on one scene (default method), measured as
    /// [`Run::measure_scene`] measures: `aa NAME SAMPLING HASH pixels P instr I ipp X
    /// stack S` (`lab/tests/lab/sampling.rs` checks the hashes against the host's).
    pub fn measure_sampling<const N: usize, const L: usize, const PL: usize, const D: usize>(
        &mut self,
        name: &str,
        scene: &Scene<N, L, PL, D>,
        params: CameraParams,
    ) {
        let Some(camera) = self.camera(name, params) else {
            return;
        };
        for sampling in SAMPLINGS {
            let mut hash = PixelHash::new(SIZE);
            let instr = self.timed(|| render_sampled(scene, &camera, sampling, &mut hash));
            self.platform.quiet(true);
            let mut again = PixelHash::new(SIZE);
            let stack = stack_of(&self.platform, || {
                render_sampled(scene, &camera, sampling, &mut again)
            });
            self.platform.quiet(false);
            let pixels = hash.pixels();
            let ipp10 = ipp10(instr, pixels);
            self.platform.print(format_args!(
                "aa {} {} {:#018x} pixels {} instr {} ipp {}.{} stack {}",
                name,
                sampling,
                hash.hash(),
                pixels,
                instr,
                ipp10 / 10,
                ipp10 % 10,
                stack.unwrap_or(0)
            ));
            if pixels != u64::from(SIZE.width) * u64::from(SIZE.height) || again != hash || stack.is_none() {
                self.fail("anti-aliasing render");
            }
        }
    }

    /// Anti-aliasing on [`SAMPLED_SCENES`].
    pub fn sampling_scenes(&mut self) {
        scenes::for_each(&mut Sampled(self));
        scenes::for_each_feature(&mut Sampled(self));
    }

    /// Every standard Lab #1 scene (`lab/src/scenes.rs`' `for_each`), every
    /// method.
    pub fn every_scene(&mut self) {
        scenes::for_each(&mut Lab1(self));
    }

    /// The standard scenes with lights, a floor and mirrors (`scenes::for_each_feature`).
    pub fn feature_scenes(&mut self) {
        scenes::for_each_feature(&mut Features(self));
    }

    /// Prints the verdict and exits QEMU with it.
    pub fn finish(self) -> ! {
        if self.failures == 0 {
            self.platform.print(format_args!("result ok"));
            self.platform.exit(true)
        } else {
            let failures = self.failures;
            self.platform.print(format_args!("result FAILED {}", failures));
            self.platform.exit(false)
        }
    }
}
