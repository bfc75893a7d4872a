//! A firmware that uses the kernel (one frame into a display-sized sink), linked with the
//! memory map its HAL-style dependency provides.
#![no_std]
#![no_main]

use core::convert::Infallible;

use cortex_m_rt::entry;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_raytracer::{Camera, Render, Scene, Sphere, Vec3};
use panic_halt as _;
// Linked for its build script's memory.x.
use memory_map as _;

static SCENE: Scene<1> = Scene::from_array(
    [Sphere::new(
        Vec3::ZERO,
        1.0,
        embedded_graphics::pixelcolor::Rgb888::RED,
    )],
    embedded_graphics::pixelcolor::Rgb888::BLACK,
);

/// Counts the lit pixels: a display that keeps nothing.
struct Count(u32);

impl OriginDimensions for Count {
    fn size(&self) -> Size {
        Size::new(32, 32)
    }
}

impl DrawTarget for Count {
    type Color = Rgb565;
    type Error = Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, pixels: I) -> Result<(), Infallible> {
        self.0 += pixels.into_iter().filter(|p| p.1 != Rgb565::BLACK).count() as u32;
        Ok(())
    }
}

#[entry]
fn main() -> ! {
    let mut count = Count(0);
    if let Ok(camera) = Camera::new(
        Vec3::new(0.0, 0.0, 5.0),
        Vec3::ZERO,
        Vec3::new(0.0, 1.0, 0.0),
        0.8,
        Size::new(32, 32),
    ) {
        let _ = Render::new(&SCENE, &camera).draw(&mut count);
    }
    loop {
        cortex_m::asm::bkpt();
    }
}
