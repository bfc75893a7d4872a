//! What the ordered dither costs on top of a render: the lab scene at the SSD1306's
//! 128×64 into a `BinaryColor` framebuffer, plain (`BinaryColor::from(Rgb888)`) against
//! `display.dithered()` (Bayer 8×8) and `dithered_with(Bayer::Four)`.
//!
//! ```text
//! cargo run --release --features tools --example dither_cost [-- SCENE.toml]
//! ```
//!
//! Runs the three variants interleaved, 15 rounds of 200 frames each, and prints each
//! one's median time per frame and its ratio to the plain render measured in the same
//! run (host timings: the ratio, not the absolute time, carries over to a target).

use std::time::Instant;

use embedded_raytracer_scenes as standard;
use standard::MAX_SPHERES;

use embedded_graphics::{pixelcolor::BinaryColor, prelude::*};
use embedded_graphics_simulator::SimulatorDisplay;
use embedded_raytracer::{
    dither::{Bayer, DitherExt},
    scene_file, Render,
};

const ROUNDS: usize = 15;
const FRAMES: u32 = 200;

fn main() -> Result<(), String> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "scenes/lab.toml".into());
    let file = scene_file::load::<MAX_SPHERES, 0, 0, 0>(&path).map_err(|e| e.to_string())?;
    let size = Size::new(128, 64);
    let camera = file
        .camera
        .params()
        .with_size(size)
        .build()
        .map_err(|e| e.to_string())?;
    let mut display = SimulatorDisplay::<BinaryColor>::new(size);

    let mut times = [[0f64; ROUNDS]; 3];
    for round in 0..ROUNDS {
        for (variant, slot) in times.iter_mut().enumerate() {
            let start = Instant::now();
            for _ in 0..FRAMES {
                let Ok(()) = match variant {
                    0 => Render::new(&file.scene, &camera).draw(&mut display),
                    1 => Render::new(&file.scene, &camera).draw(&mut display.dithered()),
                    _ => Render::new(&file.scene, &camera).draw(&mut display.dithered_with(Bayer::Four)),
                };
            }
            slot[round] = start.elapsed().as_secs_f64() / f64::from(FRAMES);
        }
    }
    let median = |t: &mut [f64; ROUNDS]| {
        t.sort_by(f64::total_cmp);
        t[ROUNDS / 2]
    };
    let [mut plain, mut eight, mut four] = times;
    let (plain, eight, four) = (median(&mut plain), median(&mut eight), median(&mut four));
    println!("{path} at 128x64, BinaryColor, median of {ROUNDS} x {FRAMES} frames:");
    println!("  plain threshold   {:8.1} us/frame  1.00", plain * 1e6);
    println!(
        "  dithered 8x8      {:8.1} us/frame  {:.2}",
        eight * 1e6,
        eight / plain
    );
    println!(
        "  dithered 4x4      {:8.1} us/frame  {:.2}",
        four * 1e6,
        four / plain
    );
    Ok(())
}
