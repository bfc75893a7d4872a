//! Rendering into embedded-graphics targets: the ASCII-art image, colour formats,
//! offsets, clipping and the one-`fill_contiguous`-per-row streaming contract.

use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::{BinaryColor, Gray8, Rgb565, Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raytracer::{Camera, Method, Render, Scene, Sphere, SphereTest, Sqrt, Vec3};

/// Red in front, blue behind it and partly hidden.
static SCENE: Scene<2> = Scene::from_array(
    [
        Sphere::new(Vec3::new(-0.6, 0.0, 0.0), 1.0, Rgb888::new(255, 0, 0)),
        Sphere::new(Vec3::new(1.0, 0.3, -1.0), 0.8, Rgb888::new(0, 0, 255)),
    ],
    Rgb888::new(0, 0, 0),
);

fn camera() -> Camera {
    Camera::new(
        Vec3::new(0.0, 0.0, 5.0),
        Vec3::ZERO,
        Vec3::new(0.0, 1.0, 0.0),
        40f32.to_radians(),
        Size::new(24, 16),
    )
    .unwrap()
}

/// The expected coverage, computed independently in f64 (no pixel of it is within
/// 1e-5 relative of a silhouette, so f32 must agree exactly).
const EXPECTED: [&str; 16] = [
    "KKKKKKKKKKKKKKKKKKKKKKKK",
    "KKKKKKKKKKKKKKKKKKKKKKKK",
    "KKKKKKKKKKKKKKKKKKKKKKKK",
    "KKKKKKKKKKKKKKKKKKKKKKKK",
    "KKKKKKRRRRRRKKBBBBKKKKKK",
    "KKKKKRRRRRRRRBBBBBKKKKKK",
    "KKKKKRRRRRRRRRBBBBBKKKKK",
    "KKKKKRRRRRRRRRBBBBBKKKKK",
    "KKKKKRRRRRRRRRBBBBKKKKKK",
    "KKKKKRRRRRRRRRBBBKKKKKKK",
    "KKKKKRRRRRRRRKKKKKKKKKKK",
    "KKKKKKRRRRRRKKKKKKKKKKKK",
    "KKKKKKKKKKKKKKKKKKKKKKKK",
    "KKKKKKKKKKKKKKKKKKKKKKKK",
    "KKKKKKKKKKKKKKKKKKKKKKKK",
    "KKKKKKKKKKKKKKKKKKKKKKKK",
];

/// Shaded colours mapped to the object they belong to.
fn coverage(c: Rgb888) -> Rgb888 {
    match (c.r() > 0, c.b() > 0) {
        (true, false) => Rgb888::RED,
        (false, true) => Rgb888::BLUE,
        (false, false) => Rgb888::BLACK,
        (true, true) => Rgb888::WHITE,
    }
}

fn render_rgb888(method: Method) -> MockDisplay<Rgb888> {
    let cam = camera();
    let mut display = MockDisplay::new();
    Render::new(&SCENE, &cam)
        .with_method(method)
        .draw(&mut display)
        .unwrap();
    display
}

#[test]
fn ascii_art_every_method() {
    let expected = MockDisplay::<Rgb888>::from_pattern(&EXPECTED);
    for method in Method::ALL {
        // MockDisplay itself panics on a pixel drawn twice or out of bounds.
        let display = render_rgb888(method).map(coverage);
        if method.sphere_test == SphereTest::Geometric && method.sqrt == Sqrt::Fast {
            // The documented failure: the geometric test normalises the ray with the
            // fast root (≤ 6.07 % long), which shrinks t_ca and loses the disc's rim.
            assert_ne!(display, expected, "{method} was expected to lose rim pixels");
            let hits = |d: &MockDisplay<Rgb888>| {
                d.affected_area()
                    .points()
                    .filter(|&p| d.get_pixel(p) != Some(Rgb888::BLACK))
                    .count()
            };
            assert!(hits(&display) < hits(&expected), "{method}");
        } else {
            display.assert_pattern(&EXPECTED);
        }
    }
}

#[test]
fn shading_is_lab1() {
    let display = render_rgb888(Method::TARGET_DEFAULT);
    // Row 7/8 around column 8 faces the eye almost head-on; the rim is darker but
    // never below 0.3 × 255 = 77 (rounded).
    let centre = display.get_pixel(Point::new(8, 8)).unwrap();
    assert!(
        centre.r() > 240 && centre.g() == 0 && centre.b() == 0,
        "{centre:?}"
    );
    let rim = display.get_pixel(Point::new(5, 5)).unwrap();
    assert!((77..centre.r()).contains(&rim.r()), "{rim:?}");
}

#[test]
fn other_colour_formats_convert_from_rgb888() {
    let cam = camera();
    let reference = render_rgb888(Method::TARGET_DEFAULT);

    let mut rgb565 = MockDisplay::<Rgb565>::new();
    Render::new(&SCENE, &cam).draw(&mut rgb565).unwrap();
    assert_eq!(rgb565, reference.map(Rgb565::from));

    let mut gray = MockDisplay::<Gray8>::new();
    Render::new(&SCENE, &cam).draw(&mut gray).unwrap();
    assert_eq!(gray, reference.map(Gray8::from));

    let mut binary = MockDisplay::<BinaryColor>::new();
    Render::new(&SCENE, &cam).draw(&mut binary).unwrap();
    assert_eq!(binary, reference.map(BinaryColor::from));

    // The same through embedded-graphics' own colour conversion adapter.
    let mut converted = MockDisplay::<Rgb565>::new();
    Render::<2, Rgb888>::new(&SCENE, &cam)
        .draw(&mut converted.color_converted())
        .unwrap();
    assert_eq!(converted, rgb565);
}

/// The image shifted by `offset`, cut to the 64×64 mock display.
fn shifted(full: &MockDisplay<Rgb888>, offset: Point) -> MockDisplay<Rgb888> {
    let mut expected = MockDisplay::new();
    let area = Rectangle::new(Point::zero(), camera().size());
    let pixels = area.points().filter_map(|p| {
        let q = p + offset;
        let inside = (0..64).contains(&q.x) && (0..64).contains(&q.y);
        inside.then(|| Pixel(q, full.get_pixel(p).unwrap()))
    });
    expected.draw_iter(pixels).unwrap();
    expected
}

#[test]
fn offset_renders_into_a_sub_rectangle() {
    let full = render_rgb888(Method::TARGET_DEFAULT);
    let cam = camera();
    let offset = Point::new(30, 20);
    let mut display = MockDisplay::new();
    Render::new(&SCENE, &cam)
        .with_offset(offset)
        .draw(&mut display)
        .unwrap();
    assert_eq!(display, shifted(&full, offset));
    assert_eq!(display.affected_area(), Rectangle::new(offset, cam.size()));
}

#[test]
fn partly_outside_is_clipped_with_identical_pixels() {
    let cam = camera();
    for method in Method::ALL {
        let full = render_rgb888(method);
        for offset in [
            Point::new(-5, -3),
            Point::new(50, 55),
            Point::new(-20, 50),
            Point::new(45, -10),
        ] {
            // MockDisplay panics on out-of-bounds drawing: clipping is proven by not panicking.
            let mut display = MockDisplay::new();
            Render::new(&SCENE, &cam)
                .with_method(method)
                .with_offset(offset)
                .draw(&mut display)
                .unwrap();
            assert_eq!(display, shifted(&full, offset), "{method} at {offset:?}");
        }
        // Entirely outside: nothing is drawn, nothing traced.
        let mut display = MockDisplay::<Rgb888>::new();
        Render::new(&SCENE, &cam)
            .with_offset(Point::new(i32::MAX - 3, i32::MIN))
            .draw(&mut display)
            .unwrap();
        assert!(display.affected_area().is_zero_sized());
    }
}

/// Records how the render talks to its target.
#[derive(Default)]
struct Recorder {
    fills: Vec<(Rectangle, usize)>,
    single_pixels: usize,
}

impl OriginDimensions for Recorder {
    fn size(&self) -> Size {
        Size::new(100, 100)
    }
}

impl DrawTarget for Recorder {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, pixels: I) -> Result<(), Self::Error> {
        self.single_pixels += pixels.into_iter().count();
        Ok(())
    }
    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        self.fills.push((*area, colors.into_iter().count()));
        Ok(())
    }
}

#[test]
fn one_fill_contiguous_per_row() {
    let cam = camera();
    let mut target = Recorder::default();
    Render::new(&SCENE, &cam)
        .with_offset(Point::new(90, 3))
        .draw(&mut target)
        .unwrap();
    assert_eq!(target.single_pixels, 0);
    assert_eq!(target.fills.len(), 16);
    for (row, (area, count)) in target.fills.iter().enumerate() {
        // Clipped to the 100-pixel-wide target: columns 90..100 of each row.
        assert_eq!(
            *area,
            Rectangle::new(Point::new(90, 3 + row as i32), Size::new(10, 1))
        );
        assert_eq!(*count, 10);
    }
}

#[test]
fn trace_sees_what_draw_draws() {
    let cam = camera();
    let display = render_rgb888(Method::TARGET_DEFAULT);
    let mut count = 0;
    Render::<2>::new(&SCENE, &cam).trace(|s| {
        count += 1;
        assert_eq!(display.get_pixel(s.pixel), Some(s.color));
        assert_eq!(s.hit.is_some(), s.color != Rgb888::BLACK);
        assert!(s.direction.is_finite());
    });
    assert_eq!(count, 24 * 16);
}

/// A target whose bounding box reaches past `i32::MAX` on both axes (a display placed
/// at the far end of the coordinate space): the render clamps the clip to coordinates
/// that exist, so no row wraps to `i32::MIN` and no row's area runs past `i32::MAX`;
/// the pixels it draws are the whole render's.
#[test]
fn targets_reaching_past_i32_max_are_clipped_to_representable_coordinates() {
    struct Edge {
        area: Rectangle,
        pixels: Vec<(i64, i64, Rgb888)>,
    }
    impl Dimensions for Edge {
        fn bounding_box(&self) -> Rectangle {
            self.area
        }
    }
    impl DrawTarget for Edge {
        type Color = Rgb888;
        type Error = core::convert::Infallible;
        fn draw_iter<I: IntoIterator<Item = Pixel<Rgb888>>>(&mut self, _: I) -> Result<(), Self::Error> {
            panic!("the render sends rows through fill_contiguous");
        }
        fn fill_contiguous<I: IntoIterator<Item = Rgb888>>(
            &mut self,
            area: &Rectangle,
            colors: I,
        ) -> Result<(), Self::Error> {
            // The area's far corner in i64: it must not pass i32::MAX.
            let (x0, y0) = (i64::from(area.top_left.x), i64::from(area.top_left.y));
            let (w, h) = (i64::from(area.size.width), i64::from(area.size.height));
            assert!(
                x0 + w - 1 <= i64::from(i32::MAX) && y0 + h - 1 <= i64::from(i32::MAX),
                "{area:?}"
            );
            let mut colors = colors.into_iter();
            for y in y0..y0 + h {
                for x in x0..x0 + w {
                    self.pixels.push((x, y, colors.next().unwrap()));
                }
            }
            Ok(())
        }
    }
    let cam = camera();
    let full = render_rgb888(Method::TARGET_DEFAULT);
    let corner = Point::new(i32::MAX - 5, i32::MAX - 3);
    let mut target = Edge {
        area: Rectangle::new(corner, Size::new(100, 100)),
        pixels: Vec::new(),
    };
    Render::new(&SCENE, &cam)
        .with_offset(corner)
        .draw(&mut target)
        .unwrap();
    // Columns MAX−5 … MAX and rows MAX−3 … MAX exist: 6 × 4 pixels.
    assert_eq!(target.pixels.len(), 6 * 4);
    for (x, y, c) in target.pixels {
        let p = Point::new((x - i64::from(corner.x)) as i32, (y - i64::from(corner.y)) as i32);
        assert_eq!(Some(c), full.get_pixel(p), "at {p:?}");
    }
}
