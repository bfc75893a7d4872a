//! The silhouettes and their cuts against exact evaluation: the integer cut, a disc's
//! image on a plane, the rows, the band reach and inside, the shrunk silhouette.

use super::*;
use crate::camera::int_cut::IntCut;
use embedded_graphics::prelude::Size;

const TWO_M20: f64 = 1.0 / 1_048_576.0;

/// Uniform `f32` draws in `[lo, hi)` from an xorshift64 generator seeded `state`.
fn uniform(mut state: u64) -> impl FnMut(f32, f32) -> f32 {
    move |lo, hi| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        lo + (hi - lo) * ((state >> 40) as f32 / (1u64 << 24) as f32)
    }
}

/// A random camera (1–300 pixels each way, eye in front of the origin) and sphere
/// (centre around the origin, radius up to 3, cubed toward small): the camera, the
/// sphere's eye-relative centre and its radius; `None` where the camera is refused.
fn random_view(next: &mut impl FnMut(f32, f32) -> f32) -> Option<(Camera, Vec3, f32)> {
    let size = Size::new(next(1.0, 300.0) as u32, next(1.0, 300.0) as u32);
    let eye = Vec3::new(next(-2.0, 2.0), next(-2.0, 2.0), next(4.0, 9.0));
    let camera = Camera::new(
        eye,
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        next(0.2, 2.5),
        size,
    )
    .ok()?;
    let centre = Vec3::new(next(-6.0, 6.0), next(-6.0, 6.0), next(-6.0, 3.0));
    let radius = next(0.0, 1.0).powi(3) * 3.0;
    Some((camera, centre - eye, radius))
}

/// The integer cut holds every column of `row_span`'s formula evaluated exactly (in
/// `f64` from the stored coefficients, with its slack and pad) on every row of the
/// image, each such row among its rows ([`Silhouette::int_cut_rows`]) where the cut is
/// in fixed point, and is at most
/// a column wider on each side: random spheres
/// and cameras, random coefficients (thin, tall, sheared, off the image's ends),
/// and the ranges where it gives up to every column.
#[test]
fn int_cut_holds_the_exact_row_span() {
    let mut next = uniform(0x9e37_79b9_7f4a_7c15);
    let mut rows_checked = 0;
    let mut check = |sil: Silhouette, (w, h): (u32, u32)| {
        let (rows, cut) = sil.int_cut_rows(h);
        let Some(Ellipse {
            y0i,
            y0f,
            q,
            h0,
            xc0,
            kx,
        }) = sil.get()
        else {
            assert_eq!(cut, IntCut::All);
            return;
        };
        for j in 0..h {
            let dy = (f64::from(j) - f64::from(y0i)) - f64::from(y0f);
            let hw2 = f64::from(h0) * (1.0 + TWO_M16) - f64::from(q) * dy * dy;
            let got = cut.row_span(j, w);
            if hw2 < 0.0 {
                continue;
            }
            let hw = hw2.sqrt();
            let shift = f64::from(kx) * dy;
            let xc = f64::from(xc0) + shift;
            let pad = 1.0 + (f64::from(xc0).abs() + shift.abs() + hw) * TWO_M20;
            let (lo, hi) = ((xc - hw - pad).ceil(), (xc + hw + pad).floor());
            let (lo, hi) = (lo.max(0.0), hi.min(f64::from(w) - 1.0));
            if lo > hi {
                continue;
            }
            rows_checked += 1;
            // A cut out of the fixed-point ranges takes `rows`' rows (tested below).
            if cut != IntCut::All {
                assert!(rows.0 <= j && j < rows.1, "{sil:?}: row {j} outside {rows:?}");
            }
            let (glo, ghi) = got.unwrap_or_else(|| panic!("{sil:?}: row {j} empty"));
            assert!(
                f64::from(glo) <= lo && f64::from(ghi) > hi,
                "{sil:?}: row {j}: {glo}..{ghi} misses {lo}..={hi}"
            );
            if cut != IntCut::All {
                assert!(
                    f64::from(glo) >= lo - 2.0 && f64::from(ghi) <= hi + 3.0,
                    "{sil:?}: row {j}: {glo}..{ghi} much wider than {lo}..={hi}"
                );
            }
        }
    };
    for _ in 0..400 {
        let Some((camera, l, radius)) = random_view(&mut next) else {
            continue;
        };
        let size = camera.size();
        let sil = Silhouette::new(l, radius, &camera, Margin::Linear, next(0.0, 0.01));
        check(sil, (size.width, size.height));
    }
    for _ in 0..3_000 {
        let y0 = next(-500.0, 3_000.0);
        let sil = Silhouette(Ellipse {
            y0i: y0.floor(),
            y0f: y0 - y0.floor(),
            q: next(0.0, 1.0).powi(4) * 300.0 + f32::MIN_POSITIVE,
            h0: next(0.0, 1.0).powi(3) * 4.0e6,
            xc0: next(-500.0, 3_000.0),
            kx: next(-3.0, 3.0),
        });
        check(sil, (2_500, 2_500));
    }
    assert!(rows_checked > 100_000, "too few rows checked: {rows_checked}");
    // Out of the fixed-point ranges: every column.
    let ellipse = |y0i: f32, q: f32, h0: f32, kx: f32| {
        Silhouette(Ellipse {
            y0i,
            y0f: 0.25,
            q,
            h0,
            xc0: 5.0,
            kx,
        })
    };
    assert_ne!(ellipse(10.0, 1.0, 100.0, 0.5).int_cut_rows(48).1, IntCut::All);
    for sil in [
        ellipse(10.0, 300.0, 100.0, 0.5),
        ellipse(10.0, 1.0, 3.0e7, 0.5),
        ellipse(10.0, 1.0, 100.0, 4.0e4),
        ellipse(10.0, f32::NAN, 100.0, 0.5),
        // An ellipse (q > 0) whose other coefficients are not finite: int_cut's
        // own rejection, not `ALL`'s.
        ellipse(10.0, 1.0, f32::NAN, 0.5),
        ellipse(f32::NAN, 1.0, 100.0, 0.5),
        ellipse(10.0, 1.0, 100.0, f32::INFINITY),
        ellipse(3.0e5, 1.0, 100.0, 0.5),
        Silhouette::ALL,
    ] {
        assert_eq!(sil.int_cut_rows(48).1, IntCut::All, "{sil:?}");
    }
    assert_eq!(IntCut::All.row_span(7, 48), Some((0, 48)));
}

/// The integer cut's coefficients against their definitions evaluated in `f64` (the
/// roundings [`IntCut`] states): `y12`, `q24`, `xc16` and `kx16` equal, `h8` the
/// exact ceiling (the `f64` product rounded up by a relative `2⁻⁵⁰` more can be one
/// above it, never below), and `pad16` at least `⌈2¹⁶·(pad + e)⌉` in `f64` and at
/// most 3/65536 above it: random coefficients as above.
#[test]
fn int_cut_coefficients_are_their_definitions() {
    let mut next = uniform(0x2545_f491_4f6c_dd1d);
    let mut compared = 0;
    for _ in 0..20_000 {
        let y0 = next(-500.0, 3_000.0);
        let (y0i, y0f) = (y0.round(), y0 - y0.round());
        let (q, h0) = (
            next(0.0, 1.0).powi(4) * 300.0 + f32::MIN_POSITIVE,
            next(0.0, 1.0).powi(3) * 4.0e6,
        );
        let (xc0, kx) = (next(-500.0, 3_000.0), next(-3.0, 3.0));
        let sil = Silhouette(Ellipse {
            y0i,
            y0f,
            q,
            h0,
            xc0,
            kx,
        });
        let ((j0, j1), cut) = sil.int_cut_rows(2_500);
        let IntCut::Ellipse {
            y12,
            q24,
            h8,
            xc16,
            kx16,
            pad16,
        } = cut
        else {
            continue;
        };
        let [y0i, y0f, q, h0, xc0, kx] = [y0i, y0f, q, h0, xc0, kx].map(f64::from);
        let h0_up = h0 * (1.0 + TWO_M16) * (1.0 + 1.0 / (1u64 << 50) as f64);
        assert_eq!(y12, (y0i * 4096.0) as i32 + (y0f * 4096.0).floor() as i32);
        assert_eq!(q24, (q * 16_777_216.0).floor() as u32);
        let h8_f64 = (h0_up * 256.0).ceil() as u32;
        assert!(h8 <= h8_f64 && h8 + 1 >= h8_f64, "h8 {h8} vs {h8_f64}");
        assert!(f64::from(h8) >= h0 * (1.0 + TWO_M16) * 256.0);
        assert_eq!(xc16, (xc0 * 65_536.0).round() as i32);
        assert_eq!(kx16, (kx * 65_536.0).round() as i32);
        let y0 = y0i + y0f;
        let dy_max = (f64::from(j0) - y0).abs().max((f64::from(j1) - y0).abs());
        let centre_err = TWO_M17 + TWO_M17 * dy_max + (kx.abs() + TWO_M17) / 4096.0 + TWO_M16;
        let pad = 1.0 + (xc0.abs() + kx.abs() * dy_max + h0_up.sqrt()) * TWO_M20 + centre_err;
        let pad16_f64 = (pad * 65_536.0).ceil() as i32;
        assert!(
            pad16 >= pad16_f64 && pad16 <= pad16_f64 + 3,
            "pad16 {pad16} vs {pad16_f64}"
        );
        compared += 1;
    }
    assert!(compared > 10_000, "too few cuts compared: {compared}");
}

/// `rows` is exactly the set of rows passing `row_span`'s test, so no row outside
/// it has a span: random spheres and cameras (on screen, off screen above and
/// below, sub-pixel, huge, with and without a margin), plain and random
/// coefficients near the ends of the image, and the degenerate cases (every row).
/// `on_plane` holds every pixel whose ray (the ideal one, or one turned by up to the
/// stepping error) meets the plane inside the disc (and the cylinder): random
/// cameras, planes, discs and cylinders, every pixel. The same set with a radius
/// 5 % short misses some of them: the check can fail.
#[test]
fn on_plane_holds_every_pixel_whose_ray_meets_it() {
    let mut next = uniform(0x5851_f42d_4c95_7f2d);
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let unit = |a: [f64; 3]| {
        let l = dot(a, a).sqrt();
        [a[0] / l, a[1] / l, a[2] / l]
    };
    let v64 = |v: Vec3| [f64::from(v.x), f64::from(v.y), f64::from(v.z)];
    let (mut inside, mut missed_short, mut bounded) = (0u32, 0u32, 0u32);
    for case in 0..300 {
        let Some((camera, _, _)) = random_view(&mut next) else {
            continue;
        };
        let size = camera.size();
        let eye = v64(camera.eye());
        let n = unit([f64::from(next(-0.5, 0.5)), 1.0, f64::from(next(-0.5, 0.5))]);
        // A point of the plane near the origin, relative to the eye.
        let on = [
            f64::from(next(-2.0, 2.0)) - eye[0],
            f64::from(next(-2.5, 0.0)) - eye[1],
            f64::from(next(-2.0, 2.0)) - eye[2],
        ];
        let radius = f64::from(next(0.05, 2.0));
        let axis = (case % 2 == 1).then(|| {
            let a = unit([
                f64::from(next(-1.0, 1.0)),
                f64::from(next(0.5, 2.0)),
                f64::from(next(-1.0, 1.0)),
            ]);
            (a, radius * dot(a, n) * f64::from(next(0.5, 1.0)))
        });
        let step_err = if case % 3 == 0 { 0.0 } else { next(0.0, 1e-4) };
        let within = |p: [f64; 3], short: f64| {
            let q = [p[0] - on[0], p[1] - on[1], p[2] - on[2]];
            dot(q, q) <= (radius * short).powi(2)
                && axis.is_none_or(|(a, r)| dot(q, q) - dot(q, a).powi(2) <= (r * short).powi(2))
        };
        let sil = Silhouette::on_plane(on, n, radius, axis, &camera, step_err);
        let short = Silhouette::on_plane(
            on,
            n,
            radius * 0.95,
            axis.map(|(a, r)| (a, r * 0.95)),
            &camera,
            0.0,
        );
        if sil.is_all() {
            continue;
        }
        bounded += 1;
        let (f, du, dv) = (
            v64(camera.first_direction()),
            v64(camera.pixel_step()),
            v64(camera.scanline_step()),
        );
        let s = dot(on, n);
        for j in 0..size.height {
            for i in 0..size.width {
                let (x, y) = (f64::from(i), f64::from(j));
                let turn = f64::from(step_err);
                let e = [
                    f64::from(next(-1.0, 1.0)) * turn / 2.0,
                    f64::from(next(-1.0, 1.0)) * turn / 2.0,
                    f64::from(next(-1.0, 1.0)) * turn / 2.0,
                ];
                let d = [
                    f[0] + x * du[0] + y * dv[0] + e[0],
                    f[1] + x * du[1] + y * dv[1] + e[1],
                    f[2] + x * du[2] + y * dv[2] + e[2],
                ];
                let t = s / dot(n, d);
                if !(t > 0.0) {
                    continue;
                }
                let p = [t * d[0], t * d[1], t * d[2]];
                if !within(p, 1.0) {
                    continue;
                }
                inside += 1;
                let holds = |sil: Silhouette| {
                    sil.row_span(j, 0, size.width)
                        .is_some_and(|(lo, hi)| lo <= i && i < hi)
                };
                assert!(
                    holds(sil),
                    "case {case}: pixel ({i}, {j}) meets the disc, outside {sil:?}"
                );
                if within(p, 0.95) && !short.is_all() && !holds(short) {
                    // Inside the short disc too, yet outside its region: cannot be.
                    panic!("case {case}: pixel ({i}, {j}) outside the short region");
                }
                if !within(p, 0.95) && !short.is_all() && !holds(short) {
                    missed_short += 1;
                }
            }
        }
    }
    assert!(
        bounded > 100 && inside > 10_000,
        "{bounded} bounded cases, {inside} pixels inside"
    );
    assert!(
        missed_short > 100,
        "a 5 % shorter disc missed only {missed_short} pixels"
    );
}

#[test]
fn rows_hold_every_row_span() {
    let mut next = uniform(0x2545_f491_4f6c_dd1d);
    let check = |sil: Silhouette, (w, h): (u32, u32)| {
        let (j0, j1) = sil.rows(h);
        assert!(j0 <= j1 && j1 <= h, "{sil:?}: rows {j0}..{j1} of {h}");
        let Some(Ellipse { y0i, y0f, q, h0, .. }) = sil.get() else {
            return 0;
        };
        let mut spans = 0;
        for j in 0..h {
            let passes = !(Silhouette::row_cut(j, y0i, y0f, q, h0).1 < 0.0);
            assert_eq!(passes, (j0..j1).contains(&j), "{sil:?}: row {j}, rows {j0}..{j1}");
            if sil.row_span(j, 0, w).is_some() {
                assert!(
                    (j0..j1).contains(&j),
                    "{sil:?}: row {j} has a span outside {j0}..{j1}"
                );
                spans += 1;
            }
        }
        spans
    };
    let mut spans = 0;
    for _ in 0..400 {
        let Some((camera, l, radius)) = random_view(&mut next) else {
            continue;
        };
        let size = camera.size();
        let margin = if next(0.0, 1.0) < 0.5 {
            0.0
        } else {
            next(0.0, 0.01)
        };
        let sil = Silhouette::new(l, radius, &camera, Margin::Linear, margin);
        spans += check(sil, (size.width, size.height));
    }
    // Random coefficients: centres near and past the image's ends, thin and tall.
    for _ in 0..2_000 {
        let y0 = next(-50.0, 350.0);
        let sil = Silhouette(Ellipse {
            y0i: y0.floor(),
            y0f: y0 - y0.floor(),
            q: next(0.0, 1.0).powi(4) * 50.0 + f32::MIN_POSITIVE,
            h0: next(-10.0, 1.0e4),
            xc0: next(-10.0, 300.0),
            kx: next(-2.0, 2.0),
        });
        spans += check(sil, (300, 300));
    }
    assert!(spans > 10_000, "too few rows with spans: {spans}");
    // `ALL` (q ≤ 0 or NaN) and ellipses whose coefficients are not finite.
    for (q, h0) in [
        (f32::NAN, 1.0),
        (0.0, 1.0),
        (-1.0, 1.0),
        (f32::INFINITY, 1.0),
        (1.0, f32::NAN),
    ] {
        let sil = Silhouette(Ellipse {
            y0i: 10.0,
            y0f: 0.5,
            q,
            h0,
            xc0: 5.0,
            kx: 0.0,
        });
        assert_eq!(sil.rows(48), (0, 48));
    }
    assert_eq!(Silhouette::ALL.rows(48), (0, 48));
    assert_eq!(Silhouette::ALL.rows(0), (0, 0));
}

/// `band_reach` contains every point of the ellipse in the band, and `band_inside`
/// holds only columns whose whole vertical segment is inside, on random spheres
/// seen by random cameras; probed on a fine grid, at the band's ends and at the
/// rows where the left and right edges reach furthest (where a reach taken at the
/// band's ends alone would be too narrow).
#[test]
fn band_reach_and_inside_hold_on_a_fine_grid() {
    let mut next = uniform(0x9E37_79B9_7F4A_7C15);
    let (mut probed, mut inside_probed, mut interior_extreme) = (0u32, 0u32, 0u32);
    for _ in 0..300 {
        let eye = Vec3::new(next(-2.0, 2.0), next(-2.0, 2.0), next(4.0, 9.0));
        let camera = Camera::new(
            eye,
            Vec3::new(next(-1.0, 1.0), next(-1.0, 1.0), 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            next(0.4, 1.6),
            Size::new(64, 48),
        )
        .unwrap();
        let centre = Vec3::new(next(-3.0, 3.0), next(-3.0, 3.0), next(-3.0, 2.0));
        let radius = next(0.05, 1.5);
        let l = centre - eye;
        let Some(Ellipse {
            y0i,
            y0f,
            q,
            h0,
            xc0,
            kx,
        }) = Silhouette::new(l, radius, &camera, Margin::Linear, 0.0).get()
        else {
            continue;
        };
        let sil = Silhouette::new(l, radius, &camera, Margin::Linear, 0.0);
        let reach = sil.reach_consts();
        // The ellipse in f64 from its own f32 coefficients.
        let y0 = f64::from(y0i) + f64::from(y0f);
        let inside = |x: f64, y: f64| {
            let dy = y - y0;
            let xc = f64::from(xc0) + f64::from(kx) * dy;
            (x - xc) * (x - xc) <= f64::from(h0) - f64::from(q) * dy * dy
        };
        let half_height = (f64::from(h0) / f64::from(q)).sqrt();
        let m = (f64::from(h0) / (f64::from(q) * (f64::from(q) + f64::from(kx) * f64::from(kx)))).sqrt();
        for j in 0..48u32 {
            for h in [0.0f32, 0.25, 0.375] {
                let (yl, yh) = (f64::from(j) - f64::from(h), f64::from(j) + f64::from(h));
                let mut ys: std::vec::Vec<f64> =
                    (0..=16).map(|k| yl + (yh - yl) * f64::from(k) / 16.0).collect();
                // The edges' extreme rows, where they fall inside the band.
                for e in [y0 - f64::from(kx) * m, y0 + f64::from(kx) * m] {
                    if e > yl && e < yh {
                        ys.push(e);
                        interior_extreme += 1;
                    }
                }
                ys.extend(
                    [y0 - half_height, y0 + half_height]
                        .iter()
                        .filter(|&&y| y >= yl && y <= yh),
                );
                let got = sil.band_reach(j, h, reach);
                for &y in &ys {
                    let dy = y - y0;
                    let hw2 = f64::from(h0) - f64::from(q) * dy * dy;
                    if hw2 < 0.0 {
                        continue;
                    }
                    let xc = f64::from(xc0) + f64::from(kx) * dy;
                    for x in [xc - hw2.sqrt(), xc + hw2.sqrt()] {
                        let (lo, hi) = got.expect("the ellipse reaches this band");
                        assert!(
                            f64::from(lo) <= x && x <= f64::from(hi),
                            "row {j} ± {h}: point ({x}, {y}) outside reach {lo}..{hi}"
                        );
                        probed += 1;
                    }
                }
                if let Some((lo, hi)) = sil.band_inside(j, h) {
                    for k in 0..=8 {
                        let x = f64::from(lo) + (f64::from(hi) - f64::from(lo)) * f64::from(k) / 8.0;
                        for &y in &ys {
                            assert!(
                                inside(x, y),
                                "row {j} ± {h}: ({x}, {y}) in band_inside but outside"
                            );
                            inside_probed += 1;
                        }
                    }
                }
            }
        }
    }
    assert!(
        probed > 10_000 && inside_probed > 10_000,
        "{probed} / {inside_probed}"
    );
    // The extreme rows were inside bands often: the case the clamp exists for.
    assert!(interior_extreme > 100, "{interior_extreme}");
}

/// The shrunk silhouette lies inside the enlarged one and both bracket the sphere's
/// own (margins zero): its cut with a row is narrower, and it disappears for a
/// sphere too small for the margins.
#[test]
fn inner_silhouette_is_inside_the_outer() {
    let camera = Camera::new(
        Vec3::new(0.0, 0.0, 10.0),
        Vec3::ZERO,
        Vec3::new(0.0, 1.0, 0.0),
        0.8,
        Size::new(64, 48),
    )
    .unwrap();
    let l = Vec3::new(0.3, -0.2, -10.0);
    let outer = Silhouette::new(l, 1.0, &camera, Margin::Quadratic, 1e-6);
    let exact = Silhouette::new(l, 1.0, &camera, Margin::Linear, 0.0);
    let inner = Silhouette::inner(l, 1.0, &camera, Margin::Quadratic, 1e-6).unwrap();
    let width = |s: &Silhouette| match s.get() {
        Some(Ellipse { h0, .. }) => h0,
        None => f32::INFINITY,
    };
    assert!(width(&inner) < width(&exact) && width(&exact) < width(&outer));
    // Quadratic margin 2⁻¹⁷·|L|² ≈ 7.6e-4 against r² = 1e-4: nothing is proven.
    assert!(Silhouette::inner(l, 0.01, &camera, Margin::Quadratic, 0.0).is_none());
    assert!(Silhouette::inner(l, 0.01, &camera, Margin::Linear, 0.0).is_some());
}
