//! The RP2040 firmware's two-core band split (`boards/rp2040/src/split.rs`, the same
//! file the firmware compiles): the cores' alternate bands cover every row exactly once,
//! and, traced by `Render::draw_band` and put on the wire in band order, they are the
//! whole render's pixels bit for bit — at the firmware's 240×240 in its bands, and
//! at a smaller size with several band heights, on every standard scene with every
//! method. And the firmware's frames over its motion (`scenes/circling.toml`, compiled in
//! by its `scenes.rs`): the integer kernel's rule takes every frame, so
//! `Render::draw_band_integer` and `draw_integer`, which the firmware traces with,
//! refuse none; the first frame goes out whole from both cores' bands, every later one
//! as changed runs (`boards/rp2040/src/runs.rs`), and the display ends with the whole
//! render of the last.

use crate::common;

#[path = "../../../boards/rp2040/src/split.rs"]
mod split;

#[path = "../../../boards/rp2040/src/runs.rs"]
mod runs;

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

/// The ST7789's memory as the firmware writes it: an address window, and a write
/// pointer that walks it row by row.
struct Controller {
    px: Vec<Option<Rgb565>>,
    window: (std::ops::Range<u32>, std::ops::Range<u32>),
    at: u32,
}

impl runs::Wire<Rgb565> for Controller {
    fn window(&mut self, x: std::ops::Range<u32>, y: std::ops::Range<u32>) {
        self.window = (x, y);
        self.at = 0;
    }

    fn pixels(&mut self, pixels: &[Rgb565]) {
        let (x, y) = self.window.clone();
        for &c in pixels {
            let (i, j) = (
                x.start + self.at % x.len() as u32,
                y.start + self.at / x.len() as u32,
            );
            assert!(y.contains(&j), "a pixel past the window");
            self.px[(j * FIRMWARE_SIZE.width + i) as usize] = Some(c);
            self.at += 1;
        }
    }
}

/// The firmware's frames over a loop of its motion (`scenes::CIRCLING_ANIMATION`, the
/// firmware's own `scenes.rs`) and back to its first frame, as it draws them: the
/// integer kernel's rule takes every frame (`draw_band_integer` and `draw_integer`
/// draw nothing where it does not); core 0's `update` plans the first frame whole,
/// whose bands, traced in the firmware's bands by both cores, are the whole integer
/// render; every later frame is changed runs, which `runs::send_runs` (the firmware's
/// own file) traces and sends window by window, a label over band 0 each frame; and
/// the display then holds the whole integer render of the last frame.
#[test]
fn the_firmware_draws_every_frame_of_its_motion() {
    let animation = &crate::scenes::CIRCLING_ANIMATION;
    let base = crate::scenes::CIRCLING_CAMERA.with_size(FIRMWARE_SIZE);
    let mut scene = crate::scenes::CIRCLING.clone();
    let mut display_has = embedded_raytracer::Incremental::<3>::new();
    let mut lcd = Controller {
        px: vec![None; (FIRMWARE_SIZE.width * FIRMWARE_SIZE.height) as usize],
        window: (0..0, 0..0),
        at: 0,
    };
    let label_area =
        embedded_graphics::primitives::Rectangle::new(Point::zero(), Size::new(FIRMWARE_SIZE.width, 12));
    let mut buf = vec![Rgb565::BLACK; (FIRMWARE_SIZE.width * split::BAND_ROWS) as usize];
    let frames = animation.frames();
    let mut camera = None;
    for (i, k) in (0..=frames).map(|k| k % frames).enumerate() {
        let mut params = base;
        animation
            .apply_frame(&crate::scenes::CIRCLING, &base, k, &mut scene, &mut params)
            .unwrap();
        let cam = params.build().unwrap();
        let render = Render::<_, Rgb565>::new(&scene, &cam).with_method(Method::INTEGER);
        assert_eq!(render.arithmetic(), Arithmetic::Integer, "frame {k}: refused");
        let changes = display_has.update(&render);
        assert!(changes.refused().is_none(), "frame {k}");
        assert_eq!(changes.is_full(), i == 0, "frame {i}");
        let last = i == frames as usize;
        let label = |band: &mut [Rgb565]| {
            if !last {
                band[(3 * FIRMWARE_SIZE.width + 2) as usize..(3 * FIRMWARE_SIZE.width + 40) as usize]
                    .fill(Rgb565::WHITE);
            }
        };
        if changes.is_full() {
            let got = two_core_frame(&render, FIRMWARE_SIZE, split::BAND_ROWS);
            let want = whole(&scene, &cam, Method::INTEGER);
            assert!(
                got == want.into_iter().map(Rgb565::from).collect::<Vec<_>>(),
                "frame {k}: the two cores' bands differ from the whole render"
            );
            lcd.window = (0..FIRMWARE_SIZE.width, 0..FIRMWARE_SIZE.height);
            lcd.at = 0;
            let mut px = got;
            label(&mut px[..]);
            runs::Wire::pixels(&mut lcd, &px);
        } else {
            runs::send_runs(&changes, &render, split::BAND_ROWS, &mut buf, label, &mut lcd).unwrap();
        }
        display_has.invalidate_area(label_area);
        camera = Some(cam);
    }
    let want: Vec<Rgb565> = whole(&scene, &camera.unwrap(), Method::INTEGER)
        .into_iter()
        .map(Rgb565::from)
        .collect();
    assert!(
        lcd.px
            .into_iter()
            .map(|p| p.expect("every pixel written"))
            .collect::<Vec<_>>()
            == want,
        "the last frame differs from the whole render"
    );
}

/// A frame in which nothing moved but the label was drawn over the picture
/// (`invalidate_area`): core 0 sends the label's runs alone, and nothing else.
#[test]
fn a_frame_without_motion_sends_only_the_label() {
    let camera = crate::scenes::CIRCLING_CAMERA
        .with_size(FIRMWARE_SIZE)
        .build()
        .unwrap();
    let mut display_has = embedded_raytracer::Incremental::<3>::new();
    let render = Render::<_, Rgb565>::new(&crate::scenes::CIRCLING, &camera).with_method(Method::INTEGER);
    assert!(display_has.update(&render).is_full());
    let label =
        embedded_graphics::primitives::Rectangle::new(Point::zero(), Size::new(FIRMWARE_SIZE.width, 12));
    display_has.invalidate_area(label);
    let changes = display_has.update(&render);
    assert!(!changes.is_full() && !changes.is_empty());
    for j in 0..FIRMWARE_SIZE.height {
        let runs: Vec<_> = changes.runs(j).collect();
        let want = if j < 12 {
            vec![(0, FIRMWARE_SIZE.width)]
        } else {
            vec![]
        };
        assert_eq!(runs, want, "row {j}");
    }
}
