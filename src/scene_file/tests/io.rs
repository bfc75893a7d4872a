//! `load`: the path in every error, a regular file only, and the size cap.

use super::*;

use std::path::PathBuf;

use crate::scene_file::load;

/// A scratch directory of this test process, empty.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("scene-file-io-{}-{name}", std::process::id()));
    drop(std::fs::remove_dir_all(&dir));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn load_err(path: &std::path::Path) -> SceneFileError {
    match load::<4, 0, 0, 0>(path) {
        Ok(_) => panic!("accepted: {}", path.display()),
        Err(e) => e,
    }
}

#[test]
fn errors_carry_the_path() {
    let dir = scratch("path");
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, GOOD.replace("radius = 1.0", "radius = 0.0")).unwrap();
    let e = load_err(&bad);
    assert_eq!(e.path.as_deref(), Some(bad.as_path()));
    assert_eq!(
        e.to_string(),
        format!(
            "{}: sphere[0].radius: radius must be greater than 0",
            bad.display()
        )
    );
    let missing = dir.join("missing.toml");
    let e = load_err(&missing);
    assert_eq!(e.path.as_deref(), Some(missing.as_path()));
    assert!(e.reason.starts_with("cannot read the file: "), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn only_a_regular_file_of_at_most_the_cap_is_read() {
    let dir = scratch("cap");
    assert_eq!(
        load_err(&dir).reason,
        "not a regular file (a directory): a scene must be a regular file"
    );

    // A comment pads a good scene to exactly the cap: read; one byte more: refused.
    let cap = usize::try_from(MAX_FILE_SIZE).unwrap();
    let fits = format!("{GOOD}#{}\n", "x".repeat(cap - GOOD.len() - 2));
    assert_eq!(fits.len(), cap);
    let path = dir.join("fits.toml");
    std::fs::write(&path, &fits).unwrap();
    assert_eq!(load::<4, 0, 0, 0>(&path).unwrap().scene.spheres().len(), 1);
    std::fs::write(&path, format!("{fits}#")).unwrap();
    assert_eq!(
        load_err(&path).reason,
        "the file is larger than 1048576 bytes (1 MiB), the limit for a scene file"
    );

    std::fs::write(&path, b"\xff").unwrap();
    assert_eq!(
        load_err(&path).reason,
        "not UTF-8 text (invalid byte at offset 0)"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
