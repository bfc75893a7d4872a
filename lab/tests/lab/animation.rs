//! Incremental frames on the microcontroller are the host's: the runs of
//! `lab/firmware/examples/qemu_animation.rs` on the Cortex-M4F and the Cortex-M33
//! (committed as `lab/data/qemu_animation_cortex_m4.txt` and `..._m33.txt` by
//! `.ci/animation --update`; `ANIMATION_QEMU_OUTPUT` names fresh runs, joined like
//! `PATH`) traced, sent and windowed the same pixels in every frame as the host's
//! `Incremental` does for the same sequence, and their display after the sequence
//! hashes as the host's full render of the last frame.

use std::collections::HashMap;

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raytracer::motion::Animation;
use embedded_raytracer::{CameraParams, Incremental, Method, Render, Scene};
use embedded_raytracer_lab::hash::PixelHash;
use embedded_raytracer_lab::scenes;

use crate::common::Panel;

const SIZE: Size = Size::new(240, 240);

/// A run's figures: per sequence, each frame's `(traced, sent, windows, strips)`, and
/// the display hash of its `check` line.
#[derive(Default)]
struct Run {
    frames: HashMap<String, Vec<[u64; 4]>>,
    display: HashMap<String, u64>,
}

fn parse(text: &str) -> Run {
    let mut run = Run::default();
    for line in text.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        let field = |key: &str| -> u64 {
            let i = w
                .iter()
                .position(|&x| x == key)
                .unwrap_or_else(|| panic!("no {key} in {line}"));
            w[i + 1]
                .parse()
                .unwrap_or_else(|e| panic!("{key} in {line}: {e}"))
        };
        match w.first() {
            Some(&"anim") => {
                let frame = field("frame") as usize;
                let list = run.frames.entry(w[1].to_string()).or_default();
                assert_eq!(list.len(), frame, "frames out of order: {line}");
                list.push([field("traced"), field("sent"), field("windows"), field("strips")]);
            }
            Some(&"check") => {
                let hash = u64::from_str_radix(w[3].trim_start_matches("0x"), 16).unwrap();
                assert_eq!(w[6], "equal", "{line}");
                run.display.insert(w[1].to_string(), hash);
            }
            _ => {}
        }
    }
    run
}

/// The runs to check: the fresh ones `ANIMATION_QEMU_OUTPUT` names, else the committed.
fn runs() -> Vec<(String, Run)> {
    let paths: Vec<String> = match std::env::var_os("ANIMATION_QEMU_OUTPUT") {
        Some(p) => std::env::split_paths(&p)
            .filter(|p| !p.as_os_str().is_empty())
            .map(|p| p.display().to_string())
            .collect(),
        None => ["qemu_animation_cortex_m4", "qemu_animation_cortex_m33"]
            .iter()
            .map(|n| format!("{}/data/{n}.txt", env!("CARGO_MANIFEST_DIR")))
            .collect(),
    };
    paths
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
            let run = parse(&text);
            (path, run)
        })
        .collect()
}

/// `Rgb565` widened to `Rgb888` into a `PixelHash`, as the firmware hashes its display.
fn hash565(colors: impl IntoIterator<Item = Rgb565>) -> u64 {
    let mut h = PixelHash::new(SIZE);
    h.fill_contiguous(
        &Rectangle::new(Point::zero(), SIZE),
        colors.into_iter().map(Rgb888::from),
    )
    .unwrap();
    h.hash()
}

/// The host's frames of the sequence: per frame `(traced, sent, windows, strips)`, and
/// the display's hash after it (checked equal to the last frame's full render).
fn host<const N: usize, const L: usize, const P: usize, const D: usize, const M: usize>(
    base: &Scene<N, L, P, D>,
    params: CameraParams,
    animation: &Animation<M>,
    method: Method,
) -> (Vec<[u64; 4]>, u64) {
    let params = params.with_size(SIZE);
    let (mut scene, mut at) = (base.clone(), params);
    let mut shown: Incremental<N, L, P, D> = Incremental::new();
    let mut display = Panel::<Rgb565>::new(SIZE);
    let mut frames = Vec::new();
    for frame in 0..=animation.frames() {
        animation
            .apply_frame(base, &params, frame, &mut scene, &mut at)
            .unwrap();
        let camera = at.build().unwrap();
        let s = shown
            .draw(&Render::new(&scene, &camera).with_method(method), &mut display)
            .unwrap();
        frames.push([s.traced, s.sent, s.windows, s.strips].map(u64::from));
    }
    let camera = at.build().unwrap();
    let mut full = Panel::new(SIZE);
    Render::new(&scene, &camera)
        .with_method(method)
        .draw(&mut full)
        .unwrap();
    let shown = display.pixels();
    assert!(
        shown == full.pixels(),
        "the host's incremental display is not the full render"
    );
    (frames, hash565(shown))
}

#[test]
fn the_firmwares_incremental_frames_are_the_hosts() {
    let bounce = host(
        &scenes::BOUNCE,
        scenes::BOUNCE_CAMERA,
        &scenes::BOUNCE_ANIMATION,
        Method::TARGET_DEFAULT,
    );
    let circling = host(
        &scenes::CIRCLING,
        scenes::CIRCLING_CAMERA,
        &scenes::CIRCLING_ANIMATION,
        Method::INTEGER,
    );
    let orbit = host(
        &scenes::BOUNCE,
        scenes::BOUNCE_CAMERA,
        &scenes::BOUNCE_ORBIT_ANIMATION,
        Method::TARGET_DEFAULT,
    );
    for (path, run) in runs() {
        for (name, (frames, hash)) in [("bounce", &bounce), ("circling", &circling), ("orbit", &orbit)] {
            let fw = run
                .frames
                .get(name)
                .unwrap_or_else(|| panic!("{path}: no {name} frames"));
            assert_eq!(fw.len(), frames.len(), "{path}: {name}: frame count");
            for (k, (a, b)) in fw.iter().zip(frames).enumerate() {
                assert_eq!(a, b, "{path}: {name} frame {k}: (traced, sent, windows, strips)");
            }
            assert_eq!(run.display.get(name), Some(hash), "{path}: {name}: display hash");
        }
    }
}
