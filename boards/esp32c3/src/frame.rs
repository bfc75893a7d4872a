//! The frame and its status line, without the HAL: the firmware (`main.rs`) and the
//! lab's host test (`lab/tests/lab/board_examples.rs`) compile this file, so the test
//! draws the frames through this code.

use core::fmt::{Debug, Write as _};
use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyleBuilder};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::text::{Baseline, Text};
use embedded_raytracer::{Camera, CameraError, FrameError, IntegerError, Render, Scene};

/// Which kernel drew a frame.
pub enum Kernel {
    Integer,
    F32,
}

/// Why a frame was not drawn.
pub enum Failed<E> {
    Camera(CameraError),
    Frame(FrameError),
    Display(E),
}

/// One frame, in one call: the integer kernel, or the `f32` kernel where the integer
/// kernel's rule refuses the frame (after `check`, since `draw` leaves a frame it
/// cannot draw exactly untouched).
pub fn frame<D: DrawTarget<Color = Rgb565>, const N: usize>(
    display: &mut D,
    scene: &Scene<N>,
    camera: Result<Camera, CameraError>,
) -> Result<Kernel, Failed<D::Error>> {
    let camera = camera.map_err(Failed::Camera)?;
    let render = Render::new(scene, &camera);
    match render.draw_integer(display) {
        Ok(()) => Ok(Kernel::Integer),
        Err(IntegerError::Target(e)) => Err(Failed::Display(e)),
        Err(_refused) => {
            render.check().map_err(Failed::Frame)?;
            render.draw(display).map_err(Failed::Display)?;
            Ok(Kernel::F32)
        }
    }
}

/// `text` in white on black from the top-left corner, cut into lines of the panel's
/// width (ASCII: the library's messages are).
pub fn show<D: DrawTarget<Color = Rgb565>>(display: &mut D, text: &str) -> Result<(), D::Error> {
    let style = MonoTextStyleBuilder::new()
        .font(&FONT_6X10)
        .text_color(Rgb565::WHITE)
        .background_color(Rgb565::BLACK)
        .build();
    let per_line = (display.bounding_box().size.width as usize / 6)
        .saturating_sub(1)
        .max(1);
    for (row, line) in text.as_bytes().chunks(per_line).enumerate() {
        let line = core::str::from_utf8(line).unwrap_or("?");
        Text::with_baseline(line, Point::new(2, 2 + 10 * row as i32), style, Baseline::Top).draw(display)?;
    }
    Ok(())
}

/// The status line: the kernel and its frame rate, or the error.
pub fn status<E: Debug>(
    drawn: &Result<Kernel, Failed<E>>,
    us: u64,
    display_errors: u32,
) -> heapless::String<256> {
    let mut s = heapless::String::new();
    let tenths = 10_000_000 / us.max(1);
    // A `String` only fails when full; 256 bytes hold every message here.
    let written = match drawn {
        Ok(Kernel::Integer) => write!(s, "integer {}.{} fps", tenths / 10, tenths % 10),
        Ok(Kernel::F32) => write!(s, "f32 (integer refused) {}.{} fps", tenths / 10, tenths % 10),
        Err(Failed::Camera(e)) => write!(s, "camera: {e}"),
        Err(Failed::Frame(e)) => write!(s, "{e}"),
        Err(Failed::Display(e)) => write!(s, "display error: {e:?}"),
    }
    .and_then(|()| match display_errors {
        0 => Ok(()),
        n => write!(s, " ({n} label writes failed)"),
    });
    if written.is_err() {
        s.clear();
        s.push_str("(message too long)").ok();
    }
    s
}
