//! # embedded-raytracer
//!
//! A `no_std`, allocation-free ray-tracing kernel that streams what a pin-hole camera
//! sees, scanline by scanline, into any embedded-graphics
//! [`DrawTarget`](embedded_graphics::draw_target::DrawTarget).
//!
//! The scene is spheres (and, where the scene's type asks for them, lights with hard
//! shadows, checkered planes and mirrors); the target an SPI LCD driver, the desktop
//! simulator, a test's `MockDisplay`. No framebuffer, no allocation, no panic.
//!
//! ## One frame
//!
//! A scene lives in flash as a `static`; the camera is checked when it is built; the
//! render draws straight into the display, converting to its colour type:
//!
//! ```
//! use embedded_graphics::{mock_display::MockDisplay, pixelcolor::{Rgb565, Rgb888}};
//! use embedded_raytracer::prelude::*;
//!
//! static SCENE: Scene<2> = Scene::from_array(
//!     [
//!         Sphere::new(Vec3::new(0.0, 0.0, 0.0), 1.0, Rgb888::new(255, 64, 64)),
//!         Sphere::new(Vec3::new(1.2, 0.5, -1.5), 1.0, Rgb888::new(64, 64, 255)),
//!     ],
//!     Rgb888::BLACK,
//! );
//!
//! fn frame<D: DrawTarget<Color = Rgb565>>(display: &mut D, angle: f32) -> Result<(), D::Error> {
//!     // Orbit the eye around the origin: move the camera between frames.
//!     let eye = Vec3::new(5.0 * angle.sin(), 0.0, 5.0 * angle.cos());
//!     let Ok(camera) = Camera::new(eye, Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), 60f32.to_radians(), display.bounding_box().size) else {
//!         return Ok(()); // a camera the kernel refuses (say, `up` parallel to the view): show an error instead
//!     };
//!     Render::new(&SCENE, &camera).draw(display)
//! }
//!
//! let mut display = MockDisplay::<Rgb565>::new();
//! frame(&mut display, 0.0)?;
//! # Ok::<(), core::convert::Infallible>(())
//! ```
//!
//! [`Render::draw_band`] traces rows into a caller's buffer instead (for DMA), and
//! [`Render::draw_integer`] draws with the integer kernel alone (chips without an FPU).
//! The optional parts of a render are its builder methods: [`Render::with_method`]
//! (the speed/accuracy trade, [`Method`]), [`Render::with_sampling`] (anti-aliasing,
//! [`Sampling`]), [`Render::with_offset`] (a sub-rectangle of the display); a
//! low-depth display takes the ordered dither, `render.draw(&mut display.dithered())`
//! ([`dither`]). A camera's optional part, non-square pixels, is [`CameraParams`]'
//! `with_fov_x`.
//!
//! ## Conventions
//!
//! Right-handed world coordinates; angles in radians (degrees only in scene-file
//! fields named `_deg`); `f32` throughout, with every approximation's error bound in
//! its doc comment. The formulas are those of *the lecture notes*, the ray-tracing
//! lecture notes this crate implements ([their terms](#terms-from-the-lecture-notes)).
//! The camera is the lecture notes': `w` toward the look-at point,
//! `u = normalize(w × up)`, `v = u × w`, image plane at distance 1, column `i` left to
//! right and row `j` top to bottom. Shading is the lecture notes' Lab #1,
//! `colour × clamp(n·(−w), 0.3, 1)`. The same scene and method give bit-identical
//! pixels on every target (IEEE-754 `f32`, no fused multiply-add, the same libm).
//! Constructors that take run-time values return typed errors; the const ones
//! (for `static` scenes) do not check, and each type's `check` applies the same rules
//! in a const context.
//!
//! ## The pipeline, and the room (folder of `src/`) for each step
//!
//! 1. **Camera** (`camera/`): the u/v/w basis, the pixel size from the field of view,
//!    the upper-left pixel's direction and the per-column and per-row steps — once,
//!    when the camera is built; each sphere's silhouette on the image (`camera/span.rs`).
//! 2. **Scene** (`scene/`): spheres, planes, lights, materials, the settings.
//! 3. **Method** (`method/`): the [`Method`] value, matched once per frame in
//!    `dispatch.rs`, becomes zero-sized strategy types — a stepping (`stepping.rs`), a
//!    sphere test (`intersect.rs`) and a square root ([`math`]) — and everything below
//!    is monomorphised over them, so the pixel loop has no branch on the method.
//! 4. **Tracing** (`trace/`), at its three rates: per frame the visible part of the
//!    image and each sphere's constants (`frame.rs`), per row the spheres whose span
//!    holds the row (`scanline.rs`), per pixel the closest hit, shaded (`shade.rs`:
//!    Lab #1). A scene type with lights, planes or a reflection depth
//!    (`Scene<N, L, P, D>`) takes the features path (`trace/lit/`): Phong shading with a
//!    shadow ray per light, the planes, the reflection loop.
//! 5. **Sampling** (`sampling/`): one ray per pixel, a grid, or extra rays only where
//!    an edge can cross the pixel.
//! 6. **The integer kernel** (`integer/`): the same Lab #1 frame in exact integer
//!    arithmetic, for chips without an FPU.
//! 7. **Output** (`output/`): each row into the target's `fill_contiguous`, a band
//!    buffer or a callback; the ordered [`dither`] for 1-, 2- and 4-bit displays.
//!
//! `ARCHITECTURE.md` in the repository says where to add a primitive, a light, a
//! sample per pixel or a number format.
//!
//! ## Terms from the lecture notes
//!
//! - **Lab #1** (shading): the notes' first lab's colour rule,
//!   `colour × clamp(n_z, 0.3, 1)`, where `n_z = n·(−w)` is the z of the unit outward
//!   normal in view space ([`shade::lab1`]).
//! - **The slides' stepping** ([`Stepping::WorldSpace`]): the pixel centre stepped in
//!   world space, `p += pw·u` per pixel and `scanlineStart −= ph·v` per row, the ray
//!   being `p − eye`.
//! - **The slides' tests**: the algebraic (`b² − 4ac`) and geometric (`t_ca`, `d²`)
//!   ray–sphere tests ([`SphereTest::Algebraic`], [`SphereTest::Geometric`]).
//! - **The literal method** ([`Method::LITERAL`]): all of the above, as the notes give them.
//!
//! ## Features
//!
//! - `std` (default): [`scene_file`], TOML scene files with field-level errors (toml and
//!   serde). Inert on bare-metal targets (`target_os = "none"`); use
//!   `default-features = false` in firmware to make that explicit.
//! - `defmt`: `defmt::Format` on the errors and the small public types.
//! - `bench-baselines`: the knobs that exist to measure the kernel against its own
//!   literal baselines, not to draw — span culling off, the forward-differenced test's
//!   anchor interval, closest-hit shadow rays ([`Options`]'s `with_span_culling`,
//!   `with_anchor_interval`, `with_shadow_any_hit`) and the constants they are
//!   measured against (`FD_ANCHOR_INTERVAL`). None changes what a pixel means; the
//!   repository's lab uses them.
//!
//! The render CLI, the desktop preview, the boards and the accuracy lab (the `f64`
//! reference renderer, the sweeps, the benchmarks) are packages of their own in the
//! repository; none of them is a dependency of this crate.
#![no_std]
#![deny(missing_docs)]
#![deny(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::indexing_slicing
)]
// Tests may unwrap and index: a panic there is a failed test, not a kernel panic.
#![cfg_attr(
    test,
    allow(
        clippy::unwrap_used,
        clippy::expect_used,
        clippy::panic,
        clippy::indexing_slicing
    )
)]
// `!(x >= bound)` is deliberate throughout: it rejects NaN along with out-of-range values.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

// The unit tests use `std` (printing, `Vec`) whatever the features.
#[cfg(any(host_std, test))]
extern crate std;

// The rooms, bottom to top: each imports only from those above it in this list
// (`.ci/module-cycles` checks it, and that no two files import each other in a circle).
mod camera; // the pin-hole camera; each sphere's silhouette on the image
mod error; // the typed errors of every constructor
pub mod incremental; // frames that re-trace and re-send only what changed
mod integer; // the integer kernel for chips without an FPU
pub mod math; // square roots, `Vec3`, the limits every bound is stated in
mod method; // the method vocabulary, its one dispatch, stepping, sphere tests, single-ray queries
pub mod motion; // scenes that move: circling, bouncing, the camera orbiting; time from the frame number
mod output; // rows into targets (sinks) and the ordered dither
mod render; // `Render`: the public renderer, where the method is matched
mod sampling; // anti-aliasing: one ray per pixel, grids, adaptive
mod scene; // the scene and its objects: spheres, planes, lights, materials
#[cfg(host_std)]
pub mod scene_file; // TOML scene files
mod trace; // per frame, per row, per pixel: options, frame constants, scanline loop, shading, features

pub use output::dither;
pub use trace::shade;

pub use camera::{Camera, CameraParams};
pub use error::{
    BandError, CameraError, CameraParam, FrameError, IntegerError, LightError, MaterialError, ObjectRef,
    ParseMethodError, PlaneError, SceneError, SettingsError, SphereError,
};
pub use incremental::{FrameStats, Incremental};
pub use math::limits::{MAX_FOV, MAX_RESOLUTION, MIN_PIXEL_SIZE, MIN_UP_ANGLE};
pub use math::vec3::Vec3;
pub use method::intersect::AUTO_FD_CAPACITY;
#[cfg(feature = "bench-baselines")]
pub use method::intersect::FD_ANCHOR_INTERVAL;
pub use method::{Arithmetic, Method, SphereTest, Sqrt, Stepping, FPU_LESS};
pub use render::Render;
pub use sampling::{Sampling, SamplingError, SubSamples, ADAPTIVE_MAX_WIDTH};
pub use scene::light::Light;
pub use scene::material::Material;
pub use scene::plane::Plane;
pub use scene::sphere::Sphere;
pub use scene::{Hit, Scene, Settings, MAX_DEPTH};
pub use trace::options::{Options, Sample, SecondaryOrigin};

/// What the one-frame loop needs, in one `use`.
///
/// It holds the scene and its objects, the camera, the renderer, the method and sampling
/// choices, and embedded-graphics' own prelude (`DrawTarget`, `Size`, `Point`, …).
///
/// ```
/// use embedded_raytracer::prelude::*;
/// let camera = Camera::new(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), 1.0, Size::new(8, 8));
/// assert!(camera.is_ok());
/// ```
pub mod prelude {
    pub use crate::dither::DitherExt as _;
    pub use crate::{
        Camera, CameraParams, Light, Material, Method, Plane, Render, Sampling, Scene, Settings, Sphere, Vec3,
    };
    pub use embedded_graphics::prelude::*;
}

// The README's code blocks run as doctests too.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
