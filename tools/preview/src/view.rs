//! What decides the pixels of a frame (the display model, the method, the secondary
//! rays' origin, the sampling, the dither's matrix, the OLED theme), and a frame drawn
//! whole through it: the difference view's reference and the tests' expectation.

use embedded_graphics::pixelcolor::Rgb888;
use embedded_raytracer::{
    dither::Bayer, Camera, Method, Options, Sampling, SecondaryOrigin, SphereTest, Sqrt, Stepping,
};
use embedded_raytracer_display::{Frame, Model, Panel, Theme};

use crate::loading::Loaded;

/// The difference view's reference: no accumulation, no cancellation, exact root (and
/// the convex origin for secondary rays: no epsilon).
pub const REFERENCE: Method = Method::new(Stepping::Direct, SphereTest::Robust, Sqrt::Exact);

/// The secondary-ray origins the `E` key cycles through: the default, the textbook
/// epsilon, one below the hit points' rounding error at the standard scenes'
/// coordinates (shadow acne), one large for them (a ray that starts near where a
/// sphere rests on the floor can skip past the surface it should meet).
pub const SECONDARY: [SecondaryOrigin; 4] = [
    SecondaryOrigin::Convex,
    SecondaryOrigin::TEXTBOOK,
    SecondaryOrigin::Epsilon(1e-6),
    SecondaryOrigin::Epsilon(1e-1),
];

/// Everything that decides the pixels of a frame.
#[derive(Clone, Copy)]
pub struct View {
    pub model: Model,
    pub method: Method,
    /// Where shadow and reflection rays start (scenes with lights or mirrors).
    pub secondary: SecondaryOrigin,
    /// Rays per pixel.
    pub sampling: Sampling,
    pub bayer: Bayer,
    pub theme: Theme,
}

/// Renders `view` of the scene (with `view`'s secondary origin) whole through the
/// display model: the colours the panel shows, one a display pixel.
pub fn shade(scene: &Loaded, camera: &Camera, view: &View, method: Method) -> Vec<Rgb888> {
    let options = Options::DEFAULT.with_secondary(view.secondary);
    let sampling = view.sampling;
    let mut panel = Panel::new(view.model, view.bayer, camera.size());
    match scene {
        Loaded::Spheres(scene) => panel.paint(Frame {
            scene: &**scene,
            camera,
            method,
            options,
            sampling,
        }),
        Loaded::Full(scene) => panel.paint(Frame {
            scene: &**scene,
            camera,
            method,
            options,
            sampling,
        }),
    }
    panel.shown(view.theme)
}

/// The status bar's name of a secondary origin: `convex`, `eps=1e-3`.
pub fn secondary_label(secondary: SecondaryOrigin) -> String {
    match secondary {
        SecondaryOrigin::Convex => "convex".to_string(),
        SecondaryOrigin::Epsilon(eps) => format!("eps={eps:e}"),
        other => other.to_string(),
    }
}
