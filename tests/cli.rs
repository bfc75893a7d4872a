//! The host CLI (`examples/render.rs`), run as a user runs it.
//!
//! `cargo test` builds the examples next to the test binaries; these tests run the
//! built `render` example from there.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn render_bin() -> PathBuf {
    // target/<profile>/deps/cli-<hash> → target/<profile>/examples/render
    let exe = std::env::current_exe().unwrap();
    let profile_dir = exe.parent().and_then(Path::parent).unwrap();
    let bin = profile_dir
        .join("examples")
        .join(format!("render{}", std::env::consts::EXE_SUFFIX));
    assert!(
        bin.exists(),
        "{} is missing: run the whole suite with `cargo test`, which builds the examples",
        bin.display()
    );
    bin
}

fn run(args: &[&str]) -> Output {
    Command::new(render_bin())
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .output()
        .unwrap()
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("embedded-raytracer-cli-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// PNG width and height from the IHDR chunk, and the colour type / bit depth.
fn png_header(bytes: &[u8]) -> (u32, u32, u8, u8) {
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "not a PNG");
    assert_eq!(&bytes[12..16], b"IHDR");
    let be = |i: usize| u32::from_be_bytes(bytes[i..i + 4].try_into().unwrap());
    (be(16), be(20), bytes[24], bytes[25])
}

#[test]
fn renders_the_lab_scene_to_a_png() {
    let dir = scratch("lab");
    let out = dir.join("lab.png");
    let o = run(&["scenes/lab.toml", "--output", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("320x240"), "{stdout}");
    let default = embedded_raytracer::Method::DEFAULT.to_string();
    assert!(stdout.contains(&default), "{stdout}");
    assert!(stdout.contains("ns/pixel"), "{stdout}");
    let (w, h, depth, colour_type) = png_header(&std::fs::read(&out).unwrap());
    assert_eq!((w, h), (320, 240));
    assert_eq!((depth, colour_type), (8, 2), "8-bit RGB");

    // A non-default method, by flag.
    let o = run(&[
        "scenes/lab.toml",
        "--output",
        out.to_str().unwrap(),
        "--stepping",
        "world-space",
        "--sphere-test",
        "algebraic",
        "--sqrt",
        "fast",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("world-space/algebraic/fast"));
}

const GOOD: &str = "[camera]\neye = [0.0, 0.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\n\
fov_y_deg = 60.0\nwidth = 32\nheight = 24\n\n[[sphere]]\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\ncolor = [255, 64, 64]\n";

/// Each bad input: exit code 2, one message naming the file and the field, and the
/// existing output file left byte-for-byte unchanged.
#[test]
fn bad_files_exit_2_and_keep_the_output() {
    let dir = scratch("bad");
    let out = dir.join("keep.png");
    let sentinel = b"not really a png, but it must survive".to_vec();
    let cases: [(&str, String, &str); 8] = [
        (
            "unknown-key",
            GOOD.replace("width = 32", "width = 32\nzoom = 3"),
            "camera.zoom",
        ),
        (
            "missing-field",
            GOOD.replace("look_at = [0.0, 0.0, 0.0]\n", ""),
            "look_at",
        ),
        (
            "radius-zero",
            GOOD.replace("radius = 1.0", "radius = 0.0"),
            "sphere[0].radius",
        ),
        (
            "parallel-up",
            GOOD.replace("up = [0.0, 1.0, 0.0]", "up = [0.0, 0.0, -3.0]"),
            "camera.up",
        ),
        (
            "fov-180",
            GOOD.replace("fov_y_deg = 60.0", "fov_y_deg = 180.0"),
            "camera.fov_y_deg",
        ),
        (
            "width-zero",
            GOOD.replace("width = 32", "width = 0"),
            "camera.width",
        ),
        ("not-toml", "this is { not toml".to_string(), "line 1"),
        (
            "wrong-type",
            GOOD.replace("height = 24", "height = \"tall\""),
            "camera.height",
        ),
    ];
    for (name, text, field) in cases {
        let file = dir.join(format!("{name}.toml"));
        std::fs::write(&file, text).unwrap();
        std::fs::write(&out, &sentinel).unwrap();
        let o = run(&[file.to_str().unwrap(), "--output", out.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {stderr}");
        assert!(
            stderr.contains(file.to_str().unwrap()),
            "{name}: file not named: {stderr}"
        );
        assert!(stderr.contains(field), "{name}: `{field}` not named: {stderr}");
        assert_eq!(stderr.trim().lines().count(), 1, "{name}: one message: {stderr}");
        assert_eq!(std::fs::read(&out).unwrap(), sentinel, "{name}: output touched");
    }
    // No output is created either.
    let fresh = dir.join("fresh.png");
    let o = run(&[
        dir.join("radius-zero.toml").to_str().unwrap(),
        "--output",
        fresh.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!fresh.exists());
    // Nor is a temporary file left behind.
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty());
}

#[test]
fn bad_flags_and_missing_files_exit_2() {
    let dir = scratch("flags");
    let out = dir.join("keep.png");
    std::fs::write(&out, b"sentinel").unwrap();
    let out_s = out.to_str().unwrap();
    for (args, expect) in [
        (
            vec!["scenes/lab.toml", "--output", out_s, "--stepping", "sideways"],
            "--stepping",
        ),
        (
            vec!["scenes/lab.toml", "--output", out_s, "--sqrt"],
            "--sqrt needs a value",
        ),
        (
            vec!["scenes/lab.toml", "--output", out_s, "--frobnicate"],
            "--frobnicate",
        ),
        (
            vec!["scenes/no-such-scene.toml", "--output", out_s],
            "no-such-scene.toml",
        ),
        (vec!["--output", out_s], "no scene file"),
    ] {
        let o = run(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(expect), "{args:?}: {stderr}");
        assert_eq!(std::fs::read(&out).unwrap(), b"sentinel");
    }
}
