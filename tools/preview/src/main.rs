//! Desktop preview: a scene file in an SDL window, through the display model the
//! firmware will drive (Rgb888, Rgb565, Gray8/4/2, BinaryColor, with or without the
//! kernel's ordered dither), at the display's real resolution and a pixel scale.
//!
//! ```text
//! cargo run --release -p embedded-raytracer-preview -- scenes/lab.toml \
//!     [--display rgb888|rgb565|gray8|gray4|gray4-dither|gray2|gray2-dither|binary|binary-dither] \
//!     [--size WxH] [--scale N] [--bayer 4|8] [--theme oled-blue|oled-white] \
//!     [--stepping …] [--sphere-test …] [--sqrt …] [--diff] [--no-overlay] \
//!     [--frame K] [--screenshot OUT.png [--frames N]]
//! ```
//!
//! Keys: ←/→ orbit around the look-at point (azimuth, 5° a press), ↑/↓ elevation; left
//! mouse drag orbits too (half a turn per display width); wheel, `+`/`=` and `-` zoom;
//! `R` resets the view; `M`/`Shift+M` next/previous method (all 30 of `Method::ALL`);
//! `I` toggles the arithmetic (f32, or the integer kernel where its per-frame rule
//! takes the frame: `integer/…` in the status bar, `→ f32` where it does not);
//! `E`/`Shift+E` next/previous origin of the shadow and reflection rays (convex, then
//! the textbook fixed epsilon at 1e-3, 1e-6 and 1e-1 scene units: [`SECONDARY`]);
//! `A`/`Shift+A` next/previous sampling (`center`, `grid:2…4`, `adaptive:2…4`:
//! `Sampling::ALL`, shown after the model in the status bar);
//! `D` toggles the difference view (pixels where the shown frame differs from the
//! `direct/robust/exact` render with the convex origin, through the same display
//! model, in magenta); `Tab`/`Shift+Tab` or `1`–`9` pick the display model; `B`
//! switches the Bayer matrix 8×8/4×4; `T` switches the OLED theme (blue/white) of the
//! binary models; `Space` pauses and resumes a scene's motion, `.`/`,` pause and step
//! one frame forward/back; `Esc`/`Q` quits.
//!
//! A scene file with `[[motion]]` plays in real time at its `[animation]` frame rate:
//! frame `k` (the moment `k / fps`) is shown from `k / fps` seconds after the start,
//! looping after its `frames`; when drawing is slower, frames are skipped rather than
//! the motion slowed. The frames are drawn onto one framebuffer of the display model
//! through one `Incremental`, as a firmware draws them: only the pixels that can
//! differ from the frame before are traced and sent. A change of view (orbit, zoom,
//! method, sampling, model) is the next frame's, which the incremental rule draws
//! whole; a reload draws the next frame whole. `--frame K` starts paused on frame `K`,
//! the render CLI's `--frame K` (the moment `(K − 1) / fps`). A still scene is drawn
//! whole at each change, so the status bar's time is always a whole frame's.
//!
//! A scene file without lights, planes or mirrors is drawn through the spheres-only
//! type `Scene<N>` (the Lab #1 loop), one with them through the full type with the
//! host's capacities, as the render CLI does: the same file gives the CLI's pixels.
//! The scene file is polled for changes (mtime, four times a second) and reloaded;
//! a file that fails to load leaves the last good scene on screen with the error text
//! over it (with `--no-overlay`, on stderr only). The display resolution is fixed for the session: the file's
//! `camera.width`/`height` at start-up, or `--size`.
//!
//! Below the image, a status bar (omitted with `--no-overlay`) shows the render time
//! of the last frame (the kernel drawing into the model's framebuffer; measured with
//! `Instant` around `Render::draw`), the model and the method, and for a scene with
//! lights, planes or mirrors the secondary rays' origin (`convex`, `eps=1e-3`). For a
//! scene that moves, its third line shows the frame rate achieved and the share of the
//! display's pixels the last frame traced and sent (`25 fps traced 12% sent 10%`), or
//! while paused the frame (`paused 12/30 traced …`). The status bar and the error text
//! are drawn on the window, never on the model's framebuffer the frames are drawn on:
//! they cover no pixel the next frame would have to redraw.
//!
//! Headless: `--screenshot OUT.png` renders one frame and writes it (the window's
//! pixels, with `--scale`) without opening a window or needing a display. With
//! `--frame K` and a scene that moves, frame `K − 1` is drawn first and frame `K` over
//! it through the incremental rule, as the player draws it: the screenshot is then the
//! render CLI's `--frame K` PNG only if that rule is exact.
//! `--screenshot OUT.png --frames N` opens the window, shows N frames, then writes the
//! frame it showed. The simulator's own `EG_SIMULATOR_DUMP=OUT.png` also works: the
//! first frame handed to the window is written and the program exits.

use std::borrow::Cow;
use std::path::{Path, PathBuf};

use clap::builder::{PossibleValuesParser, TypedValueParser};
use std::process::ExitCode;
use std::time::{Duration, Instant, SystemTime};

use embedded_graphics::{
    mono_font::{
        ascii::{FONT_4X6, FONT_6X10},
        MonoFont, MonoTextStyle,
    },
    pixelcolor::{BinaryColor, Gray2, Gray4, Gray8, Rgb565, Rgb888},
    prelude::*,
    primitives::Rectangle,
    text::{Baseline, Text},
};
use embedded_graphics_simulator::{
    sdl2::{Keycode, Mod, MouseButton},
    BinaryColorTheme, OutputSettings, OutputSettingsBuilder, SimulatorDisplay, SimulatorEvent, Window,
};
use embedded_raytracer::{
    dither::{Bayer, DitherColor, DitherExt},
    motion::{Animation, MotionError},
    scene_file::{self, MAX_MOTIONS},
    Arithmetic, Camera, CameraParams, FrameStats, Method, Options, Render, Sampling, Scene, SecondaryOrigin,
    SphereTest, Sqrt, Stepping, Vec3,
};

mod play;

use embedded_raytracer_scenes::{
    self as standard, FullSceneFile, MAX_DEPTH, MAX_LIGHTS, MAX_PLANES, MAX_SPHERES,
};

/// The difference view's reference: no accumulation, no cancellation, exact root (and
/// the convex origin for secondary rays: no epsilon).
const REFERENCE: Method = Method::new(Stepping::Direct, SphereTest::Robust, Sqrt::Exact);

/// The secondary-ray origins the `E` key cycles through: the default, the textbook
/// epsilon, one below the hit points' rounding error at the standard scenes'
/// coordinates (shadow acne), one large for them (a ray that starts near where a
/// sphere rests on the floor can skip past the surface it should meet).
const SECONDARY: [SecondaryOrigin; 4] = [
    SecondaryOrigin::Convex,
    SecondaryOrigin::TEXTBOOK,
    SecondaryOrigin::Epsilon(1e-6),
    SecondaryOrigin::Epsilon(1e-1),
];

/// Orbit step per arrow key press.
const ORBIT_STEP: f32 = 5.0 * core::f32::consts::PI / 180.0;
/// Elevation stays within ±89° of the plane normal to `up`, well clear of the
/// camera's up-parallel-to-view limit.
const MAX_ELEVATION: f32 = 89.0 * core::f32::consts::PI / 180.0;
/// Distance factor per zoom step.
const ZOOM: f32 = 1.1;
/// How often the scene file's mtime is checked.
const POLL: Duration = Duration::from_millis(250);
/// Colour of differing pixels in the difference view.
const DIFF_COLOR: Rgb888 = Rgb888::new(255, 0, 255);

fn usage() -> String {
    format!(
        "usage: ertrace-preview [SCENE.toml] [--display MODEL] [--size WxH] [--scale N] \
[--bayer 4|8] [--theme oled-blue|oled-white] {} [--sampling center|grid:N|adaptive:N] [--diff] [--no-overlay] \
[--frame K] [--screenshot OUT.png [--frames N]]\n  MODEL: rgb888 rgb565 gray8 gray4 gray4-dither gray2 \
gray2-dither binary binary-dither",
        standard::method_flags()
    )
}

/// The display the firmware drives: colour type and whether the kernel's dither sits
/// in front of it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Model {
    Rgb888,
    Rgb565,
    Gray8,
    Gray4,
    Gray4Dither,
    Gray2,
    Gray2Dither,
    Binary,
    BinaryDither,
}

impl Model {
    const ALL: [Model; 9] = [
        Model::Rgb888,
        Model::Rgb565,
        Model::Gray8,
        Model::Gray4,
        Model::Gray4Dither,
        Model::Gray2,
        Model::Gray2Dither,
        Model::Binary,
        Model::BinaryDither,
    ];

    fn name(self) -> &'static str {
        match self {
            Model::Rgb888 => "rgb888",
            Model::Rgb565 => "rgb565",
            Model::Gray8 => "gray8",
            Model::Gray4 => "gray4",
            Model::Gray4Dither => "gray4-dither",
            Model::Gray2 => "gray2",
            Model::Gray2Dither => "gray2-dither",
            Model::Binary => "binary",
            Model::BinaryDither => "binary-dither",
        }
    }

    fn parse(s: &str) -> Result<Model, String> {
        Model::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| format!("--display: unknown model `{s}`"))
    }

    fn is_binary(self) -> bool {
        matches!(self, Model::Binary | Model::BinaryDither)
    }

    fn is_dithered(self) -> bool {
        matches!(
            self,
            Model::Gray4Dither | Model::Gray2Dither | Model::BinaryDither
        )
    }

    fn index(self) -> usize {
        Model::ALL.iter().position(|&m| m == self).unwrap_or(0)
    }
}

/// Everything that decides the pixels of a frame.
#[derive(Clone, Copy)]
struct View {
    model: Model,
    method: Method,
    /// Where shadow and reflection rays start (scenes with lights or mirrors).
    secondary: SecondaryOrigin,
    /// Rays per pixel.
    sampling: Sampling,
    bayer: Bayer,
    theme: BinaryColorTheme,
}

impl View {
    /// Output settings that turn the model's framebuffer into window colours (scale 1;
    /// the window scales): the OLED theme for binary models, identity otherwise.
    fn output_settings(&self) -> OutputSettings {
        let theme = if self.model.is_binary() {
            self.theme
        } else {
            BinaryColorTheme::Default
        };
        // Scale and spacing explicitly: `theme()` alone would default them to 3 and 1.
        OutputSettingsBuilder::new()
            .scale(1)
            .pixel_spacing(0)
            .theme(theme)
            .build()
    }
}

/// A frame as the display shows it: one window colour per display pixel, row-major.
struct Shown {
    pixels: Vec<Rgb888>,
}

/// The scene type with every capacity the host tools have.
type FullScene = Scene<MAX_SPHERES, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>;

/// A loaded scene, through the type the render CLI would draw it with.
#[derive(Clone)]
enum Loaded {
    /// No light, plane or mirror: the spheres-only type, whose loop is Lab #1's.
    Spheres(Box<Scene<MAX_SPHERES>>),
    /// Lights, planes or mirrors: the full type.
    Full(Box<FullScene>),
}

impl Loaded {
    /// Loads a scene file with the full capacities; returns the scene, its camera and
    /// its motion.
    fn load(path: &Path) -> Result<(Loaded, CameraParams, Animation<MAX_MOTIONS>), String> {
        let file: Box<FullSceneFile> = Box::new(scene_file::load(path).map_err(|e| e.to_string())?);
        let params = *file.camera.params();
        let animation = file.animation.clone();
        let scene = match file.spheres_only() {
            Some(spheres) => Loaded::Spheres(Box::new(spheres.scene)),
            None => Loaded::Full(Box::new(file.scene)),
        };
        Ok((scene, params, animation))
    }

    /// The scene and camera parameters of frame `frame` of `animation`, applied to this
    /// scene and `params` (the library's `apply_frame`: the render CLI's and the
    /// boards' frame).
    fn at_frame(
        &self,
        animation: &Animation<MAX_MOTIONS>,
        params: &CameraParams,
        frame: u32,
    ) -> Result<(Loaded, CameraParams), MotionError> {
        let mut at = *params;
        let moved = match self {
            Loaded::Spheres(base) => {
                let mut scene = base.clone();
                animation.apply_frame(&**base, params, frame, &mut *scene, &mut at)?;
                Loaded::Spheres(scene)
            }
            Loaded::Full(base) => {
                let mut scene = base.clone();
                animation.apply_frame(&**base, params, frame, &mut *scene, &mut at)?;
                Loaded::Full(scene)
            }
        };
        Ok((moved, at))
    }

    /// Whether the scene is drawn through the full type (lights, planes or mirrors):
    /// the one whose shadow and reflection rays the secondary origin decides.
    fn has_features(&self) -> bool {
        matches!(self, Loaded::Full(_))
    }

    /// The arithmetic a frame of `method` is drawn in (the integer kernel's rule).
    fn arithmetic(&self, camera: &Camera, method: Method) -> Arithmetic {
        match self {
            Loaded::Spheres(scene) => Render::<'_, MAX_SPHERES>::new(&**scene, camera)
                .with_method(method)
                .arithmetic(),
            Loaded::Full(scene) => {
                Render::<'_, MAX_SPHERES, Rgb888, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>::new(&**scene, camera)
                    .with_method(method)
                    .arithmetic()
            }
        }
    }
}

/// What to render: scene, camera, method, options, sampling.
type Input<'a, const N: usize, const L: usize, const P: usize, const D: usize> =
    (&'a Scene<N, L, P, D>, &'a Camera, Method, Options, Sampling);

/// Renders `view` of the scene (with `view`'s secondary origin) through the display
/// model and converts to window colours.
fn shade(scene: &Loaded, camera: &Camera, view: &View, method: Method) -> Shown {
    let options = Options::DEFAULT.with_secondary(view.secondary);
    let s = view.sampling;
    match scene {
        Loaded::Spheres(scene) => shade_scene((&**scene, camera, method, options, s), view),
        Loaded::Full(scene) => shade_scene((&**scene, camera, method, options, s), view),
    }
}

/// [`shade`] for one scene type.
fn shade_scene<const N: usize, const L: usize, const P: usize, const D: usize>(
    render: Input<'_, N, L, P, D>,
    view: &View,
) -> Shown {
    let camera = render.1;
    let s = view.output_settings();
    let b = view.bayer;
    match view.model {
        Model::Rgb888 => plain::<Rgb888, N, L, P, D>(render, camera, &s),
        Model::Rgb565 => plain::<Rgb565, N, L, P, D>(render, camera, &s),
        Model::Gray8 => plain::<Gray8, N, L, P, D>(render, camera, &s),
        Model::Gray4 => plain::<Gray4, N, L, P, D>(render, camera, &s),
        Model::Gray2 => plain::<Gray2, N, L, P, D>(render, camera, &s),
        Model::Binary => plain::<BinaryColor, N, L, P, D>(render, camera, &s),
        Model::Gray4Dither => dithered::<Gray4, N, L, P, D>(render, camera, &s, b),
        Model::Gray2Dither => dithered::<Gray2, N, L, P, D>(render, camera, &s, b),
        Model::BinaryDither => dithered::<BinaryColor, N, L, P, D>(render, camera, &s, b),
    }
}

/// The kernel's own colour conversion (`C::from(Rgb888)`) into a `C` framebuffer.
fn plain<C, const N: usize, const L: usize, const P: usize, const D: usize>(
    input: Input<'_, N, L, P, D>,
    camera: &Camera,
    settings: &OutputSettings,
) -> Shown
where
    C: PixelColor + From<Rgb888> + Into<Rgb888> + From<BinaryColor>,
{
    let mut display = SimulatorDisplay::<C>::new(camera.size());
    let render = Render::new(input.0, input.1)
        .with_method(input.2)
        .with_options(input.3)
        .with_sampling(input.4);
    let Ok(()) = render.draw(&mut display); // the simulator cannot fail
    Shown {
        pixels: window_colors(&display, settings),
    }
}

/// The kernel's ordered dither in front of a low-depth `C` framebuffer.
fn dithered<C, const N: usize, const L: usize, const P: usize, const D: usize>(
    input: Input<'_, N, L, P, D>,
    camera: &Camera,
    settings: &OutputSettings,
    bayer: Bayer,
) -> Shown
where
    C: DitherColor + From<Rgb888> + Into<Rgb888> + From<BinaryColor>,
{
    let mut display = SimulatorDisplay::<C>::new(camera.size());
    let render = Render::new(input.0, input.1)
        .with_method(input.2)
        .with_options(input.3)
        .with_sampling(input.4);
    let Ok(()) = render.draw(&mut display.dithered_with(bayer));
    Shown {
        pixels: window_colors(&display, settings),
    }
}

/// The framebuffer in window colours, through the simulator's own conversion and theme.
fn window_colors<C>(display: &SimulatorDisplay<C>, settings: &OutputSettings) -> Vec<Rgb888>
where
    C: PixelColor + Into<Rgb888>,
{
    let image = display.to_rgb_output_image(settings);
    image
        .as_image_buffer()
        .as_raw()
        .chunks_exact(3)
        .map(|p| Rgb888::new(p[0], p[1], p[2]))
        .collect()
}

/// The user's orbit relative to the scene file's camera. All zero = the file's camera,
/// bit for bit.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Orbit {
    azimuth: f32,
    elevation: f32,
    zoom_steps: i32,
}

/// The orbit's frame around the look-at point: `k` = up, `e1` toward the file's eye
/// in the plane normal to `k`, `e2 = k × e1`; the file eye's elevation and distance.
struct OrbitFrame {
    k: Vec3,
    e1: Vec3,
    e2: Vec3,
    elevation: f32,
    distance: f32,
}

impl OrbitFrame {
    fn new(base: &CameraParams) -> Option<Self> {
        let offset = base.eye - base.look_at;
        let distance = offset.length();
        let k = base.up.try_normalize()?;
        let along = offset.dot(k);
        let horizontal = offset - k * along;
        // Looking straight along `up` cannot happen (the camera refuses it), but pick a
        // perpendicular anyway rather than fail.
        let e1 = horizontal
            .try_normalize()
            .or_else(|| k.cross(Vec3::new(1.0, 0.0, 0.0)).try_normalize())
            .or_else(|| k.cross(Vec3::new(0.0, 0.0, 1.0)).try_normalize())?;
        let e2 = k.cross(e1);
        Some(Self {
            k,
            e1,
            e2,
            elevation: along.atan2(horizontal.length()),
            distance,
        })
    }
}

impl Orbit {
    /// The camera parameters for this orbit of `base`, at the display's `size`.
    fn params(&self, base: &CameraParams, size: Size) -> CameraParams {
        let mut params = CameraParams { size, ..*base };
        if *self == Orbit::default() {
            return params; // the file's camera exactly: comparable with the render CLI
        }
        let Some(f) = OrbitFrame::new(base) else {
            return params;
        };
        let el = (f.elevation + self.elevation).clamp(-MAX_ELEVATION, MAX_ELEVATION);
        let dist = f.distance * ZOOM.powi(self.zoom_steps);
        let (sa, ca) = self.azimuth.sin_cos();
        let (se, ce) = el.sin_cos();
        params.eye = base.look_at + (f.e1 * ca + f.e2 * sa) * (dist * ce) + f.k * (dist * se);
        params
    }

    /// Adds `delta` to the elevation, keeping the total within ±`MAX_ELEVATION`.
    fn tilt(&mut self, base: &CameraParams, delta: f32) {
        let el0 = OrbitFrame::new(base).map_or(0.0, |f| f.elevation);
        self.elevation = (el0 + self.elevation + delta).clamp(-MAX_ELEVATION, MAX_ELEVATION) - el0;
    }
}

/// Command-line options.
struct Args {
    scene: PathBuf,
    model: Model,
    size: Option<Size>,
    scale: Option<u32>,
    method: Method,
    sampling: Sampling,
    bayer: Bayer,
    theme: BinaryColorTheme,
    diff: bool,
    overlay: bool,
    screenshot: Option<PathBuf>,
    frames: Option<u32>,
    /// The frame of the scene's motion to start paused on (1: its start).
    frame: Option<u32>,
}

/// The flags as clap parses them; [`parse_args`] turns them into [`Args`]. Every
/// choice is listed in `--help`: the display models from [`Model::ALL`], the method
/// axes from the kernel's own tables (`Stepping::NAMES`, …), the samplings from
/// `Sampling::ALL`.
#[derive(clap::Parser)]
#[command(
    name = "ertrace-preview",
    version,
    about = "A scene file in the embedded-graphics simulator's window, through a display model \
(keys: see docs/cli.md); --screenshot renders one frame without a display server.",
    override_usage = usage_line(),
)]
struct Cli {
    /// The scene file (TOML)
    #[arg(value_name = "SCENE.toml", default_value = "scenes/lab.toml")]
    scene: PathBuf,
    /// The display model
    #[arg(long, value_name = "MODEL", value_parser = PossibleValuesParser::new(Model::ALL.map(Model::name))
        .try_map(|s| Model::parse(&s)))]
    display: Option<Model>,
    /// The display's resolution, instead of the scene file's
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<Size>,
    /// Window pixels per display pixel (1 to 16)
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=16))]
    scale: Option<u32>,
    /// Rays per pixel
    #[arg(long, value_parser = PossibleValuesParser::new(sampling_names()).try_map(|s| s.parse::<Sampling>()))]
    sampling: Option<Sampling>,
    /// Bayer matrix of the dithered models
    #[arg(long, value_parser = PossibleValuesParser::new(["4", "8"]).map(|s| if s == "4" { Bayer::Four } else { Bayer::Eight }))]
    bayer: Option<Bayer>,
    /// OLED theme of the binary models
    #[arg(long, value_parser = PossibleValuesParser::new(["oled-blue", "oled-white"])
        .map(|s| if s == "oled-white" { BinaryColorTheme::OledWhite } else { BinaryColorTheme::OledBlue }))]
    theme: Option<BinaryColorTheme>,
    /// The starting method's stepping
    #[arg(long, value_parser = PossibleValuesParser::new(Stepping::NAMES).try_map(|s| s.parse::<Stepping>()))]
    stepping: Option<Stepping>,
    /// The starting method's ray–sphere test
    #[arg(long, value_parser = PossibleValuesParser::new(SphereTest::NAMES).try_map(|s| s.parse::<SphereTest>()))]
    sphere_test: Option<SphereTest>,
    /// The starting method's square root
    #[arg(long, value_parser = PossibleValuesParser::new(Sqrt::NAMES).try_map(|s| s.parse::<Sqrt>()))]
    sqrt: Option<Sqrt>,
    /// Start in the difference view
    #[arg(long)]
    diff: bool,
    /// No status bar: the window shows exactly the display
    #[arg(long)]
    no_overlay: bool,
    /// Write what the window shows to OUT.png and exit
    #[arg(long, value_name = "OUT.png")]
    screenshot: Option<PathBuf>,
    /// With --screenshot: open the window, show N frames, write the last
    #[arg(long, value_name = "N", requires = "screenshot", value_parser = clap::value_parser!(u32))]
    frames: Option<u32>,
    /// Start paused on frame K of the scene's motion, at t = (K - 1)/fps seconds (the
    /// render CLI's --frame K); Space plays
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(1..))]
    frame: Option<u32>,
}

/// Every sampling's name (`Sampling::ALL` as `Display` writes them), for clap, which
/// keeps `&'static str`s: seven short strings, made once per run.
fn sampling_names() -> Vec<&'static str> {
    Sampling::ALL
        .iter()
        .map(|s| &*Box::leak(s.to_string().into_boxed_str()))
        .collect()
}

/// `--size`'s value.
fn parse_size(v: &str) -> Result<Size, String> {
    v.split_once('x')
        .and_then(|(w, h)| Some(Size::new(w.parse().ok()?, h.parse().ok()?)))
        .ok_or_else(|| format!("expected WxH, got `{v}`"))
}

/// The usage line for clap (without the leading `usage: `).
fn usage_line() -> String {
    usage().trim_start_matches("usage: ").to_string()
}

/// The flags after the program's name.
fn parse_args<T: Into<std::ffi::OsString> + Clone>(
    args: impl IntoIterator<Item = T>,
) -> Result<Args, clap::Error> {
    use clap::Parser;
    let cli = Cli::try_parse_from(
        std::iter::once(std::ffi::OsString::from("ertrace-preview")).chain(args.into_iter().map(Into::into)),
    )?;
    let mut method = Method::default();
    if let Some(s) = cli.stepping {
        method.stepping = s;
    }
    if let Some(s) = cli.sphere_test {
        method.sphere_test = s;
    }
    if let Some(s) = cli.sqrt {
        method.sqrt = s;
    }
    Ok(Args {
        scene: cli.scene,
        model: cli.display.unwrap_or(Model::Rgb888),
        size: cli.size,
        scale: cli.scale,
        method,
        sampling: cli.sampling.unwrap_or(Sampling::Center),
        bayer: cli.bayer.unwrap_or(Bayer::Eight),
        theme: cli.theme.unwrap_or(BinaryColorTheme::OledBlue),
        diff: cli.diff,
        overlay: !cli.no_overlay,
        screenshot: cli.screenshot,
        frames: cli.frames.map(|n| n.max(1)),
        frame: cli.frame,
    })
}

/// The program state.
struct App {
    path: PathBuf,
    mtime: Option<SystemTime>,
    last_poll: Instant,
    /// The last scene that loaded, as its file places it (before any motion).
    scene: Loaded,
    base: CameraParams,
    /// The scene's motion (none: a still scene).
    animation: Animation<MAX_MOTIONS>,
    /// The frame of the motion shown, and whether it plays.
    clock: play::Clock,
    /// The user's view of the file's camera (before any motion of the camera).
    camera: Camera,
    /// The display's resolution (fixed for the session).
    size: Size,
    orbit: Orbit,
    view: View,
    diff: bool,
    error: Option<String>,
    overlay: bool,
    font: &'static MonoFont<'static>,
    status_height: u32,
    screen: SimulatorDisplay<Rgb888>,
    /// The display model's framebuffer the frames are drawn on, incrementally.
    display: play::Display,
    /// What the last frame cost, and the arithmetic it was drawn in.
    stats: FrameStats,
    arithmetic: Option<Arithmetic>,
    dirty: bool,
    drag: Option<Point>,
    /// Pixels that differed from the reference in the last difference view.
    differing: Option<usize>,
}

impl App {
    fn new(args: &Args) -> Result<Self, String> {
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
    fn poll_file(&mut self) {
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
    fn tick(&mut self, now: Instant) {
        if self.clock.tick(&self.animation, now) {
            self.dirty = true;
        }
    }

    /// Draws the frame shown onto the display model's framebuffer (only what changed,
    /// for a scene that moves; whole, for a still one), then the screen from it
    /// (image, difference marks, status bar).
    fn redraw(&mut self) {
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
        let shown = self.display.window_colors(&self.view.output_settings());
        let w = self.size.width as usize;
        let mut differing = 0usize;
        let reference_view = View {
            secondary: SecondaryOrigin::Convex,
            ..self.view
        };
        let reference = self
            .diff
            .then(|| shade(&scene, &camera, &reference_view, REFERENCE).pixels);
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
        self.dirty = false;
    }

    /// The status bar's three lines: render time and display model; the method (and,
    /// for a scene with lights, planes or mirrors, the secondary origin); the
    /// difference count, or for a scene that moves the frame rate achieved (the frame,
    /// paused) and the share of the display the last frame traced and sent, or the
    /// orbit.
    fn status(&self, render_time: Duration, differing: usize) -> [String; 3] {
        let ms = render_time.as_secs_f64() * 1e3;
        let mut model = self.view.model.name().to_string();
        if self.view.model.is_dithered() {
            model += if self.view.bayer == Bayer::Four {
                " 4x4"
            } else {
                " 8x8"
            };
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

    /// Handles one window event; `false` to quit.
    fn handle(&mut self, event: SimulatorEvent) -> bool {
        let shift = |m: Mod| m.intersects(Mod::LSHIFTMOD | Mod::RSHIFTMOD);
        match event {
            SimulatorEvent::Quit => return false,
            SimulatorEvent::KeyDown { keycode, keymod, .. } => match keycode {
                Keycode::Q => return false,
                Keycode::LEFT => self.turn(-ORBIT_STEP),
                Keycode::RIGHT => self.turn(ORBIT_STEP),
                Keycode::UP => self.tilt(ORBIT_STEP),
                Keycode::DOWN => self.tilt(-ORBIT_STEP),
                Keycode::PLUS | Keycode::EQUALS | Keycode::KP_PLUS => self.zoom(-1),
                Keycode::MINUS | Keycode::KP_MINUS => self.zoom(1),
                Keycode::R => {
                    self.orbit = Orbit::default();
                    self.update_camera();
                }
                Keycode::M => {
                    let all = Method::ALL;
                    let k = all.iter().position(|&m| m == self.view.method).unwrap_or(0);
                    let next = if shift(keymod) { k + all.len() - 1 } else { k + 1 };
                    self.view.method = all[next % all.len()];
                    self.dirty = true;
                }
                Keycode::I => {
                    let next = if self.view.method.arithmetic == Arithmetic::F32 {
                        Arithmetic::Integer
                    } else {
                        Arithmetic::F32
                    };
                    self.view.method = self.view.method.with_arithmetic(next);
                    self.dirty = true;
                }
                Keycode::E => {
                    let n = SECONDARY.len();
                    let k = SECONDARY
                        .iter()
                        .position(|&s| s == self.view.secondary)
                        .unwrap_or(0);
                    let next = if shift(keymod) { k + n - 1 } else { k + 1 };
                    self.view.secondary = SECONDARY[next % n];
                    self.dirty = true;
                }
                Keycode::A => {
                    let all = Sampling::ALL;
                    let k = all.iter().position(|&s| s == self.view.sampling).unwrap_or(0);
                    let next = if shift(keymod) { k + all.len() - 1 } else { k + 1 };
                    self.view.sampling = all[next % all.len()];
                    self.dirty = true;
                }
                Keycode::D => {
                    self.diff = !self.diff;
                    self.dirty = true;
                }
                Keycode::TAB => {
                    let n = Model::ALL.len();
                    let k = self.view.model.index();
                    let next = if shift(keymod) { k + n - 1 } else { k + 1 };
                    self.view.model = Model::ALL[next % n];
                    self.dirty = true;
                }
                Keycode::B => {
                    self.view.bayer = match self.view.bayer {
                        Bayer::Eight => Bayer::Four,
                        Bayer::Four => Bayer::Eight,
                    };
                    self.dirty = true;
                }
                Keycode::SPACE if self.moves() => {
                    self.clock.toggle(&self.animation, Instant::now());
                    self.dirty = true;
                }
                Keycode::PERIOD | Keycode::COMMA if self.moves() => {
                    let delta = if keycode == Keycode::PERIOD { 1 } else { -1 };
                    self.clock.step(&self.animation, delta);
                    self.dirty = true;
                }
                Keycode::T => {
                    self.view.theme = match self.view.theme {
                        BinaryColorTheme::OledBlue => BinaryColorTheme::OledWhite,
                        _ => BinaryColorTheme::OledBlue,
                    };
                    self.dirty = true;
                }
                k => {
                    let digits = [
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
                    if let Some(i) = digits.iter().position(|&d| d == k) {
                        self.view.model = Model::ALL[i];
                        self.dirty = true;
                    }
                }
            },
            SimulatorEvent::MouseButtonDown {
                mouse_btn: MouseButton::Left,
                point,
            } => self.drag = Some(point),
            SimulatorEvent::MouseButtonUp {
                mouse_btn: MouseButton::Left,
                ..
            } => self.drag = None,
            SimulatorEvent::MouseMove { point } => {
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
            SimulatorEvent::MouseWheel { scroll_delta, .. } if scroll_delta.y != 0 => {
                self.zoom(-scroll_delta.y.signum());
            }
            _ => {}
        }
        true
    }

    /// Draws the frame shown as the player reaches it: for a scene that moves, the
    /// frame before it first (none before the start), then it over that through the
    /// incremental rule.
    fn draw_as_played(&mut self) {
        let frame = self.clock.frame();
        if self.moves() && frame > 0 {
            self.clock.show(frame - 1);
            self.redraw();
            self.clock.show(frame);
        }
        self.redraw();
    }

    fn turn(&mut self, delta: f32) {
        self.orbit.azimuth += delta;
        self.update_camera();
    }

    fn tilt(&mut self, delta: f32) {
        self.orbit.tilt(&self.base, delta);
        self.update_camera();
    }

    fn zoom(&mut self, steps: i32) {
        // Between 1/1.1^40 ≈ 1/45 and 45 times the file's distance.
        self.orbit.zoom_steps = (self.orbit.zoom_steps + steps).clamp(-40, 40);
        self.update_camera();
    }
}

/// The scene and camera of frame `frame` of `animation`: for a still scene `scene`
/// through `camera` (the user's view of the file's camera); for one that moves, the
/// motion's frame applied to them.
fn moment<'a>(
    scene: &'a Loaded,
    animation: &Animation<MAX_MOTIONS>,
    camera: &Camera,
    frame: u32,
) -> Result<(Cow<'a, Loaded>, Camera), String> {
    if animation.is_still() {
        return Ok((Cow::Borrowed(scene), *camera));
    }
    let (scene, params) = scene
        .at_frame(animation, camera.params(), frame)
        .map_err(|e| format!("frame {}: {e}", u64::from(frame) + 1))?;
    let camera = params
        .build()
        .map_err(|e| format!("camera at frame {}: {e}", u64::from(frame) + 1))?;
    Ok((Cow::Owned(scene), camera))
}

/// The status bar's name of a secondary origin: `convex`, `eps=1e-3`.
fn secondary_label(secondary: SecondaryOrigin) -> String {
    match secondary {
        SecondaryOrigin::Convex => "convex".to_string(),
        SecondaryOrigin::Epsilon(eps) => format!("eps={eps:e}"),
        other => other.to_string(),
    }
}

fn mtime(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

/// Writes the screen as the window shows it (with the pixel scale).
fn save(screen: &SimulatorDisplay<Rgb888>, settings: &OutputSettings, path: &Path) -> Result<(), String> {
    screen
        .to_rgb_output_image(settings)
        .save_png(path)
        .map_err(|e| format!("{}: cannot write the PNG: {e}", path.display()))
}

fn run() -> Result<(), String> {
    let args = match parse_args(std::env::args_os().skip(1)) {
        Ok(args) => args,
        Err(e)
            if matches!(
                e.kind(),
                clap::error::ErrorKind::DisplayHelp | clap::error::ErrorKind::DisplayVersion
            ) =>
        {
            print!("{}", e.render());
            return Ok(());
        }
        // One line: the flag and the reason (clap's first paragraph), exit code 2.
        Err(e) => {
            let text = e.render().to_string();
            let first: Vec<&str> = text
                .lines()
                .take_while(|l| !l.trim().is_empty())
                .map(str::trim)
                .collect();
            let first = first.join(" ");
            return Err(first.strip_prefix("error: ").unwrap_or(&first).to_string());
        }
    };
    let mut app = App::new(&args)?;
    // Default scale: a window about 640 pixels wide.
    let scale = args.scale.unwrap_or((640 / app.size.width).clamp(1, 8));
    let settings = OutputSettingsBuilder::new().scale(scale).build();

    if let (Some(path), None) = (&args.screenshot, args.frames) {
        // Headless: no window, no SDL.
        app.draw_as_played();
        save(&app.screen, &settings, path)?;
        println!("{} -> {}", args.scene.display(), path.display());
        return Ok(());
    }

    let mut window = Window::new("embedded-raytracer", &settings);
    let mut frame = 0u32;
    loop {
        // The window paces the loop (60 a second unless the motion's rate is higher).
        window.set_max_fps(app.animation.fps().ceil().clamp(60.0, 1000.0) as u32);
        app.tick(Instant::now());
        if app.dirty {
            app.redraw();
        }
        // With EG_SIMULATOR_DUMP set, this writes the frame and exits the process.
        window.update(&app.screen);
        frame += 1;
        if let (Some(path), Some(n)) = (&args.screenshot, args.frames) {
            if frame >= n {
                save(&app.screen, &settings, path)?;
                println!(
                    "{} -> {} (after {n} window frames)",
                    args.scene.display(),
                    path.display()
                );
                return Ok(());
            }
        }
        for event in window.events() {
            if !app.handle(event) {
                return Ok(());
            }
        }
        app.poll_file();
    }
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The standard scenes, named from the repository root (tests run in this package's folder).
    const LAB: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/lab.toml");
    #[allow(dead_code)]
    const SHADOWS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/shadows.toml");
    #[allow(dead_code)]
    const MIRRORS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/mirrors.toml");

    /// Scenes that move: shadows on a floor (the full type), spheres only.
    const BOUNCE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/bounce.toml");
    const CIRCLING: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/circling.toml");

    /// The picture on the screen (the status bar left out).
    fn image(app: &App) -> Vec<Rgb888> {
        Rectangle::new(Point::zero(), app.size)
            .points()
            .map(|p| app.screen.get_pixel(p))
            .collect()
    }

    /// Frame `frame` (0: the start) of the scene file at `path` at `size`, rendered
    /// whole as the render CLI renders `--frame frame+1`: loaded with the full
    /// capacities, the motion applied at `frame / fps`, drawn through the spheres-only
    /// type if the file has no light, plane or mirror.
    fn full_frame(path: &str, size: Size, frame: u32) -> Vec<Rgb888> {
        use embedded_raytracer::motion::frame_time;
        let file: Box<FullSceneFile> = Box::new(scene_file::load(path).unwrap());
        let base = file.camera.params().with_size(size);
        let (mut moved, mut params) = (file.clone(), base);
        let t = frame_time(frame, file.animation.fps());
        file.animation
            .apply(&file.scene, &base, t, &mut moved.scene, &mut params)
            .unwrap();
        let camera = params.build().unwrap();
        let mut out = Vec::new();
        match moved.spheres_only() {
            Some(s) => Render::<'_, MAX_SPHERES, Rgb888>::new(&s.scene, &camera).trace(|s| out.push(s.color)),
            None => Render::<'_, MAX_SPHERES, Rgb888, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>::new(
                &moved.scene,
                &camera,
            )
            .trace(|s| out.push(s.color)),
        }
        out
    }

    fn args(scene: &str, extra: &[&str]) -> Args {
        let all = std::iter::once(scene)
            .chain(extra.iter().copied())
            .map(String::from);
        parse_args(all).unwrap()
    }

    fn spheres(scene: &Loaded) -> usize {
        match scene {
            Loaded::Spheres(scene) => scene.spheres().len(),
            Loaded::Full(scene) => scene.spheres().len(),
        }
    }

    fn key(keycode: Keycode) -> SimulatorEvent {
        SimulatorEvent::KeyDown {
            keycode,
            keymod: Mod::NOMOD,
            repeat: false,
        }
    }

    #[test]
    fn keys_orbit_zoom_and_reset_to_the_files_camera() {
        let mut app = App::new(&args(LAB, &[])).unwrap();
        let file = *app.camera.params();
        assert!(app.handle(key(Keycode::RIGHT)));
        let turned = app.camera.params().eye;
        assert!((turned - file.eye).length() > 0.1);
        // Orbiting keeps the distance to the look-at point.
        let dist = |e: Vec3| (e - file.look_at).length();
        assert!((dist(turned) - dist(file.eye)).abs() < 1e-4);
        app.handle(key(Keycode::PLUS));
        assert!(dist(app.camera.params().eye) < dist(file.eye) * 0.95);
        app.handle(key(Keycode::UP));
        app.handle(SimulatorEvent::MouseWheel {
            scroll_delta: Point::new(0, -1),
            direction: embedded_graphics_simulator::sdl2::MouseWheelDirection::Normal,
        });
        app.handle(key(Keycode::R));
        assert_eq!(*app.camera.params(), file);
        assert!(!app.handle(key(Keycode::Q)));
        assert!(!app.handle(SimulatorEvent::Quit));
    }

    #[test]
    fn mouse_drag_orbits() {
        let mut app = App::new(&args(LAB, &[])).unwrap();
        let file = *app.camera.params();
        app.handle(SimulatorEvent::MouseMove {
            point: Point::new(50, 50),
        });
        assert_eq!(*app.camera.params(), file, "moving without a button does nothing");
        app.handle(SimulatorEvent::MouseButtonDown {
            mouse_btn: MouseButton::Left,
            point: Point::new(50, 50),
        });
        app.handle(SimulatorEvent::MouseMove {
            point: Point::new(90, 40),
        });
        assert_ne!(app.camera.params().eye, file.eye);
        app.handle(SimulatorEvent::MouseButtonUp {
            mouse_btn: MouseButton::Left,
            point: Point::new(90, 40),
        });
        let after = app.camera.params().eye;
        app.handle(SimulatorEvent::MouseMove {
            point: Point::new(10, 10),
        });
        assert_eq!(app.camera.params().eye, after);
    }

    /// `I` toggles the integer kernel: on the lab scene it draws another picture (its
    /// own), and a second press is the f32 method's again.
    #[test]
    fn i_toggles_the_integer_kernel() {
        let mut app = App::new(&args(LAB, &[])).unwrap();
        let f32_frame = shade(&app.scene, &app.camera, &app.view, app.view.method).pixels;
        app.handle(key(Keycode::I));
        assert_eq!(
            app.view.method,
            Method::TARGET_DEFAULT.with_arithmetic(Arithmetic::Integer)
        );
        let integer_frame = shade(&app.scene, &app.camera, &app.view, app.view.method).pixels;
        assert!(
            integer_frame != f32_frame,
            "the integer kernel drew the f32 picture"
        );
        assert_eq!(
            app.scene.arithmetic(&app.camera, app.view.method),
            Arithmetic::Integer
        );
        app.handle(key(Keycode::I));
        assert_eq!(app.view.method, Method::TARGET_DEFAULT);
    }

    #[test]
    fn m_cycles_all_methods_and_tab_all_models() {
        let mut app = App::new(&args(LAB, &[])).unwrap();
        let mut seen = Vec::new();
        for _ in 0..Method::ALL.len() {
            seen.push(app.view.method);
            app.handle(key(Keycode::M));
        }
        assert_eq!(
            app.view.method,
            Method::TARGET_DEFAULT,
            "back to the start after a full cycle"
        );
        assert!(Method::ALL.iter().all(|m| seen.contains(m)));
        let mut models = Vec::new();
        for _ in 0..Model::ALL.len() {
            models.push(app.view.model);
            app.handle(key(Keycode::TAB));
        }
        assert_eq!(models, Model::ALL);
        app.handle(key(Keycode::NUM_9));
        assert_eq!(app.view.model, Model::BinaryDither);
    }

    /// `A` cycles every sampling (back to `center` after a full cycle, `Shift+A`
    /// backwards), the status bar names it, and the shown frame is the kernel's render
    /// with it.
    #[test]
    fn a_cycles_the_sampling_and_the_status_bar_shows_it() {
        let mut app = App::new(&args(LAB, &["--size", "48x36", "--display", "rgb888"])).unwrap();
        let mut seen = Vec::new();
        for _ in 0..Sampling::ALL.len() {
            seen.push(app.view.sampling);
            let line = &app.status(Duration::ZERO, 0)[0];
            assert!(line.ends_with(&format!(" {}", app.view.sampling)), "{line}");
            app.handle(key(Keycode::A));
        }
        assert_eq!(seen, Sampling::ALL);
        let flagged = args(LAB, &["--sampling", "grid:3"]);
        assert_eq!(flagged.sampling, Sampling::grid(3).unwrap());
        assert_eq!(app.view.sampling, Sampling::Center);
        app.handle(SimulatorEvent::KeyDown {
            keycode: Keycode::A,
            keymod: Mod::LSHIFTMOD,
            repeat: false,
        });
        assert_eq!(app.view.sampling, Sampling::adaptive(4).unwrap());
        let shown = shade(&app.scene, &app.camera, &app.view, app.view.method).pixels;
        let Loaded::Spheres(scene) = &app.scene else {
            panic!("lab is spheres-only")
        };
        let mut expected = Vec::new();
        Render::<'_, MAX_SPHERES, Rgb888>::new(&**scene, &app.camera)
            .with_sampling(Sampling::adaptive(4).unwrap())
            .trace(|s| expected.push(s.color));
        assert_eq!(shown, expected);
        let center = shade(
            &app.scene,
            &app.camera,
            &View {
                sampling: Sampling::Center,
                ..app.view
            },
            app.view.method,
        );
        assert_ne!(shown, center.pixels, "adaptive sampling changed no pixel");
    }

    #[test]
    fn difference_view_marks_exactly_the_differing_pixels() {
        let small = ["--size", "160x120"];
        // The reference method against itself: nothing differs.
        let mut app = App::new(&args(
            LAB,
            &[
                &small[..],
                &["--stepping", "direct", "--sphere-test", "robust", "--diff"],
            ]
            .concat(),
        ))
        .unwrap();
        app.redraw();
        assert_eq!(app.differing, Some(0));
        // The fast square root shades differently: the marked pixels are counted and
        // painted, and each marked pixel really differs between the two renders.
        let mut app = App::new(&args(LAB, &[&small[..], &["--sqrt", "fast", "--diff"]].concat())).unwrap();
        app.redraw();
        let n = app.differing.unwrap();
        assert!(n > 0);
        let shown = shade(&app.scene, &app.camera, &app.view, app.view.method).pixels;
        let reference = shade(&app.scene, &app.camera, &app.view, REFERENCE).pixels;
        let truly = shown.iter().zip(&reference).filter(|(a, b)| a != b).count();
        assert_eq!(n, truly);
        let marked = Rectangle::new(Point::zero(), app.size)
            .points()
            .filter(|&p| app.screen.get_pixel(p) == DIFF_COLOR)
            .count();
        assert_eq!(marked, n);
        // D toggles it off: the plain frame again.
        app.handle(key(Keycode::D));
        app.redraw();
        assert_eq!(app.differing, None);
        assert_eq!(app.screen.get_pixel(Point::new(80, 60)), shown[60 * 160 + 80]);
    }

    #[test]
    fn reload_keeps_the_last_good_scene_and_shows_the_error() {
        let dir = std::env::temp_dir().join(format!("simulator-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("scene.toml");
        let good = std::fs::read_to_string(LAB).unwrap();
        std::fs::write(&path, &good).unwrap();
        let mut app = App::new(&args(path.to_str().unwrap(), &["--size", "160x120"])).unwrap();
        app.redraw();
        let before: Vec<Rgb888> = Rectangle::new(Point::zero(), app.size)
            .points()
            .map(|p| app.screen.get_pixel(p))
            .collect();
        let touch = |text: &str, secs: u64| {
            std::fs::write(&path, text).unwrap();
            let t = SystemTime::UNIX_EPOCH + Duration::from_secs(secs);
            std::fs::File::options()
                .write(true)
                .open(&path)
                .unwrap()
                .set_modified(t)
                .unwrap();
        };
        let poll = |app: &mut App| {
            app.last_poll = Instant::now() - 2 * POLL;
            app.poll_file();
        };
        // A bad file: the error is kept for display, the scene is the old one.
        touch(&good.replace("radius = 1.0", "radius = -1.0"), 1_000_000);
        poll(&mut app);
        let error = app.error.clone().unwrap();
        assert!(error.contains("radius"), "{error}");
        assert_eq!(spheres(&app.scene), 5);
        app.redraw();
        // The error box covers the top rows; the rest is still the last good frame.
        assert_ne!(app.screen.get_pixel(Point::new(0, 0)), before[0]);
        assert_eq!(
            app.screen.get_pixel(Point::new(159, 119)),
            before[119 * 160 + 159]
        );
        // Fixed with one sphere less: reloaded, error gone.
        let i = good.rfind("[[sphere]]").unwrap();
        touch(&good[..i], 2_000_000);
        poll(&mut app);
        assert_eq!(app.error, None);
        assert_eq!(spheres(&app.scene), 4);
        assert!(!app.scene.has_features());
        // A file that gains lights, a floor and mirrors: reloaded through the full type.
        touch(&std::fs::read_to_string(MIRRORS).unwrap(), 3_000_000);
        poll(&mut app);
        assert_eq!(app.error, None);
        assert!(app.scene.has_features());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// The feature scenes load through the full type and show the kernel's pixels for
    /// that type (the render CLI's); `E` cycles the secondary origin, which the status
    /// bar names and the difference view measures against the convex one.
    #[test]
    fn feature_scenes_and_the_secondary_origin_key() {
        use embedded_graphics::pixelcolor::Rgb888;
        let lab = App::new(&args(LAB, &[])).unwrap();
        assert!(!lab.scene.has_features());
        assert!(!lab.status(Duration::ZERO, 0)[1].contains("convex"));
        for name in standard::FEATURE_SCENES {
            let path = standard::path(name);
            let mut app = App::new(&args(&path, &["--size", "96x96", "--no-overlay"])).unwrap();
            assert!(app.scene.has_features(), "{name}");
            app.redraw();
            let file = standard::load_full(name);
            let mut expected = Vec::new();
            Render::<'_, MAX_SPHERES, Rgb888, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>::new(
                &file.scene,
                &app.camera,
            )
            .trace(|s| expected.push(s.color));
            let shown: Vec<Rgb888> = Rectangle::new(Point::zero(), app.size)
                .points()
                .map(|p| app.screen.get_pixel(p))
                .collect();
            assert!(shown == expected, "{name}: not the kernel's pixels");
        }

        // The method the difference view compares with, so only the origin differs.
        let open = |name: &str| {
            App::new(&args(
                &standard::path(name),
                &["--size", "120x120", "--sphere-test", "robust", "--diff"],
            ))
            .unwrap()
        };
        let mut app = open("shadows");
        let mut seen = Vec::new();
        for _ in 0..SECONDARY.len() {
            seen.push(app.view.secondary);
            app.handle(key(Keycode::E));
        }
        assert_eq!(seen, SECONDARY);
        assert_eq!(app.view.secondary, SecondaryOrigin::Convex, "a full cycle");
        assert!(app.status(Duration::ZERO, 0)[1].ends_with(" convex"));
        app.redraw();
        assert_eq!(app.differing, Some(0), "convex against the convex reference");

        let shift_e = SimulatorEvent::KeyDown {
            keycode: Keycode::E,
            keymod: Mod::LSHIFTMOD,
            repeat: false,
        };
        app.handle(shift_e);
        assert_eq!(
            app.view.secondary,
            SECONDARY[SECONDARY.len() - 1],
            "Shift+E: back"
        );

        // Each epsilon that fails on a feature scene: the marked pixels are exactly
        // those that differ from the convex reference.
        let cases = [
            ("shadows", SecondaryOrigin::Epsilon(1e-6), "eps=1e-6"),
            ("mirrors", SecondaryOrigin::Epsilon(1e-1), "eps=1e-1"),
        ];
        for (name, secondary, label) in cases {
            let mut app = open(name);
            while app.view.secondary != secondary {
                app.handle(key(Keycode::E));
            }
            assert!(app.status(Duration::ZERO, 0)[1].ends_with(label));
            app.redraw();
            let n = app.differing.unwrap();
            assert!(n > 0, "{name}: {label} changed no pixel");
            let shown = shade(&app.scene, &app.camera, &app.view, app.view.method).pixels;
            let convex = View {
                secondary: SecondaryOrigin::Convex,
                ..app.view
            };
            let reference = shade(&app.scene, &app.camera, &convex, REFERENCE).pixels;
            assert_eq!(n, shown.iter().zip(&reference).filter(|(a, b)| a != b).count());
        }
    }

    #[test]
    fn bad_flags_are_errors() {
        for bad in [
            &["--display", "cmyk"][..],
            &["--size", "12"],
            &["--scale", "0"],
            &["--bayer", "3"],
            &["--sampling", "grid:5"],
            &["--sampling", "box"],
            &["--frames", "2"],
            &["--frame", "0"],
            &["--frame", "x"],
            &["--frobnicate"],
        ] {
            let all = bad.iter().map(|s| s.to_string());
            assert!(parse_args(all).is_err(), "{bad:?}");
        }
    }

    /// Playing draws each frame over the last through one `Incremental`: every frame of
    /// a loop of `bounce` (and the step back to its start) is the whole frame's render,
    /// and most were drawn tracing and sending a part of the display only.
    #[test]
    fn motion_is_drawn_incrementally_and_each_frame_is_the_full_render() {
        let size = Size::new(96, 96);
        let mut app = App::new(&args(
            BOUNCE,
            &["--size", "96x96", "--no-overlay", "--frame", "1"],
        ))
        .unwrap();
        assert!(app.moves() && app.clock.is_paused());
        app.redraw();
        assert!(app.stats.full, "the first frame is drawn whole");
        assert!(image(&app) == full_frame(BOUNCE, size, 0));
        let n = app.animation.frames();
        assert_eq!(n, 30);
        let mut partial = 0;
        for k in 1..=n {
            app.handle(key(Keycode::PERIOD));
            assert!(app.dirty);
            app.redraw();
            let frame = k % n;
            assert_eq!(app.clock.frame(), frame);
            assert!(
                image(&app) == full_frame(BOUNCE, size, frame),
                "frame {frame}: not the full render"
            );
            if !app.stats.full {
                partial += 1;
                assert!(app.stats.sent < 96 * 96 / 2, "frame {frame}: {:?}", app.stats);
            }
        }
        assert!(partial > n / 2, "only {partial} of {n} frames drawn in part");
        // And back.
        app.handle(key(Keycode::COMMA));
        app.redraw();
        assert_eq!(app.clock.frame(), n - 1);
        assert!(image(&app) == full_frame(BOUNCE, size, n - 1));
    }

    /// The headless screenshot of `--frame K` (drawn over frame K − 1, as played) is the
    /// render CLI's `--frame K`: the moment `(K − 1)/fps`, beyond the loop too.
    #[test]
    fn frame_k_screenshot_is_the_full_render_of_that_moment() {
        let shot = |k: u32, extra: &[&str]| {
            let k_text = k.to_string();
            let flags = [
                &[
                    "--display",
                    "rgb888",
                    "--scale",
                    "1",
                    "--no-overlay",
                    "--frame",
                    &k_text,
                ][..],
                extra,
            ]
            .concat();
            let mut app = App::new(&args(BOUNCE, &flags)).unwrap();
            app.draw_as_played();
            assert!(!app.stats.full, "frame {k}: not drawn over frame {}", k - 1);
            app
        };
        let app = shot(9, &[]);
        assert_eq!(app.size, Size::new(240, 240));
        assert!(image(&app) == full_frame(BOUNCE, app.size, 8));
        // The PNG the flag writes holds those pixels.
        let dir = std::env::temp_dir().join(format!("simulator-frame-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let png = dir.join("frame9.png");
        save(&app.screen, &OutputSettingsBuilder::new().scale(1).build(), &png).unwrap();
        assert!(std::fs::metadata(&png).unwrap().len() > 0);
        std::fs::remove_dir_all(&dir).unwrap();
        // Frame 41 is the moment 40/25 s, not frame 11 of the loop.
        let app = shot(41, &["--size", "64x64"]);
        assert_eq!(app.clock.frame(), 40);
        assert!(image(&app) == full_frame(BOUNCE, app.size, 40));
        // Frame 1 is drawn whole: there is no frame before it.
        let mut app = App::new(&args(BOUNCE, &["--size", "64x64", "--frame", "1"])).unwrap();
        app.draw_as_played();
        assert!(app.stats.full);
    }

    /// Changes of view while a scene moves flow into the next frame, through the same
    /// framebuffer: a new display model (or Bayer matrix) starts it again, a new method
    /// or camera is a frame the incremental rule draws whole; each frame is the
    /// model's full render.
    #[test]
    fn view_changes_flow_into_the_next_frame() {
        let mut app = App::new(&args(
            CIRCLING,
            &["--size", "64x64", "--display", "gray2-dither", "--frame", "1"],
        ))
        .unwrap();
        assert!(!app.scene.has_features());
        let check = |app: &App, what: &str| {
            let (scene, camera) = moment(&app.scene, &app.animation, &app.camera, app.clock.frame()).unwrap();
            let expected = shade(&scene, &camera, &app.view, app.view.method).pixels;
            assert!(image(app) == expected, "{what}: not the full render");
        };
        app.redraw();
        check(&app, "first");
        let steps: [(Keycode, &str, Option<bool>); 8] = [
            (Keycode::PERIOD, "step", Some(false)),
            (Keycode::PERIOD, "step", Some(false)),
            (Keycode::B, "bayer", Some(true)),
            (Keycode::TAB, "model", Some(true)),
            (Keycode::PERIOD, "step in binary", Some(false)),
            (Keycode::M, "method", Some(true)),
            (Keycode::RIGHT, "orbit", Some(true)),
            (Keycode::T, "theme", None),
        ];
        for (code, what, full) in steps {
            app.handle(key(code));
            app.redraw();
            check(&app, what);
            if let Some(full) = full {
                assert_eq!(app.stats.full, full, "{what}: {:?}", app.stats);
            }
        }
        assert_eq!(app.view.model, Model::Binary);
        app.handle(key(Keycode::NUM_9));
        app.handle(key(Keycode::I));
        app.handle(key(Keycode::PERIOD));
        app.redraw();
        check(&app, "integer kernel, binary-dither");
        app.handle(key(Keycode::PERIOD));
        app.redraw();
        check(&app, "integer kernel, next frame");
        assert!(!app.stats.full, "{:?}", app.stats);
    }

    /// A scene that moves plays at its frame rate, looping; `Space` pauses and resumes,
    /// `.`/`,` step; the status bar shows the rate, the frame while paused, and the
    /// share traced and sent.
    #[test]
    fn the_motion_plays_in_real_time_and_space_pauses_it() {
        let mut app = App::new(&args(BOUNCE, &["--size", "48x48"])).unwrap();
        assert!(!app.clock.is_paused(), "a moving scene plays from the start");
        let t0 = Instant::now();
        app.clock = play::Clock::new(None, t0);
        app.dirty = false;
        app.tick(t0 + Duration::from_millis(500));
        assert_eq!(app.clock.frame(), 12, "0.5 s at 25 fps");
        assert!(app.dirty);
        // 30 frames loop in 1.2 s.
        app.tick(t0 + Duration::from_millis(1300));
        assert_eq!(app.clock.frame(), 2);
        app.redraw();
        let line = &app.status(Duration::ZERO, 0)[2];
        assert!(
            line.contains(" fps traced ") && line.contains("% sent "),
            "{line}"
        );
        app.handle(key(Keycode::SPACE));
        assert!(app.clock.is_paused());
        app.tick(t0 + Duration::from_secs(5));
        assert_eq!(app.clock.frame(), 2, "paused");
        app.redraw();
        let line = &app.status(Duration::ZERO, 0)[2];
        assert!(line.starts_with("paused 3/30 traced "), "{line}");
        for _ in 0..3 {
            app.handle(key(Keycode::COMMA));
        }
        assert_eq!(app.clock.frame(), 29, "back over the start");
        app.handle(key(Keycode::SPACE));
        assert!(!app.clock.is_paused());
        app.tick(Instant::now());
        assert_eq!(app.clock.frame(), 29, "resumed from the frame shown");
        app.handle(key(Keycode::PERIOD));
        assert!(app.clock.is_paused(), "a step pauses");
        assert_eq!(app.clock.frame(), 0);

        // The achieved rate: frames drawn over the last second.
        let mut clock = play::Clock::new(None, t0);
        assert_eq!(clock.rate(), None);
        for k in 0..11 {
            clock.record(t0 + Duration::from_millis(40 * k));
        }
        assert!((clock.rate().unwrap() - 25.0).abs() < 1e-9);
        clock.record(t0 + Duration::from_millis(3000));
        assert_eq!(clock.rate(), None, "one frame in the last second");
    }

    /// A reload of a scene that moves keeps the paused frame and draws it whole: the
    /// new file's render of that moment.
    #[test]
    fn a_reload_keeps_the_frame_and_draws_it_whole() {
        let dir = std::env::temp_dir().join(format!("simulator-reload-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("bounce.toml");
        let text = std::fs::read_to_string(BOUNCE).unwrap();
        std::fs::write(&path, &text).unwrap();
        let p = path.to_str().unwrap();
        let mut app = App::new(&args(p, &["--size", "64x64", "--frame", "5"])).unwrap();
        app.redraw();
        app.handle(key(Keycode::PERIOD));
        app.redraw();
        assert!(!app.stats.full);
        std::fs::write(
            &path,
            text.replace("color = [230, 60, 50]", "color = [40, 60, 230]"),
        )
        .unwrap();
        let t = SystemTime::UNIX_EPOCH + Duration::from_secs(4_000_000);
        std::fs::File::options()
            .write(true)
            .open(&path)
            .unwrap()
            .set_modified(t)
            .unwrap();
        app.last_poll = Instant::now() - 2 * POLL;
        app.poll_file();
        assert_eq!(app.error, None);
        assert_eq!(app.clock.frame(), 5);
        app.redraw();
        assert!(app.stats.full, "{:?}", app.stats);
        assert!(image(&app) == full_frame(p, app.size, 5));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A still scene: no clock, `Space` and the step keys do nothing, every frame is
    /// drawn whole, the status bar shows the orbit.
    #[test]
    fn a_still_scene_is_drawn_whole_at_each_change() {
        let mut app = App::new(&args(LAB, &["--size", "48x36"])).unwrap();
        assert!(!app.moves());
        app.redraw();
        assert!(app.stats.full);
        for code in [Keycode::SPACE, Keycode::PERIOD, Keycode::COMMA] {
            app.handle(key(code));
            assert!(!app.dirty, "{code}");
        }
        app.handle(key(Keycode::T));
        app.redraw();
        assert!(app.stats.full && app.stats.sent == 48 * 36);
        assert!(app.status(Duration::ZERO, 0)[2].starts_with("az "));
    }

    #[test]
    fn zero_orbit_is_the_files_camera_and_a_full_turn_comes_back() {
        let base = CameraParams::new(
            Vec3::new(0.0, 1.0, 5.0),
            Vec3::ZERO,
            Vec3::new(0.0, 1.0, 0.0),
            1.0,
            Size::new(32, 24),
        );
        assert_eq!(Orbit::default().params(&base, base.size), base);
        let turned = Orbit {
            azimuth: 2.0 * core::f32::consts::PI,
            ..Orbit::default()
        }
        .params(&base, base.size);
        assert!((turned.eye - base.eye).length() < 1e-5);
        // A quarter turn keeps the distance and the height above the look-at plane.
        let q = Orbit {
            azimuth: core::f32::consts::FRAC_PI_2,
            ..Orbit::default()
        }
        .params(&base, base.size);
        assert!(((q.eye - q.look_at).length() - (base.eye - base.look_at).length()).abs() < 1e-5);
        assert!((q.eye.y - base.eye.y).abs() < 1e-5);
        assert!(q.eye.z.abs() < 1e-5);
    }

    #[test]
    fn tilt_is_clamped_short_of_up() {
        let base = CameraParams::new(
            Vec3::new(0.0, 0.0, 5.0),
            Vec3::ZERO,
            Vec3::new(0.0, 1.0, 0.0),
            1.0,
            Size::new(32, 24),
        );
        let mut o = Orbit::default();
        o.tilt(&base, 10.0);
        assert!((o.elevation - MAX_ELEVATION).abs() < 1e-6);
        assert!(o.params(&base, base.size).build().is_ok());
    }
}
