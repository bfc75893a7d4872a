//! The program state: the scene file and its reload, the view, the playing clock, the
//! display model's framebuffer and the window's screen drawn from it.
//!
//! What the keys and the mouse do is [`input`]; the status bar and the error text are
//! [`overlay`].

use std::path::PathBuf;
use std::time::{Duration, Instant, SystemTime};

use embedded_graphics::{
    mono_font::{
        ascii::{FONT_4X6, FONT_6X10},
        MonoFont,
    },
    pixelcolor::Rgb888,
    prelude::*,
    primitives::Rectangle,
};
use embedded_graphics_simulator::SimulatorDisplay;
use embedded_raytracer::{
    motion::Animation, scene_file::MAX_MOTIONS, Arithmetic, Camera, CameraParams, FrameStats, Options,
    SecondaryOrigin,
};

use crate::args::Args;
use crate::loading::{moment, mtime, Loaded};
use crate::orbit::Orbit;
use crate::play;
use crate::view::{shade, View, REFERENCE};

mod input;
mod overlay;
#[cfg(test)]
mod tests;

/// How often the scene file's mtime is checked.
const POLL: Duration = Duration::from_millis(250);
/// Colour of differing pixels in the difference view.
const DIFF_COLOR: Rgb888 = Rgb888::new(255, 0, 255);

/// The program state.
pub struct App {
    path: PathBuf,
    mtime: Option<SystemTime>,
    last_poll: Instant,
    /// The last scene that loaded, as its file places it (before any motion).
    scene: Loaded,
    base: CameraParams,
    /// The scene's motion (none: a still scene).
    pub animation: Animation<MAX_MOTIONS>,
    /// The frame of the motion shown, and whether it plays.
    clock: play::Clock,
    /// The user's view of the file's camera (before any motion of the camera).
    camera: Camera,
    /// The display's resolution (fixed for the session).
    pub size: Size,
    orbit: Orbit,
    view: View,
    diff: bool,
    error: Option<String>,
    overlay: bool,
    font: &'static MonoFont<'static>,
    status_height: u32,
    /// What the window shows: the display's image, the status bar below it.
    pub screen: SimulatorDisplay<Rgb888>,
    /// The display model's framebuffer the frames are drawn on, incrementally.
    display: play::Display,
    /// What the last frame cost, and the arithmetic it was drawn in.
    stats: FrameStats,
    arithmetic: Option<Arithmetic>,
    /// Whether the screen is to be drawn again.
    pub dirty: bool,
    drag: Option<Point>,
    /// Pixels that differed from the reference in the last difference view.
    differing: Option<usize>,
}

impl App {
    pub fn new(args: &Args) -> Result<Self, String> {
        let (scene, base, animation) = Loaded::load(&args.scene)?;
        let size = args.size.unwrap_or(base.size);
        let camera = base.with_size(size).build().map_err(|e| {
            format!(
                "{}: --size {}x{}: {e}",
                args.scene.display(),
                size.width,
                size.height
            )
        })?;
        let font = if size.width >= 240 { &FONT_6X10 } else { &FONT_4X6 };
        let status_height = if args.overlay {
            3 * (font.character_size.height + 1) + 1
        } else {
            0
        };
        Ok(Self {
            mtime: mtime(&args.scene),
            path: args.scene.clone(),
            last_poll: Instant::now(),
            scene,
            base,
            clock: play::Clock::new(args.frame.map(|k| k - 1), Instant::now()),
            animation,
            camera,
            size,
            orbit: Orbit::default(),
            view: View {
                model: args.model,
                method: args.method,
                secondary: Options::DEFAULT.secondary,
                sampling: args.sampling,
                bayer: args.bayer,
                theme: args.theme,
            },
            diff: args.diff,
            error: None,
            overlay: args.overlay,
            font,
            status_height,
            screen: SimulatorDisplay::new(Size::new(size.width, size.height + status_height)),
            display: play::Display::new(size, args.model, args.bayer),
            stats: FrameStats::default(),
            arithmetic: None,
            dirty: true,
            drag: None,
            differing: None,
        })
    }

    /// Rebuilds the camera from the orbit; an invalid one keeps the previous camera.
    fn update_camera(&mut self) {
        match self.orbit.params(&self.base, self.size).build() {
            Ok(camera) => self.camera = camera,
            Err(e) => eprintln!("camera: {e} (keeping the previous view)"),
        }
        self.dirty = true;
    }

    /// Reloads the scene file if its mtime changed; a bad file keeps the last good
    /// scene and shows the error.
    pub fn poll_file(&mut self) {
        if self.last_poll.elapsed() < POLL {
            return;
        }
        self.last_poll = Instant::now();
        let now = mtime(&self.path);
        if now == self.mtime {
            return;
        }
        self.mtime = now;
        match Loaded::load(&self.path) {
            Ok((scene, base, animation)) => {
                self.scene = scene;
                self.base = base;
                self.animation = animation;
                self.clock.reloaded(&self.animation, Instant::now());
                self.display.invalidate();
                self.error = None;
                self.update_camera();
                eprintln!("{}: reloaded", self.path.display());
            }
            Err(e) => {
                eprintln!("error: {e}");
                self.error = Some(e.to_string());
                self.dirty = true;
            }
        }
    }

    /// Whether the scene moves.
    fn moves(&self) -> bool {
        !self.animation.is_still()
    }

    /// Moves a playing motion on to the frame due at `now`.
    pub fn tick(&mut self, now: Instant) {
        if self.clock.tick(&self.animation, now) {
            self.dirty = true;
        }
    }

    /// Draws the frame shown onto the display model's framebuffer (only what changed,
    /// for a scene that moves; whole, for a still one), then the screen from it
    /// (image, difference marks, status bar).
    pub fn redraw(&mut self) {
        let (scene, camera) = match moment(&self.scene, &self.animation, &self.camera, self.clock.frame()) {
            Ok(moment) => moment,
            Err(e) => {
                // The last frame stays on screen.
                eprintln!("error: {}: {e}", self.path.display());
                self.dirty = false;
                return;
            }
        };
        if !self.moves() {
            self.display.invalidate();
        }
        let start = Instant::now();
        let stats = self.display.draw(&scene, &camera, &self.view);
        let render_time = start.elapsed();
        self.clock.record(Instant::now());
        if let Some(e) = stats.refused {
            eprintln!(
                "error: {}: the frame cannot be drawn exactly: {e}",
                self.path.display()
            );
        }
        self.stats = stats;
        self.arithmetic = Some(scene.arithmetic(&camera, self.view.method));
        let shown = self.display.shown(self.view.theme);
        let w = self.size.width as usize;
        let mut differing = 0usize;
        let reference_view = View {
            secondary: SecondaryOrigin::Convex,
            ..self.view
        };
        let reference = self
            .diff
            .then(|| shade(&scene, &camera, &reference_view, REFERENCE));
        drop(scene);
        let pixels = shown.iter().enumerate().map(|(k, &c)| match &reference {
            Some(r) if r.get(k) != Some(&c) => {
                differing += 1;
                DIFF_COLOR
            }
            _ => c,
        });
        let area = Rectangle::new(Point::zero(), self.size);
        let Ok(()) = self.screen.fill_contiguous(&area, pixels);
        self.differing = self.diff.then_some(differing);
        debug_assert_eq!(shown.len(), w * self.size.height as usize);

        if self.overlay {
            self.draw_overlay(render_time, differing);
        }
        self.dirty = false;
    }

    /// Draws the frame shown as the player reaches it: for a scene that moves, the
    /// frame before it first (none before the start), then it over that through the
    /// incremental rule.
    pub fn draw_as_played(&mut self) {
        let frame = self.clock.frame();
        if self.moves() && frame > 0 {
            self.clock.show(frame - 1);
            self.redraw();
            self.clock.show(frame);
        }
        self.redraw();
    }
}
