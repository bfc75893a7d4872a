//! The band path of `boards/stm32f407/src/main.rs` for the cycle model
//! (`bash .ci/cycles --bands`): the lab scene at 240×240 through the lab camera, default
//! method, traced band by band (16 rows) into the ST7789 wire format with the DMA
//! example's own code (`boards/stm32f407/src/st7789_band.rs`), each band between the region
//! markers of `lab/firmware/examples/common/cycle_region.rs`; then band 0 again with the frame-time
//! label drawn over it (the DMA example's step 4). Prints, after each region, the line
//! that labels it:
//!
//! ```text
//! region band 0 rows 0..16 pixels 3840 fnv 0x…
//! region band0+label rows 0..16 pixels 3840 fnv 0x…
//! ```
//!
//! `fnv` is the FNV-1a hash of the band's bytes as DMA would send them. The run fails
//! (exit 1) if the camera cannot be built or the bands do not cover the whole image.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(all(target_os = "none", target_abi = "eabihf", not(armv8m_main)))]
#[path = "../../src/scenes.rs"]
mod scenes;

#[cfg(all(target_os = "none", target_abi = "eabihf", not(armv8m_main)))]
#[path = "../../../boards/stm32f407/src/st7789_band.rs"]
mod st7789_band;

#[cfg(all(target_os = "none", target_abi = "eabihf", not(armv8m_main)))]
#[path = "common/cycle_region.rs"]
mod cycle_region;

#[cfg(all(target_os = "none", target_abi = "eabihf", not(armv8m_main)))]
mod fw {
    use cortex_m_rt::entry;
    use cortex_m_semihosting::{debug, hprintln};
    use embedded_graphics::prelude::*;
    use embedded_raytracer::CameraParams;
    use panic_semihosting as _;
    // The PAC's vector table: cortex-m-rt's `device` feature (turned on by the stm32f4
    // dev-dependency) requires it in every firmware example.
    use stm32f4xx_hal as _;

    use crate::cycle_region::{cycle_region_begin, cycle_region_end};
    use crate::scenes;
    use crate::st7789_band::{
        draw_label, trace_band, WireRgb565, BANDS, BAND_PIXELS, BAND_ROWS, HEIGHT, WIDTH,
    };

    /// FNV-1a (64-bit) of the band's wire bytes.
    fn fnv(buf: &[WireRgb565; BAND_PIXELS]) -> u64 {
        let mut hash = 0xcbf2_9ce4_8422_2325u64;
        for pixel in buf {
            for byte in pixel.bytes() {
                hash = (hash ^ u64::from(byte)).wrapping_mul(0x0000_0100_0000_01b3);
            }
        }
        hash
    }

    #[entry]
    fn main() -> ! {
        let params = CameraParams {
            size: Size::new(WIDTH, HEIGHT),
            ..scenes::LAB_CAMERA
        };
        let camera = params.build().ok();
        hprintln!(
            "band_cycles: lab at {}x{}, {} bands of {} rows",
            WIDTH,
            HEIGHT,
            BANDS,
            BAND_ROWS
        );
        let mut buf = [WireRgb565::BLACK; BAND_PIXELS];
        let mut pixels = 0usize;
        for k in 0..BANDS {
            cycle_region_begin();
            trace_band(camera.as_ref(), k, &mut buf);
            cycle_region_end();
            pixels += buf.len();
            hprintln!(
                "region band {} rows {}..{} pixels {} fnv {:#018x}",
                k,
                k * BAND_ROWS,
                (k + 1) * BAND_ROWS,
                buf.len(),
                fnv(&buf)
            );
        }
        // The DMA example's step 4: band 0 and a label of its usual length.
        cycle_region_begin();
        trace_band(camera.as_ref(), 0, &mut buf);
        draw_label(&mut buf, "frame 36.2 ms wait 0.1");
        cycle_region_end();
        hprintln!(
            "region band0+label rows 0..{} pixels {} fnv {:#018x}",
            BAND_ROWS,
            buf.len(),
            fnv(&buf)
        );
        if camera.is_some() && pixels == (WIDTH * HEIGHT) as usize {
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
wrong_target::firmware_for!("band_cycles", "thumbv7em-none-eabihf");

#[cfg(not(target_os = "none"))]
fn main() {
    println!("band_cycles is firmware for the cycle model: bash .ci/cycles --bands");
}
