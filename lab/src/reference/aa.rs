//! The anti-aliasing reference: every pixel the box-filtered mean of `n × n` rays
//! (16 × 16 for the README's table) in linear light, in `f64`, with this module's own
//! sRGB transfer functions (IEC 61966-2-1, `powf`). Each ray is the `f64` reference's
//! ([`trace_ray`] for Lab #1 scenes, [`lit::trace`]
//! otherwise), whose colour is rounded to 8 bits once; the mean is not rounded.

use std::vec;
use std::vec::Vec;

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};

use super::{lit, trace_ray, RefCamera, RefSphere, D3};
use embedded_raytracer::Camera;
use embedded_raytracer::Scene;

/// An 8-bit sRGB level in linear light, `[0, 1]`.
#[must_use]
pub fn srgb_to_linear(level: f64) -> f64 {
    let c = level / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear light `[0, 1]` as sRGB levels `[0, 255]`, not rounded.
#[must_use]
pub fn linear_to_srgb(l: f64) -> f64 {
    let c = if l <= 0.003_130_8 {
        l * 12.92
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    };
    255.0 * c
}

/// The supersampled reference image, row-major: per pixel the mean of `n × n` rays at
/// offsets `((a + ½)/n − ½, (b + ½)/n − ½)` pixels from its centre, in sRGB levels
/// (not rounded). Rows are split between `threads` threads. Empty when the camera's
/// `f64` basis is degenerate.
#[must_use]
pub fn supersampled<const N: usize, const L: usize, const P: usize, const D: usize>(
    scene: &Scene<N, L, P, D>,
    camera: &Camera,
    n: u32,
    threads: usize,
) -> Vec<[f64; 3]> {
    let Some(cam) = RefCamera::new(camera.params()) else {
        return Vec::new();
    };
    let lit_scene = lit::RefScene::of(scene);
    let spheres: Vec<RefSphere> = scene
        .spheres()
        .iter()
        .map(|s| RefSphere {
            center: D3::of(s.center),
            radius: f64::from(s.radius),
            color: s.color,
        })
        .collect();
    let lab1 = lit_scene.is_lab1();
    let trace = |dir: D3| -> Rgb888 {
        if lab1 {
            trace_ray(&cam, &spheres, scene.background(), dir).color
        } else {
            lit::trace(&cam, &lit_scene, dir).color
        }
    };
    let (w, h) = (cam.width, cam.height);
    let pixel = |i: u32, j: u32| -> [f64; 3] {
        let mut sum = [0.0f64; 3];
        for b in 0..n {
            let y = f64::from(j) + (f64::from(b) + 0.5) / f64::from(n);
            for a in 0..n {
                let x = f64::from(i) + (f64::from(a) + 0.5) / f64::from(n);
                // The image plane at distance 1: w + X·u + Y·v.
                let px = (x - f64::from(w) / 2.0) * cam.pixel_width;
                let py = (f64::from(h) / 2.0 - y) * cam.pixel_height;
                let c = trace(cam.w + cam.u * px + cam.v * py);
                for (s, v) in sum.iter_mut().zip([c.r(), c.g(), c.b()]) {
                    *s += srgb_to_linear(f64::from(v));
                }
            }
        }
        let count = f64::from(n * n);
        sum.map(|s| linear_to_srgb(s / count))
    };
    let threads = threads.max(1);
    let mut out = vec![[0.0f64; 3]; w as usize * h as usize];
    std::thread::scope(|scope| {
        let pixel = &pixel;
        let rows_per = (h as usize).div_ceil(threads).max(1);
        for (t, chunk) in out.chunks_mut(rows_per * w as usize).enumerate() {
            scope.spawn(move || {
                for (k, px) in chunk.iter_mut().enumerate() {
                    let j = (t * rows_per + k / w as usize) as u32;
                    *px = pixel(k as u32 % w, j);
                }
            });
        }
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The transfer functions invert each other, and the 16 × 16 mean of a flat
    /// scene is its colour.
    #[test]
    fn transfer_functions_and_a_flat_mean() {
        for k in 0..=255 {
            let v = f64::from(k);
            assert!((linear_to_srgb(srgb_to_linear(v)) - v).abs() < 1e-9, "{k}");
        }
        let scene: Scene<1> = Scene::new(Rgb888::new(10, 128, 250));
        let camera = Camera::new(
            embedded_raytracer::Vec3::new(0.0, 0.0, 5.0),
            embedded_raytracer::Vec3::ZERO,
            embedded_raytracer::Vec3::new(0.0, 1.0, 0.0),
            0.5,
            embedded_graphics::geometry::Size::new(4, 3),
        )
        .unwrap();
        let img = supersampled(&scene, &camera, 16, 2);
        assert_eq!(img.len(), 12);
        for p in img {
            for (got, want) in p.iter().zip([10.0, 128.0, 250.0]) {
                assert!((got - want).abs() < 1e-9, "{got} vs {want}");
            }
        }
    }
}
