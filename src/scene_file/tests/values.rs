//! The strict value types: arrays of exactly their length, arrays of tables capped
//! while they are read, numbers that fit their type, date-times called so.

use super::*;

#[test]
fn too_many_spheres() {
    let sphere = GOOD.split_once("[[sphere]]").unwrap().1;
    let text = format!("{GOOD}[[sphere]]{sphere}[[sphere]]{sphere}");
    assert_eq!(parse::<3, 0, 0, 0>(&text).unwrap().scene.spheres().len(), 3);
    let e = parse::<2, 0, 0, 0>(&text).unwrap_err();
    assert_eq!(e.field.as_deref(), Some("sphere"));
    assert_eq!(e.reason, "more than 2 spheres: at most 2 are supported");
    assert_eq!(
        parse::<1, 0, 0, 0>(&text).unwrap_err().reason,
        "more than 1 sphere: at most 1 is supported"
    );
}

/// The count is checked while the array is read: a bad sphere after the N-th is
/// never looked at, so the error is the count, not that sphere's field.
#[test]
fn sphere_count_is_checked_while_parsing() {
    let sphere = GOOD.split_once("[[sphere]]").unwrap().1;
    let bad = sphere.replace("radius = 1.0", "radius = \"big\"");
    let text = format!("{GOOD}[[sphere]]{sphere}[[sphere]]{bad}");
    assert_eq!(
        parse::<2, 0, 0, 0>(&text).unwrap_err().field.as_deref(),
        Some("sphere")
    );
    assert_eq!(
        parse::<3, 0, 0, 0>(&text).unwrap_err().field.as_deref(),
        Some("sphere[2].radius")
    );
}

/// The light count is checked while the array is read, like the spheres'.
#[test]
fn light_count_is_checked_while_parsing() {
    let text = LIT.replace("intensity = 0.5", "intensity = \"bright\"");
    assert_eq!(
        parse::<4, 1, 2, 8>(&text).unwrap_err().field.as_deref(),
        Some("light")
    );
    assert_eq!(
        parse::<4, 2, 2, 8>(&text).unwrap_err().field.as_deref(),
        Some("light[1].intensity")
    );
}

#[test]
fn every_fixed_length_array_has_exactly_its_length() {
    for (from, to, field, found) in [
        (
            "color = [255, 64, 64]",
            "color = [255, 64, 64, 1]",
            "sphere[0].color",
            4,
        ),
        (
            "eye = [0.0, 0.0, 5.0]",
            "eye = [0.0, 0.0, 5.0, 1.0]",
            "camera.eye",
            4,
        ),
        (
            "center = [0.0, 0.0, 0.0]",
            "center = [0, 0, 0, \"junk\"]",
            "sphere[0].center",
            4,
        ),
        (
            "background = [10, 20, 30]",
            "background = [10, 20, 30, 40]",
            "background",
            4,
        ),
        (
            "look_at = [0.0, 0.0, 0.0]",
            "look_at = [0.0, 0.0]",
            "camera.look_at",
            2,
        ),
        ("fov_y_deg", "up = []\nfov_y_deg", "camera.up", 0),
    ] {
        let e = err(&GOOD.replace(from, to));
        assert_eq!(e.field.as_deref(), Some(field), "{to}: {e}");
        assert_eq!(e.reason, format!("expected 3 values, found {found}"), "{to}");
    }
}

#[test]
fn numbers_beyond_f32_and_date_times_are_named_so() {
    // Beyond f32: out of range, not "not finite"; the element is named.
    let e = err(&GOOD.replace("eye = [0.0, 0.0, 5.0]", "eye = [0.0, 0.0, 1e39]"));
    assert_eq!(e.field.as_deref(), Some("camera.eye[2]"));
    assert!(e.reason.contains("outside the f32 range"), "{e}");
    let e = err(&GOOD.replace("radius = 1.0", "radius = 1e-50"));
    assert!(e.reason.contains("outside the f32 range"), "{e}");
    // A date where a number or array belongs is called a date.
    for (from, to, field) in [
        ("fov_y_deg = 60.0", "fov_y_deg = 1979-05-27", "camera.fov_y_deg"),
        ("width = 32", "width = 1979-05-27T07:32:00Z", "camera.width"),
        ("eye = [0.0, 0.0, 5.0]", "eye = 07:32:00", "camera.eye"),
        (
            "color = [255, 64, 64]",
            "color = [255, 1979-05-27, 64]",
            "sphere[0].color[1]",
        ),
    ] {
        let e = err(&GOOD.replace(from, to));
        assert_eq!(e.field.as_deref(), Some(field), "{to}: {e}");
        assert!(e.reason.starts_with("invalid type: date-time "), "{to}: {e}");
    }
    // An inline table is still called a map.
    let e = err(&GOOD.replace("radius = 1.0", "radius = { r = 1 }"));
    assert!(e.reason.contains("invalid type: map"), "{e}");
}
