//! The library on the host: a scene built in code, drawn into embedded-graphics-simulator's
//! headless display (any `DrawTarget` works the same way) and saved as a PNG.
//!
//! ```sh
//! cargo run --example host            # writes host.png
//! cargo run --example host -- out.png
//! ```

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
use embedded_raytracer::{Camera, Render, Scene, Sphere, Vec3};

/// Three spheres on a dark blue background, in flash on a microcontroller.
static SCENE: Scene<3> = Scene::from_array(
    [
        Sphere::new(Vec3::new(0.0, 0.0, 0.0), 1.0, Rgb888::new(255, 64, 64)),
        Sphere::new(Vec3::new(1.2, 0.6, -1.5), 1.0, Rgb888::new(64, 255, 64)),
        Sphere::new(Vec3::new(-1.7, -0.5, -0.8), 0.7, Rgb888::new(64, 64, 255)),
    ],
    Rgb888::new(0, 0, 32),
);

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args().nth(1).unwrap_or_else(|| "host.png".into());
    // An Rgb565 display, as an ST7789 or ILI9341 LCD would be: the kernel converts.
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(240, 240));
    let camera = Camera::new(
        Vec3::new(0.0, 0.0, 5.0), // eye
        Vec3::ZERO,               // look at
        Vec3::new(0.0, 1.0, 0.0), // up
        60f32.to_radians(),       // vertical field of view
        display.size(),
    )?;
    Render::new(&SCENE, &camera).draw(&mut display)?;
    display
        .to_rgb_output_image(&OutputSettingsBuilder::new().build())
        .save_png(&out)?;
    println!("wrote {out} ({} × {})", camera.size().width, camera.size().height);
    Ok(())
}
