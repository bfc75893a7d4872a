//! The frame and its status line, without the HAL: the firmware (`main.rs`) and the
//! lab's host test (`lab/tests/lab/board_examples.rs`) compile this file, so the test
//! draws the frames through this code.

use core::fmt::{Debug, Write as _};
use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyleBuilder};
use embedded_graphics::pixelcolor::BinaryColor;
use embedded_graphics::prelude::*;
use embedded_graphics::text::{Baseline, Text};
use embedded_raytracer::dither::DitherExt as _;
use embedded_raytracer::motion::{Animation, MotionError};
use embedded_raytracer::{
    Arithmetic, CameraError, CameraParams, FrameError, FrameStats, Incremental, Method, Render, Scene,
};

/// Why a frame was not drawn or not shown.
pub enum Failed<E> {
    Motion(MotionError),
    Camera(CameraError),
    Frame(FrameError),
    Display(E),
}

/// The scene at rest, its camera (at the panel's size) and its motion.
pub struct Film<'a, const N: usize, const M: usize> {
    pub scene: &'a Scene<N>,
    pub camera: CameraParams,
    pub animation: &'a Animation<M>,
}

/// Frame `k` of `film` into `scene` (a working copy) and onto `display` through
/// `shown` and the 8×8 ordered dither: only what changed since the frame `shown` remembers is traced and
/// sent. The integer kernel, or the `f32` kernel where the integer kernel's rule
/// refuses the frame; a frame `f32` cannot draw exactly is refused rather than left
/// half-drawn. Returns the kernel that drew it. After a display
/// error the display's content is unknown: the next frame is drawn whole.
pub fn frame<D, const N: usize, const M: usize>(
    display: &mut D,
    shown: &mut Incremental<N>,
    film: &Film<'_, N, M>,
    k: u32,
    scene: &mut Scene<N>,
) -> Result<(Arithmetic, FrameStats), Failed<D::Error>>
where
    D: DrawTarget<Color = BinaryColor>,
{
    let mut params = film.camera;
    film.animation
        .apply_frame(film.scene, &film.camera, k, scene, &mut params)
        .map_err(Failed::Motion)?;
    let camera = params.build().map_err(Failed::Camera)?;
    // The plan refuses what `Render::check` refuses (`stats.refused`), and says which
    // kernel drew the frame (`stats.arithmetic`): neither the check nor the integer
    // kernel's per-frame rule, soft `f64` on a chip without an FPU, runs twice.
    let render = Render::new(&*scene, &camera).with_method(Method::INTEGER);
    match shown.draw(&render, &mut display.dithered()) {
        Ok(stats) => match stats.refused {
            Some(why) => Err(Failed::Frame(why)),
            None => Ok((stats.arithmetic, stats)),
        },
        Err(e) => {
            shown.invalidate();
            Err(Failed::Display(e))
        }
    }
}

/// `text` lit on dark from the top-left corner, cut into lines of the panel's width
/// (ASCII: the library's messages are); `shown` is told which pixels of the picture it
/// covered, drawn or not, so that the next frame restores them.
pub fn show<D, const N: usize>(
    display: &mut D,
    shown: &mut Incremental<N>,
    text: &str,
) -> Result<(), D::Error>
where
    D: DrawTarget<Color = BinaryColor>,
{
    let style = MonoTextStyleBuilder::new()
        .font(&FONT_6X10)
        .text_color(BinaryColor::On)
        .background_color(BinaryColor::Off)
        .build();
    let per_line = (display.bounding_box().size.width as usize / 6).max(1);
    let mut result = Ok(());
    for (row, line) in text.as_bytes().chunks(per_line).enumerate() {
        let line = core::str::from_utf8(line).unwrap_or("?");
        let text = Text::with_baseline(line, Point::new(0, 10 * row as i32), style, Baseline::Top);
        shown.invalidate_area(text.bounding_box());
        result = result.and(text.draw(display).map(|_| ()));
    }
    result
}

/// The status line: the kernel, the frame rate of the last frame timed (`us`
/// microseconds; `None` before the first, when no rate is shown) and the share of the
/// panel sent, or the error.
pub fn status<E: Debug>(
    drawn: &Result<(Arithmetic, FrameStats), Failed<E>>,
    us: Option<u64>,
    pixels: u32,
    flush_errors: u32,
) -> heapless::String<256> {
    let mut s = heapless::String::new();
    let share = |n: u32| u64::from(n) * 100 / u64::from(pixels.max(1));
    // A `String` only fails when full; 256 bytes hold every message here.
    let written = match drawn {
        Ok((arithmetic, stats)) => {
            let kernel = match arithmetic {
                Arithmetic::Integer => "int",
                _ => "f32",
            };
            let sent = share(stats.sent);
            match us {
                Some(us) => {
                    let tenths = 10_000_000 / us.max(1);
                    write!(s, "{kernel} {}.{}fps {sent}%", tenths / 10, tenths % 10)
                }
                None => write!(s, "{kernel} {sent}%"),
            }
        }
        Err(Failed::Motion(e)) => write!(s, "motion: {e}"),
        Err(Failed::Camera(e)) => write!(s, "camera: {e}"),
        Err(Failed::Frame(e)) => write!(s, "{e}"),
        Err(Failed::Display(e)) => write!(s, "display: {e:?}"),
    }
    .and_then(|()| match flush_errors {
        0 => Ok(()),
        n => write!(s, " {n} I2C err"),
    });
    if written.is_err() {
        s.clear();
        s.push_str("(message too long)").ok();
    }
    s
}
