//! The page's player: a scene text loaded through the scene-file loader, its frames
//! drawn onto one display through `Incremental` (as a firmware draws them), what each
//! frame traced and sent, and the difference view.

use std::borrow::Cow;

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raytracer::incremental::Changes;
use embedded_raytracer::motion::Animation;
use embedded_raytracer::scene_file::{self, SceneFileError, MAX_FILE_SIZE, MAX_MOTIONS};
use embedded_raytracer::{
    Camera, CameraParams, Incremental, Method, Options, Render, Scene, SecondaryOrigin, SphereTest, Sqrt,
    Stepping,
};
use wasm_bindgen::prelude::*;

use crate::screen::Screen;
use crate::view::{Orbit, View};
use embedded_raytracer_scenes::{MAX_DEPTH, MAX_LIGHTS, MAX_PLANES, MAX_SPHERES};

/// The difference view's reference: no accumulation, no cancellation, exact root (and
/// the convex origin for secondary rays: no epsilon).
pub const REFERENCE: Method = Method::new(Stepping::Direct, SphereTest::Robust, Sqrt::Exact);

/// Colour of the pixels that differ from the reference in the difference view.
const DIFF_COLOR: Rgb888 = Rgb888::new(255, 0, 255);

/// The most pixels a display of the page has (2048 × 2048): a scene file may ask for
/// 8192 × 8192, which the render CLI streams to a PNG but a page would hold four times
/// over (display, colours, marks, canvas).
pub const MAX_PIXELS: u32 = 2048 * 2048;

/// [`Player::marks`]' bit of a pixel inside a rectangle the frame traced.
pub const TRACED: u8 = 1;
/// [`Player::marks`]' bit of a pixel the frame sent to the display.
pub const SENT: u8 = 2;

/// The scene type with every capacity the host tools have.
type FullScene = Scene<MAX_SPHERES, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>;

/// A loaded scene, through the type the render CLI draws it with.
#[derive(Clone)]
enum Loaded {
    /// No light, plane or mirror: the spheres-only type, whose loop is Lab #1's.
    Spheres(Box<Scene<MAX_SPHERES>>),
    /// Lights, planes or mirrors: the full type.
    Full(Box<FullScene>),
}

/// A loaded scene file: the scene as the file places it, its camera and its motion.
struct Film {
    scene: Loaded,
    base: CameraParams,
    animation: Animation<MAX_MOTIONS>,
}

/// Why a scene text was not loaded: the loader's field, line and reason.
#[wasm_bindgen(getter_with_clone)]
#[derive(Clone, Debug, PartialEq)]
pub struct LoadError {
    /// 1-based line, where the parser knows it.
    pub line: Option<u32>,
    /// The field to blame (`sphere[2].radius`), where one is.
    pub field: Option<String>,
    /// What is wrong.
    pub reason: String,
    /// All of it in one line, as the render CLI prints it.
    pub message: String,
}

impl From<SceneFileError> for LoadError {
    fn from(e: SceneFileError) -> Self {
        Self {
            line: e.line.and_then(|l| u32::try_from(l).ok()),
            message: e.to_string(),
            field: e.field,
            reason: e.reason,
        }
    }
}

/// A loaded scene's size and timing.
#[wasm_bindgen]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneInfo {
    /// The file's camera resolution.
    pub width: u32,
    pub height: u32,
    /// The motion's frames in a loop (1 for a still scene) and frame rate.
    pub frames: u32,
    pub fps: f32,
    /// Whether it moves.
    pub moves: bool,
    /// Whether it has lights, planes or mirrors (the secondary origin matters).
    pub features: bool,
}

/// What a frame cost and how it was drawn.
#[wasm_bindgen(getter_with_clone)]
#[derive(Clone, Debug, PartialEq)]
pub struct FrameReport {
    /// The frame of the motion (0: its start, the moment `frame / fps`).
    pub frame: u32,
    /// The whole frame was drawn.
    pub full: bool,
    /// Pixels in the rectangles traced, pixels sent and the windows they were sent in.
    pub traced: u32,
    pub sent: u32,
    pub windows: u32,
    /// The arithmetic that drew it: `integer`, or `f32` (also where the integer
    /// kernel's rule did not take the frame).
    pub arithmetic: String,
    /// Why the frame could not be drawn exactly (nothing was sent), if it could not.
    pub refused: Option<String>,
    /// The display's resolution.
    pub width: u32,
    pub height: u32,
}

/// The scene, the view and the display the frames are drawn on.
#[wasm_bindgen]
pub struct Player {
    film: Option<Film>,
    view: View,
    screen: Screen,
    /// What the display shows, per scene type: the last frame drawn through it.
    spheres: Box<Incremental<MAX_SPHERES>>,
    full: Box<Incremental<MAX_SPHERES, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>>,
    /// The kernel's colours of the frame shown (row-major): the band buffer the
    /// changed rectangles are traced into.
    image: Vec<Rgb888>,
    /// The rectangles the last frame traced.
    traced: Vec<Rectangle>,
    /// The frame last drawn.
    frame: Option<u32>,
    /// The difference view's reference frame (the screen's colours), if shown.
    reference: Option<Vec<Rgb888>>,
}

impl Default for Player {
    fn default() -> Self {
        Self::new()
    }
}

#[wasm_bindgen]
impl Player {
    /// No scene yet, the default view.
    #[wasm_bindgen(constructor)]
    pub fn new() -> Player {
        let view = View::default();
        Self {
            film: None,
            screen: Screen::new(Size::zero(), view.model, view.bayer),
            view,
            spheres: Box::new(Incremental::new()),
            full: Box::new(Incremental::new()),
            image: Vec::new(),
            traced: Vec::new(),
            frame: None,
            reference: None,
        }
    }

    /// Loads a scene file's text with the host tools' capacities (what the render CLI
    /// accepts); a text it refuses leaves the last scene loaded.
    ///
    /// The text is untrusted
    /// (a share link carries it): longer than the loader's file limit, 1 MiB, it is
    /// refused unread, as `scene_file::load` refuses such a file.
    pub fn load(&mut self, text: &str) -> Result<SceneInfo, LoadError> {
        if text.len() as u64 > MAX_FILE_SIZE {
            let reason = format!(
                "the scene text is {} bytes; at most {MAX_FILE_SIZE} are read",
                text.len()
            );
            return Err(LoadError {
                line: None,
                field: None,
                message: reason.clone(),
                reason,
            });
        }
        let file = Box::new(scene_file::parse::<MAX_SPHERES, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>(text)?);
        let scene = match file.spheres_only() {
            Some(spheres) => Loaded::Spheres(Box::new(spheres.scene)),
            None => Loaded::Full(Box::new(file.scene)),
        };
        let film = Film {
            scene,
            base: *file.camera.params(),
            animation: file.animation,
        };
        let info = film.info();
        self.film = Some(film);
        // A new scene is drawn whole.
        self.spheres.invalidate();
        self.full.invalidate();
        Ok(info)
    }

    /// Applies the view pairs of `spec` (see `View::with`); a bad pair changes nothing.
    #[wasm_bindgen(js_name = setView)]
    pub fn set_view(&mut self, spec: &str) -> Result<(), String> {
        self.view = self.view.with(spec)?;
        Ok(())
    }

    /// The view as pairs `View::with` reads, for the share link.
    #[wasm_bindgen(js_name = viewSpec)]
    pub fn view_spec(&self) -> String {
        let v = &self.view;
        let size = v
            .size
            .map_or("file".to_string(), |s| format!("{}x{}", s.width, s.height));
        let bayer = if v.bayer == embedded_raytracer::dither::Bayer::Four {
            4
        } else {
            8
        };
        format!(
            "display={}&bayer={bayer}&theme={}&method={}&sampling={}&secondary={}&size={size}\
             &azimuth={}&elevation={}&zoom={}&diff={}",
            v.model.name(),
            v.theme.name(),
            v.method,
            v.sampling,
            v.secondary,
            v.orbit.azimuth,
            v.orbit.elevation,
            v.orbit.zoom_steps,
            u8::from(v.diff)
        )
    }

    /// The range of the orbit's elevation (radians) that keeps the eye within ±89° of
    /// the plane normal to `up`: `[low, high]`.
    #[wasm_bindgen(js_name = elevationRange)]
    pub fn elevation_range(&self) -> Vec<f32> {
        let (lo, hi) = self
            .film
            .as_ref()
            .map_or((0.0, 0.0), |f| Orbit::elevation_range(&f.base));
        vec![lo, hi]
    }

    /// Draws frame `frame` of the motion (0: its start; any frame of a still scene is
    /// the scene) onto the display, tracing and sending only what can differ from the
    /// frame it shows, as a firmware's loop does.
    ///
    /// A still scene is drawn whole each
    /// time, as the preview draws it. Afterwards the display shows the frame's full
    /// render through the view's model, bit for bit.
    pub fn draw(&mut self, frame: u32) -> Result<FrameReport, String> {
        let film = self.film.as_ref().ok_or("no scene loaded")?;
        let view = self.view;
        let (scene, camera) = film.moment(&view, frame)?;
        let size = camera.size();
        if !self.screen.is(size, view.model, view.bayer) {
            // Another display: nothing of the last frame is on it.
            self.screen = Screen::new(size, view.model, view.bayer);
            self.spheres.invalidate();
            self.full.invalidate();
        }
        if film.animation.is_still() {
            self.spheres.invalidate();
            self.full.invalidate();
        }
        if self.image.len() != self.screen.shown().len() {
            self.image = vec![Rgb888::BLACK; self.screen.shown().len()];
        }
        let options = Options::DEFAULT.with_secondary(view.secondary);
        let (changes, arithmetic) = match &*scene {
            Loaded::Spheres(s) => {
                self.full.invalidate();
                let render = Render::new(&**s, &camera)
                    .with_method(view.method)
                    .with_options(options)
                    .with_sampling(view.sampling);
                (
                    trace(&mut self.spheres, &render, &mut self.image, size.height),
                    render.arithmetic(),
                )
            }
            Loaded::Full(s) => {
                self.spheres.invalidate();
                let render = Render::new(&**s, &camera)
                    .with_method(view.method)
                    .with_options(options)
                    .with_sampling(view.sampling);
                (
                    trace(&mut self.full, &render, &mut self.image, size.height),
                    render.arithmetic(),
                )
            }
        };
        // Each changed run of a row is sent as its own window, as a DMA sender sends
        // `Changes::runs` (and `Incremental::draw` an `f32` frame; an integer frame it
        // sends a strip at a time).
        self.screen.begin_frame();
        let (mut sent, mut windows) = (0, 0);
        if changes.refused().is_none() {
            for y in 0..size.height {
                for (lo, hi) in changes.runs(y) {
                    self.screen.send(y, lo, hi, &self.image);
                    sent += hi - lo;
                    windows += 1;
                }
            }
        }
        self.traced = changes.rectangles().collect();
        self.frame = Some(frame);
        self.reference = None;
        Ok(FrameReport {
            frame,
            full: changes.is_full(),
            traced: changes.traced(),
            sent,
            windows,
            arithmetic: arithmetic.to_string(),
            refused: changes.refused().map(|e| e.to_string()),
            width: size.width,
            height: size.height,
        })
    }

    /// In the difference view, draws the reference of the frame last drawn
    /// (`direct/robust/exact`, convex origin, through the same model) and returns how
    /// many pixels differ from it; `None` outside the difference view.
    ///
    /// Apart from
    /// [`Player::draw`], so that the page times the frame alone.
    pub fn compare(&mut self) -> Option<u32> {
        self.reference = None;
        let (film, frame) = (self.film.as_ref()?, self.frame?);
        if !self.view.diff {
            return None;
        }
        let (scene, camera) = film.moment(&self.view, frame).ok()?;
        let reference = reference(&scene, &camera, &self.view);
        let n = reference
            .iter()
            .zip(self.screen.shown())
            .filter(|(a, b)| a != b)
            .count();
        self.reference = Some(reference);
        Some(u32::try_from(n).unwrap_or(u32::MAX))
    }

    /// The display as the page shows it: RGBA, row-major, the 1-bit models in the
    /// view's OLED theme, and in the difference view the differing pixels in magenta.
    pub fn rgba(&self) -> Vec<u8> {
        let theme = self.screen.model().is_binary().then_some(self.view.theme);
        let shown = self.screen.shown();
        let mut out = Vec::with_capacity(shown.len() * 4);
        for (k, &c) in shown.iter().enumerate() {
            let differs = self.reference.as_ref().is_some_and(|r| r.get(k) != Some(&c));
            let window = match theme {
                _ if differs => DIFF_COLOR,
                Some(t) => t.show(c),
                None => c,
            };
            out.extend_from_slice(&[window.r(), window.g(), window.b(), 255]);
        }
        out
    }

    /// What the last frame did to each pixel, row-major: [`TRACED`] if it lies in a
    /// rectangle the render traced, plus [`SENT`] if it was sent to the display.
    pub fn marks(&self) -> Vec<u8> {
        let w = self.screen.size().width as usize;
        let mut marks: Vec<u8> = self
            .screen
            .sent()
            .iter()
            .map(|&s| if s { SENT } else { 0 })
            .collect();
        for r in &self.traced {
            for p in r.points() {
                let k = p.y as usize * w + p.x as usize;
                if let Some(m) = marks.get_mut(k) {
                    *m |= TRACED;
                }
            }
        }
        marks
    }
}

impl Film {
    fn info(&self) -> SceneInfo {
        SceneInfo {
            width: self.base.size.width,
            height: self.base.size.height,
            frames: self.animation.frames(),
            fps: self.animation.fps(),
            moves: !self.animation.is_still(),
            features: matches!(self.scene, Loaded::Full(_)),
        }
    }

    /// The scene and camera of frame `frame` in `view`: the file's camera at the
    /// view's size and orbit, and for a scene that moves the motion's frame applied to
    /// both (the render CLI's and the boards' frame).
    fn moment(&self, view: &View, frame: u32) -> Result<(Cow<'_, Loaded>, Camera), String> {
        let size = view.size.unwrap_or(self.base.size);
        if u64::from(size.width) * u64::from(size.height) > u64::from(MAX_PIXELS) {
            return Err(format!(
                "{}x{} is more than the page draws ({MAX_PIXELS} pixels)",
                size.width, size.height
            ));
        }
        let camera = view
            .orbit
            .params(&self.base, size)
            .build()
            .map_err(|e| format!("camera at {}x{}: {e}", size.width, size.height))?;
        if self.animation.is_still() {
            return Ok((Cow::Borrowed(&self.scene), camera));
        }
        let base = camera.params();
        let mut at = *base;
        let failed = |e: &dyn std::fmt::Display| format!("frame {}: {e}", u64::from(frame) + 1);
        let moved = match &self.scene {
            Loaded::Spheres(s) => {
                let mut scene = s.clone();
                self.animation
                    .apply_frame(&**s, base, frame, &mut *scene, &mut at)
                    .map_err(|e| failed(&e))?;
                Loaded::Spheres(scene)
            }
            Loaded::Full(s) => {
                let mut scene = s.clone();
                self.animation
                    .apply_frame(&**s, base, frame, &mut *scene, &mut at)
                    .map_err(|e| failed(&e))?;
                Loaded::Full(scene)
            }
        };
        let camera = at.build().map_err(|e| failed(&format!("camera: {e}")))?;
        Ok((Cow::Owned(moved), camera))
    }
}

/// Plans `render`'s frame against what `shown` remembers and traces the rectangles
/// that can have changed into `image` (the kernel's colours, row-major, the display's
/// size; the other pixels keep the last frame's).
///
/// The plan says which rectangles were traced and which runs of each row changed.
/// `height`: the camera's.
///
/// Out of line, one copy per scene type: the kernel's renders are inlined into their
/// caller (a constant method links its code alone), so each call site of
/// `Incremental::update` and `Changes::draw_band` would add every method's code to the
/// `.wasm` again.
#[inline(never)]
fn trace<const N: usize, const L: usize, const P: usize, const D: usize>(
    shown: &mut Incremental<N, L, P, D>,
    render: &Render<'_, N, Rgb888, L, P, D>,
    image: &mut [Rgb888],
    height: u32,
) -> Changes {
    let changes = shown.update(render);
    let rows = 0..height;
    if changes.refused().is_none() && changes.draw_band(render, rows, image).is_err() {
        // Not drawn (cannot happen: the image is the frame's size and the frame was
        // checked): the next frame is drawn whole.
        shown.invalidate();
    }
    changes
}

/// The difference view's reference: `scene` through `camera` with [`REFERENCE`] and the
/// convex origin, drawn whole on a display of the view's model.
fn reference(scene: &Loaded, camera: &Camera, view: &View) -> Vec<Rgb888> {
    let size = camera.size();
    let mut image = vec![Rgb888::BLACK; size.width as usize * size.height as usize];
    let options = Options::DEFAULT.with_secondary(SecondaryOrigin::Convex);
    // A fresh `Incremental` plans the whole frame.
    match scene {
        Loaded::Spheres(s) => {
            let render = Render::new(&**s, camera)
                .with_method(REFERENCE)
                .with_options(options)
                .with_sampling(view.sampling);
            trace(&mut Incremental::new(), &render, &mut image, size.height);
        }
        Loaded::Full(s) => {
            let render = Render::new(&**s, camera)
                .with_method(REFERENCE)
                .with_options(options)
                .with_sampling(view.sampling);
            trace(&mut Incremental::new(), &render, &mut image, size.height);
        }
    }
    let mut screen = Screen::new(size, view.model, view.bayer);
    for y in 0..size.height {
        screen.send(y, 0, size.width, &image);
    }
    screen.shown().to_vec()
}

#[cfg(test)]
mod tests;
