//! The renders whose Cortex-M4 cycles `.ci/cycles` estimates: the same scenes, camera
//! size, methods and `PixelHash` sink as `lab/firmware/examples/qemu_cortex_m4.rs`, each render
//! between the region markers of `lab/firmware/examples/common/cycle_region.rs`, so that
//! `cycle_model` (which reads QEMU's execution log) counts exactly the render call.
//!
//! ```sh
//! bash .ci/cycles --quick    # the default method on lab, shadows, mirrors and bounce (and the sink alone)
//! bash .ci/cycles --update   # every method on every Lab #1 scene, the default on the others
//! ```
//!
//! Which renders: the default method on `lab`; with the word `features` on QEMU's
//! semihosting command line (`-semihosting-config
//! enable=on,target=native,arg=qemu_cycles,arg=features`) instead the default method on
//! each scene with lights, a floor and mirrors (`shadows`, `mirrors`) and on the first
//! frame of `bounce` (the scene at rest, drawn whole: what every frame of a moving
//! camera costs); with the word `all`, every method in `Method::ALL` on every Lab #1
//! scene and the default on the scenes with features. Chosen at run time, so that every selection traces the same
//! ELF: the same code, the same estimates. First, the sink alone (the `sink_only` of
//! `qemu_cortex_m4`); last (not with `features`), the default method on lab traced into
//! a band buffer ([`Render::draw_band`], `Rgb888`, [`BAND_ROWS`](fw::BAND_ROWS) rows at
//! a time): the path of a display driver that sends bands, without a `DrawTarget`. Its
//! region counts the `draw_band` calls only: hashing each band (to check its pixels)
//! lies between the pause and resume markers.
//! Prints, after each region, the line that labels it:
//!
//! ```text
//! region lab direct/auto/exact hash 0x2400e66de1ccdfed pixels 57600
//! region sink pixelhash pixels 57600
//! region lab-band direct/auto/exact hash 0x2400e66de1ccdfed pixels 57600
//! ```
//!
//! The hashes must equal `qemu_cortex_m4`'s (`.ci/cycles` checks them against
//! `lab/data/qemu_cortex_m4.txt`): the estimated cycles belong to the same pixels.
//! `qemu_cortex_m4` does not draw `bounce`: its hash is checked against the host's
//! render instead (`cargo test -p embedded-raytracer-lab --test lab cycle_estimates`).
//! No SysTick interrupt runs, so no exception lands inside a region.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(all(target_os = "none", target_abi = "eabihf", not(armv8m_main)))]
#[path = "../../src/scenes.rs"]
mod scenes;

#[cfg(all(target_os = "none", target_abi = "eabihf", not(armv8m_main)))]
#[path = "common/cycle_region.rs"]
mod cycle_region;

#[cfg(all(target_os = "none", target_abi = "eabihf", not(armv8m_main)))]
mod fw {
    use cortex_m_rt::entry;
    use cortex_m_semihosting::{debug, hprintln, syscall};
    use embedded_graphics::pixelcolor::Rgb888;
    use embedded_graphics::prelude::*;
    use embedded_graphics::primitives::Rectangle;
    use embedded_raytracer::{Camera, CameraParams, Method, Render, Scene};
    use embedded_raytracer_lab::hash::PixelHash;
    use panic_semihosting as _;
    // The PAC's vector table: cortex-m-rt's `device` feature (turned on by the stm32f4
    // dev-dependency) requires it in every firmware example.
    use stm32f4xx_hal as _;

    use crate::cycle_region::{
        cycle_region_begin, cycle_region_end, cycle_region_pause, cycle_region_resume,
    };
    use crate::scenes;

    /// Every scene is rendered at this size (its own camera otherwise).
    const SIZE: Size = Size::new(240, 240);
    /// Which renders the semihosting command line asks for.
    #[derive(Clone, Copy, PartialEq)]
    enum Selection {
        /// No word: the default method on lab, then into bands.
        Quick,
        /// `features`: the default method on each scene with lights, a floor and mirrors,
        /// and on the first frame of `bounce`.
        Features,
        /// `all`: every method on every Lab #1 scene, the default on each scene with
        /// features, then the default on lab into bands.
        All,
    }

    /// The renders the semihosting command line's words ask for.
    fn selection() -> Selection {
        let mut line = [0u8; 128];
        // SAFETY: SYS_GET_CMDLINE writes at most `line.len()` bytes (NUL-terminated)
        // into `line`; a line that does not fit is an error status, not a write.
        let status = unsafe { syscall!(GET_CMDLINE, line.as_mut_ptr(), line.len()) };
        let has = |w: &[u8]| status == 0 && line.split(|&b| b == b' ' || b == 0).any(|word| word == w);
        if has(b"all") {
            Selection::All
        } else if has(b"features") {
            Selection::Features
        } else {
            Selection::Quick
        }
    }

    /// The render under test, as in `qemu_cortex_m4`: never inlined, so the region is
    /// the call and nothing of the caller's loop.
    #[inline(never)]
    fn render<const N: usize, const L: usize, const P: usize, const D: usize>(
        scene: &Scene<N, L, P, D>,
        camera: &Camera,
        method: Method,
        target: &mut PixelHash,
    ) {
        // The f32 method's fields only, as `qemu_cortex_m4` draws `Method::ALL`: the
        // arithmetic is then a constant and the integer kernel is not linked here.
        let f32_method = Method::new(method.stepping, method.sphere_test, method.sqrt);
        let Ok(()) = Render::new(scene, camera).with_method(f32_method).draw(target);
    }

    /// The default method on a scene with features: the method a constant, so that the
    /// firmware links its loop only (a run-time method would link all 30 loops for each
    /// scene type, more than the flash holds). Never inlined, like [`render`].
    #[inline(never)]
    fn render_default<const N: usize, const L: usize, const P: usize, const D: usize>(
        scene: &Scene<N, L, P, D>,
        camera: &Camera,
        target: &mut PixelHash,
    ) {
        let Ok(()) = Render::new(scene, camera)
            .with_method(Method::TARGET_DEFAULT)
            .draw(target);
    }

    /// The sink alone, as `qemu_cortex_m4`'s `sink_only`: 240 rows of 240 pixels
    /// through `fill_contiguous`, colours that cost one add each.
    #[inline(never)]
    fn sink_only(target: &mut PixelHash) {
        for y in 0..SIZE.height {
            let row = Rectangle::new(Point::new(0, y as i32), Size::new(SIZE.width, 1));
            let colors = (0..SIZE.width).map(|x| Rgb888::new(x as u8, y as u8, (x ^ y) as u8));
            let Ok(()) = target.fill_contiguous(&row, colors);
        }
    }

    /// Rows per band of the band render: three `draw_band` calls per frame, each with
    /// its own per-frame set-up; 240 × 80 `Rgb888` is 57 600 bytes of stack.
    pub const BAND_ROWS: u32 = 80;

    /// The band render under test: never inlined, like [`render`].
    #[inline(never)]
    fn render_band<const N: usize>(
        scene: &Scene<N>,
        camera: &Camera,
        method: Method,
        rows: core::ops::Range<u32>,
        band: &mut [Rgb888],
    ) -> bool {
        Render::new(scene, camera)
            .with_method(Method::new(method.stepping, method.sphere_test, method.sqrt))
            .draw_band(rows, band)
            .is_ok()
    }

    /// The whole image band by band into one buffer, each band hashed in the pause
    /// between two band renders (the hash equals the `Drawable` render's: the same
    /// pixels in the same order). False if a band could not be drawn.
    fn render_bands<const N: usize>(
        name: &str,
        scene: &Scene<N>,
        params: CameraParams,
        method: Method,
    ) -> bool {
        let Ok(camera) = (CameraParams { size: SIZE, ..params }).build() else {
            hprintln!("camera {}: cannot be built", name);
            return false;
        };
        let mut band = [Rgb888::BLACK; (SIZE.width * BAND_ROWS) as usize];
        let mut hash = PixelHash::new(SIZE);
        let mut ok = true;
        cycle_region_begin();
        let mut j0 = 0;
        while j0 < SIZE.height {
            let j1 = (j0 + BAND_ROWS).min(SIZE.height);
            let pixels = (SIZE.width * (j1 - j0)) as usize;
            let Some(band) = band.get_mut(..pixels) else {
                ok = false;
                break;
            };
            ok &= render_band(scene, &camera, method, j0..j1, band);
            cycle_region_pause();
            let area = Rectangle::new(Point::new(0, j0 as i32), Size::new(SIZE.width, j1 - j0));
            let Ok(()) = hash.fill_contiguous(&area, band.iter().copied());
            cycle_region_resume();
            j0 = j1;
        }
        cycle_region_end();
        hprintln!(
            "region {}-band {} hash {:#018x} pixels {}",
            name,
            method,
            hash.hash(),
            hash.pixels()
        );
        ok && hash.pixels() == u64::from(SIZE.width) * u64::from(SIZE.height)
    }

    /// Renders the methods on each scene it is given, each render between the markers.
    struct Renders<'a> {
        methods: &'a [Method],
        /// A camera could not be built or a pixel count was wrong.
        failed: bool,
    }

    impl scenes::EachScene for Renders<'_> {
        fn scene<const N: usize, const L: usize, const P: usize, const D: usize>(
            &mut self,
            name: &'static str,
            scene: &'static Scene<N, L, P, D>,
            params: CameraParams,
        ) {
            if !render_scene(name, scene, params, self.methods) {
                self.failed = true;
            }
        }
    }

    /// Renders the default method on each scene it is given, between the markers.
    struct DefaultRenders {
        /// A camera could not be built or a pixel count was wrong.
        failed: bool,
    }

    impl scenes::EachScene for DefaultRenders {
        fn scene<const N: usize, const L: usize, const P: usize, const D: usize>(
            &mut self,
            name: &'static str,
            scene: &'static Scene<N, L, P, D>,
            params: CameraParams,
        ) {
            let Ok(camera) = (CameraParams { size: SIZE, ..params }).build() else {
                hprintln!("camera {}: cannot be built", name);
                self.failed = true;
                return;
            };
            let mut hash = PixelHash::new(SIZE);
            cycle_region_begin();
            render_default(scene, &camera, &mut hash);
            cycle_region_end();
            print_region(name, Method::TARGET_DEFAULT, &hash);
            self.failed |= hash.pixels() != u64::from(SIZE.width) * u64::from(SIZE.height);
        }
    }

    /// The line that labels the region just ended.
    fn print_region(name: &str, method: Method, hash: &PixelHash) {
        hprintln!(
            "region {} {} hash {:#018x} pixels {}",
            name,
            method,
            hash.hash(),
            hash.pixels()
        );
    }

    /// Renders `methods` on one scene, each between the markers; false if the camera
    /// cannot be built or a pixel count is wrong.
    fn render_scene<const N: usize, const L: usize, const P: usize, const D: usize>(
        name: &str,
        scene: &Scene<N, L, P, D>,
        params: CameraParams,
        methods: &[Method],
    ) -> bool {
        let Ok(camera) = (CameraParams { size: SIZE, ..params }).build() else {
            hprintln!("camera {}: cannot be built", name);
            return false;
        };
        let mut ok = true;
        for &method in methods {
            let mut hash = PixelHash::new(SIZE);
            cycle_region_begin();
            render(scene, &camera, method, &mut hash);
            cycle_region_end();
            print_region(name, method, &hash);
            ok &= hash.pixels() == u64::from(SIZE.width) * u64::from(SIZE.height);
        }
        ok
    }

    #[entry]
    fn main() -> ! {
        let selection = selection();
        hprintln!(
            "qemu_cycles: {} at {}x{}",
            match selection {
                Selection::Quick => "the default method on lab",
                Selection::Features => "the default method on the scenes with lights, a floor and mirrors",
                Selection::All => "every method on every standard scene",
            },
            SIZE.width,
            SIZE.height
        );
        let mut hash = PixelHash::new(SIZE);
        cycle_region_begin();
        sink_only(&mut hash);
        cycle_region_end();
        hprintln!("region sink pixelhash pixels {}", hash.pixels());

        let mut ok = match selection {
            Selection::All => {
                let mut renders = Renders {
                    methods: &Method::ALL,
                    failed: false,
                };
                scenes::for_each(&mut renders);
                !renders.failed
            }
            Selection::Quick => {
                render_scene("lab", &scenes::LAB, scenes::LAB_CAMERA, &[Method::TARGET_DEFAULT])
            }
            Selection::Features => true,
        };
        if selection != Selection::Quick {
            let mut renders = DefaultRenders { failed: false };
            scenes::for_each_feature(&mut renders);
            // The first frame of the bouncing ball (the scene at rest, drawn whole):
            // what an orbiting camera pays every frame.
            scenes::EachScene::scene(&mut renders, "bounce", &scenes::BOUNCE, scenes::BOUNCE_CAMERA);
            ok &= !renders.failed;
        }
        if selection != Selection::Features {
            ok = render_bands("lab", &scenes::LAB, scenes::LAB_CAMERA, Method::TARGET_DEFAULT) && ok;
        }
        if ok {
            hprintln!("result ok");
            debug::exit(debug::EXIT_SUCCESS);
        } else {
            hprintln!("result FAILED");
            debug::exit(debug::EXIT_FAILURE);
        }
        // Not reached: QEMU exits on the semihosting call.
        loop {
            cortex_m::asm::wfi();
        }
    }
}

#[cfg(all(target_os = "none", not(all(target_abi = "eabihf", not(armv8m_main)))))]
#[path = "common/wrong_target.rs"]
mod wrong_target;
#[cfg(all(target_os = "none", not(all(target_abi = "eabihf", not(armv8m_main)))))]
wrong_target::firmware_for!("qemu_cycles", "thumbv7em-none-eabihf");

#[cfg(not(target_os = "none"))]
fn main() {
    println!("qemu_cycles is firmware: bash .ci/cycles --quick (or --update) builds and traces it");
}
