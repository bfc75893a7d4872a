//! What the integration tests share: the standard scenes (`examples/common/standard.rs`)
//! and tracing a render into comparable pixels.

#![allow(dead_code)]

#[path = "../../examples/common/standard.rs"]
mod standard;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_raytracer::Render;
#[allow(unused_imports)]
pub use standard::{load, path, MAX_SPHERES, SCENES};

/// Everything a traced pixel is: the hit sphere and `t` (bits), the colour, and the
/// ray direction (bits), so that two renders compare bit for bit.
pub type Pixel = (Option<(usize, u32)>, Rgb888, [u32; 3]);

/// Every pixel of `render`, row-major.
pub fn trace<const N: usize>(render: Render<'_, N, Rgb888>) -> Vec<Pixel> {
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
