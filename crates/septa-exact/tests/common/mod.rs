//! Shared helpers for the property tests: an independent big-rational
//! reference and seeded generators of matrices.
#![allow(clippy::needless_range_loop)] // matrix code reads best with indices
#![allow(dead_code)]

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use septa_exact::Sign;

/// The exact rational value of a finite double.
pub fn q(x: f64) -> BigRational {
    BigRational::from_float(x).expect("finite input")
}

/// Determinant by Laplace expansion along the first row, on rationals.
pub fn det_q(m: &[Vec<BigRational>]) -> BigRational {
    let n = m.len();
    if n == 0 {
        return BigRational::from_integer(1.into());
    }
    if n == 1 {
        return m[0][0].clone();
    }
    let mut acc = BigRational::zero();
    for c in 0..n {
        if m[0][c].is_zero() {
            continue;
        }
        let minor: Vec<Vec<BigRational>> = m[1..]
            .iter()
            .map(|r| r.iter().enumerate().filter(|&(j, _)| j != c).map(|(_, x)| x.clone()).collect())
            .collect();
        let t = &m[0][c] * det_q(&minor);
        if c % 2 == 0 {
            acc += t;
        } else {
            acc -= t;
        }
    }
    acc
}

/// Sign of a rational.
pub fn sign_q(x: &BigRational) -> Sign {
    if x.is_zero() {
        Sign::Zero
    } else if x.is_positive() {
        Sign::Positive
    } else {
        Sign::Negative
    }
}

/// Sign of the determinant of a rational matrix. Each row is first
/// multiplied by the lcm of its denominators (a positive factor, so the
/// sign is unchanged), after which Laplace expansion runs on integers and
/// needs no gcd normalisation (much faster for 1e-300-scale entries).
pub fn det_sign_q(m: Vec<Vec<BigRational>>) -> Sign {
    let ints: Vec<Vec<BigInt>> = m
        .into_iter()
        .map(|row| {
            let l = row.iter().fold(BigInt::one(), |l, x| l.lcm(x.denom()));
            row.into_iter().map(|x| (x * BigRational::from_integer(l.clone())).to_integer()).collect()
        })
        .collect();
    let d = det_z(&ints);
    if d.is_zero() {
        Sign::Zero
    } else if d.is_positive() {
        Sign::Positive
    } else {
        Sign::Negative
    }
}

/// Integer determinant by Laplace expansion along the first row.
pub fn det_z(m: &[Vec<BigInt>]) -> BigInt {
    let n = m.len();
    if n == 0 {
        return BigInt::one();
    }
    if n == 1 {
        return m[0][0].clone();
    }
    let mut acc = BigInt::zero();
    for c in 0..n {
        if m[0][c].is_zero() {
            continue;
        }
        let minor: Vec<Vec<BigInt>> = m[1..]
            .iter()
            .map(|r| r.iter().enumerate().filter(|&(j, _)| j != c).map(|(_, x)| x.clone()).collect())
            .collect();
        let t = &m[0][c] * det_z(&minor);
        if c % 2 == 0 {
            acc += t;
        } else {
            acc -= t;
        }
    }
    acc
}

/// Reference sign of `det(m)`.
pub fn ref_ia<const N: usize>(m: &[[f64; N]; N]) -> Sign {
    det_sign_q(m.iter().map(|row| row.iter().map(|&x| q(x)).collect()).collect())
}

/// Reference sign of `det(a - b)`, differences exact.
pub fn ref_mi<const N: usize>(a: &[[f64; N]; N], b: &[[f64; N]; N]) -> Sign {
    det_sign_q((0..N).map(|i| (0..N).map(|j| q(a[i][j]) - q(b[i][j])).collect()).collect())
}

/// Tally of reference signs, to show a category really exercises zeros.
#[derive(Default, Debug)]
pub struct Tally {
    pub cases: usize,
    pub zero: usize,
    pub naive_wrong: usize,
    /// Decided by the filter (set by tests that track it via `stats`).
    pub filter: u64,
}

/// Checks `det_sign` against the reference; returns the reference sign.
pub fn check_ia<const N: usize>(m: &[[f64; N]; N], t: &mut Tally) {
    let want = ref_ia(m);
    let got = septa_exact::det_sign(m);
    assert_eq!(got, want, "det_sign::<{N}> wrong on {m:?}");
    t.cases += 1;
    t.zero += want.is_zero() as usize;
    t.naive_wrong += (septa_exact::det_sign_f64_naive(m) != want) as usize;
}

/// Checks `det_sign_diff` against the reference.
pub fn check_mi<const N: usize>(a: &[[f64; N]; N], b: &[[f64; N]; N], t: &mut Tally) {
    let want = ref_mi(a, b);
    let got = septa_exact::det_sign_diff(a, b);
    assert_eq!(got, want, "det_sign_diff::<{N}> wrong on a = {a:?}, b = {b:?}");
    t.cases += 1;
    t.zero += want.is_zero() as usize;
    t.naive_wrong += (septa_exact::det_sign_diff_f64_naive(a, b) != want) as usize;
}

/// Uniform in `[-1, 1)`.
pub fn unit(rng: &mut ChaCha8Rng) -> f64 {
    rng.gen_range(-1.0..1.0)
}

/// A random matrix with entries from `f`.
pub fn mat<const N: usize>(rng: &mut ChaCha8Rng, mut f: impl FnMut(&mut ChaCha8Rng) -> f64) -> [[f64; N]; N] {
    let mut m = [[0.0; N]; N];
    for row in m.iter_mut() {
        for x in row.iter_mut() {
            *x = f(rng);
        }
    }
    m
}

/// `2^e` for any `e` in the double range (subnormal results included).
pub fn pow2(e: i32) -> f64 {
    if e >= -1022 {
        2f64.powi(e)
    } else {
        2f64.powi(-1022) * 2f64.powi(e + 1022)
    }
}

/// A value with a random mantissa and a binary exponent in `lo..=hi`,
/// random sign; a quarter of them zero when `zeros` is set.
pub fn wide(rng: &mut ChaCha8Rng, lo: i32, hi: i32, zeros: bool) -> f64 {
    if zeros && rng.gen_bool(0.25) {
        return 0.0;
    }
    let m: f64 = rng.gen_range(1.0..2.0);
    let s = if rng.gen_bool(0.5) { -1.0 } else { 1.0 };
    s * m * pow2(rng.gen_range(lo..=hi))
}

/// Makes row `k` of `m` a rounded combination of the other rows plus a
/// perturbation of relative size `2^-p` (no perturbation for `p = None`).
pub fn near_dependent<const N: usize>(rng: &mut ChaCha8Rng, m: &mut [[f64; N]; N], k: usize, p: Option<i32>) {
    let coef: Vec<f64> = (0..N).map(|_| unit(rng)).collect();
    for j in 0..N {
        let mut s = 0.0;
        for i in 0..N {
            if i != k {
                s += coef[i] * m[i][j];
            }
        }
        if let Some(p) = p {
            s += unit(rng) * pow2(-p);
        }
        m[k][j] = s;
    }
}

/// A 3x3 determinant in any [`septa_exact::Ring`]: the shape of the
/// orientation and line-order predicates of planar cutting.
pub fn det3<R: septa_exact::Ring>(m: &[[f64; 3]; 3]) -> R {
    let e = |i: usize, j: usize| R::of(m[i][j]);
    let minor = |a: usize, b: usize| e(1, a).mul(&e(2, b)).sub(&e(1, b).mul(&e(2, a)));
    e(0, 0).mul(&minor(1, 2)).sub(&e(0, 1).mul(&minor(0, 2))).add(&e(0, 2).mul(&minor(0, 1)))
}

/// [`det3`] in exact rationals.
pub fn det3_q(m: &[[f64; 3]; 3]) -> BigRational {
    let e = |i: usize, j: usize| q(m[i][j]);
    let minor = |a: usize, b: usize| e(1, a) * e(2, b) - e(1, b) * e(2, a);
    e(0, 0) * minor(1, 2) - e(0, 1) * minor(0, 2) + e(0, 2) * minor(0, 1)
}

/// The `i`-th matrix of the filtered-sign tests: entries from `adversarial`
/// (`i % 4 == 0`), small integers (exactly degenerate often) or moderate
/// doubles; for odd `i` the third row a rounded combination of the first
/// two, so the determinant is zero or tiny.
pub fn det3_case(r: &mut ChaCha8Rng, i: usize, adversarial: fn(&mut ChaCha8Rng) -> f64) -> [[f64; 3]; 3] {
    let mut m = [[0.0; 3]; 3];
    for row in m.iter_mut() {
        for x in row.iter_mut() {
            *x = match i % 4 {
                0 => adversarial(r),
                1 => r.gen_range(-8..8) as f64,
                _ => r.gen_range(-1.0..1.0) * pow2(r.gen_range(-3..3)),
            };
        }
    }
    if i % 2 == 1 {
        let (s, t) = (r.gen_range(-2..3) as f64 * 0.5, r.gen_range(-1.0..1.0));
        for j in 0..3 {
            m[2][j] = s * m[0][j] + if i % 4 == 3 { t * m[1][j] } else { m[1][j] };
        }
    }
    m
}
