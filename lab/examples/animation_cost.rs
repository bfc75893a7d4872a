//! What incremental frames cost on the host, as ratios to full frames measured in the
//! same run, and how much more than the changed pixels the rule traces and sends.
//!
//! ```text
//! cargo run --release -p embedded-raytracer-lab --features tools --example animation_cost            # prints
//! cargo run --release -p embedded-raytracer-lab --features tools --example animation_cost -- --update
//! ```
//!
//! `--update` writes the section between `<!-- host:begin -->` and `<!-- host:end -->` of
//! `docs/animation.md` and the per-frame data `lab/data/animation_host.csv`.
//!
//! One whole cycle of each animation (frame 0 drawn whole, then every frame up to
//! `frames()`, which is frame 0's moment again) at 240×240 onto an in-memory Rgb565
//! frame buffer ([`SliceTarget`]): `bounce` (default method), `circling` (default method
//! and the integer kernel) and `lab-one`, defined here: the Lab #1 scene (`lab`) at
//! 240×240 with only its first sphere moving (a `Circle` motion, applied with
//! `Scene::set_sphere` as every motion is). Per frame: the pixels traced, sent, the
//! windows and strips ([`FrameStats`]), the pixels that changed (the full renders of
//! consecutive frames compared), and the time of the incremental frame against the full
//! frame (`Render::draw`) of the same scene, interleaved frame by frame (which of the two
//! goes first alternates), the cycle repeated [`REPS`] times, the median per frame. A
//! machine shared with other builds is noisy: only ratios measured in the same run are
//! compared; the absolute times are this machine's. On Linux the time is the thread's
//! CPU time (see [`now`]).
//!
//! Exits non-zero if after a cycle the incremental frame buffer differs from the last
//! frame's full render, if a frame is refused, or if the still frame sends anything.

use std::fmt::Write as _;
use std::hint::black_box;
use std::path::Path;
use std::process::ExitCode;

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raytracer::motion::{Animation, Circle, Motion};
use embedded_raytracer::{CameraParams, FrameStats, Incremental, Method, Render, Scene, Vec3};
use embedded_raytracer_lab::scenes::{
    BOUNCE, BOUNCE_ANIMATION, BOUNCE_CAMERA, CIRCLING, CIRCLING_ANIMATION, CIRCLING_CAMERA, LAB, LAB_CAMERA,
};
use embedded_raytracer_lab::slice_target::SliceTarget;

/// The display: 240×240, as the firmware measurements (`qemu_animation`).
const SIZE: Size = Size::new(240, 240);
const PIXELS: usize = (SIZE.width * SIZE.height) as usize;
/// Cycles timed: each frame's time is the median over these.
const REPS: usize = 21;
/// Timed batches of still frames, each interleaved with a full frame.
const STILL_REPS: usize = 51;
/// Still frames per timed batch.
const STILL_BATCH: usize = 100;

/// `lab-one`: the Lab #1 scene's first sphere (radius 1 at the origin) circling 0.25
/// around its rest position in the horizontal plane, one turn in 2 s: 50 frames at 25 a
/// second. The other four spheres stay: the change is one sphere's.
const LAB_ONE_ANIMATION: Animation<1> = Animation::from_array([Motion::Circle(Circle::new(
    0,
    Vec3::new(0.0, 0.0, 0.0),
    0.25,
    2.0,
    0.0,
))])
.with_fps(25.0)
.with_frames(50);

/// A table row: its label and the figure it shows of a frame.
type Row<'a> = (&'a str, &'a dyn Fn(&Frame) -> f64);

/// One frame's counts and median times.
#[derive(Clone, Copy)]
struct Frame {
    stats: FrameStats,
    /// Pixels whose full render differs from the previous frame's (all of them for
    /// frame 0: the display's content is unknown).
    changed: u32,
    inc_ns: f64,
    full_ns: f64,
    /// The strips this frame traced, drawn by plain clipped renders (`Render::draw`
    /// into the target clipped to each): the traced pixels' cost with each strip's
    /// frame set-up, without the plan and the runs.
    clip_ns: f64,
}

struct Measured {
    scene: &'static str,
    method: Method,
    frames: Vec<Frame>,
    still_ns: f64,
    still_full_ns: f64,
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The time this thread has run, in ns. On Linux its CPU clock
/// (`CLOCK_THREAD_CPUTIME_ID`): on a machine shared with other builds a 2 ms frame is
/// often preempted for a whole scheduler slice, and wall-clock medians then measure the
/// other processes; the CPU clock does not count the time the thread waits.
#[cfg(all(target_os = "linux", target_pointer_width = "64"))]
// The one foreign call of the host tools: libc's thread clock, which the standard
// library does not expose.
#[allow(unsafe_code)]
fn now() -> u64 {
    #[repr(C)]
    struct Timespec {
        sec: i64,
        nsec: i64,
    }
    extern "C" {
        fn clock_gettime(clock: i32, tp: *mut Timespec) -> i32;
    }
    const CLOCK_THREAD_CPUTIME_ID: i32 = 3;
    let mut t = Timespec { sec: 0, nsec: 0 };
    // SAFETY: `t` is a valid, writable timespec for the call's duration.
    let r = unsafe { clock_gettime(CLOCK_THREAD_CPUTIME_ID, &mut t) };
    assert_eq!(r, 0, "clock_gettime(CLOCK_THREAD_CPUTIME_ID)");
    t.sec as u64 * 1_000_000_000 + t.nsec as u64
}

/// Elsewhere the wall clock.
#[cfg(not(all(target_os = "linux", target_pointer_width = "64")))]
fn now() -> u64 {
    static START: std::sync::OnceLock<std::time::Instant> = std::sync::OnceLock::new();
    START.get_or_init(std::time::Instant::now).elapsed().as_nanos() as u64
}

fn ns(start: u64) -> f64 {
    (now() - start) as f64
}

/// Which clock [`now`] reads, for the text.
const CLOCK: &str = if cfg!(all(target_os = "linux", target_pointer_width = "64")) {
    "the thread's CPU time (`CLOCK_THREAD_CPUTIME_ID`: time spent preempted by other processes not counted)"
} else {
    "the wall clock"
};

fn measure<const N: usize, const L: usize, const P: usize, const D: usize, const M: usize>(
    name: &'static str,
    base: &Scene<N, L, P, D>,
    params: CameraParams,
    animation: &Animation<M>,
    method: Method,
) -> Result<Measured, String> {
    let params = CameraParams { size: SIZE, ..params };
    let count = animation.frames() as usize + 1;
    let mut inc_times = vec![Vec::with_capacity(REPS); count];
    let mut full_times = vec![Vec::with_capacity(REPS); count];
    let mut clip_times = vec![Vec::with_capacity(REPS); count];
    let mut clip_buf = vec![Rgb565::BLACK; PIXELS];
    let mut stats: Vec<FrameStats> = Vec::with_capacity(count);
    let mut changed: Vec<u32> = Vec::with_capacity(count);

    let mut inc_buf = vec![Rgb565::BLACK; PIXELS];
    let mut full_buf = vec![Rgb565::BLACK; PIXELS];
    let mut prev_full = vec![Rgb565::BLACK; PIXELS];
    let mut scene = base.clone();
    let mut at = params;
    let mut shown: Incremental<N, L, P, D> = Incremental::new();
    for rep in 0..REPS {
        // Each cycle starts from an unknown display: frame 0 is drawn whole.
        shown = Incremental::new();
        for frame in 0..count {
            animation
                .apply_frame(base, &params, frame as u32, &mut scene, &mut at)
                .map_err(|e| format!("{name}: frame {frame}: {e}"))?;
            let camera = at.build().map_err(|e| format!("{name}: camera: {e:?}"))?;
            let mut timed_inc = |shown: &mut Incremental<N, L, P, D>| {
                let mut target = SliceTarget {
                    buf: &mut inc_buf,
                    size: SIZE,
                };
                let start = now();
                let render = Render::new(&scene, &camera).with_method(method);
                let Ok(s) = shown.draw(&render, &mut target);
                let t = ns(start);
                black_box(&inc_buf);
                (s, t)
            };
            let timed_full = |buf: &mut [Rgb565]| {
                let mut target = SliceTarget { buf, size: SIZE };
                let start = now();
                let render = Render::new(&scene, &camera).with_method(method);
                let Ok(()) = render.draw(&mut target);
                let t = ns(start);
                black_box(&target.buf);
                t
            };
            // The strips this frame will trace (a copy of what the display shows plans
            // them), each drawn by a plain clipped render.
            let strips: Vec<Rectangle> = {
                let render = Render::<N, Rgb565, L, P, D>::new(&scene, &camera).with_method(method);
                shown.clone().update(&render).rectangles().collect()
            };
            let tc = {
                let mut target = SliceTarget {
                    buf: &mut clip_buf,
                    size: SIZE,
                };
                let start = now();
                let render = Render::new(&scene, &camera).with_method(method);
                for strip in &strips {
                    let Ok(()) = render.draw(&mut target.clipped(strip));
                }
                let t = ns(start);
                black_box(&clip_buf);
                t
            };
            clip_times[frame].push(tc);
            // Which goes first alternates, so neither always finds the caches warm.
            let (s, ti, tf) = if (rep + frame) % 2 == 0 {
                let (s, ti) = timed_inc(&mut shown);
                (s, ti, timed_full(&mut full_buf))
            } else {
                let tf = timed_full(&mut full_buf);
                let (s, ti) = timed_inc(&mut shown);
                (s, ti, tf)
            };
            if let Some(e) = s.refused {
                return Err(format!("{name} ({method}): frame {frame} refused: {e:?}"));
            }
            inc_times[frame].push(ti);
            full_times[frame].push(tf);
            if rep == 0 {
                stats.push(s);
                let c = if frame == 0 {
                    PIXELS
                } else {
                    full_buf.iter().zip(&prev_full).filter(|(a, b)| a != b).count()
                };
                changed.push(c as u32);
                prev_full.copy_from_slice(&full_buf);
            } else if stats[frame] != s {
                return Err(format!(
                    "{name} ({method}): frame {frame}: stats differ between cycles"
                ));
            }
        }
        // The display shows the last frame's full render, bit for bit.
        if inc_buf != full_buf {
            let differ = inc_buf.iter().zip(&full_buf).filter(|(a, b)| a != b).count();
            return Err(format!(
                "{name} ({method}): after cycle {rep} the frame buffer differs from the last frame's full render in {differ} pixels"
            ));
        }
    }

    // Nothing changed: the last frame drawn again (one scene comparison, nothing sent).
    let camera = at.build().map_err(|e| format!("{name}: camera: {e:?}"))?;
    let mut still = Vec::with_capacity(STILL_REPS);
    let mut still_full = Vec::with_capacity(STILL_REPS);
    for _ in 0..STILL_REPS {
        let mut target = SliceTarget {
            buf: &mut inc_buf,
            size: SIZE,
        };
        // A batch: one still frame is shorter than the clock's resolution and cost.
        let start = now();
        for _ in 0..STILL_BATCH {
            let render = Render::new(&scene, &camera).with_method(method);
            let Ok(s) = shown.draw(black_box(&render), &mut target);
            if s.sent != 0 || s.traced != 0 || s.full {
                return Err(format!(
                    "{name} ({method}): still frame sent {} traced {}",
                    s.sent, s.traced
                ));
            }
        }
        still.push(ns(start) / STILL_BATCH as f64);
        let mut target = SliceTarget {
            buf: &mut full_buf,
            size: SIZE,
        };
        let start = now();
        let render = Render::new(&scene, &camera).with_method(method);
        let Ok(()) = render.draw(&mut target);
        still_full.push(ns(start));
        black_box(&full_buf);
    }

    let frames = (0..count)
        .map(|f| Frame {
            stats: stats[f],
            changed: changed[f],
            inc_ns: median(&mut inc_times[f]),
            full_ns: median(&mut full_times[f]),
            clip_ns: median(&mut clip_times[f]),
        })
        .collect();
    Ok(Measured {
        scene: name,
        method,
        frames,
        still_ns: median(&mut still),
        still_full_ns: median(&mut still_full),
    })
}

/// Min, median (the upper middle for an even count) and max.
fn spread(mut v: Vec<f64>) -> [f64; 3] {
    v.sort_by(f64::total_cmp);
    [v[0], v[v.len() / 2], v[v.len() - 1]]
}

fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    format!(
        "{cpu}, {cores} cores available, {} {}",
        std::env::consts::OS,
        std::env::consts::ARCH
    )
}

fn int(x: f64) -> String {
    format!("{}", x.round() as i64)
}

fn section(all: &[Measured]) -> Result<String, std::fmt::Error> {
    let mut md = String::new();
    writeln!(md, "## On the host\n")?;
    writeln!(
        md,
        "```text\ncargo run --release -p embedded-raytracer-lab --features tools --example animation_cost -- --update\n```\n"
    )?;
    writeln!(md, "Measured on {} (shared with other builds: ratios are measured in the same run and only they compare; the ns are this machine's). One whole cycle of each animation at 240×240 onto an in-memory Rgb565 frame buffer: frame 0 drawn whole, then every frame up to the cycle's end (frame 0's moment again). Each frame is drawn incrementally (`Incremental::draw`) and whole (`Render::draw`, the same scene into the same kind of frame buffer), the two interleaved, which goes first alternating; the cycle is repeated {REPS} times and each frame's time is its median; time is {CLOCK}. *Changed* counts the pixels whose full render differs from the previous frame's; over-trace = traced − changed, over-send = sent − changed. After every cycle the incremental frame buffer equals the last frame's full render (the example exits non-zero otherwise). `lab-one` is the Lab #1 scene (`lab`) at 240×240 with only its first sphere (radius 1, at the origin) moving: circling 0.25 around its rest position, one turn in 2 s, 50 frames at 25 a second (defined in the example). *Still* is the last frame drawn again, nothing changed: one scene comparison, nothing sent.\n", machine())?;

    writeln!(md, "| scene | method | frames | changed, median | traced, median | over-trace, median | sent, median | over-send, median | incremental ÷ full, median (min–max) | still ÷ full |")?;
    writeln!(md, "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")?;
    for m in all {
        let rest = &m.frames[1..];
        let med = |f: &dyn Fn(&Frame) -> f64| spread(rest.iter().map(f).collect())[1];
        let ratio = spread(rest.iter().map(|f| f.inc_ns / f.full_ns).collect());
        writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {:.3} ({:.3}–{:.3}) | {:.5} |",
            m.scene,
            m.method,
            rest.len(),
            int(med(&|f| f64::from(f.changed))),
            int(med(&|f| f64::from(f.stats.traced))),
            int(med(&|f| f64::from(f.stats.traced) - f64::from(f.changed))),
            int(med(&|f| f64::from(f.stats.sent))),
            int(med(&|f| f64::from(f.stats.sent) - f64::from(f.changed))),
            ratio[1],
            ratio[0],
            ratio[2],
            m.still_ns / m.still_full_ns
        )?;
    }
    writeln!(md)?;

    reading(&mut md, all)?;

    for m in all {
        let first = &m.frames[0];
        let rest = &m.frames[1..];
        let whole = rest.iter().filter(|f| f.stats.full).count();
        writeln!(md, "### {} — `{}`\n", m.scene, m.method)?;
        writeln!(md, "Frame 0, then the {} frames after it (min, median, max over them); {whole} of them drawn whole.\n", rest.len())?;
        writeln!(md, "| per frame | frame 0 | min | median | max |")?;
        writeln!(md, "|---|---:|---:|---:|---:|")?;
        let rows: [Row; 7] = [
            ("pixels changed", &|f| f64::from(f.changed)),
            ("pixels traced", &|f| f64::from(f.stats.traced)),
            ("over-trace (traced − changed)", &|f| {
                f64::from(f.stats.traced) - f64::from(f.changed)
            }),
            ("pixels sent", &|f| f64::from(f.stats.sent)),
            ("over-send (sent − changed)", &|f| {
                f64::from(f.stats.sent) - f64::from(f.changed)
            }),
            ("windows", &|f| f64::from(f.stats.windows)),
            ("strips", &|f| f64::from(f.stats.strips)),
        ];
        for (label, f) in rows {
            let s = spread(rest.iter().map(f).collect());
            writeln!(
                md,
                "| {label} | {} | {} | {} | {} |",
                int(f(first)),
                int(s[0]),
                int(s[1]),
                int(s[2])
            )?;
        }
        let r = spread(rest.iter().map(|f| f.inc_ns / f.full_ns).collect());
        writeln!(
            md,
            "| time, incremental ÷ full | {:.3} | {:.3} | {:.3} | {:.3} |",
            first.inc_ns / first.full_ns,
            r[0],
            r[1],
            r[2]
        )?;
        let c = spread(rest.iter().map(|f| f.inc_ns / f.clip_ns).collect());
        writeln!(
            md,
            "| time, incremental ÷ its strips drawn clipped | {:.3} | {:.3} | {:.3} | {:.3} |",
            first.inc_ns / first.clip_ns,
            c[0],
            c[1],
            c[2]
        )?;
        let i = spread(rest.iter().map(|f| f.inc_ns).collect());
        writeln!(
            md,
            "| incremental, µs (this machine) | {:.0} | {:.0} | {:.0} | {:.0} |",
            first.inc_ns / 1e3,
            i[0] / 1e3,
            i[1] / 1e3,
            i[2] / 1e3
        )?;
        let w = spread(rest.iter().map(|f| f.full_ns).collect());
        writeln!(
            md,
            "| full, µs (this machine) | {:.0} | {:.0} | {:.0} | {:.0} |",
            first.full_ns / 1e3,
            w[0] / 1e3,
            w[1] / 1e3,
            w[2] / 1e3
        )?;
        writeln!(md, "\nStill (the last frame drawn again): {:.2} µs against {:.0} µs for the full frame, {:.5}× (medians of {STILL_REPS} batches of {STILL_BATCH} still frames, each batch followed by a full frame).\n", m.still_ns / 1e3, m.still_full_ns / 1e3, m.still_ns / m.still_full_ns)?;
    }
    Ok(md)
}

/// The paragraph on what the table shows, its figures from this run.
fn reading(md: &mut String, all: &[Measured]) -> std::fmt::Result {
    let pct = |x: f64| 100.0 * x / PIXELS as f64;
    let med = |m: &Measured, f: &dyn Fn(&Frame) -> f64| spread(m.frames[1..].iter().map(f).collect())[1];
    let whole: usize = all
        .iter()
        .map(|m| m.frames[1..].iter().filter(|f| f.stats.full).count())
        .sum();
    write!(
        md,
        "Work follows the change, not the frame: after the first frame, "
    )?;
    if whole == 0 {
        write!(md, "no frame was drawn whole; ")?;
    } else {
        write!(md, "{whole} frames were drawn whole; ")?;
    }
    write!(md, "per frame (medians) ")?;
    for (k, m) in all.iter().enumerate() {
        let changed = med(m, &|f| f64::from(f.changed));
        let traced = med(m, &|f| f64::from(f.stats.traced));
        let sent = med(m, &|f| f64::from(f.stats.sent));
        let over = med(m, &|f| f64::from(f.stats.traced) - f64::from(f.changed));
        let ratio = med(m, &|f| f.inc_ns / f.full_ns);
        let sep = if k + 1 == all.len() { ". " } else { "; " };
        write!(
            md,
            "`{}` ({}) changed {:.1} % of the pixels, traced {:.1} % ({:.2}× the changed pixels; over-trace {} pixels) and sent {:.1} %, at {:.2} of the full frame's time{sep}",
            m.scene,
            if m.method == Method::INTEGER { "integer" } else { "f32" },
            pct(changed),
            pct(traced),
            traced / changed,
            int(over),
            pct(sent),
            ratio
        )?;
    }
    write!(md, "The over-trace is what the rule re-traces that does not change: each moved sphere's old and new silhouettes whole (the pixels inside both that keep their colour), cut into rectangles (strips) around them; with shadows (`bounce`) also the moved ball's old and new shadow on the floor and the other spheres' silhouettes, where its shadow could fall. ")?;
    write!(md, "Time does not follow the pixel count: a full frame's pixels do not cost alike (background that span culling skips is cheap), and the traced ones lie on and around the moving spheres; each incremental frame also pays its plan and one set-up for all its strips. ")?;
    let still = spread(all.iter().map(|m| m.still_ns / m.still_full_ns).collect());
    writeln!(md, "A frame in which nothing changed costs {:.5}–{:.5} of a full frame (the integer kernel's highest: its comparison computes its per-frame decision and quantisation).\n", still[0], still[2])
}

fn csv(all: &[Measured]) -> String {
    let mut out = String::from("scene,method,frame,full,traced,sent,windows,strips,changed,over_trace,over_send,incremental_ns,full_ns,ratio\n");
    for m in all {
        for (k, f) in m.frames.iter().enumerate() {
            let s = f.stats;
            let _ = writeln!(
                out,
                "{},{},{k},{},{},{},{},{},{},{},{},{:.0},{:.0},{:.4}",
                m.scene,
                m.method,
                u8::from(s.full),
                s.traced,
                s.sent,
                s.windows,
                s.strips,
                f.changed,
                i64::from(s.traced) - i64::from(f.changed),
                i64::from(s.sent) - i64::from(f.changed),
                f.inc_ns,
                f.full_ns,
                f.inc_ns / f.full_ns
            );
        }
        let _ = writeln!(
            out,
            "{},{},still,0,0,0,0,0,0,0,0,{:.0},{:.0},{:.5}",
            m.scene,
            m.method,
            m.still_ns,
            m.still_full_ns,
            m.still_ns / m.still_full_ns
        );
    }
    out
}

const BEGIN: &str = "<!-- host:begin -->";
const END: &str = "<!-- host:end -->";

/// `docs/animation.md` with the host section between its markers replaced (the file
/// made, with a one-line intro, if it does not exist).
fn update_doc(path: &Path, section: &str) -> Result<(), String> {
    let block = format!("{BEGIN}\n{section}{END}");
    let text = match std::fs::read_to_string(path) {
        Ok(old) => {
            let (Some(b), Some(e)) = (old.find(BEGIN), old.find(END)) else {
                return Err(format!("{}: markers {BEGIN} / {END} not found", path.display()));
            };
            format!("{}{block}{}", &old[..b], &old[e + END.len()..])
        }
        Err(_) => format!(
            "# Animation\n\nWhat drawing moving scenes costs, frame by frame, when only what changed is traced and sent (`Incremental`).\n\n{block}\n"
        ),
    };
    std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
}

fn run() -> Result<(), String> {
    let update = std::env::args().skip(1).any(|a| a == "--update");
    let all = vec![
        measure(
            "bounce",
            &BOUNCE,
            BOUNCE_CAMERA,
            &BOUNCE_ANIMATION,
            Method::TARGET_DEFAULT,
        )?,
        measure(
            "circling",
            &CIRCLING,
            CIRCLING_CAMERA,
            &CIRCLING_ANIMATION,
            Method::TARGET_DEFAULT,
        )?,
        measure(
            "circling",
            &CIRCLING,
            CIRCLING_CAMERA,
            &CIRCLING_ANIMATION,
            Method::INTEGER,
        )?,
        measure(
            "lab-one",
            &LAB,
            LAB_CAMERA,
            &LAB_ONE_ANIMATION,
            Method::TARGET_DEFAULT,
        )?,
    ];
    let md = section(&all).map_err(|e| e.to_string())?;
    println!("{md}");
    if update {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        update_doc(&root.join("../docs/animation.md"), &md)?;
        let data = root.join("data/animation_host.csv");
        std::fs::write(&data, csv(&all)).map_err(|e| format!("{}: {e}", data.display()))?;
        println!("wrote docs/animation.md (host section) and lab/data/animation_host.csv");
    }
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
