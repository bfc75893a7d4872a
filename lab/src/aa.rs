//! Anti-aliasing quality against the 16 × 16-ray reference, for the host tools that
//! report it (`aa_table`: the README's table; `speed_vs_accuracy`: the chart's sampling
//! panel): every sampling choice of one scene traced, its error against
//! `reference::aa::supersampled` in 8-bit levels (the largest channel difference per
//! pixel), over all pixels and over the edge pixels, and its rays per pixel.

#![allow(dead_code)]

use crate::reference::aa::supersampled;
use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_raytracer::{Camera, Render, Sampling, Scene};

/// The largest image width measured: adaptive sampling's row buffer
/// (`sampling::ADAPTIVE_MAX_WIDTH`; a wider image samples every pixel).
pub const MAX_WIDTH: u32 = embedded_raytracer::ADAPTIVE_MAX_WIDTH as u32;

/// Rays per pixel side of the reference (`n × n` rays, box filter, linear light): the
/// README's figures.
pub const REFERENCE_RAYS: u32 = 16;

/// The camera at no more than [`MAX_WIDTH`] pixels wide (same vertical field of view
/// and aspect).
pub fn capped(camera: &Camera) -> Camera {
    let size = camera.size();
    if size.width <= MAX_WIDTH {
        return *camera;
    }
    let mut p = *camera.params();
    let height = (u64::from(size.height) * u64::from(MAX_WIDTH) / u64::from(size.width)) as u32;
    p.size = Size::new(MAX_WIDTH, height.max(1));
    p.build().expect("a smaller image of a valid camera is valid")
}

/// Colours and rays of every pixel, row-major.
pub fn traced<const N: usize, const L: usize, const P: usize, const D: usize>(
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
pub fn error(c: Rgb888, r: &[f64; 3]) -> f64 {
    [c.r(), c.g(), c.b()]
        .iter()
        .zip(r)
        .map(|(&a, &b)| (f64::from(a) - b).abs())
        .fold(0.0, f64::max)
}

/// One sampling choice of one scene against the reference.
pub struct Quality {
    pub sampling: Sampling,
    /// Mean rays averaged per pixel.
    pub rays_per_pixel: f64,
    /// Mean and max error over all pixels (levels).
    pub mean: f64,
    pub max: f64,
    /// Mean and max error over the edge pixels (levels).
    pub edge_mean: f64,
    pub edge_max: f64,
    /// The traced colours, row-major.
    pub colors: Vec<Rgb888>,
}

/// Every sampling choice of one scene against the reference.
pub struct SceneQuality {
    /// The image size measured (the scene's, [`capped`]).
    pub size: Size,
    /// The pixels `Adaptive(4)` traced with the grid (`Sample::rays > 1`), row-major.
    pub edge: Vec<bool>,
    /// One per [`Sampling::ALL`], in its order.
    pub samplings: Vec<Quality>,
}

impl SceneQuality {
    /// The colours of `sampling` (empty if it was not measured).
    pub fn colors(&self, sampling: Sampling) -> &[Rgb888] {
        self.samplings
            .iter()
            .find(|q| q.sampling == sampling)
            .map_or(&[], |q| &q.colors)
    }
}

/// Traces every sampling choice of `scene` through `camera` [`capped`] and compares it
/// with the reference of `reference_rays`² rays per pixel ([`REFERENCE_RAYS`] for the
/// README's figures; computed on `threads` threads, each pixel alone, so the result
/// does not depend on the split).
pub fn measure<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    reference_rays: u32,
    threads: usize,
) -> SceneQuality {
    let camera = capped(camera);
    let reference = supersampled(scene, &camera, reference_rays, threads);
    let (_, adaptive_rays) = traced(scene, &camera, Sampling::adaptive(4).unwrap());
    let edge: Vec<bool> = adaptive_rays.iter().map(|&r| r > 1).collect();
    let samplings = Sampling::ALL
        .into_iter()
        .map(|sampling| {
            let (colors, rays) = traced(scene, &camera, sampling);
            let errors: Vec<f64> = colors.iter().zip(&reference).map(|(c, r)| error(*c, r)).collect();
            let stats = |pick: &dyn Fn(usize) -> bool| {
                let (mut sum, mut max, mut count) = (0.0, 0.0f64, 0usize);
                for (_, e) in errors.iter().enumerate().filter(|(k, _)| pick(*k)) {
                    sum += e;
                    max = max.max(*e);
                    count += 1;
                }
                (sum / count.max(1) as f64, max)
            };
            let (mean, max) = stats(&|_| true);
            let (edge_mean, edge_max) = stats(&|k| edge[k]);
            let rays_per_pixel = rays.iter().map(|&r| f64::from(r)).sum::<f64>() / rays.len() as f64;
            Quality {
                sampling,
                rays_per_pixel,
                mean,
                max,
                edge_mean,
                edge_max,
                colors,
            }
        })
        .collect();
    SceneQuality {
        size: camera.size(),
        edge,
        samplings,
    }
}
