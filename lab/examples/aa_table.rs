//! Prints the README's anti-aliasing table: per standard scene and sampling choice,
//! the error against the 16 × 16-ray box-filtered `f64` reference in linear light
//! (`reference::aa`), in 8-bit levels (the largest channel difference per pixel),
//! over all pixels and over the edge pixels; the share of edge pixels; the pixels
//! where `Center` is more than 2 levels off `Grid(4)` (those an adaptive render within
//! 2 levels of `Grid(4)` must trace with the grid); and how far `Adaptive(4)` is from
//! `Grid(4)`.
//!
//! ```text
//! cargo run --release --features tools --example aa_table
//! ```
//!
//! Edge pixels are the ones `Adaptive(4)` traced with the grid (`Sample::rays > 1`),
//! the same set for every row of a scene. The measurement is `common/aa.rs`'s, shared
//! with the speed/accuracy chart's sampling panels. Scenes wider than 256 pixels (adaptive
//! sampling's row buffer) are drawn at 256 pixels wide (same vertical field of view and
//! aspect). The output is deterministic (the reference's threads split rows,
//! each pixel computed alone).

use std::fmt::Write as _;

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_raytracer::{Camera, Sampling, Scene};

use embedded_raytracer_lab::aa;
use embedded_raytracer_scenes as standard;
use standard::{FEATURE_SCENES, SCENES};

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

fn table<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    name: &str,
    out: &mut String,
    notes: &mut String,
) {
    let quality = aa::measure(scene, camera, aa::REFERENCE_RAYS, 2);
    let (size, edge) = (quality.size, &quality.edge);
    let edges = edge.iter().filter(|&&e| e).count();
    for q in &quality.samplings {
        let _ = writeln!(
            out,
            "| {name} | {}×{} | {} | {:.2} | {:.2} | {:.1} | {:.2} | {:.1} |",
            size.width, size.height, q.sampling, q.rays_per_pixel, q.mean, q.max, q.edge_mean, q.edge_max
        );
    }
    let grid4 = quality.colors(Sampling::grid(4).unwrap());
    let adaptive4 = quality.colors(Sampling::adaptive(4).unwrap());
    let center = quality.colors(Sampling::Center);
    // The largest channel difference of each pixel between two renders.
    let apart = |x: &[Rgb888], y: &[Rgb888]| -> Vec<u8> {
        x.iter()
            .zip(y)
            .map(|(p, q)| {
                [
                    p.r().abs_diff(q.r()),
                    p.g().abs_diff(q.g()),
                    p.b().abs_diff(q.b()),
                ]
                .into_iter()
                .max()
                .unwrap_or(0)
            })
            .collect()
    };
    // Center against Grid(4): the pixels where the centre ray alone is more than 2
    // levels off the grid. An adaptive render within 2 levels of Grid(4) on 99.9 % of
    // the pixels must trace the grid in all of them but at most 0.1 % of the image.
    let must = apart(center, grid4).iter().filter(|&&d| d > 2).count();
    // Adaptive(4) against Grid(4): pixels more than 2 levels apart, the largest and where.
    let w = size.width as usize;
    let diffs = apart(grid4, adaptive4);
    let over = diffs.iter().filter(|&&d| d > 2).count();
    let (at, worst) = diffs
        .iter()
        .enumerate()
        .max_by_key(|(k, d)| (**d, usize::MAX - k))
        .map_or((0, 0), |(k, d)| (k, *d));
    let _ = writeln!(
        notes,
        "- {name}: edge pixels {edges} of {} ({:.2} %; Center is more than 2 levels off Grid(4) in {must}, {:.2} %); Adaptive(4) vs Grid(4): {over} pixels ({:.3} %) more than 2 levels apart, the largest {worst} levels at ({}, {}){}",
        edge.len(),
        100.0 * edges as f64 / edge.len() as f64,
        100.0 * must as f64 / edge.len() as f64,
        100.0 * over as f64 / edge.len() as f64,
        at % w,
        at / w,
        if edge.get(at).copied().unwrap_or(false) { " (an edge pixel)" } else { " (a centre-ray pixel)" }
    );
}
