//! `det_sign` / `det_sign_diff` against an independent big-rational
//! reference (num-rational), for N = 1..=4, both forms, on random,
//! near-degenerate, exactly degenerate and extreme-magnitude inputs.
#![allow(clippy::needless_range_loop)] // matrix code reads best with indices

mod common;

use common::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const CASES: usize = 15_000;

fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// Runs `body` for N = 1..=4 with a fresh tally, then checks the tally.
macro_rules! for_each_n {
    ($body:ident, $seed:expr, $check:expr) => {{
        let t1 = $body::<1>(&mut rng($seed + 1));
        let t2 = $body::<2>(&mut rng($seed + 2));
        let t3 = $body::<3>(&mut rng($seed + 3));
        let t4 = $body::<4>(&mut rng($seed + 4));
        for (n, t) in [(1, &t1), (2, &t2), (3, &t3), (4, &t4)] {
            eprintln!("{} N={n}: {t:?}", stringify!($body));
            let check: &dyn Fn(usize, &Tally) = &$check;
            check(n, t);
        }
    }};
}

fn random_ia<const N: usize>(r: &mut ChaCha8Rng) -> Tally {
    let mut t = Tally::default();
    for i in 0..CASES {
        let m: [[f64; N]; N] = if i % 4 == 0 { mat(r, |r| r.gen_range(-3i32..=3) as f64) } else { mat(r, unit) };
        check_ia(&m, &mut t);
    }
    t
}

fn random_mi<const N: usize>(r: &mut ChaCha8Rng) -> Tally {
    let mut t = Tally::default();
    for i in 0..CASES {
        let (a, b): ([[f64; N]; N], [[f64; N]; N]) = if i % 4 == 0 {
            (mat(r, |r| r.gen_range(-3i32..=3) as f64), mat(r, |r| r.gen_range(-3i32..=3) as f64))
        } else {
            (mat(r, unit), mat(r, unit))
        };
        check_mi(&a, &b, &mut t);
    }
    t
}

#[test]
fn random_values_ia() {
    // Small-integer matrices are singular often enough to exercise zeros.
    for_each_n!(random_ia, 100, |n, t: &Tally| assert!(n == 1 || t.zero > 0));
}

#[test]
fn random_values_mi() {
    for_each_n!(random_mi, 200, |n, t: &Tally| assert!(n == 1 || t.zero > 0));
}

fn perturbation(r: &mut ChaCha8Rng) -> Option<i32> {
    if r.gen_bool(0.2) {
        None
    } else {
        Some(r.gen_range(20..=80))
    }
}

fn near_degenerate_ia<const N: usize>(r: &mut ChaCha8Rng) -> Tally {
    let mut t = Tally::default();
    for _ in 0..CASES {
        let mut m: [[f64; N]; N] = mat(r, unit);
        let k = r.gen_range(0..N);
        let p = perturbation(r);
        near_dependent(r, &mut m, k, p);
        if r.gen_bool(0.3) {
            // A column scaled far down: rows then span more than 62 bits,
            // so the integer shortcut declines and expansions decide.
            let (c, f) = (r.gen_range(0..N), pow2(-r.gen_range(20..=120)));
            m.iter_mut().for_each(|row| row[c] *= f);
        }
        check_ia(&m, &mut t);
    }
    t
}

fn near_degenerate_mi<const N: usize>(r: &mut ChaCha8Rng) -> Tally {
    let mut t = Tally::default();
    for i in 0..CASES {
        // x is nearly singular; a - b == x only up to rounding, so the
        // predicate must see through the rounding of the differences.
        let mut x: [[f64; N]; N] = mat(r, unit);
        let k = r.gen_range(0..N);
        let p = perturbation(r);
        near_dependent(r, &mut x, k, p);
        let mut b: [[f64; N]; N] = mat(r, |r| unit(r) * 8.0);
        if r.gen_bool(0.3) {
            // As for IA: wide rows push the exact tier onto expansions.
            let (c, f) = (r.gen_range(0..N), pow2(-r.gen_range(20..=120)));
            x.iter_mut().for_each(|row| row[c] *= f);
            b.iter_mut().for_each(|row| row[c] *= f);
        }
        let a: [[f64; N]; N] = std::array::from_fn(|i| std::array::from_fn(|j| b[i][j] + x[i][j]));
        if i % 2 == 0 {
            check_mi(&a, &b, &mut t);
        } else {
            check_mi(&b, &a, &mut t);
        }
    }
    t
}

#[test]
fn near_degenerate_ia_all_n() {
    // The naive sign must be wrong sometimes for N >= 2, or the generator
    // is not near-degenerate enough to test anything.
    for_each_n!(near_degenerate_ia, 300, |n, t: &Tally| assert!(n < 2 || t.naive_wrong > 0));
}

#[test]
fn near_degenerate_mi_all_n() {
    for_each_n!(near_degenerate_mi, 400, |n, t: &Tally| assert!(n < 2 || t.naive_wrong > 0));
}

/// An exactly singular matrix of one of several patterns, rows and columns
/// scaled by powers of two (exact, so it stays singular) within `2^-s..2^s`.
fn singular<const N: usize>(r: &mut ChaCha8Rng, s: i32) -> [[f64; N]; N] {
    let mut m: [[f64; N]; N] = mat(r, unit);
    let i = r.gen_range(0..N);
    let j = (i + r.gen_range(1..N.max(2))) % N;
    match r.gen_range(0..6) {
        0 if N > 1 => m[j] = m[i],
        1 if N > 1 => m[j] = m[i].map(|x| 2.0 * x),
        2 => m[i] = [0.0; N],
        3 => m.iter_mut().for_each(|row| row[i] = 0.0),
        4 => {
            // Small integers: singular with high probability for N >= 2,
            // and made singular by a repeated column otherwise.
            m = mat(r, |r| r.gen_range(-2i32..=2) as f64);
            if N > 1 {
                for row in m.iter_mut() {
                    row[j] = row[i] + row[j] * 0.0;
                }
            }
        }
        _ => {
            if N > 1 {
                near_dependent(r, &mut m, i, None);
                // A rounded combination is rarely exactly dependent; use
                // a sum of two rows, which is exact for small integers.
                m = mat(r, |r| r.gen_range(-8i32..=8) as f64);
                for c in 0..N {
                    m[i][c] = m[j][c] + m[(j + 1) % N][c] * if (j + 1) % N == i { 0.0 } else { 1.0 };
                }
            } else {
                m[0][0] = 0.0;
            }
        }
    }
    for row in m.iter_mut() {
        let e = pow2(r.gen_range(-s..=s));
        row.iter_mut().for_each(|x| *x *= e);
    }
    for c in 0..N {
        let e = pow2(r.gen_range(-s..=s));
        m.iter_mut().for_each(|row| row[c] *= e);
    }
    m
}

fn degenerate_ia<const N: usize>(r: &mut ChaCha8Rng) -> Tally {
    let mut t = Tally::default();
    for i in 0..CASES {
        let s = if i % 3 == 0 { 400 } else { 20 };
        let m: [[f64; N]; N] = singular(r, s);
        check_ia(&m, &mut t);
    }
    t
}

fn degenerate_mi<const N: usize>(r: &mut ChaCha8Rng) -> Tally {
    let mut t = Tally::default();
    for i in 0..CASES {
        let s = if i % 3 == 0 { 300 } else { 20 };
        let (a, b) = match i % 4 {
            // b = a: the zero matrix.
            0 => {
                let a: [[f64; N]; N] = mat(r, unit);
                (a, a)
            }
            // Duplicate rows in both a and b.
            1 if N > 1 => {
                let (mut a, mut b): ([[f64; N]; N], [[f64; N]; N]) = (mat(r, unit), mat(r, unit));
                a[N - 1] = a[0];
                b[N - 1] = b[0];
                (a, b)
            }
            // a - b exactly singular: b = a - x with x singular and
            // integer-valued, so the difference is exact.
            2 => {
                let x: [[f64; N]; N] = singular(r, 0);
                let a: [[f64; N]; N] = mat(r, |r| r.gen_range(-16i32..=16) as f64);
                (a, std::array::from_fn(|i| std::array::from_fn(|j| a[i][j] - x[i][j])))
            }
            // Arbitrary-magnitude singular a, b = 0 (the IA case through MI).
            _ => (singular(r, s), [[0.0; N]; N]),
        };
        check_mi(&a, &b, &mut t);
    }
    t
}

#[test]
fn exactly_degenerate_ia() {
    for_each_n!(degenerate_ia, 500, |_n, t: &Tally| assert!(t.zero * 2 > t.cases));
}

#[test]
fn exactly_degenerate_mi() {
    for_each_n!(degenerate_mi, 600, |_n, t: &Tally| assert!(t.zero * 2 > t.cases));
}

/// Entries over the whole double range: wide exponents, subnormals, zeros,
/// one row huge and another tiny, values at the exponent-window edges.
fn extreme<const N: usize>(r: &mut ChaCha8Rng, kind: usize) -> [[f64; N]; N] {
    match kind % 5 {
        0 => mat(r, |r| wide(r, -1000, 996, true)),
        1 => mat(r, |r| {
            if r.gen_bool(0.5) {
                let bits = r.gen_range(1u64..(1u64 << 52));
                if r.gen_bool(0.5) {
                    f64::from_bits(bits)
                } else {
                    -f64::from_bits(bits)
                }
            } else {
                wide(r, -1074, -900, true)
            }
        }),
        2 => {
            let mut m: [[f64; N]; N] = mat(r, |r| wide(r, -5, 5, true));
            let i = r.gen_range(0..N);
            m[i] = m[i].map(|x| x * 1e300);
            let j = r.gen_range(0..N);
            m[j] = m[j].map(|x| x * 1e-300);
            m
        }
        3 => {
            // Around the window edges 2^+-180, 2^+-250, 2^+-400.
            let w = [180, 250, 400][r.gen_range(0..3)];
            mat(r, |r| {
                let e = if r.gen_bool(0.5) { w } else { -w } + r.gen_range(-3..=3);
                wide(r, e, e, true)
            })
        }
        _ => {
            // Near-degenerate at a random huge or tiny scale.
            let mut m: [[f64; N]; N] = mat(r, unit);
            let k = r.gen_range(0..N);
            let p = Some(r.gen_range(30..=60));
            near_dependent(r, &mut m, k, p);
            let e = pow2(r.gen_range(-1000..=240));
            m.map(|row| row.map(|x| x * e))
        }
    }
}

fn magnitudes_ia<const N: usize>(r: &mut ChaCha8Rng) -> Tally {
    let mut t = Tally::default();
    for i in 0..CASES {
        let m: [[f64; N]; N] = extreme(r, i);
        check_ia(&m, &mut t);
    }
    t
}

fn magnitudes_mi<const N: usize>(r: &mut ChaCha8Rng) -> Tally {
    let mut t = Tally::default();
    // Half the cases: each needs ~2000-bit rationals on both sides.
    for i in 0..CASES / 2 {
        let a: [[f64; N]; N] = extreme(r, i);
        let b: [[f64; N]; N] = if i % 2 == 0 {
            extreme(r, i / 2)
        } else {
            // b close to a: differences far below the entries' size.
            a.map(|row| row.map(|x| if r.gen_bool(0.3) { x } else { x * (1.0 + unit(r) * 1e-12) }))
        };
        check_mi(&a, &b, &mut t);
    }
    t
}

#[test]
fn extreme_magnitudes_ia() {
    for_each_n!(magnitudes_ia, 700, |_n, t: &Tally| assert!(t.zero > 0));
}

#[test]
fn extreme_magnitudes_mi() {
    for_each_n!(magnitudes_mi, 800, |_n, t: &Tally| assert!(t.zero > 0));
}

/// The reference itself: integer scaling of rows (used above for speed)
/// agrees with plain Laplace expansion on `BigRational`s.
#[test]
fn reference_scaling_matches_plain_rational_laplace() {
    let mut r = rng(900);
    for i in 0..2000 {
        let m: [[f64; 3]; 3] = match i % 3 {
            0 => mat(&mut r, unit),
            1 => singular(&mut r, 300),
            _ => extreme(&mut r, i),
        };
        let rows: Vec<Vec<_>> = m.iter().map(|row| row.iter().map(|&x| q(x)).collect()).collect();
        assert_eq!(sign_q(&det_q(&rows)), ref_ia(&m), "{m:?}");
    }
}

/// Row scales putting products right at the underflow threshold while the
/// permanent straddles the hot filter's `2^-700` limit (N = 3: row 0 huge,
/// rows 1..2 tiny; N = 4: rows 0..1 huge, rows 2..3 tiny).
fn underflow_edge<const N: usize>(r: &mut ChaCha8Rng) -> [[f64; N]; N] {
    let mut m: [[f64; N]; N] = mat(r, unit);
    let k = r.gen_range(0..N);
    let p = if r.gen_bool(0.5) { None } else { Some(r.gen_range(20..=70)) };
    near_dependent(r, &mut m, k, p);
    let (big, tiny) = match N {
        3 => (r.gen_range(200..=300), r.gen_range(-560..=-470)),
        4 => (r.gen_range(100..=145), r.gen_range(-530..=-470)),
        _ => (r.gen_range(0..=300), r.gen_range(-560..=-470)),
    };
    let n_big = if N == 4 { 2 } else { 1 };
    for (i, row) in m.iter_mut().enumerate() {
        let f = pow2(if i < n_big { big } else { tiny });
        row.iter_mut().for_each(|x| *x *= f);
    }
    m
}

fn underflow_ia<const N: usize>(r: &mut ChaCha8Rng) -> Tally {
    let mut t = Tally::default();
    let before = septa_exact::stats::snapshot();
    for _ in 0..CASES / 2 {
        let m: [[f64; N]; N] = underflow_edge(r);
        check_ia(&m, &mut t);
    }
    // The reference calls no predicate, so the counts are ours alone.
    t.filter = septa_exact::stats::snapshot().since(&before).filter;
    t
}

fn underflow_mi<const N: usize>(r: &mut ChaCha8Rng) -> Tally {
    let mut t = Tally::default();
    for _ in 0..CASES / 2 {
        let x: [[f64; N]; N] = underflow_edge(r);
        // b on the same row scales as x, so a = b + x rounds like x does.
        let b: [[f64; N]; N] = std::array::from_fn(|i| {
            let s = x[i].iter().fold(0.0f64, |s, v| s.max(v.abs()));
            std::array::from_fn(|_| unit(r) * s)
        });
        let a: [[f64; N]; N] = std::array::from_fn(|i| std::array::from_fn(|j| b[i][j] + x[i][j]));
        check_mi(&a, &b, &mut t);
    }
    t
}

#[test]
fn underflow_edges_ia() {
    // Products straddle the subnormal range; the filter must still decide
    // a share of them (those with a large enough permanent), correctly.
    for_each_n!(underflow_ia, 1000, |n, t: &Tally| assert!(
        n < 3 || t.filter > 100,
        "N={n}: filter never decided near underflow"
    ));
}

#[test]
fn underflow_edges_mi() {
    for_each_n!(underflow_mi, 1100, |_n, _t: &Tally| ());
}
