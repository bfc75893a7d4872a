//! The integer kernel (`Arithmetic::Integer`) against the f64 reference: where its
//! per-frame rule takes a frame, no coverage error and every shade within one level;
//! the rule's limits (distance/radius, resolution, field of view, scene extent) at the
//! points where it stops taking the frame; clip and band change no pixel.
#![cfg(not(target_os = "none"))]

mod common;

use common::{load, SCENES};
use embedded_graphics::geometry::Size;
use embedded_graphics::pixelcolor::Rgb888;
use embedded_raytracer::{reference, Arithmetic, CameraParams, Method, Render};

/// Every standard scene at its own size and at 240×240: the rule's choice, and where
/// it takes the integer kernel, 0 coverage errors and ≤ 1 level against the reference.
#[test]
fn standard_scenes_against_reference() {
    for name in SCENES {
        let file = load(name);
        for size in [file.camera.size(), Size::new(240, 240)] {
            let camera = CameraParams {
                size,
                ..*file.camera.params()
            }
            .build()
            .unwrap();
            let render = Render::<_, Rgb888>::new(&file.scene, &camera).with_method(Method::INTEGER);
            let chosen = render.arithmetic();
            let reference = reference::render(&file.scene, &camera);
            let m = reference::compare(&render, &reference);
            println!(
                "{name} {}x{}: {chosen}, coverage errors {}, shade max {}, color max {}, undecidable {}",
                size.width, size.height, m.coverage_errors, m.shade_max, m.color_max, m.undecidable
            );
            if chosen == Arithmetic::Integer {
                assert_eq!(m.coverage_errors, 0, "{name} {size:?}: {m:?}");
                assert!(m.shade_max <= 1, "{name} {size:?}: {m:?}");
            }
            assert_eq!(m.bad_samples, 0);
            assert_eq!(m.non_finite, 0);
        }
    }
}
