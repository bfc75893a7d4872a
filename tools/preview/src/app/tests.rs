//! The program state's tests: keys, mouse, reloads, the difference view and playing,
//! each frame checked against the kernel's whole render.

use std::time::{Duration, Instant, SystemTime};

use embedded_graphics::{pixelcolor::Rgb888, prelude::*, primitives::Rectangle};
use embedded_graphics_simulator::{
    sdl2::{Keycode, Mod, MouseButton},
    OutputSettingsBuilder, SimulatorEvent,
};
use embedded_raytracer::{scene_file, Arithmetic, Method, Render, Sampling, SecondaryOrigin, Vec3};
use embedded_raytracer_display::Model;
use embedded_raytracer_scenes::{
    self as standard, FullSceneFile, MAX_DEPTH, MAX_LIGHTS, MAX_PLANES, MAX_SPHERES,
};

use super::{App, DIFF_COLOR, POLL};
use crate::args::{parse_args, Args};
use crate::loading::{moment, Loaded};
use crate::play;
use crate::save;
use crate::view::{shade, View, REFERENCE, SECONDARY};

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
        None => {
            Render::<'_, MAX_SPHERES, Rgb888, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>::new(&moved.scene, &camera)
                .trace(|s| out.push(s.color))
        }
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
    let f32_frame = shade(&app.scene, &app.camera, &app.view, app.view.method);
    app.handle(key(Keycode::I));
    assert_eq!(
        app.view.method,
        Method::TARGET_DEFAULT.with_arithmetic(Arithmetic::Integer)
    );
    let integer_frame = shade(&app.scene, &app.camera, &app.view, app.view.method);
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
    let shown = shade(&app.scene, &app.camera, &app.view, app.view.method);
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
    assert_ne!(shown, center, "adaptive sampling changed no pixel");
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
    let shown = shade(&app.scene, &app.camera, &app.view, app.view.method);
    let reference = shade(&app.scene, &app.camera, &app.view, REFERENCE);
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
        Render::<'_, MAX_SPHERES, Rgb888, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>::new(&file.scene, &app.camera)
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
        let shown = shade(&app.scene, &app.camera, &app.view, app.view.method);
        let convex = View {
            secondary: SecondaryOrigin::Convex,
            ..app.view
        };
        let reference = shade(&app.scene, &app.camera, &convex, REFERENCE);
        assert_eq!(n, shown.iter().zip(&reference).filter(|(a, b)| a != b).count());
    }
}

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
        let expected = shade(&scene, &camera, &app.view, app.view.method);
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
