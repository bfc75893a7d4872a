//! # embedded-raytracer
//!
//! A `no_std`, allocation-free ray-tracing kernel: spheres — and, where the scene's
//! type asks for them, lights with hard shadows, checkered planes and mirrors — seen by
//! a pin-hole camera, streamed scanline by scanline into any embedded-graphics
//! [`DrawTarget`](embedded_graphics::draw_target::DrawTarget) — an SPI LCD driver, the
//! desktop simulator, a test's `MockDisplay`.
//!
//! ```
//! use embedded_graphics::{mock_display::MockDisplay, pixelcolor::Rgb888, prelude::*};
//! use embedded_raytracer::{Camera, Render, Scene, Sphere, Vec3};
//!
//! static SCENE: Scene<2> = Scene::from_array(
//!     [
//!         Sphere::new(Vec3::new(0.0, 0.0, 0.0), 1.0, Rgb888::new(255, 64, 64)),
//!         Sphere::new(Vec3::new(1.2, 0.5, -1.5), 1.0, Rgb888::new(64, 64, 255)),
//!     ],
//!     Rgb888::new(0, 0, 0),
//! );
//!
//! let camera = Camera::new(
//!     Vec3::new(0.0, 0.0, 5.0),   // eye
//!     Vec3::new(0.0, 0.0, 0.0),   // look at
//!     Vec3::new(0.0, 1.0, 0.0),   // up
//!     60f32.to_radians(),         // vertical field of view
//!     Size::new(64, 48),
//! )?;
//! let mut display = MockDisplay::<Rgb888>::new();
//! Render::new(&SCENE, &camera).draw(&mut display)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Conventions
//!
//! Right-handed world coordinates; angles in radians (degrees only in scene-file
//! fields named `_deg`); `f32` throughout, with every approximation's error bound in
//! its doc comment. The camera is the seed's: `w` toward the look-at point,
//! `u = normalize(w × up)`, `v = u × w`, image plane at distance 1, column `i` left to
//! right and row `j` top to bottom. Shading is the seed's Lab #1,
//! `colour × clamp(n·(−w), 0.3, 1)`. The same scene and method give bit-identical
//! pixels on every target (IEEE-754 `f32`, no fused multiply-add, the same libm).
//!
//! ## The pipeline, and the module for each step
//!
//! A frame is drawn in one pass, from the camera to the display:
//!
//! 1. **Camera** ([`camera`]): the u/v/w basis, the pixel size from the field of view,
//!    the upper-left pixel's direction and the per-column and per-row steps — once,
//!    when the camera is built.
//! 2. **Method** ([`method`], matched once per frame in `dispatch.rs`): the [`Method`]
//!    value becomes zero-sized strategy types — a stepping (`stepping.rs`), a sphere
//!    test ([`intersect`]) and a square root ([`math`]) — and everything below is
//!    monomorphised over them, so the pixel loop has no branch on the method.
//! 3. **Per-frame constants** (`frame.rs`): the visible part of the image, and per
//!    sphere its eye-relative geometry, the test's and the shader's constants.
//! 4. **Silhouettes and spans** (`span.rs`): each sphere's silhouette as an ellipse on
//!    the image, enlarged by the proven rounding margins, cut per row into the columns
//!    whose rays can hit it.
//! 5. **Per-row tests** (`scanline.rs`): per pixel, the ray's direction from the
//!    stepping, the closest hit among the spheres whose span holds the column.
//! 6. **Shade** ([`shade`]): the hit's colour (the seed's Lab #1). A scene type with
//!    lights, planes or a reflection depth (`Scene<N, L, P, D>`, see [`Scene`]) takes
//!    the scene-features path instead (`lit.rs`): the planes' hits, Phong shading with a
//!    shadow ray per light, and the reflection loop; secondary rays start as
//!    [`SecondaryOrigin`] says (no epsilon by default).
//! 7. **Sink** (`sink.rs`): each row, as an iterator, into the target's
//!    `fill_contiguous` (or to a callback for [`Render::trace`]); [`dither`] adapts the
//!    stream to 1-, 2- and 4-bit displays.
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
//! ## Low-depth displays
//!
//! [`dither`] turns the `Rgb888` stream into `BinaryColor`, `Gray2` or `Gray4` with an
//! ordered (Bayer) dither keyed by pixel position: `render.draw(&mut display.dithered())`.
//!
//! ## Features
//!
//! - `std` (default): `scene_file`, TOML scene files with field-level errors (toml and
//!   serde). Inert on bare-metal targets (`target_os = "none"`); use
//!   `default-features = false` in firmware to make that explicit.
//! - `defmt`: `defmt::Format` on the errors and the small public types.
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

#[cfg(host_std)]
extern crate std;

// The rooms, bottom to top: each imports only those above it in this list.
pub mod math; // square roots, `Vec3`, the limits every bound is stated in
pub mod error; // the typed errors of every constructor
pub mod camera; // the pin-hole camera; each sphere's silhouette on the image (`span`)
pub mod scene; // the scene and its objects: spheres, planes, lights, materials
pub mod method; // the method vocabulary, its one dispatch, stepping, sphere tests, single-ray queries
mod trace; // per frame, per row, per pixel: options, frame constants, scanline loop, shading, features
pub mod sampling; // anti-aliasing: one ray per pixel, grids, adaptive
mod integer; // the integer kernel for chips without an FPU
mod output; // rows into targets (sinks) and the ordered dither
pub mod render; // `Render`: the public renderer, where the method is matched
#[cfg(host_std)]
pub mod scene_file; // TOML scene files

pub use method::intersect;
pub use output::dither;
pub use scene::{light, material, plane, sphere};
pub use math::vec3;
pub use trace::shade;

pub use camera::{Camera, CameraParams};

// The README's code blocks run as doctests too.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
pub use error::{
    BandError, CameraError, CameraParam, IntegerError, LightError, MaterialError, ParseMethodError,
    PlaneError, SceneError, SettingsError, SphereError,
};
pub use scene::light::Light;
pub use trace::options::SecondaryOrigin;
pub use scene::material::Material;
pub use method::{Arithmetic, Method, SphereTest, Sqrt, Stepping, FPU_LESS};
pub use scene::plane::Plane;
pub use render::{Options, Render, Sample};
pub use sampling::{Sampling, SamplingError, SubSamples};
pub use scene::{Hit, Scene, Settings, MAX_DEPTH};
pub use scene::sphere::Sphere;
pub use math::vec3::Vec3;
