//! The tables through the checked constructors: each field's error names its key, the
//! scene type's capacities are the limits, and the defaults of the optional keys.

use super::*;

#[test]
fn parses_the_documented_format() {
    let f = parse::<4, 0, 0, 0>(GOOD).unwrap();
    assert_eq!(f.scene.spheres().len(), 1);
    assert_eq!(f.scene.background(), Rgb888::new(10, 20, 30));
    assert_eq!(f.camera.size(), Size::new(32, 24));
    assert_eq!(f.camera.params().up, Vec3::new(0.0, 1.0, 0.0));
}

#[test]
fn errors_blame_the_right_field_and_reason() {
    // Both sizes bad: each message names the dimension it is about.
    let both = GOOD.replace("width = 32", "width = 9000");
    let e = err(&both.replace("height = 24", "height = 0"));
    assert_eq!(
        e.to_string(),
        "camera.height: width and height must be at least 1"
    );
    let e = err(&GOOD
        .replace("width = 32", "width = 0")
        .replace("height = 24", "height = 9000"));
    assert_eq!(e.to_string(), "camera.width: width and height must be at least 1");
    let e = err(&GOOD.replace("height = 24", "height = 9000"));
    assert_eq!(e.field.as_deref(), Some("camera.height"));

    // `inf` and `nan` are TOML floats: reported as not finite by the checks.
    let e = err(&GOOD.replace("radius = 1.0", "radius = inf"));
    assert_eq!(e.field.as_deref(), Some("sphere[0].radius"));

    // A field of view that underflows to 0 rad is too narrow, not "not > 0°".
    let e = err(&GOOD.replace("fov_y_deg = 60.0", "fov_y_deg = 1e-45"));
    assert_eq!(e.field.as_deref(), Some("camera.fov_y_deg"));
    assert!(e.reason.contains("too narrow"), "{e}");
    let e = err(&GOOD.replace("fov_y_deg = 60.0", "fov_y_deg = 0.0"));
    assert!(e.reason.contains("greater than 0"), "{e}");

    // Far-away points and huge vectors are valid cameras, not "same point" or
    // "parallel".
    parse::<4, 0, 0, 0>(&GOOD.replace("eye = [0.0, 0.0, 5.0]", "eye = [0.0, 0.0, 1e20]")).unwrap();
    parse::<4, 0, 0, 0>(&GOOD.replace("fov_y_deg", "up = [0, 3e38, 3e38]\nfov_y_deg")).unwrap();
}

#[test]
fn parses_lights_planes_materials_and_settings() {
    let f = full(LIT).unwrap();
    let scene = &f.scene;
    assert_eq!(
        scene.settings(),
        Settings {
            ambient: 0.2,
            max_depth: 3,
            shadows: false
        }
    );
    assert_eq!(scene.max_depth(), 3);
    assert_eq!(
        scene.lights(),
        [
            Light::directional(Vec3::new(-1.0, -2.0, -1.0), 0.8),
            Light::point(Vec3::new(2.0, 5.0, 3.0), 0.5)
        ]
    );
    assert_eq!(scene.spheres()[0].material, Material::new(0.5, 16.0, 0.3));
    let plane = Plane::new(
        Vec3::new(0.0, -1.0, 0.0),
        Vec3::new(0.0, 2.0, 0.0),
        Rgb888::new(220, 220, 220),
    )
    .with_checker(Rgb888::new(40, 40, 40), 2.0)
    .with_material(Material::new(0.25, 8.0, 0.1));
    assert_eq!(scene.planes(), [plane]);
    assert!(f.has_features());
    assert!(f.spheres_only().is_none());
}

#[test]
fn missing_light_plane_material_and_setting_keys_take_their_defaults() {
    let light = "[[light]]\ntype = \"point\"\nposition = [0.0, 4.0, 0.0]\n";
    let plane = "[[plane]]\npoint = [0.0, -1.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\ncolor = [1, 2, 3]\n";
    let f = full(&format!("{GOOD}{light}{plane}")).unwrap();
    assert_eq!(f.scene.lights()[0].intensity(), 1.0);
    assert_eq!(f.scene.spheres()[0].material, Material::DEFAULT);
    let p = f.scene.planes()[0];
    assert_eq!(
        (p.checker, p.checker_size, p.material),
        (None, 1.0, Material::DEFAULT)
    );
    assert_eq!(f.scene.settings(), Settings::DEFAULT);

    // A checker without a size: cells of side 1.
    let checkered = plane.replace("color = [1, 2, 3]", "color = [1, 2, 3]\nchecker = [9, 9, 9]");
    let p = full(&format!("{GOOD}{checkered}")).unwrap().scene.planes()[0];
    assert_eq!((p.checker, p.checker_size), (Some(Rgb888::new(9, 9, 9)), 1.0));

    // One setting given: the others keep their defaults.
    let f = full(&format!("shadows = false\n{GOOD}")).unwrap();
    assert_eq!(
        f.scene.settings(),
        Settings {
            shadows: false,
            ..Settings::DEFAULT
        }
    );
    let f = full(&format!("ambient = 0\nmax_depth = 8\n{GOOD}")).unwrap();
    assert_eq!((f.scene.settings().ambient, f.scene.max_depth()), (0.0, 8));

    // Without settings, a type with a shallower depth keeps its own default, also
    // when another setting is given.
    let f = parse::<4, 1, 1, 1>(GOOD).unwrap();
    assert_eq!(f.scene.settings().max_depth, 1);
    let f = parse::<4, 0, 0, 0>(&format!("ambient = 0.3\n{GOOD}")).unwrap();
    assert_eq!(
        (f.scene.settings().ambient, f.scene.settings().max_depth),
        (0.3, 0)
    );
}

/// A file of a camera and spheres alone (no light, plane, material or setting key) is
/// the same scene and the same errors whatever the capacities it is loaded with, and
/// converts back to the spheres-only type.
#[test]
fn a_spheres_only_file_is_the_same_at_any_capacity() {
    let old = parse::<4, 0, 0, 0>(GOOD).unwrap();
    let new = full(GOOD).unwrap();
    assert_eq!(new.scene.spheres(), old.scene.spheres());
    assert_eq!(new.scene.background(), old.scene.background());
    assert!(new.scene.lights().is_empty() && new.scene.planes().is_empty());
    assert!(!new.has_features());
    let back = new.spheres_only().unwrap();
    assert_eq!(back.scene.spheres(), old.scene.spheres());
    assert_eq!(back.scene.background(), old.scene.background());
    assert_eq!(back.camera.params(), old.camera.params());

    // Highlights and settings without a light, plane or mirror change no pixel:
    // still the spheres-only scene.
    let shiny = format!(
        "ambient = 0.5\n{}",
        GOOD.replace("radius = 1.0", "radius = 1.0\nspecular = 1")
    );
    assert!(full(&shiny).unwrap().spheres_only().is_some());
    // A mirror alone is a feature (even at depth 0 it mixes in the background).
    let mirror = GOOD.replace("radius = 1.0", "radius = 1.0\nreflect = 0.5");
    assert!(full(&mirror).unwrap().spheres_only().is_none());

    for (from, to) in [
        ("width = 32", "width = 32\nzoom = 2"),
        ("width = 32", "width = \"wide\""),
        ("radius = 1.0", "radius = 0.0"),
        ("[255, 64, 64]", "[256, 64, 64]"),
        ("background = [10, 20, 30]", "background = [10, 20, 30]\nfog = 1"),
        ("fov_y_deg = 60.0", "fov_y_deg = 180.0"),
        ("center = [0.0, 0.0, 0.0]", "center = [nan, 0.0, 0.0]"),
    ] {
        let text = GOOD.replace(from, to);
        assert_eq!(full_err(&text), err(&text), "{to}");
    }
}

#[test]
fn every_light_plane_material_and_setting_field_has_its_error() {
    for (from, to, field, reason) in [
        // Settings.
        (
            "ambient = 0.2",
            "ambient = 1.5",
            "ambient",
            "ambient must be between 0 and 1",
        ),
        (
            "ambient = 0.2",
            "ambient = -0.1",
            "ambient",
            "ambient must be between 0 and 1",
        ),
        (
            "ambient = 0.2",
            "ambient = nan",
            "ambient",
            "ambient must be between 0 and 1",
        ),
        (
            "max_depth = 3",
            "max_depth = 9",
            "max_depth",
            "max_depth must be at most 8",
        ),
        (
            "max_depth = 3",
            "max_depth = 1000",
            "max_depth",
            "max_depth must be at most 8",
        ),
        (
            "max_depth = 3",
            "max_depth = -1",
            "max_depth",
            "expected an integer from 0 to 8",
        ),
        (
            "max_depth = 3",
            "max_depth = 2.5",
            "max_depth",
            "invalid type: floating point",
        ),
        (
            "shadows = false",
            "shadows = 1",
            "shadows",
            "invalid type: integer",
        ),
        // Lights.
        (
            "direction = [-1.0, -2.0, -1.0]",
            "direction = [0.0, 0.0, 0.0]",
            "light[0].direction",
            "a directional light's direction must not be zero",
        ),
        (
            "direction = [-1.0, -2.0, -1.0]",
            "direction = [-1.0, inf, -1.0]",
            "light[0].direction",
            "must be finite",
        ),
        (
            "position = [2.0, 5.0, 3.0]",
            "position = [2.0, nan, 3.0]",
            "light[1].position",
            "must be finite",
        ),
        (
            "intensity = 0.8",
            "intensity = -0.5",
            "light[0].intensity",
            "intensity must be a finite number of at least 0",
        ),
        (
            "intensity = 0.5",
            "intensity = inf",
            "light[1].intensity",
            "at least 0",
        ),
        (
            "type = \"directional\"",
            "type = \"spot\"",
            "light[0].type",
            "invalid value: string \"spot\", expected \"directional\" or \"point\"",
        ),
        ("type = \"directional\"\n", "", "light[0]", "missing field `type`"),
        (
            "position = [2.0, 5.0, 3.0]",
            "direction = [2.0, 5.0, 3.0]",
            "light[1].direction",
            "a point light has no direction (give `position`)",
        ),
        (
            "position = [2.0, 5.0, 3.0]\n",
            "",
            "light[1].position",
            "a point light needs a `position`",
        ),
        (
            "direction = [-1.0, -2.0, -1.0]",
            "position = [-1.0, -2.0, -1.0]",
            "light[0].position",
            "a directional light has no position (give `direction`)",
        ),
        (
            "direction = [-1.0, -2.0, -1.0]\n",
            "",
            "light[0].direction",
            "a directional light needs a `direction`",
        ),
        (
            "direction = [-1.0, -2.0, -1.0]",
            "direction = [-1.0, -2.0]",
            "light[0].direction",
            "expected 3 values, found 2",
        ),
        (
            "intensity = 0.8",
            "color = [1, 2, 3]",
            "light[0].color",
            "unknown field `color`",
        ),
        // Sphere materials.
        (
            "specular = 0.5",
            "specular = 1.5",
            "sphere[0].specular",
            "specular must be between 0 and 1",
        ),
        (
            "shininess = 16",
            "shininess = 0.5",
            "sphere[0].shininess",
            "shininess must be a finite number of at least 1",
        ),
        (
            "reflect = 0.3",
            "reflect = -0.3",
            "sphere[0].reflect",
            "reflect must be between 0 and 1",
        ),
        // Planes.
        (
            "normal = [0.0, 2.0, 0.0]",
            "normal = [0.0, 0.0, 0.0]",
            "plane[0].normal",
            "the plane's normal must not be zero",
        ),
        (
            "normal = [0.0, 2.0, 0.0]",
            "normal = [0.0, nan, 0.0]",
            "plane[0].normal",
            "must be finite",
        ),
        (
            "point = [0.0, -1.0, 0.0]",
            "point = [0.0, -inf, 0.0]",
            "plane[0].point",
            "must be finite",
        ),
        (
            "checker_size = 2.0",
            "checker_size = 0.0",
            "plane[0].checker_size",
            "checker_size must be a finite number greater than 0",
        ),
        (
            "checker = [40, 40, 40]\n",
            "",
            "plane[0].checker_size",
            "checker_size needs a second colour `checker`",
        ),
        (
            "checker = [40, 40, 40]",
            "checker = [40, 40, 40, 40]",
            "plane[0].checker",
            "expected 3 values, found 4",
        ),
        (
            "checker = [40, 40, 40]",
            "checker = [40, 256, 40]",
            "plane[0].checker[1]",
            "invalid value",
        ),
        (
            "specular = 0.25",
            "specular = 2",
            "plane[0].specular",
            "specular must be between 0 and 1",
        ),
        (
            "shininess = 8",
            "shininess = 0",
            "plane[0].shininess",
            "shininess must be a finite number of at least 1",
        ),
        (
            "reflect = 0.1",
            "reflect = 1.01",
            "plane[0].reflect",
            "reflect must be between 0 and 1",
        ),
        (
            "normal = [0.0, 2.0, 0.0]\n",
            "",
            "plane[0]",
            "missing field `normal`",
        ),
        (
            "checker_size = 2.0",
            "size = 2.0",
            "plane[0].size",
            "unknown field `size`",
        ),
    ] {
        assert_eq!(LIT.matches(from).count(), 1, "{from}");
        let e = full_err(&LIT.replace(from, to));
        assert_eq!(e.field.as_deref(), Some(field), "{to}: {e}");
        assert!(e.reason.contains(reason), "{to}: {e}");
    }
    // The parser's own errors also give the line.
    let e = full_err(&LIT.replace("\"directional\"", "\"spot\""));
    assert_eq!(
        e.line,
        Some(
            LIT.lines()
                .position(|l| l.contains("directional"))
                .map(|l| l + 1)
                .unwrap()
        )
    );
}

/// The capacities are the limits: too many lights or planes, a mirror or a depth
/// the type cannot trace.
#[test]
fn the_scene_type_limits_lights_planes_and_mirrors() {
    let e = parse::<4, 1, 2, 8>(LIT).unwrap_err();
    assert_eq!(e.field.as_deref(), Some("light"));
    assert_eq!(e.reason, "more than 1 light: at most 1 is supported");
    let e = parse::<4, 0, 2, 8>(LIT).unwrap_err();
    assert_eq!(e.reason, "more than 0 lights: at most 0 are supported");

    let second = LIT.split_once("[[plane]]").unwrap().1;
    let e = parse::<4, 2, 1, 8>(&format!("{LIT}[[plane]]{second}")).unwrap_err();
    assert_eq!(e.field.as_deref(), Some("plane"));
    assert_eq!(e.reason, "more than 1 plane: at most 1 is supported");
    assert_eq!(
        parse::<4, 2, 2, 8>(&format!("{LIT}[[plane]]{second}"))
            .unwrap()
            .scene
            .planes()
            .len(),
        2
    );

    // A depth the type cannot trace.
    let e = parse::<4, 2, 2, 2>(LIT).unwrap_err();
    assert_eq!(e.to_string(), "max_depth: max_depth must be at most 2");

    // A mirror in a type without reflection depth: the sphere's, then the plane's.
    let shallow = LIT.replace("max_depth = 3\n", "");
    let e = parse::<4, 2, 2, 0>(&shallow).unwrap_err();
    assert_eq!(e.field.as_deref(), Some("sphere[0].reflect"));
    assert!(e.reason.contains("reflection depth"), "{e}");
    let e = parse::<4, 2, 2, 0>(&shallow.replace("reflect = 0.3\n", "")).unwrap_err();
    assert_eq!(e.field.as_deref(), Some("plane[0].reflect"));
    // reflect = 0 is no mirror.
    parse::<4, 2, 2, 0>(
        &shallow
            .replace("reflect = 0.3", "reflect = 0")
            .replace("reflect = 0.1", "reflect = 0"),
    )
    .unwrap();
}
