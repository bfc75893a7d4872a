//! The design card's "tested on the host with the simulator": a frame drawn into
//! embedded-graphics-simulator's headless `SimulatorDisplay` is the frame drawn into
//! any other target, pixel for pixel, in the display's own colour format.

use embedded_graphics::pixelcolor::{BinaryColor, Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::SimulatorDisplay;
use embedded_raytracer::dither::DitherExt;
use embedded_raytracer::{Camera, Render};

use crate::common::{self, load, load_full};

/// Every pixel of a simulator display, row-major.
fn pixels<C: PixelColor>(display: &SimulatorDisplay<C>) -> Vec<C> {
    let size = display.size();
    (0..size.height as i32)
        .flat_map(|y| (0..size.width as i32).map(move |x| Point::new(x, y)))
        .map(|p| display.get_pixel(p))
        .collect()
}

/// The colour of every traced pixel of `render`, row-major: the kernel's own stream.
fn traced<const N: usize, const L: usize, const P: usize, const D: usize>(
    render: Render<'_, N, Rgb888, L, P, D>,
) -> Vec<Rgb888> {
    common::trace(render)
        .into_iter()
        .map(|(_, color, _)| color)
        .collect()
}

#[test]
fn lab_scene_in_the_simulator_is_the_traced_frame_in_rgb888_and_rgb565() {
    let file = load("lab");
    let camera: Camera = file.camera;
    let expected = traced(Render::new(&file.scene, &camera));

    let mut rgb888 = SimulatorDisplay::<Rgb888>::new(camera.size());
    Render::new(&file.scene, &camera).draw(&mut rgb888).unwrap();
    assert_eq!(pixels(&rgb888), expected);

    let mut rgb565 = SimulatorDisplay::<Rgb565>::new(camera.size());
    Render::new(&file.scene, &camera).draw(&mut rgb565).unwrap();
    let converted: Vec<Rgb565> = expected.iter().map(|&c| Rgb565::from(c)).collect();
    assert_eq!(pixels(&rgb565), converted);
}

#[test]
fn lit_scenes_in_the_simulator_are_the_traced_frames() {
    for name in common::FEATURE_SCENES {
        let file = load_full(name);
        let camera: Camera = file.camera;
        let mut display = SimulatorDisplay::<Rgb888>::new(camera.size());
        Render::new(&file.scene, &camera).draw(&mut display).unwrap();
        assert_eq!(
            pixels(&display),
            traced(Render::new(&file.scene, &camera)),
            "{name}"
        );
    }
}

#[test]
fn a_one_bit_simulator_display_gets_the_ordered_dither() {
    // A BinaryColor display takes the dithered stream: some pixels on, some off (the lab
    // scene is neither all background nor all sphere), and the same as dithering into
    // any other BinaryColor target.
    let file = load("lab");
    let camera: Camera = file.camera;
    let mut display = SimulatorDisplay::<BinaryColor>::new(camera.size());
    Render::new(&file.scene, &camera)
        .draw(&mut display.dithered())
        .unwrap();
    let shown = pixels(&display);
    let on = shown.iter().filter(|&&c| c == BinaryColor::On).count();
    assert!(on > 0 && on < shown.len(), "{on} of {} pixels on", shown.len());

    let mut again = SimulatorDisplay::<BinaryColor>::new(camera.size());
    Render::new(&file.scene, &camera)
        .draw(&mut again.dithered())
        .unwrap();
    assert_eq!(pixels(&again), shown);
}
