//! Tracing a render into comparable pixels, random scenes and cameras, a frame target:
//! what the library's API tests (`tests/api`) and the lab's tests (`lab/tests/lab`,
//! through `#[path]`) share.

#![allow(dead_code)]

use std::convert::Infallible;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raytracer::{Camera, CameraParams, Render, Scene, Sphere, Vec3};

/// Everything a traced pixel is: the hit sphere and `t` (bits), the colour, and the
/// ray direction (bits), so that two renders compare bit for bit.
pub type Traced = (Option<(usize, u32)>, Rgb888, [u32; 3]);

/// Every pixel of `render`, row-major.
pub fn trace<const N: usize, const L: usize, const P: usize, const D: usize>(
    render: Render<'_, N, Rgb888, L, P, D>,
) -> Vec<Traced> {
    let mut out = Vec::new();
    render.trace(|s| {
        out.push((
            s.hit.map(|h| (h.index, h.t.to_bits())),
            s.color,
            [
                s.direction.x.to_bits(),
                s.direction.y.to_bits(),
                s.direction.z.to_bits(),
            ],
        ))
    });
    out
}

/// xorshift64*: deterministic, no dependency.
pub struct Rng(pub u64);
impl Rng {
    pub fn next(&mut self) -> f32 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        ((self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 40) as f32) / (1u64 << 24) as f32
    }
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.next()
    }
    pub fn vec(&mut self, s: f32) -> Vec3 {
        Vec3::new(self.range(-s, s), self.range(-s, s), self.range(-s, s))
    }
}

/// A random scene around a random camera: spheres in front, behind, crossing the
/// plane through the eye, containing the eye, far and tiny, huge and near.
pub fn random_case(rng: &mut Rng) -> (Scene<12>, Camera) {
    let spread = if rng.next() < 0.3 { 2000.0 } else { 5.0 };
    let eye = rng.vec(spread);
    let look = eye + rng.vec(1.0) + Vec3::new(0.0, 0.0, -0.5);
    let fov = if rng.next() < 0.2 {
        rng.range(0.001, 0.05)
    } else {
        rng.range(0.3, 2.8)
    };
    let size = Size::new(rng.range(8.0, 72.0) as u32, rng.range(8.0, 56.0) as u32);
    let camera = Camera::new(eye, look, Vec3::new(0.0, 1.0, 0.0), fov, size)
        .or_else(|_| Camera::new(eye, look, Vec3::new(1.0, 0.0, 0.0), fov, size))
        .unwrap();
    let w = camera.w();
    let mut scene = Scene::new(Rgb888::new(1, 2, 3));
    for k in 0..12 {
        let color = Rgb888::new(40 + 17 * k as u8, 255 - 13 * k as u8, 90);
        let sphere = match k % 6 {
            // In front, on or near the view axis, at a random distance/radius.
            0 | 1 => {
                let dist = rng.range(1.5, 50.0);
                let dir = w + camera.u() * rng.range(-0.8, 0.8) + camera.v() * rng.range(-0.6, 0.6);
                let r = dist * rng.range(0.001, 0.4);
                Sphere::new(eye + dir * dist, r, color)
            }
            // Behind the eye.
            2 => Sphere::new(
                eye - w * rng.range(1.0, 10.0) + rng.vec(1.0),
                rng.range(0.2, 2.0),
                color,
            ),
            // Crossing the plane through the eye parallel to the image.
            3 => Sphere::new(
                eye + camera.u() * rng.range(-3.0, 3.0) + w * rng.range(-0.5, 0.5),
                rng.range(0.5, 4.0),
                color,
            ),
            // Containing the eye (sometimes only just).
            4 => {
                let r = rng.range(0.5, 30.0);
                Sphere::new(eye + rng.vec(1.0) * (r * rng.range(0.0, 0.57)), r, color)
            }
            // Far and tiny (distance/radius up to 1e5) in the field of view.
            _ => {
                let dist = rng.range(10.0, 5000.0);
                let dir =
                    w + camera.u() * rng.range(-0.01, 0.01) * fov + camera.v() * rng.range(-0.01, 0.01) * fov;
                Sphere::new(eye + dir * dist, dist * rng.range(1e-5, 1e-2), color)
            }
        };
        scene.push(sphere).unwrap();
    }
    (scene, camera)
}

/// A plain Rgb888 frame buffer that records every write, for comparing renders drawn
/// with clips, offsets or in parts: `buf` is row-major, `writes` counts pixels written.
pub struct Frame {
    pub size: Size,
    pub buf: Vec<Option<Rgb888>>,
    pub writes: usize,
}

impl Frame {
    pub fn new(size: Size) -> Self {
        Self {
            size,
            buf: vec![None; (size.width * size.height) as usize],
            writes: 0,
        }
    }

    pub fn get(&self, p: Point) -> Option<Rgb888> {
        let (w, h) = (self.size.width as i32, self.size.height as i32);
        ((0..w).contains(&p.x) && (0..h).contains(&p.y))
            .then(|| self.buf[(p.y * w + p.x) as usize])
            .flatten()
    }
}

impl OriginDimensions for Frame {
    fn size(&self) -> Size {
        self.size
    }
}

impl DrawTarget for Frame {
    type Color = Rgb888;
    type Error = Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb888>>>(&mut self, pixels: I) -> Result<(), Infallible> {
        let (w, h) = (self.size.width as i32, self.size.height as i32);
        for Pixel(p, c) in pixels {
            assert!(
                (0..w).contains(&p.x) && (0..h).contains(&p.y),
                "drawn outside: {p:?}"
            );
            self.buf[(p.y * w + p.x) as usize] = Some(c);
            self.writes += 1;
        }
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb888>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Infallible> {
        self.draw_iter(area.points().zip(colors).map(|(p, c)| Pixel(p, c)))
    }
}

/// A smaller camera with the same view (the big `drift` image would take minutes in a
/// debug build), keeping the pixel pitch large enough that the world-space drift stays.
pub fn shrink(camera: &Camera, width: u32, height: u32) -> Camera {
    let mut p = *camera.params();
    let scale = width as f32 / p.size.width as f32;
    p.fov_y = 2.0 * ((p.fov_y / 2.0).tan() * (height as f32 / p.size.height as f32) / scale * scale).atan();
    p.size = Size::new(width, height);
    p.build().unwrap()
}

/// One unit sphere filling 8192-wide rows from just outside it (eye 1.05 from the
/// centre, 2.6 rad field of view, 3 rows): where forward differences drift without
/// anchors.
pub fn huge_row() -> (Scene<1>, Camera) {
    let scene = Scene::from_array(
        [Sphere::new(Vec3::ZERO, 1.0, Rgb888::new(255, 255, 255))],
        Rgb888::new(0, 0, 0),
    );
    let camera = Camera::new(
        Vec3::new(0.0, 0.0, 1.05),
        Vec3::ZERO,
        Vec3::new(0.0, 1.0, 0.0),
        2.6,
        Size::new(8192, 3),
    )
    .unwrap();
    (scene, camera)
}

/// `params` at `size`: a scene's own camera, size replaced (as the firmware
/// measurements do).
pub fn at_size(params: &CameraParams, size: Size) -> Camera {
    CameraParams { size, ..*params }.build().unwrap()
}
