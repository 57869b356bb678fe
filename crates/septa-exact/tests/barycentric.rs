//! The barycentric predicate (Du et al. 2022, eq. 5-6) against a direct
//! evaluation: solve eq. 4 for the barycentric coordinates of `v` in exact
//! rationals and evaluate `g_{d+1}(v)` (eq. 3), for d = 0..3.
#![allow(clippy::needless_range_loop)] // matrix code reads best with indices

mod common;

use common::*;
use num_rational::BigRational;
use num_traits::{One, Zero};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use septa_exact::{
    barycentric_sign_ia, barycentric_sign_ia_f64_naive, barycentric_sign_mi, barycentric_sign_mi_f64_naive, Sign,
};

const CASES: usize = 5_000;

/// `g_N(v)` where `v` solves `A v = (0,..,0,1)`, `A` = rows `0..N-1` of `g`
/// plus a row of ones; `None` if `A` is singular. Gauss-Jordan on rationals.
fn g_at_vertex(g: &[Vec<BigRational>]) -> Option<BigRational> {
    let n = g.len();
    let mut a: Vec<Vec<BigRational>> = (0..n)
        .map(|i| {
            let mut row: Vec<BigRational> = if i + 1 == n { vec![BigRational::one(); n] } else { g[i].clone() };
            row.push(if i + 1 == n { BigRational::one() } else { BigRational::zero() });
            row
        })
        .collect();
    for c in 0..n {
        let p = (c..n).find(|&r| !a[r][c].is_zero())?;
        a.swap(c, p);
        let piv = a[c][c].clone();
        for x in a[c].iter_mut() {
            *x = &*x / &piv;
        }
        for r in 0..n {
            if r != c && !a[r][c].is_zero() {
                let f = a[r][c].clone();
                for k in 0..=n {
                    let t = &f * &a[c][k];
                    a[r][k] -= t;
                }
            }
        }
    }
    let v: Vec<BigRational> = (0..n).map(|i| a[i][n].clone()).collect();
    Some(g[n - 1].iter().zip(&v).map(|(x, y)| x * y).fold(BigRational::zero(), |s, t| s + t))
}

fn expected(g: Vec<Vec<BigRational>>) -> Sign {
    match g_at_vertex(&g) {
        None => Sign::Zero,
        Some(x) => sign_q(&x),
    }
}

/// Rows 0..N-1 random; the last row a rounded combination of them plus a
/// rounded constant (which leaves g_N(v) = that constant), sometimes nudged.
fn rows<const N: usize>(r: &mut ChaCha8Rng, scale: f64) -> [[f64; N]; N] {
    let mut g: [[f64; N]; N] = mat(r, |r| unit(r) * scale);
    let coef: Vec<f64> = (0..N).map(|_| unit(r)).collect();
    let konst = match r.gen_range(0..3) {
        0 => 0.0,
        1 => unit(r) * pow2(-r.gen_range(20..60)),
        _ => unit(r),
    };
    for j in 0..N {
        let mut s = konst * scale;
        for i in 0..N - 1 {
            s += coef[i] * g[i][j];
        }
        g[N - 1][j] = s;
    }
    if N > 1 && r.gen_bool(0.1) {
        // A singular A: g_1 constant on e, its zero set misses e or fills it.
        g[0] = [g[0][0]; N];
    } else if N > 1 && r.gen_bool(0.2) {
        // Small integers and an integer combination: g_N(v) is exactly 0.
        let m: [[f64; N]; N] = mat(r, |r| r.gen_range(-4i32..=4) as f64 * scale);
        g = m;
        for j in 0..N {
            g[N - 1][j] = g[0][j] * 2.0 - g[N - 2][j];
        }
    }
    g
}

/// Runs the IA check; returns (zero results, naive-baseline mismatches).
fn run_ia<const N: usize>(seed: u64) -> (usize, usize) {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    let (mut zeros, mut naive) = (0, 0);
    for i in 0..CASES {
        let g: [[f64; N]; N] = rows(&mut r, if i % 5 == 0 { 1e-200 } else { 1.0 });
        let want = expected(g.iter().map(|row| row.iter().map(|&x| q(x)).collect()).collect());
        assert_eq!(barycentric_sign_ia(&g), want, "IA d={} g={g:?}", N - 1);
        zeros += want.is_zero() as usize;
        naive += (barycentric_sign_ia_f64_naive(&g) != want) as usize;
    }
    (zeros, naive)
}

/// Runs the MI check; returns (zero results, naive-baseline mismatches).
fn run_mi<const N: usize>(seed: u64) -> (usize, usize) {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    let (mut zeros, mut naive) = (0, 0);
    for _ in 0..CASES {
        let x: [[f64; N]; N] = rows(&mut r, 1.0);
        let h: [[f64; N]; N] = mat(&mut r, |r| unit(r) * 4.0);
        let f: [[f64; N]; N] = std::array::from_fn(|i| std::array::from_fn(|j| h[i][j] + x[i][j]));
        let want = expected((0..N).map(|i| (0..N).map(|j| q(f[i][j]) - q(h[i][j])).collect()).collect());
        assert_eq!(barycentric_sign_mi(&f, &h), want, "MI d={} f={f:?} h={h:?}", N - 1);
        zeros += want.is_zero() as usize;
        naive += (barycentric_sign_mi_f64_naive(&f, &h) != want) as usize;
    }
    (zeros, naive)
}

#[test]
fn ia_matches_direct_evaluation_for_d_0_to_3() {
    let z = [run_ia::<1>(1), run_ia::<2>(2), run_ia::<3>(3), run_ia::<4>(4)];
    eprintln!("IA (zero results, naive mismatches) per d: {z:?}");
    assert!(z[1..].iter().all(|&(z, _)| z > 0), "degenerate cases must occur");
    // The naive baseline is exact at d = 0 and must fail sometimes above.
    assert_eq!(z[0].1, 0);
    assert!(z[1..].iter().all(|&(_, n)| n > 0), "the naive baseline should be fooled");
}

#[test]
fn mi_matches_direct_evaluation_for_d_0_to_3() {
    let z = [run_mi::<1>(5), run_mi::<2>(6), run_mi::<3>(7), run_mi::<4>(8)];
    eprintln!("MI (zero results, naive mismatches) per d: {z:?}");
    assert!(z[1..].iter().all(|&(z, _)| z > 0), "degenerate cases must occur");
    assert!(z[1..].iter().all(|&(_, n)| n > 0), "the naive baseline should be fooled");
}
