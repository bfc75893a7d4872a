//! The status bar below the image (render time, model, method, frame rate or orbit) and
//! the load error over it: drawn on the window's screen, never on the model's
//! framebuffer the frames are drawn on.

use std::time::Duration;

use embedded_graphics::{
    mono_font::MonoTextStyle,
    pixelcolor::Rgb888,
    prelude::*,
    primitives::Rectangle,
    text::{Baseline, Text},
};
use embedded_raytracer::Arithmetic;
use embedded_raytracer_display::bayer;

use super::App;
use crate::view::secondary_label;

impl App {
    /// The status bar below the image, and the load error, if any, over the image.
    pub(super) fn draw_overlay(&mut self, render_time: Duration, differing: usize) {
        let status = Rectangle::new(
            Point::new(0, self.size.height as i32),
            Size::new(self.size.width, self.status_height),
        );
        let Ok(()) = self.screen.fill_solid(&status, Rgb888::new(24, 24, 24));
        let lines = self.status(render_time, differing);
        let style = MonoTextStyle::new(self.font, Rgb888::new(230, 230, 230));
        let line_h = self.font.character_size.height as i32 + 1;
        for (k, line) in lines.iter().enumerate() {
            let at = Point::new(1, self.size.height as i32 + 1 + k as i32 * line_h);
            let Ok(_) = Text::with_baseline(line, at, style, Baseline::Top).draw(&mut self.screen);
        }
        if let Some(error) = self.error.clone() {
            self.draw_error(&error);
        }
    }

    /// The status bar's three lines: render time and display model; the method (and,
    /// for a scene with lights, planes or mirrors, the secondary origin); the
    /// difference count, or for a scene that moves the frame rate achieved (the frame,
    /// paused) and the share of the display the last frame traced and sent, or the
    /// orbit.
    pub(super) fn status(&self, render_time: Duration, differing: usize) -> [String; 3] {
        let ms = render_time.as_secs_f64() * 1e3;
        let mut model = self.view.model.name().to_string();
        if self.view.model.is_dithered() {
            model = format!("{model} {}", bayer::label(self.view.bayer));
        }
        let mut method = self.view.method.to_string();
        // The last frame's (a moving scene's frames can differ), else the view's.
        let arithmetic = self
            .arithmetic
            .unwrap_or_else(|| self.scene.arithmetic(&self.camera, self.view.method));
        if self.view.method.arithmetic == Arithmetic::Integer && arithmetic == Arithmetic::F32 {
            method += " → f32";
        }
        if self.scene.has_features() {
            method = format!("{method} {}", secondary_label(self.view.secondary));
        }
        let third = if self.diff {
            format!("D: {differing} px differ")
        } else if self.moves() {
            let pixels = f64::from(self.size.width) * f64::from(self.size.height);
            let share = |n: u32| 100.0 * f64::from(n) / pixels.max(1.0);
            let played = if self.clock.is_paused() {
                format!(
                    "paused {}/{}",
                    u64::from(self.clock.frame()) + 1,
                    self.animation.frames()
                )
            } else {
                match self.clock.rate() {
                    Some(rate) => format!("{rate:.0} fps"),
                    None => "- fps".to_string(),
                }
            };
            format!(
                "{played} traced {:.0}% sent {:.0}%",
                share(self.stats.traced),
                share(self.stats.sent)
            )
        } else {
            let o = self.orbit;
            format!(
                "az {:.0} el {:+.0} zoom {}",
                o.azimuth.to_degrees(),
                o.elevation.to_degrees(),
                -o.zoom_steps
            )
        };
        [
            format!("{ms:.2} ms {model} {}", self.view.sampling),
            method,
            third,
        ]
    }

    /// The load error over the (last good) image, wrapped to the display width.
    fn draw_error(&mut self, error: &str) {
        let cw = self.font.character_size.width.max(1);
        let cols = (self.size.width.saturating_sub(2) / cw).max(1) as usize;
        let line_h = self.font.character_size.height + 1;
        let chars: Vec<char> = format!("scene not reloaded: {error}").chars().collect();
        let lines: Vec<String> = chars.chunks(cols).map(|c| c.iter().collect()).collect();
        let height = (lines.len() as u32 * line_h + 2).min(self.size.height);
        let Ok(()) = self.screen.fill_solid(
            &Rectangle::new(Point::zero(), Size::new(self.size.width, height)),
            Rgb888::new(60, 0, 0),
        );
        let style = MonoTextStyle::new(self.font, Rgb888::new(255, 200, 200));
        for (k, line) in lines.iter().enumerate() {
            let at = Point::new(1, 1 + (k as u32 * line_h) as i32);
            let Ok(_) = Text::with_baseline(line, at, style, Baseline::Top).draw(&mut self.screen);
        }
    }
}
