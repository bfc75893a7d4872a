//! Playing a scene's motion: which frame is shown (the wall clock at the animation's
//! frame rate, looping, or paused on one frame), and the display model's framebuffer,
//! kept from frame to frame and drawn through one `Incremental` per scene type, so
//! that each frame traces and sends only the pixels that can differ from the last.

use std::collections::VecDeque;
use std::convert::Infallible;
use std::time::{Duration, Instant};

use embedded_graphics::{pixelcolor::Rgb888, prelude::*};
use embedded_raytracer::{
    dither::Bayer, motion::Animation, Camera, FrameStats, Incremental, Options, Render,
};
use embedded_raytracer_display::{Model, Paint, Panel, Theme};
use embedded_raytracer_scenes::{MAX_DEPTH, MAX_LIGHTS, MAX_PLANES, MAX_SPHERES};

use crate::loading::Loaded;
use crate::view::View;

/// The span of recent frames the achieved frame rate is measured over.
const RATE_WINDOW: Duration = Duration::from_secs(1);

/// Which frame of the animation is shown, and whether it plays.
pub struct Clock {
    /// The frame shown (0: the animation's start; frame `k` is the moment `k / fps`).
    frame: u32,
    paused: bool,
    /// While playing: when frame 0 of the loop was due.
    start: Instant,
    /// When the recent frames were drawn (within [`RATE_WINDOW`] of the last).
    drawn: VecDeque<Instant>,
}

impl Clock {
    /// Playing from frame 0, or paused on `frame`.
    pub fn new(frame: Option<u32>, now: Instant) -> Self {
        Self {
            frame: frame.unwrap_or(0),
            paused: frame.is_some(),
            start: now,
            drawn: VecDeque::new(),
        }
    }

    /// The frame shown.
    pub fn frame(&self) -> u32 {
        self.frame
    }

    pub fn is_paused(&self) -> bool {
        self.paused
    }

    /// Moves a playing animation on to the frame due at `now` (frames are skipped
    /// when drawing is slower than the frame rate: the motion keeps real time);
    /// whether that is another frame than the one shown.
    pub fn tick<const M: usize>(&mut self, animation: &Animation<M>, now: Instant) -> bool {
        if self.paused || animation.is_still() {
            return false;
        }
        let elapsed = now.saturating_duration_since(self.start).as_secs_f64();
        let due = (elapsed * f64::from(animation.fps())) as u64 % u64::from(animation.frames().max(1));
        // `due` < frames(), a u32.
        let due = due as u32;
        let changed = due != self.frame;
        self.frame = due;
        changed
    }

    /// Pauses on the frame shown, or resumes playing from it.
    pub fn toggle<const M: usize>(&mut self, animation: &Animation<M>, now: Instant) {
        if self.paused {
            self.resume_at(animation, now);
        }
        self.paused = !self.paused;
        self.drawn.clear();
    }

    /// Pauses on frame `frame` (which may lie beyond the loop, as the render CLI's
    /// `--frame` may).
    pub fn show(&mut self, frame: u32) {
        self.frame = frame;
        self.paused = true;
        self.drawn.clear();
    }

    /// Pauses and shows the frame `delta` frames on (looping either way).
    pub fn step<const M: usize>(&mut self, animation: &Animation<M>, delta: i64) {
        let frames = i64::from(animation.frames().max(1));
        // In 0..frames: a u32.
        self.frame = (i64::from(self.frame) + delta).rem_euclid(frames) as u32;
        self.paused = true;
        self.drawn.clear();
    }

    /// The animation changed (a reload): a paused one stays on its frame, a playing one
    /// goes on from its frame (within the new loop) at the new frame rate.
    pub fn reloaded<const M: usize>(&mut self, animation: &Animation<M>, now: Instant) {
        if !self.paused {
            self.frame %= animation.frames().max(1);
            self.resume_at(animation, now);
        }
        self.drawn.clear();
    }

    /// Sets the playing clock so that the frame shown is due at `now`: halfway through
    /// it, so that rounding does not take it back one frame.
    fn resume_at<const M: usize>(&mut self, animation: &Animation<M>, now: Instant) {
        let into = (f64::from(self.frame) + 0.5) / f64::from(animation.fps());
        self.start = Duration::try_from_secs_f64(into)
            .ok()
            .and_then(|d| now.checked_sub(d))
            .unwrap_or(now);
    }

    /// A frame was drawn at `now`.
    pub fn record(&mut self, now: Instant) {
        self.drawn.push_back(now);
        while self
            .drawn
            .front()
            .is_some_and(|&t| now.saturating_duration_since(t) > RATE_WINDOW)
        {
            self.drawn.pop_front();
        }
    }

    /// Frames drawn a second over the last [`RATE_WINDOW`] (at least two frames).
    pub fn rate(&self) -> Option<f64> {
        let (first, last) = (self.drawn.front()?, self.drawn.back()?);
        let span = last.saturating_duration_since(*first).as_secs_f64();
        (self.drawn.len() >= 2 && span > 0.0).then(|| (self.drawn.len() - 1) as f64 / span)
    }
}

/// The display the frames are drawn on: the model's panel, and what it shows as each
/// scene type's `Incremental` remembers it.
pub struct Display {
    size: Size,
    /// The framebuffer, of the model (and Bayer matrix) its pixels were drawn with.
    panel: Panel,
    /// A spheres-only scene's frames (the Lab #1 loop, as [`crate::view::shade`] draws it).
    spheres: Box<Incremental<MAX_SPHERES>>,
    /// The frames of a scene with lights, planes or mirrors.
    full: Box<Incremental<MAX_SPHERES, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>>,
}

impl Display {
    pub fn new(size: Size, model: Model, bayer: Bayer) -> Self {
        Self {
            size,
            panel: Panel::new(model, bayer, size),
            spheres: Box::new(Incremental::new()),
            full: Box::new(Incremental::new()),
        }
    }

    /// The framebuffer no longer shows the last frame drawn: the next is drawn whole.
    pub fn invalidate(&mut self) {
        self.spheres.invalidate();
        self.full.invalidate();
    }

    /// Draws `scene` through `camera` and `view` onto the framebuffer, tracing and
    /// sending only what can differ from the frame it shows. Afterwards it holds the
    /// frame's full render through the model, bit for bit. A change of model (or of a
    /// dithered model's matrix) starts a new framebuffer, drawn whole.
    pub fn draw(&mut self, scene: &Loaded, camera: &Camera, view: &View) -> FrameStats {
        if !self.panel.shows(view.model, view.bayer) {
            self.panel = Panel::new(view.model, view.bayer, self.size);
            self.invalidate();
        }
        self.panel.paint(Played {
            spheres: &mut self.spheres,
            full: &mut self.full,
            scene,
            camera,
            view,
        })
    }

    /// The colours the panel shows (one a display pixel, row-major).
    pub fn shown(&self, theme: Theme) -> Vec<Rgb888> {
        self.panel.shown(theme)
    }
}

/// [`Display::draw`]'s work on the panel: the render [`crate::view::shade`] would draw,
/// through its scene type's `Incremental`. The other type's forgets the target: what it
/// drew last is no longer shown.
struct Played<'a> {
    spheres: &'a mut Incremental<MAX_SPHERES>,
    full: &'a mut Incremental<MAX_SPHERES, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>,
    scene: &'a Loaded,
    camera: &'a Camera,
    view: &'a View,
}

impl Paint for Played<'_> {
    type Output = FrameStats;

    fn paint<Tg>(self, target: &mut Tg) -> FrameStats
    where
        Tg: DrawTarget<Error = Infallible>,
        Tg::Color: From<Rgb888>,
    {
        let Played {
            spheres,
            full,
            scene,
            camera,
            view,
        } = self;
        let options = Options::DEFAULT.with_secondary(view.secondary);
        match scene {
            Loaded::Spheres(scene) => {
                full.invalidate();
                let render = Render::new(&**scene, camera)
                    .with_method(view.method)
                    .with_options(options)
                    .with_sampling(view.sampling);
                let Ok(stats) = spheres.draw(&render, target);
                stats
            }
            Loaded::Full(scene) => {
                spheres.invalidate();
                let render = Render::new(&**scene, camera)
                    .with_method(view.method)
                    .with_options(options)
                    .with_sampling(view.sampling);
                let Ok(stats) = full.draw(&render, target);
                stats
            }
        }
    }
}
