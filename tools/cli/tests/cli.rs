//! The host CLI (`ertrace`), run as a user runs it, from the repository root.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use embedded_raytracer_scenes as standard;

/// The repository root: the scene files and the docs are named from there.
const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

fn render_bin() -> PathBuf {
    PathBuf::from(env!("CARGO_BIN_EXE_ertrace"))
}

fn run(args: &[&str]) -> Output {
    Command::new(render_bin())
        .current_dir(ROOT)
        .args(args)
        .output()
        .unwrap()
}

/// A fresh directory for one test, removed when the test passes (kept when it fails,
/// for a look at what the CLI wrote).
struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if std::thread::panicking() {
            eprintln!("kept {}", self.0.display());
        } else {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

fn scratch(name: &str) -> Scratch {
    let dir = std::env::temp_dir().join(format!("embedded-raytracer-cli-{}-{name}", std::process::id()));
    // A directory left by an earlier run with the same process id starts empty.
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    Scratch(dir)
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
    let default = embedded_raytracer::Method::TARGET_DEFAULT.to_string();
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

// --- The output: never destroy what the CLI was not asked to write ---

/// Runs the CLI with `dir` as the current directory; arguments may be any OS strings.
fn run_in<S: AsRef<std::ffi::OsStr>>(dir: &Path, args: &[S]) -> Output {
    Command::new(render_bin())
        .current_dir(dir)
        .args(args)
        .output()
        .unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Exit code 2 with one message on stderr that contains `expect`.
fn assert_refused(o: &Output, expect: &str) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains(expect), "`{expect}` not in: {err}");
    assert_eq!(err.trim().lines().count(), 1, "one message: {err}");
}

fn assert_rendered(o: &Output) {
    assert!(o.status.success(), "{}", stderr(o));
}

fn is_png(bytes: &[u8]) -> bool {
    bytes.starts_with(b"\x89PNG\r\n\x1a\n")
}

/// A fresh directory holding `s.toml`, a small good scene.
fn scene_dir(name: &str) -> Scratch {
    let dir = scratch(name);
    std::fs::write(dir.join("s.toml"), GOOD).unwrap();
    dir
}

/// Whether this process runs as root: the owner of a file it just created.
#[cfg(unix)]
fn is_root(dir: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    let probe = dir.join("owner-probe");
    std::fs::write(&probe, b"").unwrap();
    std::fs::metadata(&probe).unwrap().uid() == 0
}

#[test]
fn the_scene_file_is_never_the_output() {
    let dir = scene_dir("same-file");
    // Named directly, as the default output of a scene called `*.png`, through a
    // symbolic link and through a hard link: all the same inode.
    assert_refused(
        &run_in(&dir, &["s.toml", "--output", "s.toml"]),
        "is the scene file",
    );
    std::fs::write(dir.join("scene.png"), GOOD).unwrap();
    assert_refused(&run_in(&dir, &["scene.png"]), "is the scene file");
    assert_eq!(std::fs::read_to_string(dir.join("scene.png")).unwrap(), GOOD);
    #[cfg(unix)]
    std::os::unix::fs::symlink("s.toml", dir.join("link.png")).unwrap();
    #[cfg(unix)]
    assert_refused(&run_in(&dir, &["s.toml", "-o", "link.png"]), "is the scene file");
    std::fs::hard_link(dir.join("s.toml"), dir.join("hard.png")).unwrap();
    assert_refused(&run_in(&dir, &["s.toml", "-o", "hard.png"]), "is the scene file");
    assert_eq!(std::fs::read_to_string(dir.join("s.toml")).unwrap(), GOOD);
    // The default output beside a scene elsewhere is a different file: rendered.
    let elsewhere = scratch("same-file-cwd");
    assert_rendered(&run_in(&elsewhere, &[dir.join("scene.png")]));
    assert!(is_png(&std::fs::read(elsewhere.join("scene.png")).unwrap()));
}

#[cfg(unix)]
#[test]
fn a_symlinked_output_writes_its_target_and_a_dangling_one_is_refused() {
    use std::os::unix::fs::symlink;
    let dir = scene_dir("symlink");
    std::fs::write(dir.join("target.png"), b"old").unwrap();
    symlink("target.png", dir.join("link.png")).unwrap();
    assert_rendered(&run_in(&dir, &["s.toml", "-o", "link.png"]));
    let link = std::fs::symlink_metadata(dir.join("link.png")).unwrap();
    assert!(link.file_type().is_symlink(), "the link was replaced");
    assert!(is_png(&std::fs::read(dir.join("target.png")).unwrap()));

    symlink("nowhere/missing.png", dir.join("dangling.png")).unwrap();
    assert_refused(&run_in(&dir, &["s.toml", "-o", "dangling.png"]), "does not exist");
    assert!(std::fs::symlink_metadata(dir.join("dangling.png"))
        .unwrap()
        .file_type()
        .is_symlink());
}

#[cfg(unix)]
#[test]
fn a_read_only_output_is_refused_unless_forced_and_keeps_its_permissions() {
    use std::os::unix::fs::PermissionsExt;
    let dir = scene_dir("read-only");
    let out = dir.join("ro.png");
    std::fs::write(&out, b"keep me").unwrap();
    std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o444)).unwrap();
    // As root the write itself would succeed: the refusal is the CLI's own rule.
    assert_refused(&run_in(&dir, &["s.toml", "-o", "ro.png"]), "read-only");
    assert_eq!(std::fs::read(&out).unwrap(), b"keep me");

    assert_rendered(&run_in(&dir, &["s.toml", "-o", "ro.png", "--force"]));
    assert!(is_png(&std::fs::read(&out).unwrap()));
    let mode = std::fs::metadata(&out).unwrap().permissions().mode() & 0o7777;
    assert_eq!(mode, 0o444, "replaced with mode {mode:o}");

    // A writable file keeps its own (unusual) mode too.
    let private = dir.join("private.png");
    std::fs::write(&private, b"x").unwrap();
    std::fs::set_permissions(&private, std::fs::Permissions::from_mode(0o640)).unwrap();
    assert_rendered(&run_in(&dir, &["s.toml", "-o", "private.png"]));
    let mode = std::fs::metadata(&private).unwrap().permissions().mode() & 0o7777;
    assert_eq!(mode, 0o640);
}

#[cfg(unix)]
#[test]
fn devices_and_fifos_are_written_through_and_never_replaced() {
    use std::os::unix::fs::{FileTypeExt, MetadataExt};
    let dir = scene_dir("special");

    // A FIFO: the PNG comes out of its other end, and it is still a FIFO.
    let fifo = dir.join("pipe.png");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let reader = Command::new("cat")
        .arg(&fifo)
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let o = run_in(&dir, &["s.toml", "-o", "pipe.png"]);
    if !o.status.success() {
        // Unblock the reader, which is waiting for a writer that never came.
        drop(std::fs::OpenOptions::new().write(true).open(&fifo));
    }
    let piped = reader.wait_with_output().unwrap();
    assert_rendered(&o);
    assert!(
        is_png(&piped.stdout),
        "{} bytes through the FIFO",
        piped.stdout.len()
    );
    assert!(std::fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());

    // A socket cannot be written as a file: refused, left in place.
    let socket = dir.join("sock.png");
    let _listener = std::os::unix::net::UnixListener::bind(&socket).unwrap();
    assert_refused(&run_in(&dir, &["s.toml", "-o", "sock.png"]), "refusing");
    assert!(std::fs::symlink_metadata(&socket)
        .unwrap()
        .file_type()
        .is_socket());

    // A directory: refused.
    assert_refused(&run_in(&dir, &["s.toml", "-o", "."]), "directory");

    // `/dev/stdout` (here a pipe): the PNG alone on stdout, the summary on stderr.
    if Path::new("/dev/stdout").exists() {
        let o = run_in(&dir, &["s.toml", "-o", "/dev/stdout"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let (w, h, _) = decode(&o.stdout);
        assert_eq!((w, h), (32, 24));
        assert!(
            o.stdout.ends_with(b"IEND\xaeB`\x82"),
            "bytes after the PNG on stdout"
        );
        assert!(stderr(&o).contains("32x24 pixels"), "{}", stderr(&o));
    }

    // Device nodes need root (or CAP_MKNOD) to create.
    if !is_root(&dir) {
        println!("skipped the device-node cases: not root");
        return;
    }
    let null = dir.join("null.png");
    let made = Command::new("mknod").arg(&null).args(["c", "1", "3"]).status();
    if !made.is_ok_and(|s| s.success()) {
        println!("skipped the device-node cases: mknod is not permitted here");
        return;
    }
    let before = std::fs::metadata(&null).unwrap().rdev();
    assert_rendered(&run_in(&dir, &["s.toml", "-o", "null.png"]));
    let after = std::fs::symlink_metadata(&null).unwrap();
    assert!(after.file_type().is_char_device(), "the device node was replaced");
    assert_eq!(after.rdev(), before);
    // A block device is storage, not a stream: refused (this node names no device).
    let block = dir.join("block.png");
    if Command::new("mknod")
        .arg(&block)
        .args(["b", "0", "0"])
        .status()
        .is_ok_and(|s| s.success())
    {
        assert_refused(&run_in(&dir, &["s.toml", "-o", "block.png"]), "block device");
        assert!(std::fs::symlink_metadata(&block)
            .unwrap()
            .file_type()
            .is_block_device());
    }
}

/// A link planted where a predictable temporary name would be is never followed: the
/// CLI is started stopped (`kill -STOP` in the shell it is then `exec`ed from, which
/// keeps the process id), the links are planted at the names its process id gives,
/// and only then does it continue.
#[cfg(target_os = "linux")]
#[test]
fn the_temporary_file_follows_no_planted_link() {
    let dir = scene_dir("planted");
    let victim = dir.join("victim.txt");
    std::fs::write(&victim, b"precious").unwrap();
    let mut child = Command::new("sh")
        .current_dir(&dir)
        .args(["-c", "kill -STOP $$; exec \"$0\" \"$@\""])
        .arg(render_bin())
        .args(["s.toml", "--output", "out.png"])
        .spawn()
        .unwrap();
    let pid = child.id();
    // Wait until the shell has stopped itself (state `T` in /proc/PID/stat).
    loop {
        let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap();
        let state = stat
            .rsplit_once(')')
            .unwrap()
            .1
            .split_whitespace()
            .next()
            .unwrap();
        if state == "T" {
            break;
        }
        std::thread::yield_now();
    }
    for name in [
        format!(".out.png.{pid}.tmp"),
        format!("out.png.{pid}.tmp"),
        "out.png.tmp".to_string(),
    ] {
        std::os::unix::fs::symlink(&victim, dir.join(name)).unwrap();
    }
    assert!(Command::new("kill")
        .args(["-CONT", &pid.to_string()])
        .status()
        .unwrap()
        .success());
    assert!(child.wait().unwrap().success());
    assert_eq!(
        std::fs::read(&victim).unwrap(),
        b"precious",
        "the PNG went through a link"
    );
    assert!(is_png(&std::fs::read(dir.join("out.png")).unwrap()));
    // Nothing of the CLI's own is left behind: only the planted links end in `.tmp`.
    for entry in std::fs::read_dir(&dir).unwrap() {
        let entry = entry.unwrap();
        if entry.file_name().to_string_lossy().ends_with(".tmp") {
            assert!(
                entry.file_type().unwrap().is_symlink(),
                "{:?} left behind",
                entry.file_name()
            );
        }
    }
}

// --- Arguments ---

#[cfg(unix)]
#[test]
fn non_utf8_paths_work_and_non_utf8_flags_are_one_message() {
    use std::ffi::OsStr;
    use std::os::unix::ffi::OsStrExt;
    let dir = scratch("non-utf8");
    let scene = OsStr::from_bytes(b"sc\xffene.toml");
    std::fs::write(dir.join(scene), GOOD).unwrap();
    // The default output keeps the name's bytes.
    assert_rendered(&run_in(&dir, &[scene]));
    assert!(is_png(
        &std::fs::read(dir.join(OsStr::from_bytes(b"sc\xffene.png"))).unwrap()
    ));
    let out = OsStr::from_bytes(b"--output=\xfe.png");
    assert_rendered(&run_in(&dir, &[scene, out]));
    assert!(dir.join(OsStr::from_bytes(b"\xfe.png")).exists());
    // A method name or a flag that is not UTF-8: one message, exit 2 (no panic).
    let bad = OsStr::from_bytes(b"dir\xffect");
    assert_refused(
        &run_in(&dir, &[scene, OsStr::new("--stepping"), bad]),
        "--stepping",
    );
    assert_refused(
        &run_in(&dir, &[scene, OsStr::from_bytes(b"--\xff")]),
        "unknown flag",
    );
    // A scene path that is not UTF-8 and does not exist is named in the message.
    let missing = OsStr::from_bytes(b"mis\xffsing.toml");
    assert_refused(&run_in(&dir, &[missing]), "sing.toml");
}

#[test]
fn help_flag_forms_and_repeated_or_missing_values() {
    let dir = scene_dir("flags-forms");
    for help in ["--help", "-h"] {
        let o = run_in(&dir, &[help]);
        assert_eq!(o.status.code(), Some(0), "{help}: {}", stderr(&o));
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(text.starts_with("usage: ertrace"), "{text}");
        assert!(text.contains("Worst case measured"), "{text}");
        for scene in standard::FEATURE_SCENES {
            assert!(text.contains(&format!("scenes/{scene}.toml")), "{scene}: {text}");
        }
        assert!(text.contains("8 lights and 8 planes"), "{text}");
    }
    // `--flag=value` forms.
    let o = run_in(
        &dir,
        &[
            "s.toml",
            "--output=eq.png",
            "--stepping=world-space",
            "--sqrt=fast",
        ],
    );
    assert_rendered(&o);
    assert!(String::from_utf8_lossy(&o.stdout).contains("world-space/auto/fast"));
    assert!(is_png(&std::fs::read(dir.join("eq.png")).unwrap()));
    // Given twice (in either spelling): an error naming the flag.
    assert_refused(
        &run_in(&dir, &["s.toml", "-o", "a.png", "--output", "b.png"]),
        "--output is given twice",
    );
    assert_refused(
        &run_in(&dir, &["s.toml", "--sqrt=fast", "--sqrt", "exact"]),
        "--sqrt is given twice",
    );
    // A value that looks like a flag is not taken as one.
    assert_refused(
        &run_in(&dir, &["s.toml", "--output", "--stepping", "direct"]),
        "--output needs a value",
    );
    assert!(!dir.join("--stepping").exists());
    // With `=`, or after `--`, a leading `-` is a name.
    assert_rendered(&run_in(&dir, &["s.toml", "--output=-dash.png"]));
    assert!(dir.join("-dash.png").exists());
    std::fs::copy(dir.join("s.toml"), dir.join("-s.toml")).unwrap();
    assert_rendered(&run_in(&dir, &["--", "-s.toml"]));
    assert!(dir.join("-s.png").exists());
    assert_refused(
        &run_in(&dir, &["s.toml", "--force=yes"]),
        "--force takes no value",
    );
}

// --- The scene file: regular files only, with a size cap ---

#[cfg(unix)]
#[test]
fn the_scene_must_be_a_regular_file_of_at_most_1_mib() {
    let dir = scratch("scene-kinds");
    if Path::new("/dev/zero").exists() {
        assert_refused(&run_in(&dir, &["/dev/zero"]), "not a regular file");
    }
    assert_refused(&run_in(&dir, &[".", "-o", "x.png"]), "not a regular file");

    // A FIFO is refused without being opened. If it were opened, the writer below
    // would feed it a good scene and the render would succeed.
    let fifo = dir.join("scene.toml");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let writer = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::write(fifo, GOOD))
    };
    let o = run_in(&dir, &["scene.toml", "-o", "out.png"]);
    assert_refused(&o, "not a regular file");
    // Release the writer, still waiting for a reader.
    drop(std::fs::read(&fifo));
    writer.join().unwrap().unwrap();

    // Just over the cap (a comment pads a good scene): refused, naming the cap.
    let big = format!("{GOOD}#{}\n", "x".repeat(1 << 20));
    std::fs::write(dir.join("big.toml"), &big).unwrap();
    assert_refused(&run_in(&dir, &["big.toml"]), "1 MiB");
    // Just under it: read.
    let padding = (1 << 20) - GOOD.len() - 2;
    std::fs::write(dir.join("fits.toml"), format!("{GOOD}#{}\n", "x".repeat(padding))).unwrap();
    assert_eq!(std::fs::metadata(dir.join("fits.toml")).unwrap().len(), 1 << 20);
    assert_rendered(&run_in(&dir, &["fits.toml"]));
}

#[test]
fn too_long_arrays_are_refused_naming_the_field() {
    let dir = scratch("long-arrays");
    let sphere = GOOD.split_once("[[sphere]]").unwrap().1;
    let three = format!(
        "{GOOD}[[sphere]]{sphere}[[sphere]]{}",
        sphere.replace("[255, 64, 64]", "[255, 64, 64, 1]")
    );
    std::fs::write(dir.join("s.toml"), three).unwrap();
    assert_refused(
        &run_in(&dir, &["s.toml"]),
        "sphere[2].color: expected 3 values, found 4",
    );
    assert!(!dir.join("s.png").exists());
}

// --- The PNG: streamed, the same pixels ---

/// Decoded 8-bit RGB pixels and the size of a PNG.
fn decode(bytes: &[u8]) -> (u32, u32, Vec<u8>) {
    let mut reader = png::Decoder::new(std::io::Cursor::new(bytes))
        .read_info()
        .unwrap();
    let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut pixels).unwrap();
    assert_eq!(
        (info.color_type, info.bit_depth),
        (png::ColorType::Rgb, png::BitDepth::Eight)
    );
    pixels.truncate(info.buffer_size());
    (info.width, info.height, pixels)
}

#[test]
fn the_streamed_png_has_the_renders_pixels() {
    use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
    use embedded_raytracer::{scene_file, Render};
    let dir = scratch("pixels");
    let png_of = |scene: &str| {
        let path = Path::new(ROOT).join(format!("scenes/{scene}.toml"));
        assert_rendered(&run_in(&dir, &[path.as_os_str()]));
        decode(&std::fs::read(dir.join(format!("{scene}.png"))).unwrap())
    };
    // Spheres only: the spheres-only type's render.
    for scene in ["lab", "crowd"] {
        let (w, h, pixels) = png_of(scene);
        let file = scene_file::load::<256, 0, 0, 0>(standard::path(scene)).unwrap();
        let mut expected = Vec::new();
        Render::<256>::new(&file.scene, &file.camera)
            .trace(|s| expected.extend([s.color.r(), s.color.g(), s.color.b()]));
        assert_eq!((w, h), (file.camera.size().width, file.camera.size().height));
        assert!(
            pixels == expected,
            "{scene}: the PNG's pixels differ from the render's"
        );
    }
    // Lights, planes, mirrors: the full type's render, whatever it draws.
    for scene in standard::FEATURE_SCENES {
        let (w, h, pixels) = png_of(scene);
        let file = standard::load_full(scene);
        let mut expected = Vec::new();
        use standard::{MAX_DEPTH, MAX_LIGHTS, MAX_PLANES, MAX_SPHERES};
        let render: Render<'_, MAX_SPHERES, Rgb888, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH> =
            Render::new(&file.scene, &file.camera);
        render.trace(|s| expected.extend([s.color.r(), s.color.g(), s.color.b()]));
        assert_eq!((w, h), (file.camera.size().width, file.camera.size().height));
        assert!(
            pixels == expected,
            "{scene}: the PNG's pixels differ from the render's"
        );
    }
}

// --- Lights, planes and mirrors ---

/// A small scene with every new key: two lights, a mirror sphere, a checkered floor.
const LIT: &str = "ambient = 0.2\nmax_depth = 3\nshadows = true\n\
[camera]\neye = [0.0, 1.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_y_deg = 60.0\nwidth = 32\nheight = 24\n\
[[light]]\ntype = \"directional\"\ndirection = [-1.0, -2.0, -1.0]\nintensity = 0.8\n\
[[light]]\ntype = \"point\"\nposition = [2.0, 5.0, 3.0]\n\
[[sphere]]\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\ncolor = [255, 64, 64]\nspecular = 0.5\nshininess = 32\nreflect = 0.3\n\
[[plane]]\npoint = [0.0, -1.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\ncolor = [220, 220, 220]\nchecker = [40, 40, 40]\n";

/// Each bad light, plane, material or setting field: exit code 2, one message naming the file, the field and the
/// reason, and no output created.
#[test]
fn bad_light_plane_and_setting_fields_exit_2_naming_file_field_and_reason() {
    let dir = scratch("bad-feature-fields");
    assert_rendered(&run_in(&dir, &[write(&dir, "lit.toml", LIT)]));
    assert!(is_png(&std::fs::read(dir.join("lit.png")).unwrap()));

    let light = LIT
        .split_once("[[light]]")
        .unwrap()
        .1
        .split_once("[[light]]")
        .unwrap()
        .0;
    let plane = LIT.split_once("[[plane]]").unwrap().1;
    // LIT has 2 lights and 1 plane: `total` of one kind.
    let with = |table: &str, body: &str, total: usize| {
        let have = if table == "light" { 2 } else { 1 };
        format!("{LIT}{}", format!("[[{table}]]{body}").repeat(total - have))
    };
    let cases: [(&str, String, &str, &str); 14] = [
        (
            "zero-normal",
            LIT.replace("normal = [0.0, 1.0, 0.0]", "normal = [0.0, 0.0, 0.0]"),
            "plane[0].normal",
            "must not be zero",
        ),
        (
            "zero-direction",
            LIT.replace("[-1.0, -2.0, -1.0]", "[0, 0, 0]"),
            "light[0].direction",
            "must not be zero",
        ),
        (
            "negative-intensity",
            LIT.replace("intensity = 0.8", "intensity = -1"),
            "light[0].intensity",
            "at least 0",
        ),
        (
            "ambient",
            LIT.replace("ambient = 0.2", "ambient = 2"),
            "ambient",
            "between 0 and 1",
        ),
        (
            "specular",
            LIT.replace("specular = 0.5", "specular = 1.5"),
            "sphere[0].specular",
            "between 0 and 1",
        ),
        (
            "reflect",
            LIT.replace("reflect = 0.3", "reflect = -0.3"),
            "sphere[0].reflect",
            "between 0 and 1",
        ),
        (
            "shininess",
            LIT.replace("shininess = 32", "shininess = 0.5"),
            "sphere[0].shininess",
            "at least 1",
        ),
        (
            "max-depth",
            LIT.replace("max_depth = 3", "max_depth = 9"),
            "max_depth",
            "at most 8",
        ),
        (
            "unknown-type",
            LIT.replace("\"point\"", "\"spot\""),
            "light[1].type",
            "invalid value: string \"spot\", expected \"directional\" or \"point\"",
        ),
        (
            "point-without-position",
            LIT.replace("position = [2.0, 5.0, 3.0]\n", ""),
            "light[1].position",
            "needs a `position`",
        ),
        (
            "point-with-direction",
            LIT.replace("position = [2.0, 5.0, 3.0]", "direction = [2.0, 5.0, 3.0]"),
            "light[1].direction",
            "has no direction",
        ),
        (
            "checker-size",
            LIT.replace(
                "checker = [40, 40, 40]",
                "checker = [40, 40, 40]\nchecker_size = 0",
            ),
            "plane[0].checker_size",
            "greater than 0",
        ),
        (
            "nine-lights",
            with("light", light, 9),
            "light",
            "more than 8 lights: at most 8 are supported",
        ),
        (
            "nine-planes",
            with("plane", plane, 9),
            "plane",
            "more than 8 planes: at most 8 are supported",
        ),
    ];
    for (name, text, field, reason) in cases {
        let file = dir.join(format!("{name}.toml"));
        std::fs::write(&file, text).unwrap();
        let out = dir.join(format!("{name}.png"));
        let o = run(&[file.to_str().unwrap(), "--output", out.to_str().unwrap()]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{name}: {err}");
        assert!(
            err.starts_with(&format!("error: {}: ", file.display())),
            "{name}: {err}"
        );
        assert!(
            err.contains(&format!(" {field}: ")),
            "{name}: `{field}` not named: {err}"
        );
        assert!(err.contains(reason), "{name}: `{reason}` not in: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{name}: one message: {err}");
        assert!(!out.exists(), "{name}: output created");
    }
    // Eight of each is the capacity: accepted.
    assert_rendered(&run_in(
        &dir,
        &[write(&dir, "eight-lights.toml", &with("light", light, 8))],
    ));
    assert_rendered(&run_in(
        &dir,
        &[write(&dir, "eight-planes.toml", &with("plane", plane, 8))],
    ));
    let leftovers = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .count();
    assert_eq!(leftovers, 0);
}

/// `text` as `dir/name`; the name, for `run_in(dir, …)`.
fn write<'n>(dir: &Path, name: &'n str, text: &str) -> &'n str {
    std::fs::write(dir.join(name), text).unwrap();
    name
}

/// The standard feature scenes are what their names promise, load with the CLI's
/// capacities and render to a PNG of their size; the summary says what they hold.
#[test]
fn the_feature_scenes_load_and_render() {
    let dir = scratch("feature-scenes");
    for scene in standard::FEATURE_SCENES {
        let file = standard::load_full(scene);
        assert!(file.has_features(), "{scene}");
        let s = &file.scene;
        let [floor] = s.planes() else {
            panic!("{scene}: one floor plane")
        };
        assert!(floor.checker.is_some(), "{scene}: the floor is checkered");
        assert!(s.settings().shadows, "{scene}: shadows on");
        assert!(s.spheres().len() >= 3, "{scene}");
        assert_eq!(
            file.camera.size(),
            embedded_graphics::geometry::Size::new(240, 240)
        );

        let o = run_in(&dir, &[standard::path(scene)]);
        assert_rendered(&o);
        let summary = String::from_utf8_lossy(&o.stdout);
        let lights = s.lights().len();
        assert!(
            summary.contains(&format!("240x240 pixels ({lights} light")),
            "{scene}: {summary}"
        );
        let (w, h, _) = decode(&std::fs::read(dir.join(format!("{scene}.png"))).unwrap());
        assert_eq!((w, h), (240, 240));
    }

    // shadows: a directional and a point light, a sphere resting exactly on the floor.
    let shadows = standard::load_full("shadows");
    let s = &shadows.scene;
    use embedded_raytracer::Light;
    assert!(s.lights().iter().any(|l| matches!(l, Light::Directional { .. })));
    assert!(s.lights().iter().any(|l| matches!(l, Light::Point { .. })));
    let floor = s.planes()[0];
    let up = floor.normal.try_normalize().unwrap();
    assert!(
        s.spheres()
            .iter()
            .any(|b| (b.center - floor.point).dot(up) == b.radius),
        "no sphere rests exactly on the floor"
    );
    // mirrors: depth 3 and mirror spheres.
    let mirrors = standard::load_full("mirrors");
    assert_eq!(mirrors.scene.max_depth(), 3);
    let mirror_spheres = mirrors
        .scene
        .spheres()
        .iter()
        .filter(|b| b.material.reflect >= 0.5)
        .count();
    assert!(mirror_spheres >= 2, "{mirror_spheres} mirror spheres");
}

/// A file without lights, planes or mirrors is drawn through the spheres-only type:
/// the keys that change nothing without them (highlights, settings) leave the PNG
/// byte-identical, and the summary is the Lab #1 one.
#[test]
fn a_file_without_features_keeps_its_png() {
    let dir = scratch("no-features");
    let lab = std::fs::read_to_string(standard::path("lab")).unwrap();
    let inert = format!(
        "ambient = 0.5\nmax_depth = 8\nshadows = false\n{}",
        lab.replace("radius = 1.0", "radius = 1.0\nspecular = 0.9\nshininess = 4")
    );
    assert_ne!(inert, lab);
    let o = run_in(&dir, &[write(&dir, "lab.toml", &lab)]);
    assert_rendered(&o);
    assert!(String::from_utf8_lossy(&o.stdout).contains("320x240 pixels, method"));
    let plain = std::fs::read(dir.join("lab.png")).unwrap();
    let o = run_in(&dir, &[write(&dir, "inert.toml", &inert)]);
    assert_rendered(&o);
    assert!(String::from_utf8_lossy(&o.stdout).contains("320x240 pixels, method"));
    assert!(
        std::fs::read(dir.join("inert.png")).unwrap() == plain,
        "the PNG changed"
    );
}

/// The CLI's reported peak memory, in MB.
fn peak_mb(o: &Output) -> f64 {
    let out = String::from_utf8_lossy(&o.stdout);
    let tail = out
        .split_once("peak memory ")
        .unwrap_or_else(|| panic!("no peak memory in: {out}"))
        .1;
    tail.split_whitespace().next().unwrap().parse().unwrap()
}

/// Memory grows with the width, not with the height: an 8192×512 image peaks at about
/// the same memory as an 8192×64 one. A whole-image buffer would add at least the 11 MB
/// of RGB of the 448 extra rows (twice that when the image was copied for the encoder).
/// The thread count is pinned: at most `2 × threads` bands are in flight, and the 64 rows
/// are 4 bands, the window of 2 threads; the machine's default count would let the tall
/// image hold more bands than the short one has.
#[cfg(target_os = "linux")]
#[test]
fn memory_does_not_grow_with_the_height() {
    let dir = scratch("memory");
    let empty = |h: u32| {
        format!(
            "background = [10, 20, 30]\n[camera]\neye = [0.0, 0.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\n\
             fov_y_deg = 60.0\nwidth = 8192\nheight = {h}\n"
        )
    };
    std::fs::write(dir.join("short.toml"), empty(64)).unwrap();
    std::fs::write(dir.join("tall.toml"), empty(512)).unwrap();
    let short = run_in(&dir, &["short.toml", "--threads", "2"]);
    assert_rendered(&short);
    let tall = run_in(&dir, &["tall.toml", "--threads", "2"]);
    assert_rendered(&tall);
    let (short, tall) = (peak_mb(&short), peak_mb(&tall));
    let extra_rows_mb = 8192.0 * 448.0 * 3.0 / 1e6;
    // A quarter of the extra rows: the allocator's own peaks move by up to 1.5 MB from
    // run to run (measured: 11.0 against 12.5 MB on a loaded machine), far below the
    // 11 MB a whole-image buffer would add.
    assert!(
        tall - short < extra_rows_mb / 4.0,
        "peak {short} MB at 8192x64, {tall} MB at 8192x512"
    );
}

/// The scene the `--help` and README worst-case figures were measured on is the worst
/// the CLI accepts: the largest image, the most spheres, and every sphere enclosing the
/// eye (so span culling removes none).
#[test]
fn the_measured_worst_case_is_the_worst_accepted_scene() {
    use embedded_raytracer::MAX_RESOLUTION;
    let path = Path::new(ROOT).join("docs/cli_worst_case.toml");
    let file = embedded_raytracer::scene_file::load::<256, 0, 0, 0>(&path).unwrap();
    assert_eq!(
        file.camera.size(),
        embedded_graphics::geometry::Size::new(MAX_RESOLUTION, MAX_RESOLUTION)
    );
    assert_eq!(file.scene.spheres().len(), 256);
    let eye = file.camera.eye();
    for (k, s) in file.scene.spheres().iter().enumerate() {
        assert!(
            (s.center - eye).length() < s.radius,
            "sphere {k} does not enclose the eye"
        );
    }
}

/// `--secondary`: `convex` is the default's PNG, `epsilon:VALUE` is the kernel's render
/// with that epsilon (and a large one visibly moves the shadows), the summary names it;
/// a bad value is one message naming the flag, exit 2, and nothing written.
#[test]
fn secondary_origin_flag() {
    use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
    use embedded_raytracer::{scene_file, Options, Render, SecondaryOrigin};
    let dir = scratch("secondary");
    let lit = write(&dir, "lit.toml", LIT);
    let png = |args: &[&str], out: &str| {
        let o = run_in(&dir, &[&[lit, "--output", out][..], args].concat());
        assert_rendered(&o);
        let summary = String::from_utf8_lossy(&o.stdout).into_owned();
        (summary, decode(&std::fs::read(dir.join(out)).unwrap()).2)
    };
    let traced = |secondary| {
        let file = scene_file::load::<1, 2, 1, 3>(dir.join(lit)).unwrap();
        let mut pixels = Vec::new();
        Render::<'_, 1, Rgb888, 2, 1, 3>::new(&file.scene, &file.camera)
            .with_options(Options::DEFAULT.with_secondary(secondary))
            .trace(|s| pixels.extend([s.color.r(), s.color.g(), s.color.b()]));
        pixels
    };

    let (summary, default) = png(&[], "default.png");
    assert!(summary.contains("max_depth 3, secondary convex)"), "{summary}");
    assert!(default == traced(SecondaryOrigin::Convex));
    let (summary, convex) = png(&["--secondary", "convex"], "convex.png");
    assert!(summary.contains("secondary convex)"), "{summary}");
    assert!(convex == default, "--secondary convex is not the default");
    // Half a unit: the floor's shadow rays start above the sphere resting on it, so
    // light leaks under it and the picture changes.
    let (summary, leaky) = png(&["--secondary=epsilon:0.5"], "leaky.png");
    assert!(summary.contains("secondary epsilon:0.5)"), "{summary}");
    assert!(leaky == traced(SecondaryOrigin::Epsilon(0.5)));
    assert!(leaky != default, "epsilon 0.5 changed no pixel");
    let (summary, textbook) = png(&["--secondary", "epsilon:1e-3"], "textbook.png");
    assert!(summary.contains("secondary epsilon:0.001)"), "{summary}");
    assert!(textbook == traced(SecondaryOrigin::TEXTBOOK));

    // A spheres-only file traces no secondary ray: any choice, the same PNG.
    let s = write(&dir, "s.toml", GOOD);
    let spheres = |args: &[&str], out: &str| {
        assert_rendered(&run_in(&dir, &[&[s, "--output", out][..], args].concat()));
        std::fs::read(dir.join(out)).unwrap()
    };
    assert!(spheres(&[], "s-default.png") == spheres(&["--secondary", "epsilon:0.5"], "s-eps.png"));

    let out = dir.join("keep.png");
    std::fs::write(&out, b"sentinel").unwrap();
    let out_s = out.to_str().unwrap();
    for (value, expect) in [
        (
            "concave",
            "--secondary: expected convex or epsilon:VALUE, got `concave`",
        ),
        ("epsilon", "expected convex or epsilon:VALUE"),
        ("epsilon:", "--secondary: epsilon `` is not a number"),
        ("epsilon:abc", "--secondary: epsilon `abc` is not a number"),
        (
            "epsilon:0",
            "--secondary: epsilon must be a positive finite number, got `0`",
        ),
        ("epsilon:-0.001", "positive finite number, got `-0.001`"),
        ("epsilon:NaN", "positive finite number, got `NaN`"),
        ("epsilon:inf", "positive finite number, got `inf`"),
        ("epsilon:1e39", "positive finite number, got `1e39`"),
    ] {
        assert_refused(
            &run_in(&dir, &[lit, "--output", out_s, &format!("--secondary={value}")]),
            expect,
        );
        assert_eq!(std::fs::read(&out).unwrap(), b"sentinel", "{value}");
        let fresh = dir.join("fresh.png");
        assert_refused(
            &run_in(
                &dir,
                &[lit, "--output", fresh.to_str().unwrap(), "--secondary", value],
            ),
            "--secondary",
        );
        assert!(!fresh.exists(), "{value}: an output was written");
    }
    assert_refused(&run_in(&dir, &[lit, "--secondary"]), "--secondary needs a value");
    assert_refused(
        &run_in(&dir, &[lit, "--secondary", "convex", "--secondary=convex"]),
        "--secondary is given twice",
    );
    // The usage names the flag and its choices.
    let help = String::from_utf8_lossy(&run_in(&dir, &["--help"]).stdout).into_owned();
    assert!(
        help.lines()
            .next()
            .unwrap()
            .contains("[--secondary convex|epsilon:VALUE]"),
        "{help}"
    );
    assert!(help.contains("secondary convex)"), "{help}");
}

/// `--sampling`: each choice's PNG is the kernel's render with it (spheres-only and lit
/// files), the summary names a non-default one; a bad value is one message naming the
/// flag, exit 2, and nothing written.
#[test]
fn sampling_flag() {
    use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
    use embedded_raytracer::{scene_file, Render, Sampling};
    let dir = scratch("sampling");
    let lit = write(&dir, "lit.toml", LIT);
    let s = write(&dir, "s.toml", GOOD);
    let png = |file: &str, args: &[&str], out: &str| {
        let o = run_in(&dir, &[&[file, "--output", out][..], args].concat());
        assert_rendered(&o);
        let summary = String::from_utf8_lossy(&o.stdout).into_owned();
        (summary, decode(&std::fs::read(dir.join(out)).unwrap()).2)
    };
    let traced_lit = |sampling| {
        let file = scene_file::load::<1, 2, 1, 3>(dir.join(lit)).unwrap();
        let mut pixels = Vec::new();
        Render::<'_, 1, Rgb888, 2, 1, 3>::new(&file.scene, &file.camera)
            .with_sampling(sampling)
            .trace(|s| pixels.extend([s.color.r(), s.color.g(), s.color.b()]));
        pixels
    };
    let traced_spheres = |sampling| {
        let file = scene_file::load::<8, 0, 0, 0>(dir.join(s)).unwrap();
        let mut pixels = Vec::new();
        Render::<'_, 8, Rgb888>::new(&file.scene, &file.camera)
            .with_sampling(sampling)
            .trace(|s| pixels.extend([s.color.r(), s.color.g(), s.color.b()]));
        pixels
    };
    let (summary, default) = png(lit, &[], "default.png");
    assert!(!summary.contains("sampling"), "{summary}");
    let (_, center) = png(lit, &["--sampling", "center"], "center.png");
    assert!(center == default);
    for value in ["grid:2", "grid:3", "adaptive:4"] {
        let sampling: Sampling = value.parse().unwrap();
        let (summary, pixels) = png(lit, &[&format!("--sampling={value}")], "lit.png");
        assert!(summary.contains(&format!("sampling {value},")), "{summary}");
        assert!(pixels == traced_lit(sampling), "{value}");
        assert!(pixels != default, "{value} changed no pixel");
        let (_, pixels) = png(s, &["--sampling", value], "s.png");
        assert!(pixels == traced_spheres(sampling), "spheres {value}");
    }
    let out = dir.join("keep.png");
    std::fs::write(&out, b"sentinel").unwrap();
    let out_s = out.to_str().unwrap();
    for (value, expect) in [
        (
            "grid:5",
            "--sampling: sub-samples per axis must be 2, 3 or 4, not 5, got `grid:5`",
        ),
        ("adaptive:1", "not 1, got `adaptive:1`"),
        ("grid", "--sampling: expected center, grid:N or adaptive:N"),
        ("box:2", "--sampling: expected center, grid:N or adaptive:N"),
        ("adaptive:x", "got `adaptive:x`"),
    ] {
        assert_refused(
            &run_in(&dir, &[lit, "--output", out_s, &format!("--sampling={value}")]),
            expect,
        );
        assert_eq!(std::fs::read(&out).unwrap(), b"sentinel", "{value}");
    }
    assert_refused(&run_in(&dir, &[lit, "--sampling"]), "--sampling needs a value");
    assert_refused(
        &run_in(&dir, &[lit, "--sampling", "center", "--sampling=grid:2"]),
        "--sampling is given twice",
    );
    let help = String::from_utf8_lossy(&run_in(&dir, &["--help"]).stdout).into_owned();
    assert!(
        help.lines()
            .next()
            .unwrap()
            .contains("[--sampling center|grid:N|adaptive:N]"),
        "{help}"
    );
    assert!(help.contains("sampling center, "), "{help}");
}

/// `--arithmetic`: without it the default method's arithmetic (f32 on the host) draws
/// and the summary says so; `integer` draws the integer kernel's picture where its rule
/// takes the frame (the lab scene) and the f32 method's where it does not (the grazing
/// scene, whose eye is beside a sphere), and the summary names what drew it; a bad value
/// is one message naming the flag, exit 2.
#[test]
fn arithmetic_flag() {
    use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
    use embedded_raytracer::{scene_file, Arithmetic, Method, Render};
    let dir = scratch("arithmetic");
    let out = dir.join("out.png");
    let png = |scene: &str, args: &[&str]| {
        let o = run(&[&[scene, "--output", out.to_str().unwrap(), "--force"][..], args].concat());
        assert_rendered(&o);
        let summary = String::from_utf8_lossy(&o.stdout).into_owned();
        (summary, decode(&std::fs::read(&out).unwrap()).2)
    };
    let traced = |scene: &str, method: Method| {
        let file: scene_file::SceneFile<8> = scene_file::load(Path::new(ROOT).join(scene)).unwrap();
        let mut pixels = Vec::new();
        Render::<'_, 8, Rgb888>::new(&file.scene, &file.camera)
            .with_method(method)
            .trace(|s| pixels.extend([s.color.r(), s.color.g(), s.color.b()]));
        pixels
    };
    let (summary, default) = png("scenes/lab.toml", &[]);
    assert!(
        summary.contains("method direct/auto/exact, arithmetic f32,"),
        "{summary}"
    );
    assert!(default == traced("scenes/lab.toml", Method::TARGET_DEFAULT));
    let (summary, integer) = png("scenes/lab.toml", &["--arithmetic", "integer"]);
    assert!(
        summary.contains("method integer/direct/auto/exact, arithmetic integer,"),
        "{summary}"
    );
    assert!(integer == traced("scenes/lab.toml", Method::INTEGER));
    assert!(integer != default, "the integer kernel drew the f32 picture");
    let (summary, f32_png) = png("scenes/lab.toml", &["--arithmetic=f32"]);
    assert!(summary.contains("arithmetic f32,"), "{summary}");
    assert!(f32_png == default);
    let (summary, grazing) = png("scenes/grazing.toml", &["--arithmetic", "integer"]);
    assert!(
        summary.contains("method integer/direct/auto/exact, arithmetic f32,"),
        "{summary}"
    );
    let f32_method = Method::INTEGER.with_arithmetic(Arithmetic::F32);
    assert!(grazing == traced("scenes/grazing.toml", f32_method));
    let o = run(&[
        "scenes/lab.toml",
        "--output",
        out.to_str().unwrap(),
        "--arithmetic",
        "fixed",
    ]);
    assert_refused(
        &o,
        "--arithmetic: unknown arithmetic: expected one of f32, integer",
    );
}

// --- Every core, the same bytes ---

/// The PNG's bytes are the same at 1, 2, 3 and 7 tracing threads for every standard
/// scene, with centre, grid and adaptive sampling, in f32 and the integer arithmetic.
/// The size is shrunk (`--size`) to keep a debug build within a minute; 72 rows are
/// four whole bands of 16 rows and a partial one, so threads finish out of order.
#[test]
fn the_png_is_the_same_for_every_thread_count() {
    let dir = scratch("threads");
    let mut compared = 0;
    for scene in standard::SCENES.iter().chain(&standard::FEATURE_SCENES) {
        let path = standard::path(scene);
        for sampling in ["center", "grid:4", "adaptive:4"] {
            for arithmetic in ["f32", "integer"] {
                let png = |threads: &str| {
                    let out = dir.join(format!("{scene}-{threads}.png"));
                    let o = run(&[
                        &path,
                        "--size",
                        "40x72",
                        "--sampling",
                        sampling,
                        "--arithmetic",
                        arithmetic,
                        "--threads",
                        threads,
                        "--output",
                        out.to_str().unwrap(),
                    ]);
                    assert_rendered(&o);
                    assert!(
                        String::from_utf8_lossy(&o.stdout).contains(&format!("{threads} thread")),
                        "{}",
                        String::from_utf8_lossy(&o.stdout)
                    );
                    std::fs::read(out).unwrap()
                };
                let one = png("1");
                assert_eq!(png_header(&one).0, 40);
                for threads in ["2", "3", "7"] {
                    assert!(
                        png(threads) == one,
                        "{scene} {sampling} {arithmetic}: {threads} threads differ from 1"
                    );
                    compared += 1;
                }
            }
        }
    }
    assert_eq!(compared, 7 * 3 * 2 * 3);
}

// --- Time: the estimate, and what a signal leaves ---

/// Spawns the CLI on the worst accepted scene (hours in a debug build), output into
/// `dir`, stdout and stderr piped.
fn spawn_worst_case(dir: &Path, extra: &[&str]) -> std::process::Child {
    Command::new(render_bin())
        .current_dir(ROOT)
        .args([
            "docs/cli_worst_case.toml",
            "--output",
            dir.join("worst.png").to_str().unwrap(),
        ])
        .args(extra)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap()
}

/// The names in `dir`.
fn names_in(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

/// Waits (up to a minute) until `dir` holds a file whose name starts with `prefix`.
fn wait_for_file(dir: &Path, prefix: &str) -> bool {
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    while std::time::Instant::now() < deadline {
        if names_in(dir).iter().any(|n| n.starts_with(prefix)) {
            return true;
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    false
}

fn send(child: &std::process::Child, signal: &str) {
    let status = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success(), "kill {signal}");
}

/// SIGINT and SIGTERM during a render: the temporary file is removed, stderr says so,
/// the exit code is 130 / 143, and the output was not created.
#[cfg(unix)]
#[test]
fn a_signal_removes_the_temporary_file() {
    for (signal, name, code) in [("-INT", "SIGINT", 130), ("-TERM", "SIGTERM", 143)] {
        let dir = scratch(&format!("signal-{name}"));
        let child = spawn_worst_case(&dir, &["--threads", "1", "--quiet"]);
        let seen = wait_for_file(&dir, ".render-");
        send(&child, signal);
        let o = child.wait_with_output().unwrap();
        assert!(seen, "{name}: no temporary file appeared: {}", stderr(&o));
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(code), "{name}: {err}");
        assert!(err.contains(&format!("interrupted by {name}")), "{err}");
        assert!(err.contains("removed the unfinished temporary file"), "{err}");
        assert!(err.contains("worst.png was not written"), "{err}");
        assert!(!err.contains(".render-"), "the temporary file is named: {err}");
        assert!(names_in(&dir).is_empty(), "{name} left {:?}", names_in(&dir));
    }
}

/// The bound is printed before a render that may take long (the worst accepted scene),
/// not before a short one (the lab scene), nor with `--quiet`.
#[cfg(unix)]
#[test]
fn the_estimate_is_printed_before_a_long_render_only() {
    let dir = scratch("estimate");
    let o = run(&[
        "scenes/lab.toml",
        "--output",
        dir.join("lab.png").to_str().unwrap(),
    ]);
    assert_rendered(&o);
    assert!(!stderr(&o).contains("estimate"), "{}", stderr(&o));
    assert!(stderr(&o).is_empty(), "stderr on a pipe: {}", stderr(&o));

    use std::io::{BufRead, BufReader};
    let mut child = spawn_worst_case(&dir, &["--threads", "1"]);
    let mut line = String::new();
    // Kept open until the child has exited: its message on the signal goes there too.
    let mut err = BufReader::new(child.stderr.take().unwrap());
    err.read_line(&mut line).unwrap();
    send(&child, "-TERM");
    let o = child.wait_with_output().unwrap();
    drop(err);
    assert_eq!(o.status.code(), Some(143));
    assert!(line.starts_with("ertrace: estimate: at most "), "{line}");
    // 8192 x 8192 pixels, one ray, 256 spheres each.
    assert!(
        line.contains("67108864 pixels x 1 ray x 256 object tests"),
        "{line}"
    );
    assert!(!names_in(&dir).iter().any(|n| n.starts_with(".render-")));

    let mut child = spawn_worst_case(&dir, &["--threads", "1", "--quiet"]);
    assert!(wait_for_file(&dir, ".render-"));
    send(&child, "-INT");
    let mut err = String::new();
    use std::io::Read;
    child.stderr.take().unwrap().read_to_string(&mut err).unwrap();
    assert_eq!(child.wait().unwrap().code(), Some(130), "{err}");
    assert!(!err.contains("ertrace: estimate"), "--quiet: {err}");
}

/// What can be checked before tracing is: on the worst accepted scene (hours in a debug
/// build) a name ending in `/` and a missing directory fail at once, exit 2, naming the
/// output and never the temporary file, and nothing is created.
#[test]
fn a_bad_output_path_fails_before_tracing() {
    let dir = scratch("early");
    for (out, expect) in [
        (dir.join("late.png/"), "ends with /"),
        (dir.join("no-such-dir/x.png"), "does not exist"),
    ] {
        let mut out_s = out.to_str().unwrap().to_string();
        if expect == "ends with /" && !out_s.ends_with('/') {
            out_s.push('/');
        }
        let mut child = Command::new(render_bin())
            .current_dir(ROOT)
            .args(["docs/cli_worst_case.toml", "--output", &out_s])
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
        while child.try_wait().unwrap().is_none() {
            if std::time::Instant::now() > deadline {
                let _ = child.kill();
                panic!("{out_s}: still tracing after a minute");
            }
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
        let o = child.wait_with_output().unwrap();
        assert_refused(&o, expect);
        let err = stderr(&o);
        assert!(err.contains(&out_s), "the output is not named: {err}");
        assert!(!err.contains(".render-"), "the temporary file is named: {err}");
        assert!(names_in(&dir).is_empty(), "{:?}", names_in(&dir));
    }
}

/// The read-only rule asks the system whether this user may write the file, as the
/// shell does: as root, a world-writable directory holding a root-owned 0644 file; as
/// `nobody`, `echo x > o.png` fails, and so does the CLI without `--force`; with it the
/// file is replaced by a rename and belongs to `nobody`. An unwritable directory is
/// refused before tracing. Needs root, the user `nobody` and `setpriv` or `runuser`.
#[cfg(unix)]
#[test]
fn a_file_this_user_may_not_write_is_refused_unless_forced() {
    use std::os::unix::fs::{MetadataExt, PermissionsExt};
    let probe = scratch("as-nobody-probe");
    if !is_root(&probe) {
        eprintln!("skipped: needs root (to make a file that another user may not write)");
        return;
    }
    let nobody = Command::new("id").args(["-u", "nobody"]).output().unwrap();
    if !nobody.status.success() {
        eprintln!("skipped: no user `nobody`");
        return;
    }
    let nobody_uid: u32 = String::from_utf8_lossy(&nobody.stdout).trim().parse().unwrap();
    let as_nobody: Vec<String> = if Command::new("setpriv").arg("--version").output().is_ok() {
        ["setpriv", "--reuid=nobody", "--regid=nogroup", "--clear-groups"]
            .map(String::from)
            .to_vec()
    } else if Command::new("runuser").arg("--version").output().is_ok() {
        ["runuser", "-u", "nobody", "--"].map(String::from).to_vec()
    } else {
        eprintln!("skipped: neither setpriv nor runuser is installed");
        return;
    };
    // Under /tmp: the repository's directories need not be open to `nobody`.
    let dir = std::path::PathBuf::from(format!(
        "/tmp/embedded-raytracer-cli-nobody-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir(&dir).unwrap();
    let dir = Scratch(dir);
    std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o777)).unwrap();
    let bin = dir.join("ertrace");
    std::fs::copy(render_bin(), &bin).unwrap();
    std::fs::set_permissions(&bin, std::fs::Permissions::from_mode(0o755)).unwrap();
    std::fs::write(dir.join("s.toml"), GOOD).unwrap();
    std::fs::write(dir.join("o.png"), b"X").unwrap();
    std::fs::set_permissions(dir.join("o.png"), std::fs::Permissions::from_mode(0o644)).unwrap();
    std::fs::create_dir(dir.join("closed")).unwrap();
    std::fs::set_permissions(dir.join("closed"), std::fs::Permissions::from_mode(0o755)).unwrap();
    let run_as_nobody = |args: &[&str]| {
        Command::new(&as_nobody[0])
            .args(&as_nobody[1..])
            .args(args)
            .current_dir(&*dir)
            .output()
            .unwrap()
    };
    // The shell's answer.
    let shell = run_as_nobody(&["sh", "-c", "echo x > o.png"]);
    assert!(!shell.status.success(), "nobody could write o.png");
    // The CLI's: the same, without --force.
    let ertrace = bin.to_str().unwrap();
    assert_refused(
        &run_as_nobody(&[ertrace, "s.toml", "-o", "o.png"]),
        "read-only for this user",
    );
    assert_eq!(std::fs::read(dir.join("o.png")).unwrap(), b"X");
    assert_eq!(std::fs::metadata(dir.join("o.png")).unwrap().uid(), 0);
    // An unwritable directory: refused before tracing, naming the output.
    assert_refused(
        &run_as_nobody(&[ertrace, "s.toml", "-o", "closed/new.png"]),
        "closed/new.png: cannot create a file in the directory closed",
    );
    assert!(!dir.join("closed/new.png").exists());
    // With --force the file is replaced by a rename: it now belongs to nobody, as
    // `--help` says.
    assert_rendered(&run_as_nobody(&[ertrace, "s.toml", "-o", "o.png", "--force"]));
    let meta = std::fs::metadata(dir.join("o.png")).unwrap();
    assert!(is_png(&std::fs::read(dir.join("o.png")).unwrap()));
    assert_eq!(meta.uid(), nobody_uid);
    assert_eq!(meta.mode() & 0o7777, 0o644);
}

/// `--version`, `--completions SHELL`, and the choices `--help` lists from the
/// kernel's tables.
#[test]
fn version_completions_and_listed_choices() {
    let o = run(&["--version"]);
    assert_rendered(&o);
    assert_eq!(
        String::from_utf8_lossy(&o.stdout).trim(),
        format!("ertrace {}", env!("CARGO_PKG_VERSION"))
    );
    for shell in ["bash", "zsh", "fish"] {
        let o = run(&["--completions", shell]);
        assert_rendered(&o);
        let script = String::from_utf8_lossy(&o.stdout);
        assert!(script.contains("ertrace"), "{shell}: {script}");
        assert!(
            script.contains("threads") && script.contains("world-space"),
            "{shell}: {script}"
        );
    }
    assert_refused(&run(&["--completions", "tcsh"]), "--completions");
    let help = String::from_utf8_lossy(&run(&["--help"]).stdout).into_owned();
    use embedded_raytracer::{Arithmetic, Sampling, SphereTest, Sqrt, Stepping};
    let names = [Stepping::NAMES, SphereTest::NAMES, Sqrt::NAMES, Arithmetic::NAMES];
    for table in names {
        assert!(help.contains(&table.join(", ")), "{table:?} not listed: {help}");
    }
    let sampling: Vec<String> = Sampling::ALL.iter().map(|s| s.to_string()).collect();
    assert!(help.contains(&sampling.join(", ")), "{help}");
    assert!(help.contains("Worst case proven from the limits"), "{help}");
    assert!(help.contains("--force"), "{help}");
    assert!(help.contains("belongs to whoever ran ertrace"), "{help}");
    // Errors: the flag and the reason on one line, with clap's suggestion.
    assert_refused(
        &run(&["scenes/lab.toml", "--setpping", "direct"]),
        "unknown flag `--setpping` (did you mean `--stepping`?)",
    );
    assert_refused(
        &run(&["scenes/lab.toml", "--threads", "0"]),
        "--threads: expected a number",
    );
    assert_refused(
        &run(&["scenes/lab.toml", "--size", "12"]),
        "--size: expected WxH, got `12`",
    );
}

/// A scene no `f32` frame can draw exactly — a lamp 10³⁰ away beside spheres a few units
/// from the eye — exits 2 naming the file, both objects as the file names them and the
/// reason, and leaves the output that was there; a sphere 10³⁰ away outside the view of
/// a spheres-only scene is left out and the rest drawn.
#[test]
fn a_scene_no_frame_can_hold_exits_2_naming_the_object() {
    let dir = scratch("far-objects");
    let lab = std::fs::read_to_string(standard::path("lab")).unwrap();
    let lamp = format!("{lab}\n[[light]]\ntype = \"point\"\nposition = [1e30, 1e30, 1e30]\n");
    std::fs::write(dir.join("far.png"), b"keep me").unwrap();
    let o = run_in(&dir, &[write(&dir, "far.toml", &lamp), "--force"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("far.toml: light[0]: more than 2^90 times farther") && e.contains("than sphere["),
        "{e}"
    );
    assert_eq!(std::fs::read(dir.join("far.png")).unwrap(), b"keep me");

    let sphere =
        format!("{lab}\n[[sphere]]\ncenter = [0.0, -1e30, 0.0]\nradius = 1.0\ncolor = [255, 255, 255]\n");
    let o = run_in(&dir, &[write(&dir, "hidden.toml", &sphere)]);
    assert_rendered(&o);
    let o = run_in(&dir, &[write(&dir, "lab.toml", &lab)]);
    assert_rendered(&o);
    assert!(
        std::fs::read(dir.join("hidden.png")).unwrap() == std::fs::read(dir.join("lab.png")).unwrap(),
        "a sphere out of view changed the picture"
    );
}

// --- Sequences: several files, or one scene's motion ---

/// The frames of an APNG, each decoded whole, and the frame count its `acTL` declares.
fn decode_animated(bytes: &[u8]) -> (u32, Vec<Vec<u8>>) {
    let mut reader = png::Decoder::new(std::io::Cursor::new(bytes))
        .read_info()
        .unwrap();
    let declared = reader.info().animation_control().unwrap().num_frames;
    let mut frames = Vec::new();
    for _ in 0..declared {
        let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut pixels).unwrap();
        let control = reader.info().frame_control().unwrap();
        assert_eq!(
            (control.x_offset, control.y_offset, control.width, control.height),
            (0, 0, info.width, info.height),
            "every frame is the whole image"
        );
        pixels.truncate(info.buffer_size());
        frames.push(pixels);
    }
    (declared, frames)
}

/// The stderr lines of the frames (`frame k/n: traced …`).
fn frame_lines(o: &Output) -> Vec<String> {
    stderr(o)
        .lines()
        .filter(|l| l.starts_with("frame "))
        .map(str::to_string)
        .collect()
}

/// Several files are the frames of one display: each frame's PNG is the bytes of that
/// file's single-frame PNG, through a change of scene type (spheres only, lit, spheres
/// only) and with the flags the frames share. Nothing else in the directory is touched.
#[test]
fn several_files_are_the_frames_of_one_display() {
    let dir = scratch("file-frames");
    let frames = dir.join("frames");
    std::fs::create_dir(&frames).unwrap();
    std::fs::write(frames.join("notes.txt"), b"keep me").unwrap();
    let scenes = ["lab", "crowd", "shadows", "shadows", "lab"];
    let paths: Vec<String> = scenes
        .iter()
        .map(|s| {
            Path::new(ROOT)
                .join(format!("scenes/{s}.toml"))
                .display()
                .to_string()
        })
        .collect();
    for flags in [
        &["--size", "64x48"][..],
        &["--size", "48x40", "--sampling", "adaptive:2"],
    ] {
        let mut args: Vec<&str> = paths.iter().map(String::as_str).collect();
        args.extend_from_slice(flags);
        args.extend_from_slice(&["--output-frames", frames.to_str().unwrap()]);
        let o = run_in(&dir, &args);
        assert_rendered(&o);
        let lines = frame_lines(&o);
        assert_eq!(lines.len(), scenes.len(), "{}", stderr(&o));
        assert!(lines[0].starts_with("frame 1/5: traced "), "{}", lines[0]);
        // The same file again: nothing changed, nothing sent.
        assert!(lines[3].contains("sent 0 px"), "{}", lines[3]);
        for (k, path) in paths.iter().enumerate() {
            let single = dir.join("single.png");
            let mut args = vec![path.as_str(), "--output", single.to_str().unwrap()];
            args.extend_from_slice(flags);
            assert_rendered(&run_in(&dir, &args));
            let frame = std::fs::read(frames.join(format!("{:04}.png", k + 1))).unwrap();
            assert!(
                frame == std::fs::read(&single).unwrap(),
                "frame {} ({}) differs from its single-frame PNG with {flags:?}",
                k + 1,
                scenes[k]
            );
        }
    }
    assert_eq!(std::fs::read(frames.join("notes.txt")).unwrap(), b"keep me");
}

/// A scene's motion: `--frames N` writes N frames and an APNG of them; each frame is
/// the single-frame render of its moment (`--frame k`), the APNG declares N frames and
/// holds the same pixels; one line a frame on stderr, none with --quiet.
#[test]
fn a_moving_scene_draws_its_frames_and_an_apng() {
    let dir = scratch("motion-frames");
    for scene in ["bounce", "circling"] {
        let path = Path::new(ROOT).join(format!("scenes/{scene}.toml"));
        let anim = dir.join(format!("{scene}.png"));
        let frames = dir.join(scene);
        let o = run_in(
            &dir,
            &[
                path.to_str().unwrap(),
                "--frames",
                "6",
                "--fps",
                "4",
                "--size",
                "80x80",
                "--output",
                anim.to_str().unwrap(),
                "--output-frames",
                frames.to_str().unwrap(),
            ],
        );
        assert_rendered(&o);
        let lines = frame_lines(&o);
        assert_eq!(lines.len(), 6, "{}", stderr(&o));
        assert!(lines[0].contains("(whole frame)"), "{}", lines[0]);
        let (declared, animated) = decode_animated(&std::fs::read(&anim).unwrap());
        assert_eq!((declared, animated.len()), (6, 6), "{scene}");
        for k in 1..=6 {
            let single = dir.join("single.png");
            let k_text = k.to_string();
            assert_rendered(&run_in(
                &dir,
                &[
                    path.to_str().unwrap(),
                    "--frame",
                    &k_text,
                    "--fps",
                    "4",
                    "--size",
                    "80x80",
                    "--output",
                    single.to_str().unwrap(),
                ],
            ));
            let single = std::fs::read(&single).unwrap();
            let frame = std::fs::read(frames.join(format!("{k:04}.png"))).unwrap();
            assert!(
                frame == single,
                "{scene}: frame {k}'s PNG differs from --frame {k}"
            );
            let (_, _, pixels) = decode(&single);
            assert!(
                animated[k - 1] == pixels,
                "{scene}: the APNG's frame {k} differs from --frame {k}"
            );
        }
        // The moments differ: the scene moves.
        assert_ne!(animated[0], animated[1], "{scene}");
        let quiet = run_in(
            &dir,
            &[
                path.to_str().unwrap(),
                "--frames",
                "2",
                "--size",
                "32x32",
                "--quiet",
                "--output",
                anim.to_str().unwrap(),
            ],
        );
        assert_rendered(&quiet);
        assert!(frame_lines(&quiet).is_empty(), "{}", stderr(&quiet));
    }
}

/// Bad motion, frame flags or a sequence of mismatched files: exit 2 naming the file,
/// field and reason, before anything is written: an existing output is kept, no frame
/// directory is made.
#[test]
fn bad_sequences_exit_2_and_write_nothing() {
    let dir = scratch("bad-sequences");
    let out = dir.join("keep.png");
    let sentinel = b"must survive".to_vec();
    let moving = format!("{GOOD}[[motion]]\nkind = \"bounce\"\nsphere = 0\nheight = 1.0\nperiod = 1.0\n");
    let good = write(&dir, "moving.toml", &moving);
    let zero = write(&dir, "zero.toml", &moving.replace("period = 1.0", "period = 0"));
    let far = write(&dir, "far.toml", &moving.replace("sphere = 0", "sphere = 3"));
    let wide = write(&dir, "wide.toml", &GOOD.replace("width = 32", "width = 40"));
    let fps = write(&dir, "fps.toml", &format!("[animation]\nfps = -2\n{GOOD}"));
    let frames_dir = dir.join("frames");
    let frames_s = frames_dir.to_str().unwrap();
    let out_s = out.to_str().unwrap();
    let first_frame = frames_dir.join("0002.png");
    let first_frame_s = first_frame.to_str().unwrap();
    for (args, expect) in [
        (
            vec![zero, "--frames", "3", "--output", out_s],
            "zero.toml: motion[0].period: period must be",
        ),
        (
            vec![zero, "--output-frames", frames_s],
            "motion[0].period: period must be a finite number greater than 0",
        ),
        (
            vec![far, "--output", out_s],
            "motion[0].sphere: the scene has no sphere[3] (it has 1 sphere)",
        ),
        (
            vec![fps, "--frames", "2", "--output", out_s],
            "animation.fps: fps must be a finite number greater than 0",
        ),
        (
            vec![good, wide, "--output-frames", frames_s],
            "wide.toml: camera.width/height: 40x24 is not the sequence's 32x24",
        ),
        (
            vec![good, good, "--frames", "2", "--output", out_s],
            "--frames draws the motion of one scene file",
        ),
        (
            vec![good, "--frames", "0", "--output", out_s],
            "--frames: expected a number of frames from 1 to",
        ),
        (
            vec![good, "--fps", "0", "--frames", "2", "--output", out_s],
            "--fps: expected a positive finite number",
        ),
        (
            vec![good, "--fps", "1e-40", "--frames", "3", "--output", out_s],
            "--fps: 1e-40 frames a second is too few: frame 2's moment",
        ),
        (
            vec![
                good,
                "--frames",
                "3",
                "--output",
                first_frame_s,
                "--output-frames",
                frames_s,
            ],
            "0002.png: --output: it is also frame 2 of --output-frames",
        ),
        (
            vec![good, "--frame", "0", "--output", out_s],
            "--frame: expected a frame number from 1",
        ),
        (
            vec![good, "--frame", "2", "--frames", "2", "--output", out_s],
            "--frame",
        ),
        (
            vec![good, "--output-frames", out_s],
            "--output-frames: not a directory",
        ),
    ] {
        std::fs::write(&out, &sentinel).unwrap();
        let o = run_in(&dir, &args);
        assert_refused(&o, expect);
        assert_eq!(std::fs::read(&out).unwrap(), sentinel, "{args:?}: output touched");
        assert!(!frames_dir.exists(), "{args:?}: frame directory made");
    }
    // The period's error names the field and the reason too.
    let o = run_in(&dir, &[zero, "--frames", "3", "--output", out_s]);
    assert!(stderr(&o).contains("motion[0].period"), "{}", stderr(&o));
}

/// An `--output` that is a link to one of `--output-frames`' files is that file: refused
/// (exit 2) before anything is traced, and the frame the link leads to is kept.
#[cfg(unix)]
#[test]
fn an_output_linked_to_a_frame_is_refused() {
    let dir = scratch("output-link");
    let moving = format!("{GOOD}[[motion]]\nkind = \"bounce\"\nsphere = 0\nheight = 1.0\nperiod = 1.0\n");
    let good = write(&dir, "moving.toml", &moving);
    let frames = dir.join("frames");
    std::fs::create_dir(&frames).unwrap();
    let frame = frames.join("0001.png");
    std::fs::write(&frame, b"frame one").unwrap();
    std::os::unix::fs::symlink(&frame, dir.join("out.png")).unwrap();
    let o = run_in(
        &dir,
        &[
            good,
            "--frames",
            "2",
            "--output",
            "out.png",
            "--output-frames",
            "frames",
            "--force",
        ],
    );
    assert_refused(
        &o,
        "out.png: --output: it is also frame 1 of --output-frames frames",
    );
    assert_eq!(std::fs::read(&frame).unwrap(), b"frame one");
}
