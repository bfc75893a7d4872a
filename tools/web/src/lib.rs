//! The kernel in the browser: the scene-file loader, the display models and the
//! incremental player, compiled to WebAssembly for the page in `www/` (`docs/web.md`).
//!
//! The page's worker makes one [`Player`], loads the editor's text into it
//! ([`Player::load`]), sets the pickers' view ([`Player::set_view`]) and draws frame
//! after frame ([`Player::draw`]), reading the display ([`Player::rgba`]) and what each
//! frame traced and sent ([`Player::marks`]). The functions below give the page its
//! menus, each from the kernel's own tables. Nothing here reads a clock: the page
//! times frames with the browser's (`std::time::Instant` panics on `wasm32`).

mod player;
mod screen;
mod view;

pub use player::{FrameReport, LoadError, Player, SceneInfo, REFERENCE, SENT, TRACED};

use embedded_raytracer::{Method, Sampling, SphereTest, Sqrt, Stepping};
use wasm_bindgen::prelude::*;

use embedded_raytracer_display::Model;
use embedded_raytracer_scenes as standard;

/// The standard scenes' names, in the menu's order.
#[wasm_bindgen(js_name = sceneNames)]
pub fn scene_names() -> Vec<String> {
    standard::TEXTS.iter().map(|(name, _)| name.to_string()).collect()
}

/// The text of standard scene `name` (empty if there is none).
#[wasm_bindgen(js_name = sceneText)]
pub fn scene_text(name: &str) -> String {
    standard::TEXTS
        .iter()
        .find(|(n, _)| *n == name)
        .map_or(String::new(), |(_, text)| text.to_string())
}

/// The display models' names (the preview's `--display`).
#[wasm_bindgen(js_name = displayModels)]
pub fn display_models() -> Vec<String> {
    Model::ALL.iter().map(|m| m.name().to_string()).collect()
}

/// The method axes' names: `kind` is `stepping`, `sphere-test` or `sqrt`.
#[wasm_bindgen(js_name = methodAxis)]
pub fn method_axis(kind: &str) -> Vec<String> {
    let names: &[&str] = match kind {
        "stepping" => Stepping::NAMES,
        "sphere-test" => SphereTest::NAMES,
        "sqrt" => Sqrt::NAMES,
        _ => &[],
    };
    names.iter().map(|n| n.to_string()).collect()
}

/// The samplings' names (`center`, `grid:2`, …, `adaptive:4`).
#[wasm_bindgen]
pub fn samplings() -> Vec<String> {
    Sampling::ALL.iter().map(ToString::to_string).collect()
}

/// The secondary-ray origins offered (`convex`, `epsilon:0.001`, …).
#[wasm_bindgen]
pub fn secondaries() -> Vec<String> {
    view::SECONDARY.iter().map(ToString::to_string).collect()
}

/// This target's default method (`direct/auto/exact`: WebAssembly has floating point).
#[wasm_bindgen(js_name = defaultMethod)]
pub fn default_method() -> String {
    Method::default().to_string()
}

/// The difference view's reference method.
#[wasm_bindgen(js_name = referenceMethod)]
pub fn reference_method() -> String {
    REFERENCE.to_string()
}
