//! The scan before the parser: hostile texts refused, the fullest scenes let through.

use super::*;

/// A megabyte of one array, of nested brackets or of table headers is refused by
/// the pre-check, before the parser allocates a value for it.
#[test]
fn hostile_files_are_refused_before_parsing() {
    let numbers = format!("{GOOD}x = [{}]\n", "1, ".repeat(523_901));
    let e = match parse::<256, 8, 8, 8>(&numbers) {
        Ok(_) => panic!("accepted"),
        Err(e) => e,
    };
    assert!(
        e.reason
            .contains("more keys and values than a scene of 256 spheres"),
        "{e}"
    );

    let nested = format!("{GOOD}y = {}{}\n", "[".repeat(200_000), "]".repeat(200_000));
    let e = match parse::<256, 8, 8, 8>(&nested) {
        Ok(_) => panic!("accepted"),
        Err(e) => e,
    };
    assert!(e.reason.contains("nested 4 deep"), "{e}");
    assert_eq!(e.line, Some(GOOD.lines().count() + 1), "{e}");

    let tables = format!("{GOOD}{}", "[[z]]\n".repeat(170_000));
    let e = match parse::<256, 8, 8, 8>(&tables) {
        Ok(_) => panic!("accepted"),
        Err(e) => e,
    };
    assert!(e.reason.contains("more table headers"), "{e}");
}

/// The pre-check never refuses a scene the parser accepts: the fullest scene of
/// each capacity (every object at its capacity with every key, trailing commas,
/// comments and strings holding what the scan counts, the inline-table form)
/// passes it and parses.
#[test]
fn the_precheck_takes_the_fullest_scenes() {
    let sphere = "[[sphere]] # a [[comment]], = , {\ncenter = [0.0, 0.0, -5.0,]\nradius = 0.5\n\
                  color = [1, 2, 3,]\nspecular = 0.5\nshininess = 8.0\nreflect = 0.5\n";
    let light = "[[light]]\ntype = \"point\"\nposition = [0.0, 5.0, 0.0,]\nintensity = 0.5\n";
    let plane = "[[plane]]\npoint = [0.0, -1.0, 0.0,]\nnormal = [0.0, 1.0, 0.0,]\ncolor = [9, 9, 9,]\n\
                 checker = [1, 1, 1,]\nchecker_size = 1.0\nspecular = 0.1\nshininess = 4.0\nreflect = 0.2\n";
    let top = "background = [0, 0, 0,]\nambient = 0.1\nmax_depth = 8\nshadows = true\n\
               [camera]\neye = [0.0, 0.0, 5.0,]\nlook_at = [0.0, 0.0, 0.0,]\nup = [0.0, 1.0, 0.0,]\n\
               fov_y_deg = 60.0\nfov_x_deg = 70.0\nwidth = 32\nheight = 24\n";
    let text = format!(
        "{top}{}{}{}",
        sphere.repeat(256),
        light.repeat(8),
        plane.repeat(8)
    );
    let file = parse::<256, 8, 8, 8>(&text).unwrap_or_else(|e| panic!("{e}"));
    let counts = (
        file.scene.spheres().len(),
        file.scene.lights().len(),
        file.scene.planes().len(),
    );
    assert_eq!(counts, (256, 8, 8));
    assert!(parse::<1, 1, 1, 8>(&format!("{top}{sphere}{light}{plane}")).is_ok());

    // Inline tables, one line per sphere, beside comments that hold brackets,
    // commas, equals signs and quotes.
    let top_keys = "background = [0, 0, 0,] # \"[{,=\" '''[[x]]'''\nambient = 0.1\nmax_depth = 8\n";
    let camera = "[camera]\neye = [0.0, 0.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_y_deg = 60.0\nwidth = 32\nheight = 24\n";
    let inline = "{ center = [0.0, 0.0, -5.0,], radius = 0.5, color = [1, 2, 3,], specular = 0.5, shininess = 8.0, reflect = 0.5 }";
    let text = format!(
        "{top_keys}sphere = [\n{},\n]\n{camera}{}{}",
        [inline; 256].join(",\n"),
        light.repeat(8),
        plane.repeat(8)
    );
    let file = parse::<256, 8, 8, 8>(&text).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(file.scene.spheres().len(), 256);
}
