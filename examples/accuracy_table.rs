//! Prints the README's accuracy tables: every method on every standard scene against
//! the f64 reference, and the failure points the stability sweeps find.
//!
//! ```text
//! cargo run --release --example accuracy_table
//! ```
//!
//! The output is deterministic (IEEE arithmetic, no threads, no clock), and `.ci/run`
//! checks that README.md's `## Accuracy` section is exactly this output.

use std::process::ExitCode;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_raytracer::reference::{self, sweeps};
use embedded_raytracer::{scene_file, Method, Render, Stepping};

#[path = "common/standard.rs"]
mod standard;
use standard::{MAX_SPHERES, SCENES};

fn main() -> ExitCode {
    let mut out = String::new();
    if let Err(e) = scenes_table(&mut out) {
        eprintln!("error: {e}");
        return ExitCode::from(2);
    }
    failure_points(&mut out);
    print!("{out}");
    ExitCode::SUCCESS
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
         direction, in pixels.\n\n",
    );
    out.push_str("| scene | method | coverage errors | fraction | shade max | shade mean | drift (px) | undecidable |\n");
    out.push_str("|---|---|---:|---:|---:|---:|---:|---:|\n");
    for name in SCENES {
        let f = scene_file::load::<MAX_SPHERES, 0, 0, 0>(standard::path(name))?;
        let truth = reference::render(&f.scene, &f.camera);
        for method in Method::ALL {
            let render = Render::<MAX_SPHERES, Rgb888>::new(&f.scene, &f.camera).with_method(method);
            let m = reference::compare(&render, &truth);
            out.push_str(&format!(
                "| {name} | {method}{} | {} | {:.2e} | {} | {:.4} | {:.4} | {} |\n",
                if method == Method::DEFAULT {
                    " (default)"
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

    out.push_str("### Failure points (`tests/stability.rs` asserts them)\n\n");
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
