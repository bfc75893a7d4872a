//! The display models of `embedded-raytracer`'s front ends: what a frame looks like on
//! the panel a firmware drives.
//!
//! - [`Model`]: the panel's colour type (`Rgb888` down to `BinaryColor`) and whether
//!   the kernel's ordered dither sits in front of it.
//! - [`bayer`]: the names of the dither's Bayer matrices.
//! - [`Theme`]: the colours a 1-bit OLED panel lights and leaves dark.
//! - [`Panel`]: a model's framebuffer; a [`Paint`] (a whole [`Frame`], or a front
//!   end's own, such as an `Incremental` frame) draws on it through the model, and
//!   [`Panel::shown`] gives the colours the panel shows, one a pixel.
//!
//! `no_std` with `alloc` (the framebuffer): the desktop preview and a browser page
//! compiled to `wasm32-unknown-unknown` show the same pixels.
//!
//! ```
//! use embedded_graphics::{pixelcolor::Rgb888, prelude::*};
//! use embedded_raytracer::{Camera, Scene, Sphere, Vec3};
//! use embedded_raytracer_display::{bayer::Bayer, Frame, Model, Panel, Theme};
//!
//! let scene: Scene<1> = Scene::from_array(
//!     [Sphere::new(Vec3::new(0.0, 0.0, 0.0), 1.0, Rgb888::new(255, 64, 64))],
//!     Rgb888::BLACK,
//! );
//! let up = Vec3::new(0.0, 1.0, 0.0);
//! let camera = Camera::new(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, up, 0.8, Size::new(128, 64)).unwrap();
//! // A 1-bit OLED behind the kernel's 8×8 ordered dither.
//! let mut panel = Panel::new(Model::BinaryDither, Bayer::Eight, camera.size());
//! panel.paint(Frame::new(&scene, &camera));
//! let shown: Vec<Rgb888> = panel.shown(Theme::OledBlue);
//! assert_eq!(shown.len(), 128 * 64);
//! assert!(shown.iter().all(|&c| c == Theme::OledBlue.on() || c == Theme::OledBlue.off()));
//! ```
#![no_std]

extern crate alloc;

pub mod bayer;
mod framebuffer;
mod model;
mod panel;
mod theme;

pub use model::Model;
pub use panel::{Frame, Paint, Panel};
pub use theme::Theme;
