//! Prints the README's accuracy tables: every method on every standard scene against
//! the f64 reference (the feature scenes also per secondary-ray origin), and the
//! failure points the stability sweeps find (`lab/tests/lab/stability.rs` and
//! `lab/tests/lab/lit_stability.rs` assert them).
//!
//! ```text
//! cargo run --release --features tools --example accuracy_table
//! ```
//!
//! The output is deterministic (IEEE arithmetic, no threads, no clock), and `.ci/run`
//! checks that README.md's `## Accuracy` section is exactly this output.

use std::process::ExitCode;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_raytracer::{scene_file, Arithmetic, Method, Options, Render, SecondaryOrigin, Stepping};
use embedded_raytracer_lab::reference::sweeps::{LitPoint, SECONDARY};
use embedded_raytracer_lab::reference::{self, sweeps};

use embedded_raytracer_scenes as standard;
use standard::{FEATURE_SCENES, MAX_DEPTH, MAX_LIGHTS, MAX_PLANES, MAX_SPHERES, SCENES};

fn main() -> ExitCode {
    let mut out = String::new();
    if let Err(e) = scenes_table(&mut out).and_then(|()| feature_scenes_table(&mut out)) {
        eprintln!("error: {e}");
        return ExitCode::from(2);
    }
    failure_points(&mut out);
    integer_table(&mut out);
    if let Err(e) = secondary_failure_points(&mut out) {
        eprintln!("error: {e}");
        return ExitCode::from(2);
    }
    print!("{out}");
    ExitCode::SUCCESS
}

fn feature_scenes_table(out: &mut String) -> Result<(), scene_file::SceneFileError> {
    out.push_str("### Every method on the feature scenes, per secondary-ray origin\n\n");
    out.push_str(
        "240×240. Over 2: pixels with a channel more than 2 levels off the f64 reference, \
         undecidable pixels (silhouettes, horizons, shadow boundaries, checker edges, the \
         `n·l > 0` gate and mirror chains within `f32` rounding) excluded; max and mean: \
         absolute channel difference over the decidable pixels; coverage errors: pixels \
         whose object differs. Convex: the default secondary-ray origin; ε = 1e-3: the \
         textbook epsilon.\n\n",
    );
    out.push_str(
        "| scene | method | over 2, convex | over 2, ε = 1e-3 | max, convex | max, ε = 1e-3 | mean, convex | mean, ε = 1e-3 | coverage errors | undecidable |\n",
    );
    out.push_str("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for name in FEATURE_SCENES {
        let f = scene_file::load::<MAX_SPHERES, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>(standard::path(name))?;
        let truth = reference::render(&f.scene, &f.camera);
        for method in Method::ALL {
            let [c, e] = SECONDARY.map(|secondary| {
                let render = Render::<MAX_SPHERES, Rgb888, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>::new(
                    &f.scene, &f.camera,
                )
                .with_method(method)
                .with_options(Options::DEFAULT.with_secondary(secondary));
                reference::compare(&render, &truth)
            });
            // Primary rays do not depend on the secondary origin: one count unless they differ.
            let coverage = if c.coverage_errors == e.coverage_errors {
                c.coverage_errors.to_string()
            } else {
                format!("{} / {}", c.coverage_errors, e.coverage_errors)
            };
            out.push_str(&format!(
                "| {name} | {method}{} | {} | {} | {} | {} | {:.4} | {:.4} | {coverage} | {} |\n",
                if method == Method::TARGET_DEFAULT {
                    " (default)"
                } else {
                    ""
                },
                c.over_2,
                e.over_2,
                c.color_max,
                e.color_max,
                c.color_mean,
                e.color_mean,
                c.undecidable,
            ));
        }
    }
    out.push('\n');
    Ok(())
}

/// A scale as a column header.
fn scale(x: f64) -> String {
    format!("{x:.1e}")
}

/// An elevation (degrees) as a column header.
fn degrees(x: f64) -> String {
    format!("{x}°")
}

/// One sweep as a table: a column per swept value, rows for the convex exit's pixels
/// more than 2 levels off and the epsilon's, split into acne and leaks.
fn lit_sweep_table(out: &mut String, label: &str, points: &[LitPoint], header: fn(f64) -> String) {
    let xs: Vec<f64> = points
        .iter()
        .filter(|p| p.secondary == SecondaryOrigin::Convex)
        .map(|p| p.x)
        .collect();
    out.push_str(&format!("| {label} |"));
    for &x in &xs {
        out.push_str(&format!(" {} |", header(x)));
    }
    out.push_str("\n|---|");
    out.push_str(&"---:|".repeat(xs.len()));
    out.push('\n');
    let row = |out: &mut String, name: &str, o: SecondaryOrigin, f: &dyn Fn(&sweeps::LitErrors) -> usize| {
        out.push_str(&format!("| {name} |"));
        for p in points.iter().filter(|p| p.secondary == o) {
            out.push_str(&format!(" {} |", f(&p.errors)));
        }
        out.push('\n');
    };
    let eps = SecondaryOrigin::TEXTBOOK;
    row(out, "convex: over 2", SecondaryOrigin::Convex, &|e| {
        e.metrics.over_2
    });
    row(out, "ε = 1e-3: over 2", eps, &|e| e.metrics.over_2);
    row(out, "ε = 1e-3: acne", eps, &|e| e.acne);
    row(out, "ε = 1e-3: leak", eps, &|e| e.leak);
    out.push('\n');
}

fn secondary_failure_points(out: &mut String) -> Result<(), scene_file::SceneFileError> {
    let f = scene_file::load::<MAX_SPHERES, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>(standard::path("shadows"))?;
    out.push_str(
        "\n### Failure points of the secondary-ray origin (`lab/tests/lab/lit_stability.rs` asserts them)\n\n",
    );
    out.push_str(
        "Pixels more than 2 levels off the f64 reference outside the undecidable band, default \
         method, for the convex exit (the default) and the textbook ε = 10⁻³. Acne: the \
         kernel darker than the reference (a shadow ray blocked that reaches the light); \
         leak: brighter where the reference is in shadow.\n\n",
    );
    out.push_str(
        "**Scene scale** — `shadows` with every length and position (camera too) multiplied \
         by 10⁻³ … 10⁵, 240×240:\n\n",
    );
    let points = sweeps::scale_sweep(&f.scene, &f.camera, f.camera.size(), &sweeps::lit_scales());
    lit_sweep_table(out, "scale", &points, scale);
    out.push_str(
        "**Light elevation** — `shadows` under one directional light 60° … 0.25° above the \
         floor (intensity 1), 240×240, at scale 1 and at scale 31.6:\n\n",
    );
    for k in [1.0, 31.6] {
        let points = sweeps::elevation_sweep(&f.scene, &f.camera, f.camera.size(), k, &sweeps::ELEVATIONS);
        lit_sweep_table(out, &format!("elevation, scale {k}"), &points, degrees);
    }
    out.push_str(
        "**Spheres on and in the floor** — radius 1 resting on a checkered floor, sunk by half \
         and by a whole radius, back-lit so their shadows fall toward the camera, 120×60, the \
         scene shrunk from 1 to 10⁻⁴:\n\n",
    );
    lit_sweep_table(
        out,
        "scale",
        &sweeps::contact_sweep(&sweeps::contact_scales()),
        scale,
    );
    out.push_str(
        "**Eye inside a mirror sphere** — radius 5, reflect 0.8, a ball and a point light \
         inside, reflections 8 deep, 120×90, scaled 10⁻³ … 10⁵:\n\n",
    );
    lit_sweep_table(
        out,
        "scale",
        &sweeps::mirror_inside_sweep(Size::new(120, 90), &sweeps::lit_scales()),
        scale,
    );
    out.push_str(
        "**Plane hits near the horizon** — a checkered floor (cells of 1) seen from 1 above \
         it, 240×240, the horizon `offset` px above the centre of row 120 (0.5: a level \
         camera): the hit distance at row 120 and its largest relative error there and \
         below; pixels more than 2 levels off (outside the band) over rows 120 … 239; the \
         rows where a pixel's footprint along the view exceeds a cell (the checker aliases: \
         the kernel and the reference both sample pixel centres, anti-aliasing is a separate \
         feature):\n\n",
    );
    out.push_str("| offset (px) | distance at row 120 | its relative error | rows 121 … 239: largest relative error | over 2 | undecidable | checker finer than a pixel |\n");
    out.push_str("|---:|---:|---:|---:|---:|---:|---|\n");
    for offset in [0.5, 0.1, 0.02, 0.005] {
        let rows = sweeps::horizon_rows(240, 240, offset);
        let (Some(first), Some(rest)) = (rows.first(), rows.get(1..)) else {
            continue;
        };
        let below = rest.iter().fold(0.0f64, |a, r| a.max(r.distance_rel_max));
        let aliased: Vec<_> = rows.iter().filter(|r| r.footprint_cells > 1.0).collect();
        let alias = match aliased.last() {
            Some(last) => format!(
                "rows {} … {} (distance ≥ {:.1})",
                first.row, last.row, last.distance
            ),
            None => "none".to_string(),
        };
        out.push_str(&format!(
            "| {offset} | {:.0} | {:.1e} | {below:.1e} | {} | {} | {alias} |\n",
            first.distance,
            first.distance_rel_max,
            rows.iter().map(|r| r.over_2).sum::<usize>(),
            rows.iter().map(|r| r.undecidable).sum::<usize>(),
        ));
    }
    Ok(())
}

/// Where the integer kernel's per-frame rule gives way to f32
/// (`reference::sweeps::integer_sweep`, asserted by `lab/tests/lab/integer.rs`).
fn integer_table(out: &mut String) {
    out.push_str("\n### Where the integer kernel gives way to f32\n\n");
    out.push_str(
        "`integer/direct/auto/exact` (the default on chips without an FPU) over the sweeps of \
         `lab/tests/lab/integer.rs`: the last value its per-frame rule takes and the first it gives \
         to the f32 method; where taken, coverage errors and the largest shade difference \
         against the f64 reference. Resolution never limits it (taken up to 8192×8192).\n\n",
    );
    out.push_str(
        "| sweep | last taken | first refused | coverage errors where taken | shade max where taken |\n",
    );
    out.push_str("|---|---:|---:|---:|---:|\n");
    for kind in sweeps::IntegerSweep::ALL {
        let points = sweeps::integer_sweep(kind);
        let (last, refused) = sweeps::integer_limit(&points);
        let taken = points.iter().filter(|p| p.integer);
        let coverage: usize = taken.clone().map(|p| p.metrics.coverage_errors).sum();
        let shade = taken.map(|p| p.metrics.shade_max).max().unwrap_or(0);
        out.push_str(&format!(
            "| {} | {} | {} | {coverage} | {shade} |\n",
            kind.name(),
            fmt_opt(last),
            fmt_opt(refused)
        ));
    }
}

fn fmt_opt(v: Option<f64>) -> String {
    v.map_or_else(|| "—".to_string(), |v| format!("{v:.0}"))
}

fn scenes_table(out: &mut String) -> Result<(), scene_file::SceneFileError> {
    out.push_str("### Every method on every standard scene\n\n");
    out.push_str(
        "Coverage errors: pixels whose object (or hit/miss) differs from the f64 reference, \
         undecidable pixels excluded. Shade: absolute channel difference in 8-bit levels \
         where both show the same sphere. Drift: largest pixel-centre error of the ray \
         direction, in pixels (for the integer kernel, of the f32 direction its trace \
         reports; its own rays differ from the ideal ones by ≤ 1/128 pixel). \
         `integer/…`: the integer kernel, marked `(rule: f32)` where its per-frame rule \
         gives the frame to the f32 method named after it.\n\n",
    );
    out.push_str("| scene | method | coverage errors | fraction | shade max | shade mean | drift (px) | undecidable |\n");
    out.push_str("|---|---|---:|---:|---:|---:|---:|---:|\n");
    for name in SCENES {
        let f = scene_file::load::<MAX_SPHERES, 0, 0, 0>(standard::path(name))?;
        let truth = reference::render(&f.scene, &f.camera);
        // The f32 methods, then the integer kernel (the default on chips without an
        // FPU), marked where its rule gives the frame to the f32 method.
        for method in Method::ALL.into_iter().chain([Method::INTEGER]) {
            let render = Render::<MAX_SPHERES, Rgb888>::new(&f.scene, &f.camera).with_method(method);
            let m = reference::compare(&render, &truth);
            out.push_str(&format!(
                "| {name} | {method}{} | {} | {:.2e} | {} | {:.4} | {:.4} | {} |\n",
                if method == Method::TARGET_DEFAULT {
                    " (default)"
                } else if method.arithmetic == Arithmetic::Integer && render.arithmetic() == Arithmetic::F32 {
                    " (rule: f32)"
                } else if method == Method::INTEGER {
                    " (no-FPU default)"
                } else {
                    ""
                },
                m.coverage_errors,
                m.coverage_fraction(),
                m.shade_max,
                m.shade_mean,
                m.drift_max,
                m.undecidable,
            ));
        }
    }
    out.push('\n');
    Ok(())
}

fn failure_points(out: &mut String) {
    let methods = sweeps::sphere_methods();

    out.push_str("### Failure points (`lab/tests/lab/stability.rs` asserts them)\n\n");
    out.push_str(
        "**Distance/radius** — a unit sphere at distance 10 … 1e5 (17 steps of 10^¼), \
         64×64, half the image wide until the narrowest field of view stops the zoom \
         (21 px across at 1e5), Direct stepping:\n\n",
    );
    out.push_str("| sphere test / sqrt | no error up to | first coverage error | errors ≥ half the disc |\n");
    out.push_str("|---|---:|---:|---:|\n");
    let points = sweeps::distance_sweep(64, &methods);
    for f in sweeps::distance_failures(&points, &methods) {
        out.push_str(&format!(
            "| {}/{} | {} | {} | {} |\n",
            f.method.sphere_test,
            f.method.sqrt,
            fmt_opt(f.clean_up_to),
            fmt_opt(f.first_error),
            fmt_opt(f.outright)
        ));
    }

    out.push_str(
        "\n**A huge sphere as the ground** — radius R, eye 1 above its surface, 64×64, \
         Direct stepping: largest relative error of the hit distance (shade max / \
         coverage errors over all R):\n\n",
    );
    out.push_str("| sphere test / sqrt |");
    for r in sweeps::GROUND_RADII {
        out.push_str(&format!(" R = {r:.0e} |"));
    }
    out.push_str(" shade max | coverage errors |\n|---|");
    out.push_str(&"---:|".repeat(sweeps::GROUND_RADII.len() + 2));
    out.push('\n');
    let ground = sweeps::ground_sweep(64, &methods);
    for method in methods {
        out.push_str(&format!("| {}/{} |", method.sphere_test, method.sqrt));
        let mine: Vec<_> = ground.iter().filter(|p| p.method == method).collect();
        for p in &mine {
            out.push_str(&format!(" {:.1e} |", p.metrics.distance_rel_max));
        }
        let shade = mine.iter().map(|p| p.metrics.shade_max).max().unwrap_or(0);
        let cov = mine.iter().map(|p| p.metrics.coverage_errors).max().unwrap_or(0);
        out.push_str(&format!(" {shade} | {cov} |\n"));
    }

    out.push_str(
        "\n**Stepping drift** — oblique camera, rows n×1 and columns 1×n of square pixels \
         over 60°, |eye| = 0 … 1e4, n = 64 … 8192; and at the narrowest field of view \
         (pixels of `MIN_PIXEL_SIZE`), eye at the origin:\n\n",
    );
    out.push_str("| stepping | ≥ 1 px at n = 1920 from \\|eye\\| = | ≥ 1 px at n = 4096 from \\|eye\\| = | largest drift (px) | narrow fov, n = 1024, oblique | narrow fov, n = 8192, oblique | narrow fov, n = 8192, axis-aligned |\n");
    out.push_str("|---|---:|---:|---:|---:|---:|---:|\n");
    let drift = sweeps::drift_sweep(&sweeps::DRIFT_PIXELS, &sweeps::DRIFT_EYE);
    for stepping in [Stepping::WorldSpace, Stepping::Incremental, Stepping::Direct] {
        let (o1024, _) = sweeps::narrow_fov_drift(1024, stepping);
        let (o8192, a8192) = sweeps::narrow_fov_drift(8192, stepping);
        let px = |v: Option<f64>| v.map_or_else(|| "—".to_string(), |v| format!("{v:.4}"));
        out.push_str(&format!(
            "| {stepping} | {} | {} | {:.4} | {} | {} | {} |\n",
            fmt_opt(sweeps::first_pixel_drift(&drift, stepping, 1920)),
            fmt_opt(sweeps::first_pixel_drift(&drift, stepping, 4096)),
            sweeps::max_drift(&drift, stepping),
            px(o1024),
            px(o8192),
            px(a8192),
        ));
    }

    out.push_str(
        "\n**Near-tangent rays** — rays from the origin passing r·(1 ± 2⁻ᵏ) from the \
         centre of a unit sphere at distance D, k = 1 … 40, 16 angles: the largest \
         relative distance from the silhouette of a misclassified ray (0: none):\n\n",
    );
    let distances = [2.0f32, 10.0, 100.0, 1e4];
    out.push_str("| sphere test / sqrt |");
    for d in distances {
        out.push_str(&format!(" D = {d} |"));
    }
    out.push_str("\n|---|");
    out.push_str(&"---:|".repeat(distances.len()));
    out.push('\n');
    for method in methods {
        out.push_str(&format!("| {}/{} |", method.sphere_test, method.sqrt));
        for d in distances {
            out.push_str(&format!(" {:.1e} |", sweeps::grazing_resolution(d, method).worst));
        }
        out.push('\n');
    }

    out.push_str(
        "\n**Camera limits** — `up` at an angle from the view direction (64×64, default method):\n\n",
    );
    out.push_str("| angle (rad) | result |\n|---:|---|\n");
    for p in sweeps::up_angle_sweep() {
        let result = match p.result {
            Ok(drift) => format!("accepted, drift {drift:.4} px"),
            Err(e) => format!("refused: {e:?}"),
        };
        out.push_str(&format!("| {:.2e} | {result} |\n", p.angle));
    }
}
