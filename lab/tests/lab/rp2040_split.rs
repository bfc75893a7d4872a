//! The RP2040 firmware's two-core band split (`boards/rp2040/src/split.rs`, the same
//! file the firmware compiles): the cores' alternate bands cover every row exactly once,
//! and, traced by `Render::draw_band` and put on the wire in band order, they are the
//! whole render's pixels bit for bit — at the firmware's 240×240 in its bands, and
//! at a smaller size with several band heights, on every standard scene with every
//! method. And the firmware's camera orbit (`boards/rp2040/src/orbit.rs`): the integer
//! kernel's rule takes every frame of it, so `Render::draw_band_integer`, which the
//! firmware traces with, refuses none.

use crate::common;

#[path = "../../../boards/rp2040/src/split.rs"]
mod split;

use embedded_raytracer_lab::scenes;

#[path = "../../../boards/rp2040/src/orbit.rs"]
pub(crate) mod orbit;

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_raytracer::{Arithmetic, Camera, Method, Render, Scene};

/// The firmware's panel (`boards/stm32f407/src/st7789_band.rs`: `WIDTH`, `HEIGHT`); its band
/// height is `split::BAND_ROWS`.
const FIRMWARE_SIZE: Size = Size::new(240, 240);

/// The frame as the display receives it: every core traces its bands
/// (`split::core_bands`) into its own buffers, and the bands go out in index order.
fn two_core_frame<const N: usize, C: PixelColor + From<Rgb888>>(
    render: &Render<'_, N, C>,
    size: Size,
    band_rows: u32,
) -> Vec<C> {
    let bands = split::band_count(size.height, band_rows);
    let mut sent: Vec<Option<Vec<C>>> = vec![None; bands as usize];
    for core in 0..split::CORES {
        for (k, rows) in split::core_bands(core, size.height, band_rows) {
            let mut buf = vec![C::from(Rgb888::new(1, 2, 3)); (size.width * rows.len() as u32) as usize];
            render.draw_band(rows, &mut buf).unwrap();
            let slot = &mut sent[k as usize];
            assert!(slot.is_none(), "band {k} traced twice");
            *slot = Some(buf);
        }
    }
    sent.into_iter()
        .enumerate()
        .flat_map(|(k, band)| band.unwrap_or_else(|| panic!("band {k} traced by no core")))
        .collect()
}

/// The whole render, drawn as one `Drawable` into a frame buffer, row-major.
fn whole<const N: usize>(scene: &Scene<N>, camera: &Camera, method: Method) -> Vec<Rgb888> {
    let mut frame = common::Frame::new(camera.size());
    Render::new(scene, camera)
        .with_method(method)
        .draw(&mut frame)
        .unwrap();
    frame
        .buf
        .into_iter()
        .map(|p| p.expect("every pixel drawn"))
        .collect()
}

#[test]
fn the_cores_take_alternate_bands_that_cover_every_row_once() {
    for (height, band_rows) in [
        (240, split::BAND_ROWS),
        (240, 16),
        (240, 7),
        (36, 5),
        (7, 3),
        (1, 1),
        (5, 9),
        (6, 2),
        (10, 0),
    ] {
        let bands = split::band_count(height, band_rows);
        let mut next_row = 0;
        let mut seen = 0;
        let per_core: Vec<Vec<_>> = (0..split::CORES)
            .map(|core| split::core_bands(core, height, band_rows).collect())
            .collect();
        for k in 0..bands {
            let core = split::core_of(k);
            assert_eq!(core, k % 2, "band {k}: alternate cores, core 0 first");
            let (band, rows) = per_core[core as usize]
                .iter()
                .find(|(band, _)| *band == k)
                .cloned()
                .unwrap_or_else(|| panic!("{height}/{band_rows}: band {k} not in core {core}'s list"));
            assert_eq!(band, k);
            assert_eq!(rows, split::band_rows(k, height, band_rows));
            assert_eq!(
                rows.start,
                next_row,
                "{height}/{band_rows}: band {k} starts where {} ended",
                k.max(1) - 1
            );
            assert!(!rows.is_empty() && rows.len() as u32 <= band_rows.max(1));
            next_row = rows.end;
            seen += 1;
        }
        assert_eq!(
            next_row, height,
            "{height}/{band_rows}: the bands end at the last row"
        );
        // Every core's list: its own bands only, in increasing order.
        let listed: usize = per_core.iter().map(Vec::len).sum();
        assert_eq!(
            listed, seen,
            "{height}/{band_rows}: no band listed twice or out of range"
        );
        for (core, list) in per_core.iter().enumerate() {
            assert!(
                list.windows(2).all(|w| w[0].0 < w[1].0),
                "core {core}: in band order"
            );
            assert!(list.iter().all(|(k, _)| split::core_of(*k) == core as u32));
        }
    }
}

#[test]
fn firmware_bands_equal_the_whole_render_on_every_standard_scene_and_method() {
    for name in common::SCENES {
        let file = common::load(name);
        let camera = common::at_size(file.camera.params(), FIRMWARE_SIZE);
        for method in Method::ALL.into_iter().chain([Method::INTEGER]) {
            let want = whole(&file.scene, &camera, method);
            let render = Render::<_, Rgb888>::new(&file.scene, &camera).with_method(method);
            let got = two_core_frame(&render, FIRMWARE_SIZE, split::BAND_ROWS);
            assert!(
                got == want,
                "{name} {method}: two-core bands differ from the whole render"
            );
        }
        // The firmware's method on the Pico (the integer kernel, the default without an
        // FPU) and pixel format: Rgb565 (sent high byte first: lab/tests/lab/band_wire.rs).
        let want = whole(&file.scene, &camera, Method::INTEGER);
        let rgb565 = Render::<_, Rgb565>::new(&file.scene, &camera).with_method(Method::INTEGER);
        let got = two_core_frame(&rgb565, FIRMWARE_SIZE, split::BAND_ROWS);
        let want565: Vec<Rgb565> = want.iter().map(|&c| c.into()).collect();
        assert!(
            got == want565,
            "{name}: two-core Rgb565 bands differ from the whole render"
        );
    }
}

#[test]
fn every_method_every_scene_every_band_height_equals_the_whole_render() {
    let size = Size::new(40, 30);
    for name in common::SCENES {
        let file = common::load(name);
        let camera = common::at_size(file.camera.params(), size);
        for method in Method::ALL.into_iter().chain([Method::INTEGER]) {
            let want = whole(&file.scene, &camera, method);
            let render = Render::<_, Rgb888>::new(&file.scene, &camera).with_method(method);
            // Bands that divide the height or not, an odd or even count of them, one
            // band per row, one band for the whole frame.
            for band_rows in [1, 4, 5, 7, 16, 30] {
                let got = two_core_frame(&render, size, band_rows);
                assert!(got == want, "{name} {method}: two-core bands of {band_rows} rows");
            }
        }
    }
}

/// The firmware draws every frame with `draw_band_integer`, which draws nothing where the
/// integer kernel's rule refuses the frame: on the orbit it must take every frame — the
/// first 20,000 angles the firmware steps through (from 0 by `orbit::next_angle`; the
/// whole cycle, until the angle is 0 again, is the `--ignored` test below) and the whole
/// circle every 0.01° — and, traced band by band in the firmware's bands, some of those
/// frames are the whole integer render's pixels.
#[test]
fn the_integer_kernel_takes_every_frame_of_the_firmware_orbit() {
    let taken = integer_takes;
    let mut angle = 0.0f32;
    for frame in 0..20_000 {
        assert!(taken(angle), "frame {frame} at {angle} rad: refused");
        angle = orbit::next_angle(angle);
    }
    for k in 0..36_000 {
        let angle = (k as f32 / 100.0).to_radians();
        assert!(taken(angle), "{} degrees: refused", k as f32 / 100.0);
    }
    // Frames 0, 18, 37 and 55 (0°, 90°, 185°, 275°): the firmware's bands, traced with
    // draw_band_integer, are the whole integer render.
    let mut angle = 0.0f32;
    for frame in 0..56 {
        if [0, 18, 37, 55].contains(&frame) {
            let camera = orbit::camera_at(angle, FIRMWARE_SIZE).unwrap();
            let want = whole(&scenes::LAB, &camera, Method::INTEGER);
            let render = Render::<_, Rgb888>::new(&scenes::LAB, &camera);
            let bands = split::band_count(FIRMWARE_SIZE.height, split::BAND_ROWS);
            let mut got = Vec::new();
            for k in 0..bands {
                let rows = split::band_rows(k, FIRMWARE_SIZE.height, split::BAND_ROWS);
                let mut buf = vec![Rgb888::new(1, 2, 3); (FIRMWARE_SIZE.width * rows.len() as u32) as usize];
                render.draw_band_integer(rows, &mut buf).unwrap();
                got.extend(buf);
            }
            assert!(
                got == want,
                "frame {frame}: integer bands differ from the whole render"
            );
        }
        angle = orbit::next_angle(angle);
    }
}

/// Whether the integer kernel takes the firmware's frame at `angle`.
fn integer_takes(angle: f32) -> bool {
    let camera = orbit::camera_at(angle, FIRMWARE_SIZE).unwrap_or_else(|| panic!("no camera at {angle}"));
    let render = Render::<_, Rgb565>::new(&scenes::LAB, &camera).with_method(Method::INTEGER);
    render.arithmetic() == Arithmetic::Integer
}

/// Every frame the firmware can draw: stepped by `orbit::next_angle` from 0, the `f32`
/// angle comes back to exactly 0 (after some 13 million frames) and the orbit repeats;
/// the rule takes every frame of that cycle. Slow in debug: run in release by `.ci/run`
/// (`cargo test --release --test rp2040_split -- --ignored`).
#[test]
#[ignore = "13 million per-frame rules: release only"]
fn the_integer_kernel_takes_the_whole_orbit_cycle() {
    let (mut angle, mut frames) = (0.0f32, 0u64);
    loop {
        assert!(integer_takes(angle), "frame {frames} at {angle} rad: refused");
        angle = orbit::next_angle(angle);
        frames += 1;
        if angle == 0.0 {
            break;
        }
        assert!(frames < 100_000_000, "the orbit did not come back to 0");
    }
    println!("the orbit repeats after {frames} frames, every one taken by the integer kernel");
}
