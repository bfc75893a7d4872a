//! The integer routines against the operators they stand in for, on ARMv6-M and
//! everywhere else: exact, over their whole ranges (exhaustively where marked
//! `#[ignore]`, run in release mode).

use super::*;

/// One step of the xorshift64 generator the random tests draw from.
fn xorshift(x: &mut u64) {
    *x ^= *x << 13;
    *x ^= *x >> 7;
    *x ^= *x << 17;
}

/// `div_q16(n, d) = ⌊n·2¹⁶/d⌋` for every divisor, the numerators at the ends and
/// spread over the range, every numerator for divisors at the normalisation's and
/// the table's boundaries; and outside the range (it divides there).
#[test]
fn div_q16_is_exact() {
    let check = |n: u32, d: u32| assert_eq!(div_q16(n, d), (n << 16) / d, "{n}/{d}");
    for d in 1..1u32 << 15 {
        for n in [0, 1, d / 3, d / 2, d.saturating_sub(2), d - 1, d] {
            check(n, d);
        }
        for k in 1..16 {
            check(d * k / 16, d);
        }
    }
    for d in [
        1, 2, 3, 63, 64, 65, 127, 128, 16_383, 16_384, 16_385, 16_447, 16_448, 32_703, 32_704, 32_767,
    ] {
        for n in 0..=d {
            check(n, d);
        }
    }
    assert_eq!(div_q16(5, 0), 0);
    assert_eq!(div_q16(40_000, 40_000), 1 << 16);
    assert_eq!(div_q16(3, 1 << 15), (3 << 16) >> 15);
}

/// Every `(n, d)` of [`div_q16`]'s range: 2²⁹ pairs, seconds in release mode
/// (`cargo test --release --lib -- --ignored _is_exact_everywhere`, run by `.ci/run`).
#[test]
#[ignore = "exhaustive: run in release mode"]
fn div_q16_is_exact_everywhere() {
    for d in 1..1u32 << 15 {
        for n in 0..=d {
            assert_eq!(div_q16(n, d), (n << 16) / d, "{n}/{d}");
        }
    }
}

/// `mul_wide_halves` equals the `u64` product for every size of `x` and `y`: the
/// halves' extremes, the carries out of the cross products and out of the low
/// word, and random values of every width.
#[test]
fn mul_wide_equals_the_product() {
    let mut x = 0x2545_f491_4f6c_dd1du64;
    let mut values = std::vec![0u32, 1, 0xffff, 0x1_0000, 0x1_ffff, 0x8000_0000, 0x7fff_ffff];
    values.extend([u32::MAX, u32::MAX - 1, 0xffff_0000, 0x0001_ffff, 0xfffe_0001]);
    for _ in 0..2_000 {
        xorshift(&mut x);
        values.push((x as u32) >> (x % 32));
    }
    for &a in &values {
        for &b in &values {
            assert_eq!(mul_wide_halves(a, b), u64::from(a) * u64::from(b), "{a}·{b}");
        }
    }
}

/// The signed wide products from halves (the ARMv6-M code) equal the operators for
/// operands of every sign and size: zero, ±1, the extremes (`MIN`, whose magnitude
/// is not an `i32`/`i64`), the halves' boundaries and random values of every width.
#[test]
fn signed_wide_products_equal_the_operators() {
    let mut x = 0x5851_f42d_4c95_7f2du64;
    let mut values = std::vec![0i64, 1, -1, 0xffff_ffff, -0xffff_ffff, 1 << 32, -(1 << 32)];
    values.extend([
        i64::MAX,
        i64::MIN,
        i64::MIN + 1,
        i64::from(i32::MAX),
        i64::from(i32::MIN),
    ]);
    for _ in 0..1_000 {
        xorshift(&mut x);
        values.push((x as i64) >> (x % 64));
    }
    for &a in &values {
        for &b in &values {
            assert_eq!(
                mul_i64_wide_halves(a, b),
                i128::from(a) * i128::from(b),
                "{a}·{b}"
            );
            let (a32, b32) = (a as i32, b as i32);
            assert_eq!(
                mul_i32_wide_halves(a32, b32),
                i64::from(a32) * i64::from(b32),
                "{a32}·{b32}"
            );
        }
    }
}

/// The word-wise shifts equal the operators, at every distance, on values with
/// every bit pattern class (zero, all ones, sign bit, random).
#[test]
fn word_shifts_equal_the_operators() {
    let mut x = 0x9e37_79b9_7f4a_7c15u64;
    let mut values = std::vec![
        0u64,
        1,
        u64::MAX,
        1 << 63,
        (1 << 63) - 1,
        0x8000_0001,
        0xffff_ffff
    ];
    for _ in 0..200 {
        xorshift(&mut x);
        values.push(x);
    }
    for &v in &values {
        for s in 0..64 {
            assert_eq!(shr_u64_low_words(v, s), (v >> s) as u32, "{v:#x} >> {s}");
            assert_eq!(
                shl_u64_words(v as u32, s),
                u64::from(v as u32) << s,
                "{v:#x} << {s}"
            );
        }
        for &w in &values {
            let wide = (u128::from(v) << 64) | u128::from(w);
            for s in 0..128 {
                assert_eq!(
                    shr_u128_low_words(wide, s),
                    (wide >> s) as u32,
                    "{wide:#x} >> {s}"
                );
            }
        }
    }
}

/// `r = ⌊√v⌋`: `r² ≤ v < (r + 1)²`.
fn check_isqrt32(v: u32) {
    let r = u64::from(isqrt32(v));
    assert!(
        r * r <= u64::from(v) && (r + 1) * (r + 1) > u64::from(v),
        "√{v}: {r}"
    );
}

/// [`isqrt32`] on the first million, next to every square (where `⌊√v⌋` steps), at
/// the normalisation's and the table's boundaries, and at the top of the range.
#[test]
fn isqrt32_is_exact() {
    for v in 0..1_000_000u32 {
        check_isqrt32(v);
    }
    for r in 0..=0xffffu32 {
        let sq = r * r;
        for v in [sq.wrapping_sub(1), sq, sq + 1, sq + r, sq + 2 * r] {
            check_isqrt32(v);
        }
    }
    for b in 0..32 {
        let p = 1u32 << b;
        for v in [p - 1, p, p + 1, p | (p >> 1), p | (p - 1)] {
            check_isqrt32(v);
        }
    }
    for k in 64..256u32 {
        let n = k << 24;
        for v in [n.wrapping_sub(1), n, n | 0xff_ffff] {
            check_isqrt32(v);
        }
    }
}

/// Every `u32`: 2³² roots, about a minute in release mode
/// (`cargo test --release --lib -- --ignored _is_exact_everywhere`, run by `.ci/run`).
#[test]
#[ignore = "exhaustive: run in release mode"]
fn isqrt32_is_exact_everywhere() {
    for v in 0..=u32::MAX {
        check_isqrt32(v);
    }
}

/// `0 ≤ √v − isqrt(v) < 2^(h+1)`, at the bound's worst places (just below powers of
/// four, where the truncated bits are all ones) and on random values of every size.
#[test]
fn isqrt_bound() {
    let mut vs = std::vec::Vec::new();
    // The kernel's discriminants are below 2¹⁰⁶ (roots below 2⁵³: no u64 overflow).
    for b in 0..106u32 {
        let p = 1u128 << b;
        vs.extend([p, p - 1, p + 1, p | (p >> 1), (p << 1) - 1]);
    }
    let mut x = 0x9e37_79b9_7f4a_7c15u64;
    for _ in 0..100_000 {
        xorshift(&mut x);
        let y = x.rotate_left(17) ^ 0x5555;
        vs.push(((u128::from(x) << 64) | u128::from(y)) >> (22 + x % 106));
    }
    for v in vs {
        let bits = 128 - v.leading_zeros();
        // The smallest admissible h, and larger ones (a frame's h fits its largest D).
        let h0 = (bits.max(32) - 32).div_ceil(2);
        for h in [h0, h0 + 1, h0 + 7] {
            let got = isqrt(v, h);
            // Exact check in integers: got² ≤ v < (got + 2^(h+1))².
            assert!(u128::from(got) * u128::from(got) <= v, "{v}: {got} too large");
            let hi = u128::from(got) + (1u128 << (h + 1));
            assert!(hi * hi > v, "{v}: {got} below √v by 2^(h+1) or more, h {h}");
        }
    }
}

/// The written-out `f32` product equals the `f64` operator's, bit for bit: on random
/// bit patterns (every class: zeros, subnormals, infinities, NaN payloads), at the
/// exponent range's ends, and where the significands' product does and does not carry
/// into bit 47.
#[test]
fn f32_products_equal_the_operator() {
    let same = |a: f32, b: f32| {
        let (got, want) = (mul_f32_exact_words(a, b), f64::from(a) * f64::from(b));
        assert!(
            got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
            "{a:e} × {b:e}: {got:e} vs {want:e}"
        );
        assert_eq!(mul_f32_exact(a, b).to_bits(), got.to_bits());
    };
    let mut x = 0x9e37_79b9_7f4a_7c15u64;
    for _ in 0..2_000_000 {
        xorshift(&mut x);
        same(f32::from_bits(x as u32), f32::from_bits((x >> 32) as u32));
    }
    let edges = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        1.5,
        f32::MIN_POSITIVE,
        f32::MAX,
        -f32::MAX,
        f32::EPSILON,
        f32::from_bits(1),
        f32::from_bits(0x007f_ffff),
        f32::from_bits(0x3fff_ffff),
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
    ];
    for a in edges {
        for b in edges {
            same(a, b);
        }
    }
}
