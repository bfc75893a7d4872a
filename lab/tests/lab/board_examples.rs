//! The board examples, drawn on the host through each one's own code — its `frame.rs`
//! (the frame through `Incremental` with the library's motion, and the status line
//! drawn over the picture; for the STM32 DMA example the changed runs it sends) and its
//! `scenes.rs` (the scene, camera and motion compiled in), the files the firmware
//! compiles — frame after frame, a whole loop of the motion and back to its first
//! frame: the panel then shows the library's whole render of the last frame, bit for
//! bit, status lines and all restored; the first frame is drawn whole and the others
//! only where they changed; the chips without an FPU take every frame with the integer
//! kernel. The compiled-in scenes and motions are the files, bit for bit.

use std::convert::Infallible;

use embedded_graphics::pixelcolor::{BinaryColor, Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_raytracer::dither::{dither, Bayer};
use embedded_raytracer::motion::{Animation, MotionError};
use embedded_raytracer::{
    scene_file, Arithmetic, Camera, CameraParams, FrameError, FrameStats, Incremental, Method, ObjectRef,
    Render, Scene, Vec3,
};
use embedded_raytracer_scenes as standard;

#[path = "../../../boards/rp2040/src/bin/simple/frame.rs"]
mod rp2040_simple;
// The Pico's scenes are `crate::scenes` (`boards/rp2040/src/scenes.rs`).

#[path = "../../../boards/rp2350/src/frame.rs"]
mod rp2350;
#[path = "../../../boards/rp2350/src/scenes.rs"]
mod rp2350_scenes;

#[path = "../../../boards/esp32c3/src/frame.rs"]
mod esp32c3;
#[path = "../../../boards/esp32c3/src/scenes.rs"]
mod esp32c3_scenes;

#[path = "../../../boards/rp2040-ssd1306/src/frame.rs"]
mod ssd1306;
#[path = "../../../boards/rp2040-ssd1306/src/scenes.rs"]
mod ssd1306_scenes;

#[path = "../../../boards/stm32f407/src/frame.rs"]
mod stm32f407;
// One module per file: `board_scenes` loads this board's scenes (its `lab` scene).
use crate::board_scenes::stm32f407 as stm32f407_scenes;
use crate::common::Panel;

/// The ST7789 panels.
const PANEL: Size = Size::new(240, 240);
/// The SSD1306.
const OLED: Size = Size::new(128, 64);

/// The library's whole render of `scene` seen by `camera` with `method`.
fn whole<C, const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    method: Method,
) -> Vec<C>
where
    C: PixelColor + From<Rgb888>,
{
    let mut panel = Panel::new(camera.size());
    let Ok(()) = Render::new(scene, camera).with_method(method).draw(&mut panel);
    panel.pixels()
}

/// A moving scene's compiled-in copy is the file: the scene at rest and its camera
/// (`firmware_scenes::same`), and the motion, frame rate and frames, bit for bit.
fn same_moving<const N: usize, const L: usize, const P: usize, const D: usize, const M: usize>(
    name: &str,
    scene: &Scene<N, L, P, D>,
    camera: CameraParams,
    animation: &Animation<M>,
) {
    crate::firmware_scenes::same(name, scene, camera);
    let loaded: scene_file::SceneFile<N, L, P, D> =
        scene_file::load(standard::path(name)).unwrap_or_else(|e| panic!("{e}"));
    let file = &loaded.animation;
    // `{:?}` prints each number's shortest round-trip form: equal text is equal bits.
    assert_eq!(
        format!("{:?}", file.motions()),
        format!("{:?}", animation.motions()),
        "{name}: motions differ"
    );
    assert_eq!(file.fps().to_bits(), animation.fps().to_bits(), "{name}: fps");
    assert_eq!(file.frames(), animation.frames(), "{name}: frames");
}

#[test]
fn the_boards_compiled_in_scenes_and_motions_are_the_files() {
    use crate::scenes as rp2040_scenes;
    same_moving(
        "circling",
        &rp2040_scenes::CIRCLING,
        rp2040_scenes::CIRCLING_CAMERA,
        &rp2040_scenes::CIRCLING_ANIMATION,
    );
    same_moving(
        "circling",
        &esp32c3_scenes::CIRCLING,
        esp32c3_scenes::CIRCLING_CAMERA,
        &esp32c3_scenes::CIRCLING_ANIMATION,
    );
    same_moving(
        "circling",
        &ssd1306_scenes::CIRCLING,
        ssd1306_scenes::CIRCLING_CAMERA,
        &ssd1306_scenes::CIRCLING_ANIMATION,
    );
    same_moving(
        "bounce",
        &rp2350_scenes::BOUNCE,
        rp2350_scenes::BOUNCE_CAMERA,
        &rp2350_scenes::BOUNCE_ANIMATION,
    );
    same_moving(
        "bounce",
        &stm32f407_scenes::BOUNCE,
        stm32f407_scenes::BOUNCE_CAMERA,
        &stm32f407_scenes::BOUNCE_ANIMATION,
    );
}

/// The frames of a whole loop of a motion of `frames` frames and back to its first, as
/// the firmware counts them.
fn a_loop(frames: u32) -> impl Iterator<Item = u32> {
    (0..=frames).map(move |k| k % frames)
}

/// An example's frames over a loop of its motion on one panel: `frame(panel, shown, k)`
/// draws frame `k` through the example's own `frame.rs` and returns its kernel and
/// statistics; `show(panel, shown, k, drawn)` draws the status line over it. The last
/// frame is left without one. Returns each frame's statistics, after checking that the
/// first frame is drawn whole and no other is.
fn sequence<T, S>(
    panel: &mut T,
    shown: &mut S,
    frames: u32,
    mut frame: impl FnMut(&mut T, &mut S, u32) -> (Arithmetic, FrameStats),
    mut show: impl FnMut(&mut T, &mut S, u32, (Arithmetic, FrameStats)),
) -> Vec<(Arithmetic, FrameStats)> {
    let ks: Vec<u32> = a_loop(frames).collect();
    let drawn: Vec<_> = ks
        .iter()
        .enumerate()
        .map(|(i, &k)| {
            let drawn = frame(panel, shown, k);
            if i + 1 < ks.len() {
                show(panel, shown, k, drawn);
            }
            drawn
        })
        .collect();
    for (i, (_, stats)) in drawn.iter().enumerate() {
        assert_eq!(stats.full, i == 0, "frame {i}: {stats:?}");
    }
    drawn
}

/// The mean and largest share of the panel (%) the frames after the first traced and
/// sent, printed.
fn report(what: &str, stats: &[(Arithmetic, FrameStats)], pixels: u32) -> (u32, u32) {
    let rest = &stats[1..];
    let pct = |n: u32| n * 100 / pixels;
    let mean =
        |f: fn(&FrameStats) -> u32| pct(rest.iter().map(|(_, s)| f(s)).sum::<u32>() / rest.len() as u32);
    let max = |f: fn(&FrameStats) -> u32| pct(rest.iter().map(|(_, s)| f(s)).max().unwrap_or(0));
    let (traced, sent) = (max(|s| s.traced), max(|s| s.sent));
    println!(
        "{what}: after the first frame, traced {}% (at most {traced}%), sent {}% (at most {sent}%) of the panel",
        mean(|s| s.traced),
        mean(|s| s.sent)
    );
    (traced, sent)
}

/// The Pico's simple example: the integer kernel takes every frame of a loop of
/// `circling` (the screen says `integer`), and the panel shows the whole integer render
/// of the last.
#[test]
fn rp2040_simple_draws_the_integer_render_of_every_frame() {
    use crate::scenes as rp2040_scenes;
    let film = rp2040_simple::Film {
        scene: &rp2040_scenes::CIRCLING,
        camera: rp2040_scenes::CIRCLING_CAMERA.with_size(PANEL),
        animation: &rp2040_scenes::CIRCLING_ANIMATION,
    };
    let mut scene = rp2040_scenes::CIRCLING.clone();
    let mut panel = Panel::new(PANEL);
    let stats = sequence(
        &mut panel,
        &mut Incremental::new(),
        film.animation.frames(),
        |panel, shown, k| match rp2040_simple::frame(panel, shown, &film, k, &mut scene) {
            Ok(drawn) => drawn,
            Err(_) => panic!("frame {k}: not drawn"),
        },
        |panel, shown, k, drawn| {
            let line = rp2040_simple::status::<Infallible>(&Ok(drawn), 90_000 + u64::from(k), 57_600, 0);
            let Ok(()) = rp2040_simple::show(panel, shown, &line);
        },
    );
    for (i, (arithmetic, _)) in stats.iter().enumerate() {
        assert_eq!(
            *arithmetic,
            Arithmetic::Integer,
            "frame {i}: not the integer kernel"
        );
    }
    report("rp2040 simple", &stats, 57_600);
    let camera = film.camera.build().unwrap();
    assert!(
        panel.pixels() == whole::<Rgb565, 3, 0, 0, 0>(&scene, &camera, Method::INTEGER),
        "the last frame differs from the whole render"
    );
}

/// The ESP32-C3: as the Pico's simple example, through its own files.
#[test]
fn esp32c3_draws_the_integer_render_of_every_frame() {
    let film = esp32c3::Film {
        scene: &esp32c3_scenes::CIRCLING,
        camera: esp32c3_scenes::CIRCLING_CAMERA.with_size(PANEL),
        animation: &esp32c3_scenes::CIRCLING_ANIMATION,
    };
    let mut scene = esp32c3_scenes::CIRCLING.clone();
    let mut panel = Panel::new(PANEL);
    let stats = sequence(
        &mut panel,
        &mut Incremental::new(),
        film.animation.frames(),
        |panel, shown, k| match esp32c3::frame(panel, shown, &film, k, &mut scene) {
            Ok(drawn) => drawn,
            Err(_) => panic!("frame {k}: not drawn"),
        },
        |panel, shown, k, drawn| {
            let line = esp32c3::status::<Infallible>(&Ok(drawn), 90_000 + u64::from(k), 57_600, 0);
            let Ok(()) = esp32c3::show(panel, shown, &line);
        },
    );
    for (i, (arithmetic, _)) in stats.iter().enumerate() {
        assert_eq!(
            *arithmetic,
            Arithmetic::Integer,
            "frame {i}: not the integer kernel"
        );
    }
    report("esp32c3", &stats, 57_600);
    let camera = film.camera.build().unwrap();
    assert!(
        panel.pixels() == whole::<Rgb565, 3, 0, 0, 0>(&scene, &camera, Method::INTEGER),
        "the last frame differs from the whole render"
    );
}

/// The SSD1306: the integer kernel takes every 128×64 frame of a loop, and the 1-bit
/// panel shows the last frame's whole integer render dithered pixel by pixel (8×8
/// matrix).
#[test]
fn ssd1306_draws_the_dithered_integer_render_of_every_frame() {
    let film = ssd1306::Film {
        scene: &ssd1306_scenes::CIRCLING,
        camera: ssd1306_scenes::CIRCLING_CAMERA.with_size(OLED),
        animation: &ssd1306_scenes::CIRCLING_ANIMATION,
    };
    let mut scene = ssd1306_scenes::CIRCLING.clone();
    let mut panel = Panel::new(OLED);
    let stats = sequence(
        &mut panel,
        &mut Incremental::new(),
        film.animation.frames(),
        |panel, shown, k| match ssd1306::frame(panel, shown, &film, k, &mut scene) {
            Ok(drawn) => drawn,
            Err(_) => panic!("frame {k}: not drawn"),
        },
        |panel, shown, k, drawn| {
            // As the firmware: no frame rate before a frame has been timed.
            let us = (k != 0).then(|| 900_000 + u64::from(k));
            let line = ssd1306::status::<Infallible>(&Ok(drawn), us, 8_192, 0);
            let Ok(()) = ssd1306::show(panel, shown, &line);
        },
    );
    for (i, (arithmetic, _)) in stats.iter().enumerate() {
        assert_eq!(
            *arithmetic,
            Arithmetic::Integer,
            "frame {i}: not the integer kernel"
        );
    }
    report("ssd1306", &stats, 8_192);
    let camera = film.camera.build().unwrap();
    let want: Vec<BinaryColor> = whole::<Rgb888, 3, 0, 0, 0>(&scene, &camera, Method::INTEGER)
        .into_iter()
        .enumerate()
        .map(|(i, c)| {
            let p = Point::new((i as u32 % OLED.width) as i32, (i as u32 / OLED.width) as i32);
            dither(c, p, Bayer::Eight)
        })
        .collect();
    assert!(
        panel.pixels() == want,
        "the last frame differs from the dithered whole render"
    );
}

/// The Pico 2: a loop of `bounce` drawn incrementally through its `frame.rs`, the panel
/// shows the whole `f32` render of the lit scene's last frame; after the first, a frame
/// traces and sends less than a quarter of the panel (the ball, its shadow, the
/// spheres the shadow can fall on, and the status line).
#[test]
fn rp2350_draws_the_lit_render_of_every_frame() {
    let film = rp2350::Film {
        scene: &rp2350_scenes::BOUNCE,
        camera: rp2350_scenes::BOUNCE_CAMERA.with_size(PANEL),
        animation: &rp2350_scenes::BOUNCE_ANIMATION,
    };
    let mut scene = rp2350_scenes::BOUNCE.clone();
    let mut panel = Panel::new(PANEL);
    let stats = sequence(
        &mut panel,
        &mut Incremental::new(),
        film.animation.frames(),
        |panel, shown, k| match rp2350::frame(panel, shown, &film, k, &mut scene) {
            Ok(stats) => (Arithmetic::F32, stats),
            Err(_) => panic!("frame {k}: not drawn"),
        },
        |panel, shown, k, (_, stats)| {
            let line = rp2350::status::<Infallible>(&Ok(stats), 90_000 + u64::from(k), 57_600, 0);
            let Ok(()) = rp2350::show(panel, shown, &line);
        },
    );
    let (traced, sent) = report("rp2350", &stats, 57_600);
    assert!(traced < 25 && sent < 25, "traced {traced}%, sent {sent}%");
    let camera = film.camera.build().unwrap();
    assert!(
        panel.pixels() == whole::<Rgb565, 3, 1, 1, 0>(&scene, &camera, Method::default()),
        "the last frame differs from the whole render"
    );
}

/// The ST7789's memory as the STM32 DMA example writes it: an address window, and a
/// write pointer that walks it row by row.
struct Controller {
    px: Vec<Option<Rgb565>>,
    window: (std::ops::Range<u32>, std::ops::Range<u32>),
    at: u32,
}

impl stm32f407::Wire<Rgb565> for Controller {
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
            self.px[(j * PANEL.width + i) as usize] = Some(c);
            self.at += 1;
        }
    }
}

/// The STM32F407 DMA example: its first frame whole (every band traced and sent in one
/// window, as its DMA path does), then a loop of `bounce` through `update` and its
/// `frame.rs`'s `send_runs` (each run in its own window, a label over band 0 every
/// frame and `invalidate_area` for it): the controller's memory holds the whole render
/// of the last frame, label rows included, and no frame after the first sends a
/// quarter of the panel.
#[test]
fn stm32f407_sends_the_changed_runs_of_every_frame() {
    use stm32f407::Wire as _;
    const BAND_ROWS: u32 = 16;
    let base = stm32f407_scenes::BOUNCE_CAMERA.with_size(PANEL);
    let animation = &stm32f407_scenes::BOUNCE_ANIMATION;
    let mut scene = stm32f407_scenes::BOUNCE.clone();
    let mut display_has = Incremental::<3, 1, 1, 0>::new();
    let mut lcd = Controller {
        px: vec![None; (PANEL.width * PANEL.height) as usize],
        window: (0..0, 0..0),
        at: 0,
    };
    let label_area = embedded_graphics::primitives::Rectangle::new(
        Point::zero(),
        Size::new(PANEL.width, stm32f407::LABEL_ROWS),
    );
    let mut buf = vec![Rgb565::BLACK; (PANEL.width * BAND_ROWS) as usize];
    let ks: Vec<u32> = a_loop(animation.frames()).collect();
    let mut sends = Vec::new();
    for (i, &k) in ks.iter().enumerate() {
        let mut params = base;
        animation
            .apply_frame(&stm32f407_scenes::BOUNCE, &base, k, &mut scene, &mut params)
            .unwrap();
        let camera = params.build().unwrap();
        let render = Render::<_, Rgb565, 1, 1, 0>::new(&scene, &camera);
        let changes = display_has.update(&render);
        assert_eq!(changes.is_full(), i == 0, "frame {i}");
        // A label: white where the text would be, on the last frame none.
        let last = i + 1 == ks.len();
        let label = |band: &mut [Rgb565]| {
            if !last {
                band[(3 * PANEL.width + 2) as usize..(3 * PANEL.width + 40) as usize].fill(Rgb565::WHITE);
            }
        };
        if changes.is_full() {
            lcd.window(0..PANEL.width, 0..PANEL.height);
            for top in (0..PANEL.height).step_by(BAND_ROWS as usize) {
                render.draw_band(top..top + BAND_ROWS, &mut buf).unwrap();
                if top == 0 {
                    label(&mut buf);
                }
                lcd.pixels(&buf);
            }
        } else {
            let sent = stm32f407::send_runs(&changes, &render, BAND_ROWS, &mut buf, label, &mut lcd).unwrap();
            assert!(
                sent < PANEL.width * PANEL.height / 4,
                "frame {i}: {sent} pixels sent"
            );
            sends.push(sent);
        }
        display_has.invalidate_area(label_area);
    }
    println!(
        "stm32f407: after the first frame, {}–{} pixels sent a frame",
        sends.iter().min().unwrap(),
        sends.iter().max().unwrap()
    );
    let want = whole::<Rgb565, 3, 1, 1, 0>(&scene, &camera_of(base), Method::default());
    assert!(
        lcd.px
            .into_iter()
            .map(|p| p.expect("every pixel written"))
            .collect::<Vec<_>>()
            == want,
        "the last frame differs from the whole render"
    );
}

/// The camera of `params` (one no motion moves).
fn camera_of(params: CameraParams) -> Camera {
    params.build().unwrap()
}

/// Every status line the examples can show fits their label buffer (the kernel's
/// longest message, a camera error), and draws.
#[test]
fn every_status_line_fits_and_draws() {
    let far = FrameError::Magnitudes {
        far: ObjectRef::Light(1),
        near: ObjectRef::Sphere(3),
    };
    let Err(camera_error) = Camera::new(
        Vec3::new(0.0, 0.0, 5.0),
        Vec3::ZERO,
        Vec3::new(0.0, 0.0, 1.0),
        1.0,
        PANEL,
    ) else {
        panic!("a camera looking along its up vector was accepted");
    };
    let motion_error = MotionError::NoSuchSphere { motion: 2, sphere: 9 };
    let stats = FrameStats::default();
    let px = PANEL.width * PANEL.height;
    let lines = [
        rp2040_simple::status::<Infallible>(&Err(rp2040_simple::Failed::Frame(far)), 1, px, 3),
        rp2040_simple::status::<Infallible>(&Err(rp2040_simple::Failed::Camera(camera_error)), 1, px, 0),
        rp2040_simple::status::<Infallible>(&Ok((Arithmetic::F32, stats)), 812_345, px, 0),
        esp32c3::status::<Infallible>(&Err(esp32c3::Failed::Frame(far)), 1, px, 3),
        esp32c3::status::<Infallible>(&Err(esp32c3::Failed::Camera(camera_error)), 1, px, 0),
        esp32c3::status::<Infallible>(&Err(esp32c3::Failed::Motion(motion_error)), 1, px, 3),
        rp2040_simple::status::<Infallible>(&Err(rp2040_simple::Failed::Motion(motion_error)), 1, px, 3),
        ssd1306::status::<Infallible>(&Err(ssd1306::Failed::Motion(motion_error)), Some(1), 8_192, 3),
        ssd1306::status::<Infallible>(&Err(ssd1306::Failed::Frame(far)), Some(1), 8_192, 3),
        ssd1306::status::<Infallible>(&Err(ssd1306::Failed::Camera(camera_error)), None, 8_192, 0),
        rp2350::status::<Infallible>(&Err(rp2350::Failed::Frame(far)), 1, px, 3),
        rp2350::status::<Infallible>(&Err(rp2350::Failed::Camera(camera_error)), 1, px, 0),
        rp2350::status::<Infallible>(&Err(rp2350::Failed::Motion(motion_error)), 1, px, 0),
        rp2350::status::<Infallible>(&Ok(stats), 812_345, px, 0),
    ];
    for line in &lines {
        assert!(!line.contains("too long"), "{line}");
        assert!(line.is_ascii(), "{line}: the lines are cut at bytes");
    }
    assert!(lines[0].contains(&far.to_string()), "{}", lines[0]);
    assert!(
        lines[2].starts_with("f32 (integer refused) 1.2 fps sent 0%"),
        "{}",
        lines[2]
    );
    // The frame-rate lines fit one line of their panel (39 and 21 characters).
    assert!(lines[13].len() <= 39, "{}", lines[13]);
    let oled_line = ssd1306::status::<Infallible>(&Ok((Arithmetic::Integer, stats)), Some(1_000), 8_192, 0);
    assert!(oled_line.len() <= 21, "{oled_line}");
    // Before the first frame has been timed the SSD1306 shows no frame rate.
    let first_line = ssd1306::status::<Infallible>(&Ok((Arithmetic::Integer, stats)), None, 8_192, 0);
    assert_eq!(first_line, "int 0%");

    // The longest line drawn: every line within the panel, nothing outside it; the
    // lines' rectangles go to `Incremental`, which has nothing to restore before a
    // first frame.
    let mut panel = Panel::<Rgb565>::new(PANEL);
    let Ok(()) = rp2350::show(&mut panel, &mut Incremental::<4, 2, 1, 0>::new(), &lines[10]);
    let Ok(()) = rp2040_simple::show(&mut panel, &mut Incremental::<5>::new(), &lines[0]);
    let Ok(()) = esp32c3::show(&mut panel, &mut Incremental::<5>::new(), &lines[3]);
    assert!(panel.px.iter().any(Option::is_some));
    let mut oled = Panel::<BinaryColor>::new(OLED);
    let Ok(()) = ssd1306::show(&mut oled, &mut Incremental::<5>::new(), &lines[8]);
    assert!(oled.px.iter().any(Option::is_some));
}
