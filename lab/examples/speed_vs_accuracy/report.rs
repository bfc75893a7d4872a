//! The report: the md (a table per scene, the lit scenes, the growth table, the
//! project's speed targets as measured, the sampling axis) and the csv, with the
//! machine they were measured on; then the chart.

use std::fmt::Write as _;

use embedded_raytracer::{Method, Stepping};
use embedded_raytracer_scenes::{FEATURE_SCENES, SCENES};

use crate::measure::{Isolated, LitPoint, Point3, BASELINE};
use crate::plot::plot;
use crate::sampling::{write_sampling, SamplingPoint};
use crate::Args;

/// Timing noise margin of the Pareto marks in the tables: on a shared machine medians
/// of the same work differ by a few percent from run to run.
const NOISE: f64 = 0.05;

/// On the front unless another point is at least as accurate and more than `NOISE`
/// faster, or more accurate and not slower.
fn on_noisy_front(p: (f64, f64), all: &[(f64, f64)]) -> bool {
    !all.iter()
        .any(|q| (q.1 <= p.1 && q.0 < p.0 * (1.0 - NOISE)) || (q.1 < p.1 && q.0 <= p.0))
}

/// The machine the run measured on: its CPU, cores, OS and architecture.
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

/// Writes the csv, the md (also to stdout) and the chart into `args.out`.
pub fn write_outputs(
    args: &Args,
    points: &[Point3],
    lit: &[LitPoint],
    growth: &[(usize, String, f64)],
    cycles: &[(String, String, f64)],
    isolated: &[Isolated],
    sampled: &[SamplingPoint],
) -> Result<(), Box<dyn std::error::Error>> {
    let command = if args.quick {
        "cargo run --release --features tools --example speed_vs_accuracy -- --quick"
    } else {
        "cargo run --release --features tools --example speed_vs_accuracy"
    };
    // CSV.
    let mut csv = String::from("scene,method,culling,ns_per_pixel,speedup_vs_baseline,coverage_errors,coverage_error_fraction,max_shade_error,pareto_coverage,pareto_shade\n");
    // Markdown.
    let mut md = String::new();
    writeln!(md, "# Speed against accuracy\n")?;
    let runs = args.runs();
    writeln!(md, "Made by `{command}` on {} ({runs} timed renders per point, median; into an in-memory Rgb565 frame buffer).", machine())?;
    writeln!(md, "Errors are against the accuracy lab's independent `f64` reference renderer (`embedded_raytracer_lab::reference`: the seed's camera, robust test and Lab #1 shading in `f64`; undecidable pixels not counted): **coverage** = pixels whose hit sphere differs from the reference's, **shade** = the largest 8-bit channel difference where the hit sphere agrees. Speed-up = baseline ns/pixel ÷ method ns/pixel, same process. The baseline is the seed taken literally: world-space stepping, the quadratic against every sphere at every pixel, libm square root, no span culling. *P* marks the Pareto front for coverage / shade: no other method is at least as accurate and more than 5 % faster (the timing noise of this shared machine), or more accurate and not slower. The chart's grey line is the strict front of the measured medians.\n")?;
    writeln!(md, "![speed against accuracy](speed_vs_accuracy.png)\n")?;
    let ns_of = |scene: &str, label: &str| {
        points
            .iter()
            .find(|p| p.scene == scene && p.label == label)
            .map(|p| p.ns)
    };
    for scene in SCENES {
        let pts: Vec<&Point3> = points.iter().filter(|p| p.scene == scene).collect();
        let base = ns_of(scene, BASELINE).unwrap_or(f64::NAN);
        let on_front = |metric: usize| {
            let xy: Vec<(f64, f64)> = pts
                .iter()
                .map(|p| {
                    (
                        p.ns,
                        if metric == 0 {
                            p.coverage as f64
                        } else {
                            f64::from(p.shade)
                        },
                    )
                })
                .collect();
            xy.iter().map(|p| on_noisy_front(*p, &xy)).collect::<Vec<bool>>()
        };
        let (fc, fs) = (on_front(0), on_front(1));
        writeln!(md, "## {scene}\n")?;
        writeln!(
            md,
            "| method | ns/pixel | speed-up | coverage errors | max shade error | Pareto |"
        )?;
        writeln!(md, "|---|---:|---:|---:|---:|---|")?;
        for (k, p) in pts.iter().enumerate() {
            let default = if p.method == Some(Method::TARGET_DEFAULT) {
                " (default)"
            } else {
                ""
            };
            let front = match (fc[k], fs[k]) {
                (true, true) => "P / P",
                (true, false) => "P / –",
                (false, true) => "– / P",
                (false, false) => "",
            };
            writeln!(
                md,
                "| {}{default} | {:.2} | {:.2}× | {} | {} | {front} |",
                p.label,
                p.ns,
                base / p.ns,
                p.coverage,
                p.shade
            )?;
            writeln!(
                csv,
                "{},{},{},{:.3},{:.3},{},{:.6},{},{},{}",
                p.scene,
                p.method.map_or("baseline".to_string(), |m| m.to_string()),
                p.method.is_some(),
                p.ns,
                base / p.ns,
                p.coverage,
                p.coverage as f64 / p.pixels as f64,
                p.shade,
                fc[k],
                fs[k]
            )?;
        }
        writeln!(md)?;
    }
    // The lit scenes.
    let mut lit_csv = String::from(
        "\nlit_scene,method,secondary,ns_per_pixel,speedup_vs_baseline,over_2_levels,max_error,mean_error\n",
    );
    for scene in FEATURE_SCENES {
        let base = lit
            .iter()
            .find(|p| p.scene == scene && p.method.is_none())
            .map_or(f64::NAN, |p| p.ns);
        writeln!(md, "## {scene} (lights, a checkered floor, mirrors)\n")?;
        writeln!(md, "Errors outside the reference's undecidable band; speed-up against the literal baseline (every object tested for every ray, closest-hit shadow rays, no culling).\n")?;
        writeln!(
            md,
            "| method | secondary rays | ns/pixel | speed-up | pixels > 2 levels off | max error | mean error |"
        )?;
        writeln!(md, "|---|---|---:|---:|---:|---:|---:|")?;
        for p in lit.iter().filter(|p| p.scene == scene) {
            let default = if p.method == Some(Method::TARGET_DEFAULT) && p.origin == "convex" {
                " (default)"
            } else {
                ""
            };
            writeln!(
                md,
                "| {}{default} | {} | {:.2} | {:.2}× | {} | {} | {:.3} |",
                p.label,
                p.origin,
                p.ns,
                base / p.ns,
                p.over_2,
                p.color_max,
                p.color_mean
            )?;
            writeln!(
                lit_csv,
                "{},{},{},{:.3},{:.3},{},{},{:.4}",
                p.scene,
                p.method.map_or("baseline".to_string(), |m| m.to_string()),
                p.origin,
                p.ns,
                base / p.ns,
                p.over_2,
                p.color_max,
                p.color_mean
            )?;
        }
        writeln!(md)?;
    }
    // Growth table.
    writeln!(
        md,
        "## Growth: ns/pixel against sphere count (the first n spheres of `crowd`)\n"
    )?;
    let mut names: Vec<&String> = growth.iter().map(|g| &g.1).collect();
    names.dedup();
    let counts: Vec<usize> = growth.iter().filter(|g| &g.1 == names[0]).map(|g| g.0).collect();
    write!(md, "| method |")?;
    for n in &counts {
        write!(md, " n = {n} |")?;
    }
    writeln!(md, "\n|---|{}", "---:|".repeat(counts.len()))?;
    for name in &names {
        write!(md, "| {name} |")?;
        for g in growth.iter().filter(|g| &g.1 == *name) {
            write!(md, " {:.2} |", g.2)?;
        }
        writeln!(md)?;
    }
    // The speed targets the project set itself, as measured.
    let default = Method::TARGET_DEFAULT.to_string();
    let ratio = |scene: &str, a: &str, b: &str| Some(ns_of(scene, a)? / ns_of(scene, b)?);
    writeln!(md, "\n## Targets (measured in this run)\n")?;
    if let Some(r) = ratio("lab", BASELINE, &default) {
        writeln!(md, "- default ({default}) on `lab`: {r:.2}× faster per pixel than the literal baseline (target ≥ 8×).")?;
    }
    for stepping in [Stepping::Direct, Stepping::Incremental] {
        for scene in ["lab", "crowd"] {
            if let Some(r) = ratio(
                scene,
                &format!("{stepping}/robust/exact"),
                &format!("{stepping}/forward-diff/exact"),
            ) {
                writeln!(md, "- {stepping}/forward-diff/exact vs {stepping}/robust/exact on `{scene}`: {r:.2}× faster (target ≥ 2×).")?;
            }
        }
    }
    for (scene, stepping, r, f) in isolated {
        writeln!(
            md,
            "- the same without span culling (the tests' own cost, every sphere at every pixel), {stepping} stepping on `{scene}`: robust {r:.2}, forward-diff {f:.2} ns/pixel, {:.2}× faster.",
            r / f
        )?;
    }
    if let Some(r) = ns_of("crowd", &default)
        .zip(ns_of("lab", &default))
        .map(|(c, l)| c / l)
    {
        writeln!(
            md,
            "- default on `crowd` (64 spheres) costs {r:.2}× its ns/pixel on `lab` (target ≤ 4×)."
        )?;
    }
    for scene in FEATURE_SCENES {
        let find = |f: &dyn Fn(&LitPoint) -> bool| lit.iter().find(|p| p.scene == scene && f(p));
        if let (Some(d), Some(b)) = (
            find(&|p| p.method == Some(Method::TARGET_DEFAULT) && p.origin == "convex"),
            find(&|p| p.method.is_none()),
        ) {
            writeln!(md, "- default on `{scene}`: {:.2}× faster per pixel than the literal baseline (target ≥ 3×); {} pixels more than 2 levels off the reference outside its undecidable band (target 0).", b.ns / d.ns, d.over_2)?;
        }
    }
    let worst_default = points
        .iter()
        .filter(|p| p.method == Some(Method::TARGET_DEFAULT))
        .map(|p| (p.coverage, p.shade))
        .fold((0, 0), |a, b| (a.0.max(b.0), a.1.max(b.1)));
    writeln!(md, "- default's worst case over the standard scenes: {} coverage errors, max shade error {} levels (target 0 and ≤ 1).", worst_default.0, worst_default.1)?;

    // Growth CSV rows appended as their own block.
    writeln!(csv, "\ngrowth_method,spheres,ns_per_pixel")?;
    for g in growth {
        writeln!(csv, "{},{},{:.3}", g.1, g.0, g.2)?;
    }

    csv.push_str(&lit_csv);
    write_sampling(&mut md, &mut csv, sampled)?;
    let out = &args.out;
    std::fs::write(out.join("speed_vs_accuracy.csv"), csv)?;
    std::fs::write(out.join("speed_vs_accuracy.md"), &md)?;
    plot(
        points,
        lit,
        growth,
        cycles,
        sampled,
        &out.join("speed_vs_accuracy.png"),
    )?;
    println!("{md}");
    println!("wrote {}/speed_vs_accuracy.{{csv,md,png}}", out.display());
    Ok(())
}
