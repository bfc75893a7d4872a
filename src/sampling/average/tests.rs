//! The sRGB tables and the linear-light average against the IEC 61966-2-1 formulas in
//! `f64`.

use super::{decode, encode};
use std::println;

fn srgb_to_linear(c: f64) -> f64 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

fn linear_to_srgb(l: f64) -> f64 {
    if l <= 0.003_130_8 {
        l * 12.92
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    }
}

/// A constant colour averages to itself, for every level and count.
#[test]
fn encode_steps_at_most_once_per_bucket() {
    use super::{LEVELS_BELOW_HIGH, LEVELS_BELOW_LOW, LINEAR_THRESHOLDS};
    let bucket = |x: u32| if x < 1 << 16 { x >> 8 } else { (1 << 8) + (x >> 10) };
    for w in LINEAR_THRESHOLDS.windows(2) {
        assert_ne!(
            bucket(w[0]),
            bucket(w[1]),
            "thresholds {} and {} share a bucket",
            w[0],
            w[1]
        );
    }
    // The tables count the thresholds below each bucket's start.
    for (b, &k) in LEVELS_BELOW_LOW.iter().enumerate() {
        assert_eq!(
            usize::from(k),
            LINEAR_THRESHOLDS.partition_point(|&t| t < (b as u32) << 8)
        );
    }
    for (b, &k) in LEVELS_BELOW_HIGH.iter().enumerate() {
        assert_eq!(
            usize::from(k),
            LINEAR_THRESHOLDS.partition_point(|&t| t < (b as u32) << 10)
        );
    }
}

#[test]
fn encode_equals_the_search_for_every_mean() {
    use super::LINEAR_THRESHOLDS;
    for count in 1..=16u32 {
        // Every sum of `count` decoded values (each ≤ 65535), step 1 for the
        // largest grid and a prime step otherwise.
        let step = if count == 16 { 1 } else { 7 };
        for sum in (0..=count * 65535).step_by(step) {
            let want = LINEAR_THRESHOLDS.partition_point(|&t| t * count <= sum * 16);
            assert_eq!(usize::from(encode(sum, count)), want, "sum {sum}, count {count}");
        }
    }
}

#[test]
fn constant_round_trips() {
    for n in [4u32, 9, 16] {
        for v in 0..=255u8 {
            assert_eq!(encode(decode(v) * n, n), v, "level {v}, {n} samples");
        }
    }
}

/// The table average of 8-bit-rounded samples against the exact linear-light
/// average of the unrounded ones, encoded and rounded in f64: at most one level.
#[test]
fn rounded_samples_within_one_level() {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut worst, mut off) = (0.0f64, 0usize);
    let trials = 200_000;
    for t in 0..trials {
        let n = [4usize, 9, 16][t % 3];
        // Two-tone samples (an edge) and spread ones, over the whole range.
        let (a, b) = (next() * 255.0, next() * 255.0);
        let unrounded: std::vec::Vec<f64> = (0..n)
            .map(|_| {
                if t % 2 == 0 {
                    if next() < 0.5 {
                        a
                    } else {
                        b
                    }
                } else {
                    next() * 255.0
                }
            })
            .collect();
        let exact_lin = unrounded.iter().map(|&x| srgb_to_linear(x / 255.0)).sum::<f64>() / n as f64;
        let exact = linear_to_srgb(exact_lin) * 255.0;
        let sum: u32 = unrounded.iter().map(|&x| decode(x.round() as u8)).sum();
        let got = f64::from(encode(sum, n as u32));
        let diff = (got - exact).abs();
        worst = worst.max(diff);
        if (got - exact.round()).abs() > 0.0 {
            off += 1;
        }
        assert!(diff <= 1.0, "{unrounded:?}: {got} vs {exact}");
    }
    // Not vacuous: rounding the samples first does change some results.
    assert!(off > 0);
    println!(
        "table average of rounded samples vs exact average of unrounded: max {worst:.3} levels, \
         {off} of {trials} results differ from the exact one rounded"
    );
}

/// Exactly on a threshold's neighbourhood the encoding rounds to nearest: a mean
/// just below `k + ½` (encoded) gives k, just above gives k + 1.
#[test]
fn encoding_rounds_to_nearest() {
    let mut checked = 0;
    for k in 0..255u32 {
        let mid = srgb_to_linear((f64::from(k) + 0.5) / 255.0) * 65535.0;
        // 16 samples summing to just below / above 16·mid (one unit of slack on
        // the table's integer rounding).
        let below = (mid * 16.0 - 2.0).floor() as u32;
        let above = (mid * 16.0 + 2.0).ceil() as u32;
        assert_eq!(u32::from(encode(below, 16)), k, "below k + ½, k = {k}");
        assert_eq!(u32::from(encode(above, 16)), k + 1, "above k + ½, k = {k}");
        checked += 1;
    }
    assert_eq!(checked, 255);
}
