//! The DMA example's band path on the firmware sends the pixels the blocking example
//! draws: every 16-row band that `lab/firmware/examples/band_cycles.rs` traced in QEMU (with the DMA
//! example's own code, `boards/stm32f407/src/st7789_band.rs`) holds, byte for byte, the
//! host's whole `Render::draw` of the lab scene at 240×240 in Rgb565, high byte first.
//! Compared by each band's FNV-1a hash, which the firmware prints.
//!
//! The firmware output read is `lab/data/band_cycles.txt` (a committed QEMU run,
//! stored by `bash .ci/cycles --bands`), or the file named by `BAND_CYCLES_OUTPUT` —
//! `.ci/cycles --bands` points it at its fresh run.

use embedded_raytracer_lab::scenes;

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_raytracer::{CameraParams, Render};

const WIDTH: u32 = 240;
const HEIGHT: u32 = 240;
const BAND_ROWS: u32 = 16;

/// A row-major Rgb565 framebuffer: the blocking example's display, in memory.
struct Framebuffer(Vec<Rgb565>);

impl OriginDimensions for Framebuffer {
    fn size(&self) -> Size {
        Size::new(WIDTH, HEIGHT)
    }
}

impl DrawTarget for Framebuffer {
    type Color = Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, pixels: I) -> Result<(), Self::Error> {
        for Pixel(p, color) in pixels {
            let (x, y) = (u32::try_from(p.x).unwrap(), u32::try_from(p.y).unwrap());
            assert!(x < WIDTH && y < HEIGHT, "pixel {p} outside the frame");
            self.0[(y * WIDTH + x) as usize] = color;
        }
        Ok(())
    }
}

/// FNV-1a (64-bit), as `lab/firmware/examples/band_cycles.rs` computes it.
fn fnv(bytes: impl IntoIterator<Item = u8>) -> u64 {
    bytes.into_iter().fold(0xcbf2_9ce4_8422_2325, |hash, byte| {
        (hash ^ u64::from(byte)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// `(band, rows, fnv)` of every `region band K rows J0..J1 pixels N fnv 0x…` line.
fn firmware_bands(text: &str) -> Vec<(u32, String, u64)> {
    text.lines()
        .filter_map(|line| line.strip_prefix("region band "))
        .map(|rest| {
            let words: Vec<&str> = rest.split_whitespace().collect();
            let value = |key: &str| {
                let i = words
                    .iter()
                    .position(|w| *w == key)
                    .unwrap_or_else(|| panic!("no {key}: {rest}"));
                words[i + 1]
            };
            let hash = value("fnv");
            (
                words[0]
                    .parse()
                    .unwrap_or_else(|e| panic!("band number in {rest}: {e}")),
                value("rows").to_string(),
                u64::from_str_radix(hash.trim_start_matches("0x"), 16)
                    .unwrap_or_else(|e| panic!("{hash}: {e}")),
            )
        })
        .collect()
}

#[test]
fn firmware_bands_equal_the_hosts_rgb565_frame_in_wire_order() {
    let path = std::env::var("BAND_CYCLES_OUTPUT").unwrap_or_else(|_| "data/band_cycles.txt".into());
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    assert!(
        text.lines().any(|l| l == "result ok"),
        "{path}: no 'result ok' line"
    );
    let bands = firmware_bands(&text);
    assert_eq!(
        bands.iter().map(|b| b.0).collect::<Vec<_>>(),
        (0..HEIGHT / BAND_ROWS).collect::<Vec<_>>(),
        "{path}: one line per band, in order"
    );

    let camera = CameraParams {
        size: Size::new(WIDTH, HEIGHT),
        ..scenes::LAB_CAMERA
    }
    .build()
    .unwrap();
    let mut frame = Framebuffer(vec![Rgb565::new(1, 2, 3); (WIDTH * HEIGHT) as usize]);
    let Ok(()) = Render::new(&scenes::LAB, &camera).draw(&mut frame);

    for (k, rows, firmware) in bands {
        let (j0, j1) = (k * BAND_ROWS, (k + 1) * BAND_ROWS);
        assert_eq!(rows, format!("{j0}..{j1}"), "{path}: band {k}'s rows");
        let pixels = &frame.0[(j0 * WIDTH) as usize..(j1 * WIDTH) as usize];
        let host = fnv(pixels.iter().flat_map(|c| c.into_storage().to_be_bytes()));
        assert_eq!(
            firmware, host,
            "{path}: band {k} (rows {rows}): firmware {firmware:#018x}, host {host:#018x}"
        );
    }
}
