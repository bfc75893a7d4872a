//! The simple board examples (`boards/rp2040/src/bin/simple`, `boards/rp2350`,
//! `boards/esp32c3`, `boards/rp2040-ssd1306`), drawn on the host through each one's own
//! code — its `frame.rs` (the one call that draws a frame, and the status line) and its
//! `orbit.rs` (the camera sequence), the files the firmware compiles — against the
//! library's whole render: the same pixels, frame after frame of the orbit, and the
//! kernel the screen names (the integer kernel on the chips without an FPU, which must
//! take every frame of the orbit; the `f32` kernel's `check` on the Pico 2). Their
//! compiled-in scenes are the files, bit for bit.

use std::convert::Infallible;

use embedded_graphics::pixelcolor::{BinaryColor, Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_raytracer::dither::{dither, Bayer};
use embedded_raytracer::{Arithmetic, Camera, FrameError, Method, ObjectRef, Render, Scene, Vec3};

#[path = "../../../boards/rp2040/src/bin/simple/frame.rs"]
mod rp2040_simple;
// The Pico's orbit (shared with the two-core example, whose test compiles it; its
// scene is `crate::scenes`).
use crate::rp2040_split::orbit as rp2040_orbit;

#[path = "../../../boards/rp2350/src/frame.rs"]
mod rp2350;
#[path = "../../../boards/rp2350/src/orbit.rs"]
mod rp2350_orbit;
#[path = "../../../boards/rp2350/src/scenes.rs"]
mod rp2350_scenes;

#[path = "../../../boards/esp32c3/src/frame.rs"]
mod esp32c3;
#[path = "../../../boards/esp32c3/src/orbit.rs"]
mod esp32c3_orbit;
#[path = "../../../boards/esp32c3/src/scenes.rs"]
mod esp32c3_scenes;

#[path = "../../../boards/rp2040-ssd1306/src/frame.rs"]
mod ssd1306;
#[path = "../../../boards/rp2040-ssd1306/src/orbit.rs"]
mod ssd1306_orbit;
#[path = "../../../boards/rp2040-ssd1306/src/scenes.rs"]
mod ssd1306_scenes;

/// The ST7789 panels.
const PANEL: Size = Size::new(240, 240);
/// The SSD1306.
const OLED: Size = Size::new(128, 64);
/// Frames whose pixels are compared in full: 0°, 90°, 185°, 275° of the orbit.
const FULL: [u32; 4] = [0, 18, 37, 55];
/// Frames whose kernel choice is checked (cheap: no pixel traced): 2,000 frames, 27
/// times round the orbit.
const FRAMES: u32 = 2_000;

/// A display on the host: what was drawn where, `None` where nothing was.
struct Panel<C> {
    size: Size,
    px: Vec<Option<C>>,
}

impl<C: PixelColor> Panel<C> {
    fn new(size: Size) -> Self {
        Self {
            size,
            px: vec![None; (size.width * size.height) as usize],
        }
    }

    /// Every pixel, all drawn.
    fn pixels(self) -> Vec<C> {
        self.px
            .into_iter()
            .map(|p| p.expect("every pixel drawn"))
            .collect()
    }
}

impl<C: PixelColor> OriginDimensions for Panel<C> {
    fn size(&self) -> Size {
        self.size
    }
}

impl<C: PixelColor> DrawTarget for Panel<C> {
    type Color = C;
    type Error = Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(&mut self, pixels: I) -> Result<(), Infallible> {
        for Pixel(p, c) in pixels {
            if self.bounding_box().contains(p) {
                self.px[(p.y as u32 * self.size.width + p.x as u32) as usize] = Some(c);
            }
        }
        Ok(())
    }
}

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

/// The orbit's angles, frame by frame, as the firmware steps them.
fn angles(next: fn(f32) -> f32) -> impl Iterator<Item = (u32, f32)> {
    (0..FRAMES).scan(0.0f32, move |angle, k| {
        let this = *angle;
        *angle = next(this);
        Some((k, this))
    })
}

#[test]
fn the_boards_compiled_in_scenes_are_the_files() {
    crate::board_scenes::check("boards/esp32c3", &esp32c3_scenes::LAB, esp32c3_scenes::LAB_CAMERA);
    crate::board_scenes::check(
        "boards/rp2040-ssd1306",
        &ssd1306_scenes::LAB,
        ssd1306_scenes::LAB_CAMERA,
    );
    crate::firmware_scenes::same("shadows", &rp2350_scenes::SHADOWS, rp2350_scenes::SHADOWS_CAMERA);
}

/// The Pico's simple example: the integer kernel takes every frame (the screen says
/// `integer`), and its frames are the whole integer render.
#[test]
fn rp2040_simple_draws_the_integer_render_of_every_orbit_frame() {
    for (k, angle) in angles(rp2040_orbit::next_angle) {
        let camera = rp2040_orbit::camera_at(angle, PANEL).unwrap_or_else(|| panic!("frame {k}: no camera"));
        let render = Render::<_, Rgb565>::new(&crate::scenes::LAB, &camera).with_method(Method::INTEGER);
        assert_eq!(render.arithmetic(), Arithmetic::Integer, "frame {k}: refused");
        if FULL.contains(&k) {
            let mut panel = Panel::new(PANEL);
            let drawn = rp2040_simple::frame(&mut panel, &crate::scenes::LAB, Some(&camera));
            assert!(
                matches!(drawn, Ok(rp2040_simple::Kernel::Integer)),
                "frame {k}: not the integer kernel"
            );
            assert!(
                panel.pixels() == whole::<Rgb565, 5, 0, 0, 0>(&crate::scenes::LAB, &camera, Method::INTEGER),
                "frame {k}: differs from the whole render"
            );
        }
    }
}

/// The ESP32-C3: as the Pico's simple example, through its own files.
#[test]
fn esp32c3_draws_the_integer_render_of_every_orbit_frame() {
    for (k, angle) in angles(esp32c3_orbit::next_angle) {
        let camera = esp32c3_orbit::orbit(&esp32c3_scenes::LAB_CAMERA, angle, PANEL)
            .unwrap_or_else(|e| panic!("frame {k}: {e}"));
        let render = Render::<_, Rgb565>::new(&esp32c3_scenes::LAB, &camera).with_method(Method::INTEGER);
        assert_eq!(render.arithmetic(), Arithmetic::Integer, "frame {k}: refused");
        if FULL.contains(&k) {
            let mut panel = Panel::new(PANEL);
            let drawn = esp32c3::frame(&mut panel, &esp32c3_scenes::LAB, Ok(camera));
            assert!(
                matches!(drawn, Ok(esp32c3::Kernel::Integer)),
                "frame {k}: not the integer kernel"
            );
            assert!(
                panel.pixels() == whole::<Rgb565, 5, 0, 0, 0>(&esp32c3_scenes::LAB, &camera, Method::INTEGER),
                "frame {k}: differs from the whole render"
            );
        }
    }
}

/// The SSD1306: the integer kernel takes every 128×64 frame of the orbit, and the
/// 1-bit frame is the whole integer render dithered pixel by pixel (8×8 matrix).
#[test]
fn ssd1306_draws_the_dithered_integer_render_of_every_orbit_frame() {
    for (k, angle) in angles(ssd1306_orbit::next_angle) {
        let camera = ssd1306_orbit::orbit(&ssd1306_scenes::LAB_CAMERA, angle, OLED)
            .unwrap_or_else(|e| panic!("frame {k}: {e}"));
        let render = Render::<_, Rgb888>::new(&ssd1306_scenes::LAB, &camera).with_method(Method::INTEGER);
        assert_eq!(render.arithmetic(), Arithmetic::Integer, "frame {k}: refused");
        if FULL.contains(&k) {
            let mut panel = Panel::new(OLED);
            let drawn = ssd1306::frame(&mut panel, &ssd1306_scenes::LAB, Ok(camera));
            assert!(
                matches!(drawn, Ok(ssd1306::Kernel::Integer)),
                "frame {k}: not the integer kernel"
            );
            let want: Vec<BinaryColor> =
                whole::<Rgb888, 5, 0, 0, 0>(&ssd1306_scenes::LAB, &camera, Method::INTEGER)
                    .into_iter()
                    .enumerate()
                    .map(|(i, c)| {
                        let p = Point::new((i as u32 % OLED.width) as i32, (i as u32 / OLED.width) as i32);
                        dither(c, p, Bayer::Eight)
                    })
                    .collect();
            assert!(
                panel.pixels() == want,
                "frame {k}: differs from the dithered whole render"
            );
        }
    }
}

/// The Pico 2: `check` passes every frame of the orbit (no error screen), and the
/// frames are the whole `f32` render of the lit scene.
#[test]
fn rp2350_draws_the_lit_render_of_every_orbit_frame() {
    for (k, angle) in angles(rp2350_orbit::next_angle) {
        let camera = rp2350_orbit::orbit(&rp2350_scenes::SHADOWS_CAMERA, angle, PANEL)
            .unwrap_or_else(|e| panic!("frame {k}: {e}"));
        let render = Render::<_, Rgb565, 2, 1, 0>::new(&rp2350_scenes::SHADOWS, &camera);
        assert_eq!(render.check(), Ok(()), "frame {k}");
        if FULL.contains(&k) {
            let mut panel = Panel::new(PANEL);
            let drawn = rp2350::frame(&mut panel, &rp2350_scenes::SHADOWS, Ok(camera));
            assert!(drawn.is_ok(), "frame {k}: not drawn");
            assert!(
                panel.pixels()
                    == whole::<Rgb565, 4, 2, 1, 0>(&rp2350_scenes::SHADOWS, &camera, Method::default()),
                "frame {k}: differs from the whole render"
            );
        }
    }
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
    let lines = [
        rp2040_simple::status::<Infallible>(&Err(rp2040_simple::Failed::Frame(far)), 1, 3),
        rp2040_simple::status::<Infallible>(&Err(rp2040_simple::Failed::Camera), 1, 0),
        rp2040_simple::status::<Infallible>(&Ok(rp2040_simple::Kernel::F32), 812_345, 0),
        esp32c3::status::<Infallible>(&Err(esp32c3::Failed::Frame(far)), 1, 3),
        esp32c3::status::<Infallible>(&Err(esp32c3::Failed::Camera(camera_error)), 1, 0),
        esp32c3::status::<Infallible>(&Ok(esp32c3::Kernel::Integer), 812_345, 0),
        ssd1306::status::<Infallible>(&Err(ssd1306::Failed::Frame(far)), 1, 3),
        ssd1306::status::<Infallible>(&Err(ssd1306::Failed::Camera(camera_error)), 1, 0),
        rp2350::status::<Infallible>(&Err(rp2350::Failed::Frame(far)), 1, 3),
        rp2350::status::<Infallible>(&Err(rp2350::Failed::Camera(camera_error)), 1, 0),
        rp2350::status::<Infallible>(&Ok(()), 812_345, 0),
    ];
    for line in &lines {
        assert!(!line.contains("too long"), "{line}");
        assert!(line.is_ascii(), "{line}: the lines are cut at bytes");
    }
    assert!(lines[0].contains(&far.to_string()), "{}", lines[0]);
    assert!(
        lines[2].starts_with("f32 (integer refused) 1.2 fps"),
        "{}",
        lines[2]
    );

    // The longest line drawn: every line within the panel, nothing outside it.
    let mut panel = Panel::<Rgb565>::new(PANEL);
    let Ok(()) = rp2350::show(&mut panel, &lines[8]);
    let Ok(()) = rp2040_simple::show(&mut panel, &lines[0]);
    let Ok(()) = esp32c3::show(&mut panel, &lines[3]);
    assert!(panel.px.iter().any(Option::is_some));
    let mut oled = Panel::<BinaryColor>::new(OLED);
    let Ok(()) = ssd1306::show(&mut oled, &lines[6]);
    assert!(oled.px.iter().any(Option::is_some));
}
