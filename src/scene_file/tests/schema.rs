//! TOML into the raw tables: the failing field's path and line, a duplicate key's
//! table, the choices of a `type`.

use super::*;

#[test]
fn a_duplicate_key_names_the_key_and_its_table() {
    let text = format!(
        "{GOOD}[[light]]\ntype = \"point\"\nposition = [0.0, 1.0, 0.0]\n\
         [[light]]\ntype = \"point\"\nposition = [0.0, 1.0, 0.0]\nintensity = 1.0\nintensity = 2.0\n"
    );
    let e = match parse::<4, 2, 0, 0>(&text) {
        Ok(_) => panic!("accepted"),
        Err(e) => e,
    };
    assert_eq!(e.field.as_deref(), Some("light[1].intensity"), "{e}");
    assert!(e.reason.contains("duplicate key"), "{e}");
    assert_eq!(e.line, Some(GOOD.lines().count() + 8), "{e}");
    // At the top level and in a plain table, too.
    let e = err(&GOOD.replace("width = 32", "width = 32\nwidth = 33"));
    assert_eq!(e.field.as_deref(), Some("camera.width"), "{e}");
    let e = err(&format!("background = [0, 0, 0]\n{GOOD}"));
    assert_eq!(e.field.as_deref(), Some("background"), "{e}");
}

#[test]
fn a_light_type_of_another_type_names_the_choices() {
    let text = format!("{GOOD}[[light]]\ntype = 5\ndirection = [0.0, -1.0, 0.0]\n");
    let e = match parse::<4, 1, 0, 0>(&text) {
        Ok(_) => panic!("accepted"),
        Err(e) => e,
    };
    assert_eq!(e.field.as_deref(), Some("light[0].type"), "{e}");
    assert!(
        e.reason.contains("integer `5`") && e.reason.contains("\"directional\" or \"point\""),
        "{e}"
    );
    let text = format!("{GOOD}[[light]]\ntype = \"spot\"\ndirection = [0.0, -1.0, 0.0]\n");
    let e = match parse::<4, 1, 0, 0>(&text) {
        Ok(_) => panic!("accepted"),
        Err(e) => e,
    };
    assert_eq!(e.field.as_deref(), Some("light[0].type"), "{e}");
    assert!(
        e.reason.contains("\"spot\"") && e.reason.contains("\"directional\" or \"point\""),
        "{e}"
    );
}

#[test]
fn errors_name_field_and_line() {
    let e = err(&GOOD.replace("width = 32", "width = 32\nzoom = 2"));
    assert_eq!(e.field.as_deref(), Some("camera.zoom"));
    assert!(e.reason.contains("unknown field `zoom`"), "{e}");
    assert_eq!(e.line, Some(8));

    let e = err(&GOOD.replace("width = 32", "width = \"wide\""));
    assert_eq!(e.field.as_deref(), Some("camera.width"), "{e}");
    assert_eq!(e.line, Some(7));

    let e = err(&GOOD.replace("eye = [0.0, 0.0, 5.0]\n", ""));
    assert!(e.reason.contains("missing field `eye`"), "{e}");

    let e = err(&GOOD.replace("radius = 1.0", "radius = 0.0"));
    assert_eq!(e.to_string(), "sphere[0].radius: radius must be greater than 0");

    let e = err(&GOOD.replace("[255, 64, 64]", "[256, 64, 64]"));
    assert_eq!(e.field.as_deref(), Some("sphere[0].color[0]"), "{e}");

    let e = err(&GOOD.replace("fov_y_deg = 60.0", "fov_y_deg = 180.0"));
    assert_eq!(e.field.as_deref(), Some("camera.fov_y_deg"));

    let e = err(&GOOD.replace("look_at = [0.0, 0.0, 0.0]", "look_at = [0.0, 0.0, 5.0]"));
    assert_eq!(e.field.as_deref(), Some("camera.look_at"));

    let e = err(&GOOD.replace("fov_y_deg", "up = [0.0, 0.0, 2.0]\nfov_y_deg"));
    assert_eq!(e.field.as_deref(), Some("camera.up"));

    let e = err(&GOOD.replace("height = 24", "height = 0"));
    assert_eq!(e.field.as_deref(), Some("camera.height"));
    let e = err(&GOOD.replace("width = 32", "width = 9000"));
    assert_eq!(e.field.as_deref(), Some("camera.width"));

    let e = err("this is [not toml");
    assert!(e.reason.starts_with("not valid TOML"), "{e}");
    assert_eq!(e.line, Some(1));

    let e = err(&GOOD.replace("center = [0.0, 0.0, 0.0]", "center = [nan, 0.0, 0.0]"));
    assert_eq!(e.field.as_deref(), Some("sphere[0].center"));
}
