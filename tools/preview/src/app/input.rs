//! What the keys and the mouse do: one function an action, each changing the view,
//! the orbit or the clock and marking the screen for redrawing.

use std::time::Instant;

use embedded_graphics::prelude::Point;
use embedded_graphics_simulator::{
    sdl2::{Keycode, Mod, MouseButton},
    SimulatorEvent,
};
use embedded_raytracer::{Arithmetic, Method, Sampling};
use embedded_raytracer_display::{bayer, Model};

use super::App;
use crate::orbit::{Orbit, ORBIT_STEP};
use crate::view::SECONDARY;

/// The keys `1`–`9`: the display models of [`Model::ALL`], in order.
const DIGITS: [Keycode; 9] = [
    Keycode::NUM_1,
    Keycode::NUM_2,
    Keycode::NUM_3,
    Keycode::NUM_4,
    Keycode::NUM_5,
    Keycode::NUM_6,
    Keycode::NUM_7,
    Keycode::NUM_8,
    Keycode::NUM_9,
];

/// The choice after `current` in `all` (before it, `back`), looping; from the first if
/// `current` is not among them.
fn cycle<T: Copy + PartialEq>(all: &[T], current: T, back: bool) -> T {
    let n = all.len();
    let k = all.iter().position(|&c| c == current).unwrap_or(0);
    let next = if back { k + n - 1 } else { k + 1 };
    all[next % n]
}

impl App {
    /// Handles one window event; `false` to quit.
    pub fn handle(&mut self, event: SimulatorEvent) -> bool {
        match event {
            SimulatorEvent::Quit => return false,
            SimulatorEvent::KeyDown { keycode, keymod, .. } => {
                let shift = keymod.intersects(Mod::LSHIFTMOD | Mod::RSHIFTMOD);
                return self.key(keycode, shift);
            }
            SimulatorEvent::MouseButtonDown {
                mouse_btn: MouseButton::Left,
                point,
            } => self.drag = Some(point),
            SimulatorEvent::MouseButtonUp {
                mouse_btn: MouseButton::Left,
                ..
            } => self.drag = None,
            SimulatorEvent::MouseMove { point } => self.drag_to(point),
            SimulatorEvent::MouseWheel { scroll_delta, .. } if scroll_delta.y != 0 => {
                self.zoom(-scroll_delta.y.signum());
            }
            _ => {}
        }
        true
    }

    /// Handles a key press (`shift`: with Shift held, which goes back through a
    /// cycle); `false` to quit.
    fn key(&mut self, keycode: Keycode, shift: bool) -> bool {
        match keycode {
            Keycode::Q => return false,
            Keycode::LEFT => self.turn(-ORBIT_STEP),
            Keycode::RIGHT => self.turn(ORBIT_STEP),
            Keycode::UP => self.tilt(ORBIT_STEP),
            Keycode::DOWN => self.tilt(-ORBIT_STEP),
            Keycode::PLUS | Keycode::EQUALS | Keycode::KP_PLUS => self.zoom(-1),
            Keycode::MINUS | Keycode::KP_MINUS => self.zoom(1),
            Keycode::R => self.reset_orbit(),
            Keycode::M => self.next_method(shift),
            Keycode::I => self.toggle_arithmetic(),
            Keycode::E => self.next_secondary(shift),
            Keycode::A => self.next_sampling(shift),
            Keycode::D => self.toggle_difference(),
            Keycode::TAB => self.next_model(shift),
            Keycode::B => self.switch_bayer(),
            Keycode::SPACE if self.moves() => self.toggle_playing(),
            Keycode::PERIOD if self.moves() => self.step(1),
            Keycode::COMMA if self.moves() => self.step(-1),
            Keycode::T => self.switch_theme(),
            k => {
                if let Some(i) = DIGITS.iter().position(|&d| d == k) {
                    self.pick_model(Model::ALL[i]);
                }
            }
        }
        true
    }

    /// `R`: the file's camera again.
    fn reset_orbit(&mut self) {
        self.orbit = Orbit::default();
        self.update_camera();
    }

    /// `M`/`Shift+M`: the next (previous) method of `Method::ALL`.
    fn next_method(&mut self, back: bool) {
        self.view.method = cycle(&Method::ALL, self.view.method, back);
        self.dirty = true;
    }

    /// `I`: the integer kernel, or f32 again.
    fn toggle_arithmetic(&mut self) {
        let next = if self.view.method.arithmetic == Arithmetic::F32 {
            Arithmetic::Integer
        } else {
            Arithmetic::F32
        };
        self.view.method = self.view.method.with_arithmetic(next);
        self.dirty = true;
    }

    /// `E`/`Shift+E`: the next (previous) origin of the secondary rays.
    fn next_secondary(&mut self, back: bool) {
        self.view.secondary = cycle(&SECONDARY, self.view.secondary, back);
        self.dirty = true;
    }

    /// `A`/`Shift+A`: the next (previous) sampling of `Sampling::ALL`.
    fn next_sampling(&mut self, back: bool) {
        self.view.sampling = cycle(&Sampling::ALL, self.view.sampling, back);
        self.dirty = true;
    }

    /// `D`: the difference view on or off.
    fn toggle_difference(&mut self) {
        self.diff = !self.diff;
        self.dirty = true;
    }

    /// `Tab`/`Shift+Tab`: the next (previous) display model.
    fn next_model(&mut self, back: bool) {
        self.pick_model(cycle(&Model::ALL, self.view.model, back));
    }

    /// `1`–`9`: display model `model`.
    fn pick_model(&mut self, model: Model) {
        self.view.model = model;
        self.dirty = true;
    }

    /// `B`: the other Bayer matrix.
    fn switch_bayer(&mut self) {
        self.view.bayer = bayer::other(self.view.bayer);
        self.dirty = true;
    }

    /// `T`: the other OLED theme of the binary models.
    fn switch_theme(&mut self) {
        self.view.theme = self.view.theme.next();
        self.dirty = true;
    }

    /// `Space`: pauses a scene that moves, or plays it on.
    fn toggle_playing(&mut self) {
        self.clock.toggle(&self.animation, Instant::now());
        self.dirty = true;
    }

    /// `.`/`,`: pauses and steps `delta` frames on.
    fn step(&mut self, delta: i64) {
        self.clock.step(&self.animation, delta);
        self.dirty = true;
    }

    /// The mouse moved to `point`: with the left button held, the orbit follows it.
    fn drag_to(&mut self, point: Point) {
        if let Some(from) = self.drag {
            let d = point - from;
            if d != Point::zero() {
                // Half a turn per display width, both axes.
                let per_px = core::f32::consts::PI / self.size.width as f32;
                self.orbit.azimuth -= d.x as f32 * per_px;
                self.orbit.tilt(&self.base, d.y as f32 * per_px);
                self.update_camera();
                self.drag = Some(point);
            }
        }
    }

    /// Turns the orbit by `delta` radians of azimuth.
    fn turn(&mut self, delta: f32) {
        self.orbit.azimuth += delta;
        self.update_camera();
    }

    /// Tilts the orbit by `delta` radians of elevation.
    fn tilt(&mut self, delta: f32) {
        self.orbit.tilt(&self.base, delta);
        self.update_camera();
    }

    /// Zooms `steps` steps out (in, negative).
    fn zoom(&mut self, steps: i32) {
        // Between 1/1.1^40 ≈ 1/45 and 45 times the file's distance.
        self.orbit.zoom_steps = (self.orbit.zoom_steps + steps).clamp(-40, 40);
        self.update_camera();
    }
}
