//! Bands: `Render::draw_band` traces any rows into a caller's buffer, and bands of every
//! height, or split at random, concatenate to the whole render's pixels bit for bit —
//! every method, every standard scene, two colour formats.

use crate::common;

use common::Rng;
use embedded_graphics::pixelcolor::{Rgb565, Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_raytracer::{BandError, Camera, Method, Render, Scene};

/// The whole render's pixels, row-major.
fn whole<const N: usize>(scene: &Scene<N>, camera: &Camera, method: Method) -> Vec<Rgb888> {
    common::trace(Render::new(scene, camera).with_method(method))
        .into_iter()
        .map(|p| p.1)
        .collect()
}

/// The image drawn band by band, the bands' heights from `heights` (cycled).
fn in_bands<const N: usize, C: PixelColor + From<Rgb888>>(
    render: &Render<'_, N, C>,
    size: Size,
    mut heights: impl FnMut() -> u32,
) -> Vec<C> {
    let mut out = Vec::new();
    let mut j = 0;
    while j < size.height {
        let end = (j + heights().max(1)).min(size.height);
        let mut band = vec![C::from(Rgb888::new(1, 2, 3)); (size.width * (end - j)) as usize];
        render.draw_band(j..end, &mut band).unwrap();
        out.extend(band);
        j = end;
    }
    out
}

#[test]
fn bands_of_every_height_and_random_splits_equal_the_whole_render() {
    let mut rng = Rng(0xB00_0B1E5);
    for name in common::SCENES {
        let file = common::load(name);
        let camera = common::shrink(&file.camera, 32, 24);
        let size = camera.size();
        for method in Method::ALL.into_iter().chain([Method::INTEGER]) {
            let want = whole(&file.scene, &camera, method);
            let render = Render::<_, Rgb888>::new(&file.scene, &camera).with_method(method);
            for h in 1..=size.height {
                assert!(
                    in_bands(&render, size, || h) == want,
                    "{name} {method}: bands of {h} rows"
                );
            }
            let got = in_bands(&render, size, || rng.range(1.0, 9.0) as u32);
            assert!(got == want, "{name} {method}: random bands");
            // Another colour format: the same conversion as a DrawTarget of that format.
            let rgb565 = Render::<_, Rgb565>::new(&file.scene, &camera).with_method(method);
            let got = in_bands(&rgb565, size, || 5);
            let want565: Vec<Rgb565> = want.iter().map(|&c| c.into()).collect();
            assert!(got == want565, "{name} {method}: Rgb565 bands");
        }
    }
}

#[test]
fn bad_bands_are_refused_and_nothing_is_written() {
    let lab = common::load("lab");
    let camera = common::shrink(&lab.camera, 32, 24);
    let render = Render::<_, Rgb888>::new(&lab.scene, &camera);
    let mut buf = vec![Rgb888::WHITE; 32 * 4];
    assert_eq!(
        render.draw_band(22..26, &mut buf),
        Err(BandError::Rows {
            start: 22,
            end: 26,
            height: 24
        })
    );
    assert_eq!(
        render.draw_band(5..5, &mut buf[..0]),
        Err(BandError::Rows {
            start: 5,
            end: 5,
            height: 24
        })
    );
    assert_eq!(
        render.draw_band(0..3, &mut buf),
        Err(BandError::BufferSize {
            expected: 96,
            found: 128
        })
    );
    assert!(buf.iter().all(|&c| c == Rgb888::WHITE));
    assert_eq!(
        BandError::BufferSize {
            expected: 96,
            found: 128
        }
        .to_string(),
        "the band buffer holds 128 pixels; the rows need exactly 96"
    );
}
