//! Prints the README's anti-aliasing table: per standard scene and sampling choice,
//! the error against the 16 × 16-ray box-filtered `f64` reference in linear light
//! (`reference::aa`), in 8-bit levels (the largest channel difference per pixel),
//! over all pixels and over the edge pixels; the share of edge pixels; and how far
//! `Adaptive(4)` is from `Grid(4)`.
//!
//! ```text
//! cargo run --release --example aa_table
//! ```
//!
//! Edge pixels are the ones `Adaptive(4)` traced with the grid (`Sample::rays > 1`),
//! the same set for every row of a scene. Scenes wider than 256 pixels (adaptive
//! sampling's row buffer) are drawn at 256 pixels wide (same vertical field of view and
//! aspect). The output is deterministic (the reference's threads split rows,
//! each pixel computed alone).

use std::fmt::Write as _;

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_raytracer::reference::aa::supersampled;
use embedded_raytracer::{Camera, Render, Sampling, Scene};

#[path = "common/standard.rs"]
mod standard;
use standard::{FEATURE_SCENES, SCENES};

/// The largest image width the table renders at: adaptive sampling's row buffer
/// (`sampling::ADAPTIVE_MAX_WIDTH`; a wider image samples every pixel).
const MAX_WIDTH: u32 = embedded_raytracer::sampling::ADAPTIVE_MAX_WIDTH as u32;

fn main() {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "| scene | size | sampling | rays/pixel | mean error | max error | mean error, edge pixels | max error, edge pixels |"
    );
    let _ = writeln!(out, "|---|---|---|---:|---:|---:|---:|---:|");
    let mut notes = String::new();
    for name in SCENES {
        let file = standard::load(name);
        table(&file.scene, &file.camera, name, &mut out, &mut notes);
    }
    for name in FEATURE_SCENES {
        let file = standard::load_full(name);
        table(&file.scene, &file.camera, name, &mut out, &mut notes);
    }
    print!("{out}\n{notes}");
}

/// The camera at no more than [`MAX_WIDTH`] pixels wide.
fn capped(camera: &Camera) -> Camera {
    let size = camera.size();
    if size.width <= MAX_WIDTH {
        return *camera;
    }
    let mut p = *camera.params();
    let height = (u64::from(size.height) * u64::from(MAX_WIDTH) / u64::from(size.width)) as u32;
    p.size = Size::new(MAX_WIDTH, height.max(1));
    Camera::from_params(p).expect("a smaller image of a valid camera is valid")
}

/// Colours and rays of every pixel, row-major.
fn traced<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    sampling: Sampling,
) -> (Vec<Rgb888>, Vec<u32>) {
    let (mut colors, mut rays) = (Vec::new(), Vec::new());
    Render::<N, Rgb888, L, P, D>::new(scene, camera)
        .with_sampling(sampling)
        .trace(|s| {
            colors.push(s.color);
            rays.push(s.rays);
        });
    (colors, rays)
}

/// The largest channel difference.
fn error(c: Rgb888, r: &[f64; 3]) -> f64 {
    [c.r(), c.g(), c.b()]
        .iter()
        .zip(r)
        .map(|(&a, &b)| (f64::from(a) - b).abs())
        .fold(0.0, f64::max)
}

fn table<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    name: &str,
    out: &mut String,
    notes: &mut String,
) {
    let camera = capped(camera);
    let size = camera.size();
    let reference = supersampled(scene, &camera, 16, 2);
    let (_, adaptive_rays) = traced(scene, &camera, Sampling::adaptive(4).unwrap());
    let edge: Vec<bool> = adaptive_rays.iter().map(|&r| r > 1).collect();
    let edges = edge.iter().filter(|&&e| e).count();
    let mut grid4 = Vec::new();
    let mut adaptive4 = Vec::new();
    for sampling in Sampling::ALL {
        let (colors, rays) = traced(scene, &camera, sampling);
        let errors: Vec<f64> = colors.iter().zip(&reference).map(|(c, r)| error(*c, r)).collect();
        let stats = |pick: &dyn Fn(usize) -> bool| {
            let (mut sum, mut max, mut count) = (0.0, 0.0f64, 0usize);
            for (k, e) in errors.iter().enumerate().filter(|(k, _)| pick(*k)) {
                let _ = k;
                sum += e;
                max = max.max(*e);
                count += 1;
            }
            (sum / count.max(1) as f64, max)
        };
        let (mean, max) = stats(&|_| true);
        let (edge_mean, edge_max) = stats(&|k| edge[k]);
        let per_pixel = rays.iter().map(|&r| f64::from(r)).sum::<f64>() / rays.len() as f64;
        let _ = writeln!(
            out,
            "| {name} | {}×{} | {sampling} | {per_pixel:.2} | {mean:.2} | {max:.1} | {edge_mean:.2} | {edge_max:.1} |",
            size.width, size.height
        );
        if sampling == Sampling::grid(4).unwrap() {
            grid4 = colors;
        } else if sampling == Sampling::adaptive(4).unwrap() {
            adaptive4 = colors;
        }
    }
    // Adaptive(4) against Grid(4): pixels more than 2 levels apart, the largest and where.
    let w = size.width as usize;
    let diffs: Vec<u8> = grid4
        .iter()
        .zip(&adaptive4)
        .map(|(g, a)| {
            [
                g.r().abs_diff(a.r()),
                g.g().abs_diff(a.g()),
                g.b().abs_diff(a.b()),
            ]
            .into_iter()
            .max()
            .unwrap_or(0)
        })
        .collect();
    let over = diffs.iter().filter(|&&d| d > 2).count();
    let (at, worst) = diffs
        .iter()
        .enumerate()
        .max_by_key(|(k, d)| (**d, usize::MAX - k))
        .map_or((0, 0), |(k, d)| (k, *d));
    let _ = writeln!(
        notes,
        "- {name}: edge pixels {edges} of {} ({:.2} %); Adaptive(4) vs Grid(4): {over} pixels ({:.3} %) more than 2 levels apart, the largest {worst} levels at ({}, {}){}",
        edge.len(),
        100.0 * edges as f64 / edge.len() as f64,
        100.0 * over as f64 / edge.len() as f64,
        at % w,
        at / w,
        if edge.get(at).copied().unwrap_or(false) { " (an edge pixel)" } else { " (a centre-ray pixel)" }
    );
}
