//! The player against the kernel's whole render, its errors and its view.

use super::*;
use embedded_raytracer_scenes::TEXTS;

fn text(name: &str) -> &'static str {
    TEXTS.iter().find(|(n, _)| *n == name).unwrap().1
}

fn player(name: &str, view: &str) -> Player {
    let mut p = Player::new();
    p.load(text(name)).unwrap();
    p.set_view(view).unwrap();
    p
}

/// Frame `frame` drawn whole, on a display that showed nothing before.
fn whole(name: &str, view: &str, frame: u32) -> Vec<Rgb888> {
    let mut p = player(name, view);
    assert!(p.draw(frame).unwrap().full);
    p.screen.shown().to_vec()
}

/// Each frame of a loop drawn over the one before through `Incremental` is the
/// frame drawn whole, and most frames trace and send a part of the display; the
/// marks say which pixels (every sent pixel lies in a traced rectangle).
fn check_loop(name: &str, view: &str) {
    let mut p = player(name, view);
    let frames = p.film.as_ref().unwrap().animation.frames();
    let mut partial = 0;
    for k in 0..frames {
        let report = p.draw(k).unwrap();
        assert_eq!(report.refused, None);
        assert!(p.screen.shown() == whole(name, view, k), "{name} frame {k}");
        let marks = p.marks();
        let sent = marks.iter().filter(|&&m| m & SENT != 0).count();
        let traced = marks.iter().filter(|&&m| m & TRACED != 0).count();
        assert_eq!(sent as u32, report.sent, "{name} frame {k}");
        assert_eq!(traced as u32, report.traced, "{name} frame {k}");
        assert!(marks.iter().all(|&m| m & SENT == 0 || m & TRACED != 0));
        if !report.full {
            partial += 1;
            assert!(report.sent < report.width * report.height / 2);
        }
    }
    assert!(
        partial > frames / 2,
        "{name}: {partial} of {frames} frames in part"
    );
}

#[test]
fn a_lit_loop_played_is_each_frame_drawn_whole() {
    check_loop("bounce", "size=64x48");
}

#[test]
fn an_integer_dithered_loop_played_is_each_frame_drawn_whole() {
    let view = "size=96x48&display=binary-dither&bayer=4&method=integer/direct/auto/exact";
    check_loop("circling", view);
    assert_eq!(player("circling", view).draw(0).unwrap().arithmetic, "integer");
}

#[test]
fn the_rgb888_display_is_the_kernels_render() {
    let mut p = player("lab", "");
    let report = p.draw(0).unwrap();
    assert_eq!((report.width, report.height), (320, 240));
    assert_eq!(report.arithmetic, "f32");
    let file = scene_file::parse::<MAX_SPHERES, 0, 0, 0>(text("lab")).unwrap();
    let mut expected = Vec::new();
    Render::<MAX_SPHERES>::new(&file.scene, &file.camera).trace(|s| expected.push(s.color));
    assert!(p.screen.shown() == expected);
    let rgba = p.rgba();
    assert_eq!(rgba.len(), expected.len() * 4);
    assert_eq!(
        &rgba[..4],
        &[expected[0].r(), expected[0].g(), expected[0].b(), 255]
    );
}

#[test]
fn a_refused_text_names_its_field_and_keeps_the_scene() {
    let mut p = player("lab", "size=32x24");
    let before = p.draw(0).unwrap();
    let bad = text("lab").replacen("radius = ", "radius = -", 1);
    let e = p.load(&bad).unwrap_err();
    assert_eq!(e.field.as_deref(), Some("sphere[0].radius"));
    assert!(e.message.starts_with("sphere[0].radius: "), "{}", e.message);
    assert_eq!(p.draw(0).unwrap(), before, "the last scene is still drawn");
    // A syntax error has a line.
    let e = p.load("[camera\n").unwrap_err();
    assert_eq!(e.line, Some(1));
    // Untrusted text over the loader's file limit is refused unread.
    let huge = "#".repeat(MAX_FILE_SIZE as usize + 1);
    let e = p.load(&huge).unwrap_err();
    assert_eq!((e.line, e.field), (None, None));
    assert!(e.reason.contains("at most 1048576"), "{}", e.reason);
}

#[test]
fn the_view_spec_round_trips_and_refuses_bad_pairs() {
    let mut p = Player::new();
    let spec = "display=gray2-dither&bayer=4&theme=oled-white&method=integer/incremental/robust/fast\
                &sampling=adaptive:3&secondary=epsilon:0.001&size=128x64&azimuth=0.5\
                &elevation=-0.25&zoom=-3&diff=1";
    p.set_view(spec).unwrap();
    let view = p.view;
    assert_eq!(View::default().with(&p.view_spec()).unwrap(), view);
    for bad in [
        "display=cmyk",
        "bayer=3",
        "size=12",
        "zoom=x",
        "azimuth=nan",
        "frob=1",
        "method=a/b",
    ] {
        assert!(p.set_view(bad).is_err(), "{bad}");
        assert_eq!(p.view, view, "{bad} changed the view");
    }
    // A display larger than the page draws is refused, not allocated.
    let mut p = player("lab", "size=4096x4096");
    assert!(p.draw(0).unwrap_err().contains("more than the page draws"));
}

#[test]
fn the_difference_view_marks_what_differs_from_the_reference() {
    let mut p = player("shadows", "size=120x120&method=direct/robust/exact&diff=1");
    p.draw(0).unwrap();
    assert_eq!(p.compare(), Some(0), "the reference against itself");
    p.set_view("secondary=epsilon:0.000001").unwrap();
    p.draw(0).unwrap();
    let n = p.compare().unwrap();
    assert!(n > 0, "shadow acne at a small epsilon");
    let magenta = p.rgba().chunks(4).filter(|c| c[..3] == [255, 0, 255]).count();
    assert_eq!(magenta as u32, n);
    p.set_view("diff=0").unwrap();
    p.draw(0).unwrap();
    assert_eq!(p.compare(), None);
}
