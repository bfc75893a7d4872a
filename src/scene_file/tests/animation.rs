//! `[[motion]]` and `[animation]`: the motions in file order, the timing's defaults and
//! each field's error.

use super::*;

/// Two spheres, one circling and one bouncing, and the camera orbiting.
const MOVING: &str = r#"
[camera]
eye = [0.0, 2.0, 8.0]
look_at = [0.0, 0.0, 0.0]
fov_y_deg = 40.0
width = 32
height = 24
[animation]
fps = 30
frames = 90
[[sphere]]
center = [0.0, 1.0, 0.0]
radius = 1.0
color = [255, 64, 64]
[[sphere]]
center = [2.0, 0.5, 0.0]
radius = 0.5
color = [64, 64, 255]
[[motion]]
kind = "circle"
sphere = 1
center = [0.0, 0.5, 0.0]
radius = 2.0
period = 3.0
phase = 0.25
[[motion]]
kind = "bounce"
sphere = 0
height = 1.5
period = 1.0
[[motion]]
kind = "orbit"
period = 10.0
"#;

#[test]
fn parses_motions_and_timing() {
    let f = parse::<2, 0, 0, 0>(MOVING).unwrap();
    let want: Animation<3> = Animation::from_array([
        Motion::Circle(Circle::new(1, Vec3::new(0.0, 0.5, 0.0), 2.0, 3.0, 0.25)),
        Motion::Bounce(Bounce::new(0, 1.5, 1.0)),
        Motion::Orbit(Orbit::new(10.0)),
    ]);
    assert_eq!(f.animation.motions(), want.motions());
    assert_eq!((f.animation.fps(), f.animation.frames()), (30.0, 90));
    // Defaults: 25 frames a second, one loop of the longest period (10 s).
    let f = parse::<2, 0, 0, 0>(&MOVING.replace("fps = 30\nframes = 90\n", "")).unwrap();
    assert_eq!((f.animation.fps(), f.animation.frames()), (25.0, 250));
    // A file without motion: still, one frame.
    let f = parse::<4, 0, 0, 0>(GOOD).unwrap();
    assert!(f.animation.is_still());
    assert_eq!(f.animation.frames(), 1);
    assert_eq!(f.spheres_only().unwrap().animation, f.animation);
}

#[test]
fn every_motion_field_has_its_error() {
    for (from, to, field, reason) in [
        (
            "period = 3.0",
            "period = 0",
            "motion[0].period",
            "period must be a finite number greater than 0",
        ),
        (
            "period = 1.0",
            "period = -1.0",
            "motion[1].period",
            "greater than 0",
        ),
        (
            "period = 10.0",
            "period = nan",
            "motion[2].period",
            "greater than 0",
        ),
        ("period = 10.0\n", "", "motion[2]", "missing field `period`"),
        (
            "sphere = 1",
            "sphere = 2",
            "motion[0].sphere",
            "the scene has no sphere[2] (it has 2 spheres)",
        ),
        (
            "sphere = 0",
            "sphere = -1",
            "motion[1].sphere",
            "expected an integer",
        ),
        (
            "sphere = 1\n",
            "",
            "motion[0].sphere",
            "a circle needs a `sphere`",
        ),
        (
            "radius = 2.0\n",
            "",
            "motion[0].radius",
            "a circle needs a `radius`",
        ),
        (
            "radius = 2.0",
            "radius = inf",
            "motion[0].radius",
            "radius must be a finite number",
        ),
        (
            "center = [0.0, 0.5, 0.0]",
            "center = [0.0, 0.5]",
            "motion[0].center",
            "expected 3 values, found 2",
        ),
        (
            "center = [0.0, 0.5, 0.0]",
            "center = [0.0, nan, 0.0]",
            "motion[0].center",
            "finite",
        ),
        ("phase = 0.25", "phase = inf", "motion[0].phase", "finite"),
        (
            "height = 1.5",
            "height = 1.5\nradius = 1",
            "motion[1].radius",
            "a bounce has no radius",
        ),
        (
            "height = 1.5\n",
            "",
            "motion[1].height",
            "a bounce needs a `height`",
        ),
        (
            "period = 10.0",
            "period = 10.0\nsphere = 0",
            "motion[2].sphere",
            "an orbit has no sphere",
        ),
        (
            "kind = \"orbit\"",
            "kind = \"spin\"",
            "motion[2].kind",
            "expected \"circle\", \"bounce\" or \"orbit\"",
        ),
        (
            "period = 10.0",
            "period = 10.0\nspeed = 2",
            "motion[2].speed",
            "unknown field `speed`",
        ),
        (
            "fps = 30",
            "fps = 0",
            "animation.fps",
            "fps must be a finite number greater than 0",
        ),
        (
            "frames = 90",
            "frames = 0",
            "animation.frames",
            "frames must be at least 1",
        ),
        ("frames = 90", "frames = 1.5", "animation.frames", "invalid type"),
        (
            "frames = 90",
            "loop = true",
            "animation.loop",
            "unknown field `loop`",
        ),
    ] {
        assert_eq!(MOVING.matches(from).count(), 1, "{from}");
        let e = match parse::<2, 0, 0, 0>(&MOVING.replace(from, to)) {
            Ok(_) => panic!("accepted: {to}"),
            Err(e) => e,
        };
        assert_eq!(e.field.as_deref(), Some(field), "{to}: {e}");
        assert!(e.reason.contains(reason), "{to}: {e}");
    }
    // More than MAX_MOTIONS motions.
    let orbit = "[[motion]]\nkind = \"orbit\"\nperiod = 1.0\n";
    let e = parse::<4, 0, 0, 0>(&format!("{GOOD}{}", orbit.repeat(MAX_MOTIONS + 1))).unwrap_err();
    assert_eq!(e.field.as_deref(), Some("motion"));
    assert_eq!(e.reason, "more than 8 motions: at most 8 are supported");
    parse::<4, 0, 0, 0>(&format!("{GOOD}{}", orbit.repeat(MAX_MOTIONS))).unwrap();
}
