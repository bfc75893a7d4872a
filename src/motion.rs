//! Scenes that move: a small vocabulary of motions ([`Circle`], [`Bounce`], [`Orbit`])
//! that an [`Animation`] applies to a base scene and camera to give the scene of any
//! moment.
//!
//! ## The rules
//!
//! - **Time from the frame number**: frame `k` of an animation at `fps` frames a second
//!   is the moment `t = k / fps` seconds ([`frame_time`]); the render CLI, the simulator
//!   and the boards all call that one function, so they draw the same frames, bit for
//!   bit.
//! - **From the base, never accumulated**: [`Animation::apply`] computes frame `t`'s
//!   scene from the base scene and camera each time: frame `k` is the same whatever
//!   frames came before (or whether any did), and a board can skip frames.
//! - **Bit-identical everywhere**: each motion reduces `t` to its phase `s ∈ [0, 1)` of
//!   the period (`s = frac(t / period)`), then uses IEEE `f32` products and the same
//!   `libm` sine and cosine on every target.
//! - **In order**: the motions apply in the order given, each to the sphere (or camera)
//!   as the motions before it left it: a [`Circle`] then a [`Bounce`] on the same
//!   sphere circles while it bounces.
//!
//! Plain `Copy` data with `const fn` constructors, so that firmware compiles its
//! animation in as a constant:
//!
//! ```
//! use embedded_graphics::pixelcolor::Rgb888;
//! use embedded_graphics::prelude::*;
//! use embedded_raytracer::motion::{frame_time, Animation, Bounce, Circle, Motion};
//! use embedded_raytracer::{CameraParams, Scene, Sphere, Vec3};
//!
//! static SCENE: Scene<2> = Scene::from_array(
//!     [
//!         Sphere::new(Vec3::new(0.0, 0.0, 0.0), 0.5, Rgb888::new(255, 64, 64)),
//!         Sphere::new(Vec3::new(1.5, 0.0, 0.0), 0.3, Rgb888::new(64, 64, 255)),
//!     ],
//!     Rgb888::new(0, 0, 0),
//! );
//! const CAMERA: CameraParams = CameraParams::new(
//!     Vec3::new(0.0, 2.0, 6.0), Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), 0.8, Size::new(64, 64),
//! );
//! // The red ball bounces 1 unit high every second; the blue one circles it every 2 s.
//! const ANIMATION: Animation<2> = Animation::from_array([
//!     Motion::Bounce(Bounce::new(0, 1.0, 1.0)),
//!     Motion::Circle(Circle::new(1, Vec3::ZERO, 1.5, 2.0, 0.25)),
//! ]);
//!
//! let (mut scene, mut params) = (SCENE.clone(), CAMERA);
//! // Frame 12 at 24 frames a second: half a second in, the ball at the top.
//! ANIMATION.apply(&SCENE, &CAMERA, frame_time(12, 24.0), &mut scene, &mut params)?;
//! assert_eq!(scene.spheres()[0].center.y, 1.0);
//! // The blue sphere a quarter turn further on its circle of radius 1.5 about the origin.
//! let c = scene.spheres()[1].center;
//! assert!((c.x - 0.0).abs() < 1e-6 && (c.z + 1.5).abs() < 1e-6 && c.y == 0.0);
//! let camera = params.build()?; // ready for `Render::new(&scene, &camera)`
//! # let _ = camera;
//! # Ok::<(), Box<dyn core::error::Error>>(())
//! ```

use core::f32::consts::TAU;
use core::fmt;

use heapless::Vec;

use crate::camera::CameraParams;
use crate::error::{SceneError, SphereError};
use crate::math::vec3::Vec3;
use crate::scene::sphere::Sphere;
use crate::scene::Scene;

/// The frame rate an animation has unless it says otherwise (frames a second).
pub const DEFAULT_FPS: f32 = 25.0;

/// The moment of frame `frame` at `fps` frames a second, in seconds: `frame / fps`.
///
/// One `f32` division, the same bits on every target. Frame 0 is `t = 0`.
///
/// ```
/// use embedded_raytracer::motion::frame_time;
/// assert_eq!(frame_time(0, 25.0), 0.0);
/// assert_eq!(frame_time(50, 25.0), 2.0);
/// ```
#[must_use]
pub const fn frame_time(frame: u32, fps: f32) -> f32 {
    frame as f32 / fps
}

/// The phase of `t` in a motion of period `period`, offset by `phase` periods:
/// `s = frac(t / period + phase)`.
///
/// It lies in `[0, 1]` (1 only where rounding lifts a value just below a whole number
/// to it, which every motion draws as 0).
fn phase_of(t: f32, period: f32, phase: f32) -> f32 {
    let q = t / period + phase;
    q - libm::floorf(q)
}

/// A sphere circling a point in the horizontal plane through it (`y = center.y`).
///
/// At phase `s` of its period it is at `center + radius·(sin 2πs, 0, cos 2πs)` — at
/// `s = 0` on the `+z` side of the centre, a quarter period later on the `+x` side (the
/// sense of [`CameraParams::orbited`]). The sphere's own centre in the base scene is not
/// used; its radius, colour and material are kept.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Circle {
    /// The sphere that moves (its index in [`Scene::spheres`]).
    pub sphere: usize,
    /// The centre of the circle.
    pub center: Vec3,
    /// The circle's radius (scene units; finite).
    pub radius: f32,
    /// Seconds for one turn (finite, `> 0`).
    pub period: f32,
    /// Where on the circle it is at `t = 0`, in turns (`0.5`: on the `−z` side).
    pub phase: f32,
}

impl Circle {
    /// Sphere `sphere` circling `center` at distance `radius` once every `period`
    /// seconds, `phase` turns along at `t = 0` (unchecked; [`Motion::check`]).
    #[must_use]
    pub const fn new(sphere: usize, center: Vec3, radius: f32, period: f32, phase: f32) -> Self {
        Self {
            sphere,
            center,
            radius,
            period,
            phase,
        }
    }

    /// The centre of the sphere at `t`.
    #[must_use]
    pub fn position(&self, t: f32) -> Vec3 {
        let angle = TAU * phase_of(t, self.period, self.phase);
        let (s, c) = (libm::sinf(angle), libm::cosf(angle));
        Vec3::new(
            self.center.x + self.radius * s,
            self.center.y,
            self.center.z + self.radius * c,
        )
    }
}

/// A sphere bouncing: its height above its base position is a parabola in time.
///
/// It is `y = y₀ + height·4·s·(1 − s)` with `s = frac(t / period)` (no trigonometry): on
/// its base position at `t = 0` and every `period` seconds, `height` above it half a
/// period later. `y₀` is the sphere's `y` as the motions before this one left it (the base
/// scene's, if none moved it); `x`, `z`, the radius and the colours are kept. A ball
/// resting on a floor (`y₀` = radius above it) touches the floor at every bounce.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Bounce {
    /// The sphere that moves (its index in [`Scene::spheres`]).
    pub sphere: usize,
    /// The top of the bounce above the base position (scene units; finite).
    pub height: f32,
    /// Seconds from one touch of the base position to the next (finite, `> 0`).
    pub period: f32,
}

impl Bounce {
    /// Sphere `sphere` bouncing `height` high every `period` seconds (unchecked;
    /// [`Motion::check`]).
    #[must_use]
    pub const fn new(sphere: usize, height: f32, period: f32) -> Self {
        Self {
            sphere,
            height,
            period,
        }
    }

    /// How far above its base position the sphere is at `t`: `height·4·s·(1 − s)`.
    #[must_use]
    pub fn lift(&self, t: f32) -> f32 {
        let s = phase_of(t, self.period, 0.0);
        self.height * 4.0 * s * (1.0 - s)
    }
}

/// The camera orbiting the point it looks at, once every `period` seconds.
///
/// At moment `t` the camera is [`CameraParams::orbited`]`(2π·frac(t / period))` — about
/// the line through `look_at` along `up`, keeping height and distance, from `+z` towards
/// `+x` for a camera on the `+z` side.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Orbit {
    /// Seconds for one turn (finite, `> 0`).
    pub period: f32,
}

impl Orbit {
    /// One turn every `period` seconds (unchecked; [`Motion::check`]).
    #[must_use]
    pub const fn new(period: f32) -> Self {
        Self { period }
    }

    /// The angle turned at `t`, radians in `[0, 2π]`.
    #[must_use]
    pub fn angle(&self, t: f32) -> f32 {
        TAU * phase_of(t, self.period, 0.0)
    }
}

/// One motion of an [`Animation`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Motion {
    /// A sphere circling a point.
    Circle(Circle),
    /// A sphere bouncing.
    Bounce(Bounce),
    /// The camera orbiting its look-at point.
    Orbit(Orbit),
}

impl Motion {
    /// The motion's period, seconds.
    #[must_use]
    pub const fn period(&self) -> f32 {
        match self {
            Motion::Circle(c) => c.period,
            Motion::Bounce(b) => b.period,
            Motion::Orbit(o) => o.period,
        }
    }

    /// The sphere it moves, if it moves one.
    #[must_use]
    pub const fn sphere(&self) -> Option<usize> {
        match self {
            Motion::Circle(c) => Some(c.sphere),
            Motion::Bounce(b) => Some(b.sphere),
            Motion::Orbit(_) => None,
        }
    }

    /// The motion if its numbers are usable: every number finite, the period `> 0`.
    ///
    /// `index` is the motion's place in its animation, for the error.
    pub const fn check(self, index: usize) -> Result<Self, MotionError> {
        let period = self.period();
        if !(period.is_finite() && period > 0.0) {
            return Err(MotionError::Period { motion: index });
        }
        let bad = match self {
            Motion::Circle(c) => {
                if !c.center.is_finite() {
                    Some("center")
                } else if !c.radius.is_finite() {
                    Some("radius")
                } else if !c.phase.is_finite() {
                    Some("phase")
                } else {
                    None
                }
            }
            Motion::Bounce(b) => {
                if b.height.is_finite() {
                    None
                } else {
                    Some("height")
                }
            }
            Motion::Orbit(_) => None,
        };
        match bad {
            Some(field) => Err(MotionError::NotFinite { motion: index, field }),
            None => Ok(self),
        }
    }
}

/// Why an [`Animation`] cannot be applied (or a motion not added to it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum MotionError {
    /// Motion `motion`'s period is zero, negative or not finite.
    Period {
        /// The motion's index in the animation.
        motion: usize,
    },
    /// A number of motion `motion` is not finite.
    NotFinite {
        /// The motion's index in the animation.
        motion: usize,
        /// The field (`center`, `radius`, `phase`, `height`).
        field: &'static str,
    },
    /// Motion `motion` moves a sphere the scene does not have.
    NoSuchSphere {
        /// The motion's index in the animation.
        motion: usize,
        /// The sphere it names.
        sphere: usize,
    },
    /// The scene refused the sphere motion `motion` moved (a position beyond `f32`).
    Moved {
        /// The motion's index in the animation.
        motion: usize,
        /// Why the sphere was refused.
        error: SphereError,
    },
    /// The frame rate is not a finite number `> 0`.
    Fps,
    /// The number of frames is 0.
    Frames,
    /// More motions than the animation's capacity.
    Full {
        /// The capacity `M`.
        capacity: usize,
    },
}

impl MotionError {
    /// The motion the error is about, if one is.
    #[must_use]
    pub const fn motion(&self) -> Option<usize> {
        match *self {
            MotionError::Period { motion }
            | MotionError::NotFinite { motion, .. }
            | MotionError::NoSuchSphere { motion, .. }
            | MotionError::Moved { motion, .. } => Some(motion),
            MotionError::Fps | MotionError::Frames | MotionError::Full { .. } => None,
        }
    }

    /// The scene-file key the error is about: a motion's (`period`, `sphere`, …) or the
    /// animation's (`fps`, `frames`).
    #[must_use]
    pub const fn file_key(&self) -> &'static str {
        match *self {
            MotionError::Period { .. } => "period",
            MotionError::NotFinite { field, .. } => field,
            MotionError::NoSuchSphere { .. } | MotionError::Moved { .. } => "sphere",
            MotionError::Fps => "fps",
            MotionError::Frames => "frames",
            MotionError::Full { .. } => "motion",
        }
    }
}

impl fmt::Display for MotionError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            MotionError::Period { .. } => f.write_str("period must be a finite number greater than 0"),
            MotionError::NotFinite { field, .. } => write!(f, "{field} must be a finite number"),
            MotionError::NoSuchSphere { sphere, .. } => write!(f, "the scene has no sphere[{sphere}]"),
            MotionError::Moved { error, .. } => write!(f, "the moved sphere is refused: {error}"),
            MotionError::Fps => f.write_str("fps must be a finite number greater than 0"),
            MotionError::Frames => f.write_str("frames must be at least 1"),
            MotionError::Full { capacity } => write!(f, "more than {capacity} motions"),
        }
    }
}

impl core::error::Error for MotionError {}

/// Up to `M` motions, with the frame rate and the number of frames a loop of the
/// animation has.
///
/// `fps` and `frames` describe how the animation is played (the CLI's default `--fps`
/// and `--frames`); [`apply`](Self::apply) needs only the moment `t`.
#[derive(Clone, Debug, PartialEq)]
pub struct Animation<const M: usize> {
    motions: Vec<Motion, M>,
    fps: f32,
    frames: u32,
}

impl<const M: usize> Default for Animation<M> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const M: usize> Animation<M> {
    /// No motion, [`DEFAULT_FPS`], one frame.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            motions: Vec::new(),
            fps: DEFAULT_FPS,
            frames: 1,
        }
    }

    /// The motions of an array of `K ≤ M` (a compile-time error otherwise), usable in
    /// a `const` or `static`.
    ///
    /// Its frame rate is [`DEFAULT_FPS`] and its frames one loop of the longest period
    /// ([`frames_for`](Self::frames_for)). Unchecked: [`check`](Self::check).
    #[must_use]
    pub const fn from_array<const K: usize>(motions: [Motion; K]) -> Self {
        let mut longest = 0.0f32;
        let mut rest: &[Motion] = &motions;
        while let [m, tail @ ..] = rest {
            if m.period() > longest {
                longest = m.period();
            }
            rest = tail;
        }
        Self {
            motions: Vec::from_array(motions),
            fps: DEFAULT_FPS,
            frames: Self::frames_for(longest, DEFAULT_FPS),
        }
    }

    /// The same animation at `fps` frames a second (unchecked).
    #[must_use]
    pub const fn with_fps(mut self, fps: f32) -> Self {
        self.fps = fps;
        self
    }

    /// The same animation with `frames` frames a loop (unchecked).
    #[must_use]
    pub const fn with_frames(mut self, frames: u32) -> Self {
        self.frames = frames;
        self
    }

    /// The frames one loop of `period` seconds takes at `fps`, `⌈period·fps⌉`, at least
    /// 1 (and at most `u32::MAX`): the default number of frames, from the longest
    /// period.
    #[must_use]
    pub const fn frames_for(period: f32, fps: f32) -> u32 {
        let f = period * fps;
        if !(f >= 1.0) {
            return 1;
        }
        if !(f < 4.0e9) {
            return u32::MAX;
        }
        let whole = f as u32;
        if (whole as f32) < f {
            whole + 1
        } else {
            whole
        }
    }

    /// Adds a motion after checking it ([`Motion::check`]).
    pub fn push(&mut self, motion: Motion) -> Result<(), MotionError> {
        let motion = motion.check(self.motions.len())?;
        self.motions
            .push(motion)
            .map_err(|_| MotionError::Full { capacity: M })
    }

    /// The motions, in the order they apply.
    #[must_use]
    pub fn motions(&self) -> &[Motion] {
        &self.motions
    }

    /// Frames a second.
    #[must_use]
    pub const fn fps(&self) -> f32 {
        self.fps
    }

    /// Frames in a loop of the animation.
    #[must_use]
    pub const fn frames(&self) -> u32 {
        self.frames
    }

    /// The moment of frame `frame`: [`frame_time`]`(frame, self.fps())`.
    #[must_use]
    pub const fn time(&self, frame: u32) -> f32 {
        frame_time(frame, self.fps)
    }

    /// Whether anything moves.
    #[must_use]
    pub fn is_still(&self) -> bool {
        self.motions.is_empty()
    }

    /// The animation if every motion passes [`Motion::check`], the frame rate is a
    /// finite number `> 0` and the number of frames at least 1.
    pub fn check(&self) -> Result<(), MotionError> {
        for (k, m) in self.motions.iter().enumerate() {
            m.check(k)?;
        }
        if !(self.fps.is_finite() && self.fps > 0.0) {
            return Err(MotionError::Fps);
        }
        if self.frames == 0 {
            return Err(MotionError::Frames);
        }
        Ok(())
    }

    /// Whether every sphere a motion moves is in `scene`.
    pub fn check_scene<const N: usize, const L: usize, const P: usize, const D: usize>(
        &self,
        scene: &Scene<N, L, P, D>,
    ) -> Result<(), MotionError> {
        for (k, m) in self.motions.iter().enumerate() {
            if let Some(sphere) = m.sphere() {
                if sphere >= scene.spheres().len() {
                    return Err(MotionError::NoSuchSphere { motion: k, sphere });
                }
            }
        }
        Ok(())
    }

    /// The scene and camera at moment `t` (seconds).
    ///
    /// `scene` becomes a copy of `base` and `params` of `base_params`, then each motion
    /// moves its sphere or the camera, in order. Nothing of an earlier frame is used.
    ///
    /// # Errors
    ///
    /// A motion that [`Motion::check`] refuses, that names a sphere `base` lacks, or
    /// that moves a sphere beyond what `f32` holds. `scene` and `params` then hold the
    /// motions before it.
    pub fn apply<const N: usize, const L: usize, const P: usize, const D: usize>(
        &self,
        base: &Scene<N, L, P, D>,
        base_params: &CameraParams,
        t: f32,
        scene: &mut Scene<N, L, P, D>,
        params: &mut CameraParams,
    ) -> Result<(), MotionError> {
        scene.clone_from(base);
        *params = *base_params;
        for (k, m) in self.motions.iter().enumerate() {
            let m = m.check(k)?;
            let moved = |scene: &mut Scene<N, L, P, D>, sphere: usize, to: &dyn Fn(Vec3) -> Vec3| {
                let Some(&s) = scene.spheres().get(sphere) else {
                    return Err(MotionError::NoSuchSphere { motion: k, sphere });
                };
                let s = Sphere {
                    center: to(s.center),
                    ..s
                };
                scene.set_sphere(sphere, s).map_err(|e| match e {
                    SceneError::Sphere(error) => MotionError::Moved { motion: k, error },
                    _ => MotionError::NoSuchSphere { motion: k, sphere },
                })
            };
            match m {
                Motion::Circle(c) => moved(scene, c.sphere, &|_| c.position(t))?,
                Motion::Bounce(b) => {
                    let lift = b.lift(t);
                    moved(scene, b.sphere, &|p| Vec3::new(p.x, p.y + lift, p.z))?;
                }
                Motion::Orbit(o) => *params = params.orbited(o.angle(t)),
            }
        }
        Ok(())
    }

    /// [`apply`](Self::apply) at frame `frame`'s moment ([`time`](Self::time)).
    pub fn apply_frame<const N: usize, const L: usize, const P: usize, const D: usize>(
        &self,
        base: &Scene<N, L, P, D>,
        base_params: &CameraParams,
        frame: u32,
        scene: &mut Scene<N, L, P, D>,
        params: &mut CameraParams,
    ) -> Result<(), MotionError> {
        self.apply(base, base_params, self.time(frame), scene, params)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::geometry::Size;
    use embedded_graphics::pixelcolor::Rgb888;
    extern crate std;
    use std::format;

    fn scene() -> Scene<2> {
        Scene::from_array(
            [
                Sphere::new(Vec3::new(0.0, 1.0, 0.0), 1.0, Rgb888::new(255, 0, 0)),
                Sphere::new(Vec3::new(3.0, 0.5, 0.0), 0.5, Rgb888::new(0, 0, 255)),
            ],
            Rgb888::new(0, 0, 0),
        )
    }

    const PARAMS: CameraParams = CameraParams::new(
        Vec3::new(0.0, 2.0, 8.0),
        Vec3::ZERO,
        Vec3::new(0.0, 1.0, 0.0),
        0.8,
        Size::new(32, 32),
    );

    #[test]
    fn bounce_is_a_parabola_touching_the_base() {
        let b = Bounce::new(0, 2.0, 1.0);
        assert_eq!(b.lift(0.0), 0.0);
        assert_eq!(b.lift(0.5), 2.0);
        assert_eq!(b.lift(1.0), 0.0);
        assert_eq!(b.lift(0.25), 1.5);
        assert_eq!(b.lift(3.25), 1.5);
    }

    #[test]
    fn frames_do_not_accumulate() {
        let base = scene();
        let anim: Animation<3> = Animation::from_array([
            Motion::Bounce(Bounce::new(0, 2.0, 1.2)),
            Motion::Circle(Circle::new(1, Vec3::ZERO, 3.0, 2.0, 0.0)),
            Motion::Orbit(Orbit::new(5.0)),
        ]);
        let (mut a, mut pa) = (base.clone(), PARAMS);
        let (mut b, mut pb) = (base.clone(), PARAMS);
        for k in 0..40 {
            anim.apply_frame(&base, &PARAMS, k, &mut a, &mut pa).unwrap();
        }
        anim.apply_frame(&base, &PARAMS, 39, &mut b, &mut pb).unwrap();
        assert_eq!(format!("{a:?}{pa:?}"), format!("{b:?}{pb:?}"));
        // Frame 0: the bounce and orbit at their start, the circle at its phase.
        anim.apply_frame(&base, &PARAMS, 0, &mut a, &mut pa).unwrap();
        assert_eq!(a.spheres()[0], base.spheres()[0]);
        assert_eq!(a.spheres()[1].center, Vec3::new(0.0, 0.0, 3.0));
        assert_eq!(pa, PARAMS.orbited(0.0));
    }

    #[test]
    fn motions_compose_in_order() {
        let base = scene();
        let anim: Animation<2> = Animation::from_array([
            Motion::Circle(Circle::new(1, Vec3::new(0.0, 1.0, 0.0), 2.0, 4.0, 0.0)),
            Motion::Bounce(Bounce::new(1, 1.0, 2.0)),
        ]);
        let (mut s, mut p) = (base.clone(), PARAMS);
        anim.apply(&base, &PARAMS, 1.0, &mut s, &mut p).unwrap();
        let c = s.spheres()[1].center;
        assert!((c.x - 2.0).abs() < 1e-6 && c.z.abs() < 1e-6);
        assert_eq!(c.y, 2.0);
    }

    #[test]
    fn errors_are_typed() {
        let base = scene();
        let (mut s, mut p) = (base.clone(), PARAMS);
        let anim: Animation<1> = Animation::from_array([Motion::Bounce(Bounce::new(2, 1.0, 1.0))]);
        assert_eq!(
            anim.check_scene(&base),
            Err(MotionError::NoSuchSphere { motion: 0, sphere: 2 })
        );
        assert_eq!(
            anim.apply(&base, &PARAMS, 0.0, &mut s, &mut p),
            Err(MotionError::NoSuchSphere { motion: 0, sphere: 2 })
        );
        for period in [0.0, -1.0, f32::NAN, f32::INFINITY] {
            let anim: Animation<2> =
                Animation::from_array([Motion::Orbit(Orbit::new(1.0)), Motion::Orbit(Orbit::new(period))]);
            assert_eq!(anim.check(), Err(MotionError::Period { motion: 1 }));
            assert_eq!(
                anim.apply(&base, &PARAMS, 0.0, &mut s, &mut p),
                Err(MotionError::Period { motion: 1 })
            );
        }
        let huge: Animation<1> = Animation::from_array([Motion::Bounce(Bounce::new(0, 3e38, 1.0))]);
        assert!(matches!(
            huge.apply(&base, &PARAMS, 0.5, &mut s, &mut p),
            Err(MotionError::Moved { motion: 0, .. })
        ));
        let mut one: Animation<1> = Animation::new();
        one.push(Motion::Orbit(Orbit::new(1.0))).unwrap();
        assert_eq!(
            one.push(Motion::Orbit(Orbit::new(1.0))),
            Err(MotionError::Full { capacity: 1 })
        );
        assert_eq!(Animation::<1>::new().with_fps(0.0).check(), Err(MotionError::Fps));
        let e = MotionError::Period { motion: 1 };
        assert_eq!((e.file_key(), e.motion()), ("period", Some(1)));
    }

    #[test]
    fn the_default_frames_are_one_loop_of_the_longest_period() {
        let anim: Animation<2> = Animation::from_array([
            Motion::Orbit(Orbit::new(1.0)),
            Motion::Bounce(Bounce::new(0, 1.0, 1.5)),
        ]);
        assert_eq!((anim.fps(), anim.frames()), (25.0, 38));
        assert_eq!(Animation::<1>::frames_for(2.0, 25.0), 50);
        assert_eq!(Animation::<1>::new().frames(), 1);
    }
}
