//! The incremental tests' display: a frame buffer of any colour that can clip itself.
//!
//! One type for whole and clipped targets: the kernel is instantiated once per scene
//! type and colour, where a separate `Clipped<Buffer>` would instantiate every method
//! again (about a quarter of this test binary's code, and of its build time).

use std::convert::Infallible;

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

/// A frame buffer, every pixel starting at the fill colour; counts the pixels and
/// `fill_contiguous` calls it gets, and keeps the calls' rectangles.
///
/// With `clip` set it behaves as embedded-graphics' `display.clipped(&clip)`: its
/// bounding box is the clip (within the buffer), pixels outside it are dropped, and a
/// `fill_contiguous` is recorded as its rectangle's part within the clip. Without a
/// clip, a pixel outside the buffer fails the test.
#[derive(Clone, PartialEq, Debug)]
pub struct Buffer<C> {
    pub size: Size,
    pub px: Vec<C>,
    pub clip: Option<Rectangle>,
    pub written: usize,
    pub calls: usize,
    pub windows: Vec<Rectangle>,
}

impl<C: PixelColor> Buffer<C> {
    pub fn new(size: Size, fill: C) -> Self {
        Self {
            size,
            px: vec![fill; (size.width * size.height) as usize],
            clip: None,
            written: 0,
            calls: 0,
            windows: Vec::new(),
        }
    }

    /// The pixels that differ from `other`'s.
    pub fn diff(&self, other: &Self) -> usize {
        self.px.iter().zip(&other.px).filter(|(a, b)| a != b).count()
    }

    /// Sets the clip (`None`: the whole buffer) and returns the buffer, to draw on.
    pub fn clipped_to(&mut self, clip: Option<Rectangle>) -> &mut Self {
        self.clip = clip;
        self
    }

    fn put(&mut self, p: Point, c: C) {
        if self.clip.is_some() && !self.bounding_box().contains(p) {
            return;
        }
        let w = self.size.width as i32;
        assert!(
            (0..w).contains(&p.x) && (0..self.size.height as i32).contains(&p.y),
            "drawn outside the target: {p:?}"
        );
        self.px[(p.y * w + p.x) as usize] = c;
        self.written += 1;
    }
}

impl<C: PixelColor> Dimensions for Buffer<C> {
    fn bounding_box(&self) -> Rectangle {
        let whole = Rectangle::new(Point::zero(), self.size);
        self.clip.map_or(whole, |c| c.intersection(&whole))
    }
}

impl<C: PixelColor> DrawTarget for Buffer<C> {
    type Color = C;
    type Error = Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(&mut self, pixels: I) -> Result<(), Infallible> {
        for Pixel(p, c) in pixels {
            self.put(p, c);
        }
        Ok(())
    }
    fn fill_contiguous<I: IntoIterator<Item = C>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Infallible> {
        self.calls += 1;
        let window = match self.clip {
            Some(_) => area.intersection(&self.bounding_box()),
            None => *area,
        };
        self.windows.push(window);
        for (p, c) in area.points().zip(colors) {
            self.put(p, c);
        }
        Ok(())
    }
}

/// The self-clipping buffer draws what `Clipped` draws, bit for bit, and records the
/// same windows: whole, clipped inside, clipped across an edge, offset.
#[test]
fn a_clipped_buffer_is_embedded_graphics_clipped() {
    use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
    use embedded_raytracer::{Camera, Render, Scene, Sphere, Vec3};

    let scene: Scene<3> = Scene::from_array(
        [
            Sphere::new(Vec3::ZERO, 1.0, Rgb888::new(200, 40, 40)),
            Sphere::new(Vec3::new(0.8, 0.5, -1.0), 0.7, Rgb888::new(40, 200, 40)),
        ],
        Rgb888::new(5, 6, 7),
    );
    let up = Vec3::new(0.0, 1.0, 0.0);
    let camera = Camera::new(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, up, 0.8, Size::new(24, 18)).unwrap();
    let fill = Rgb565::new(3, 7, 11);
    for (clip, offset) in [
        (None, Point::zero()),
        (
            Some(Rectangle::new(Point::new(3, 2), Size::new(10, 9))),
            Point::zero(),
        ),
        (
            Some(Rectangle::new(Point::new(-4, 12), Size::new(40, 40))),
            Point::new(2, 1),
        ),
    ] {
        let render = Render::new(&scene, &camera).with_offset(offset);
        let mut own = Buffer::new(Size::new(30, 22), fill);
        render.draw(own.clipped_to(clip)).unwrap();
        let mut theirs = Buffer::new(Size::new(30, 22), fill);
        match clip {
            None => render.draw(&mut theirs).unwrap(),
            Some(c) => render.draw(&mut theirs.clipped(&c)).unwrap(),
        }
        assert!(own.written > 0);
        assert_eq!(own.diff(&theirs), 0, "clip {clip:?}");
        assert_eq!(own.windows, theirs.windows, "clip {clip:?}");
        assert_eq!(own.written, theirs.written, "clip {clip:?}");
    }
}
