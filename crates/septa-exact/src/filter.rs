//! Floating-point filters for `sign(det)` with proven error bounds.
//!
//! Method: Shewchuk 1997, "Adaptive Precision Floating-Point Arithmetic and
//! Fast Robust Geometric Predicates" (Sec. 4: evaluate in floating point,
//! bound the error by a constant times a "permanent" of absolute values,
//! and trust the sign only when the result exceeds the bound).
//!
//! ## Derivation (standard model `fl(a op b) = (a op b)(1 + d)`, `|d| <= u = 2^-53`)
//!
//! The determinant is evaluated by Laplace expansion (N = 3 along the first
//! row with 2x2 minors of rows 1,2; N = 4 along rows 0,1 with products of
//! complementary 2x2 minors, summed as `((t0+t1)+(t2+t3))+(t4+t5)`). Each of
//! the `N!` monomials `prod_i x_{i,s(i)}` reaches the result through at
//! most `m` roundings, so (Higham, *Accuracy and Stability*, Lemma 3.1) the
//! computed value is `sum_s (+-monomial_s)(1 + theta_s)` with
//! `|theta_s| <= gamma_m = m u / (1 - m u)`.
//!
//! * The **last** operation is an addition and rounding preserves sign, so
//!   the sign of the computed `D` is the sign of the exact sum `E` of its two
//!   computed operands, for which only `m' = m - 1` roundings count:
//!   `|E - det| <= gamma_{m'} P`, `P = sum_s |monomial_s| = perm(|X|)`.
//!   Since `|E| >= |D| / (1 + u)`, `|D| > (1 + u) gamma_{m'} P` proves
//!   `sign(D) = sign(det) != 0`.
//! * `P` is unknown; the same expression tree evaluated on `|x|` (all terms
//!   nonnegative, `mP` roundings per path) gives `P^ >= (1 - u)^mP P`, and the
//!   bound `B = fl(c P^) >= c P^ (1 - u)`. So it suffices that
//!   `c >= (1 + u) gamma_{m'} / (1 - u)^(mP + 1)
//!      = m' u + m'(m' + mP + 2) u^2 + O(u^3)`.
//! * MI form: each entry `x = fl(a - b) = (a - b)(1 + d)` adds `N` roundings
//!   to every monomial of both trees.
//!
//! | form | N | m' | mP | needed            | used `c`        |
//! |------|---|----|----|-------------------|-----------------|
//! | IA   | 2 | -  | -  | monotone compare (below) | -        |
//! | IA   | 3 | 4  | 5  | 4u + 44u^2        | 4u + 64u^2      |
//! | IA   | 4 | 7  | 8  | 7u + 119u^2       | 7u + 128u^2     |
//! | MI   | 2 | 3  | 4  | 3u + 27u^2        | 3u + 32u^2      |
//! | MI   | 3 | 7  | 8  | 7u + 119u^2       | 7u + 128u^2     |
//! | MI   | 4 | 11 | 12 | 11u + 275u^2      | 11u + 512u^2    |
//!
//! (The spare `u^2` coefficient dwarfs the `O(u^3)` remainder; every `c`
//! is an exactly representable double.)
//!
//! IA with N = 2 needs no bound: rounding is monotone, so
//! `fl(ad) > fl(bc)` implies `ad > bc` for *any* finite inputs (overflow and
//! underflow included); only `fl(ad) == fl(bc)` goes on.
//!
//! ## Validity: no underflow, no overflow
//!
//! The model above fails when a product underflows. Each filter therefore
//! also checks the *exponent window* of the entries: every nonzero `|x|` in
//! `[2^-W, 2^W]`, `W = 400, 250, 180` for `N = 2, 3, 4`. Then every entry is
//! an integer multiple of `2^(-W-52)`, every nonzero intermediate of degree
//! `k` is a multiple of, hence at least, `2^(-k(W+52)) >= 2^-960` (no product
//! underflows, `B` is a normal number) and at most `N! 2^(N(W+1)) < 2^990`
//! (nothing overflows). Inside the window a computed permanent `P^ == 0`
//! means every monomial is exactly zero, so the determinant is exactly zero:
//! zero rows and columns, common on degenerate grids, are decided here.
//! Outside the window the bignum tier decides.

use crate::Sign;

const U: f64 = f64::EPSILON / 2.0;
const C_IA3: f64 = 4.0 * U + 64.0 * U * U;
const C_IA4: f64 = 7.0 * U + 128.0 * U * U;
const C_MI2: f64 = 3.0 * U + 32.0 * U * U;
const C_MI3: f64 = 7.0 * U + 128.0 * U * U;
const C_MI4: f64 = 11.0 * U + 512.0 * U * U;

/// Exponent window `[2^-W, 2^W]` per size (see the module doc).
pub(crate) const fn window(n: usize) -> (f64, f64) {
    match n {
        0..=2 => (f64::from_bits((1023 - 400) << 52), f64::from_bits((1023 + 400) << 52)),
        3 => (f64::from_bits((1023 - 250) << 52), f64::from_bits((1023 + 250) << 52)),
        _ => (f64::from_bits((1023 - 180) << 52), f64::from_bits((1023 + 180) << 52)),
    }
}

/// What the filter concluded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Outcome {
    /// The sign is proven.
    Decided(Sign),
    /// Undecided, inputs inside the window: the expansion tier is exact.
    Expansion,
    /// Inputs outside the window: only the bignum tier is exact.
    Bignum,
}

/// True if every nonzero `|x|` lies in the window for size `N`.
#[inline(always)]
pub(crate) fn in_window<const N: usize>(m: &[[f64; N]; N]) -> bool {
    let (lo, hi) = window(N);
    let mut ok = true;
    for row in m {
        for &x in row {
            let a = x.abs();
            ok &= (a <= hi) & ((a >= lo) | (a == 0.0));
        }
    }
    ok
}

#[inline(always)]
fn decide(d: f64, bound: f64, perm: f64) -> Option<Sign> {
    if d > bound {
        Some(Sign::Positive)
    } else if -d > bound {
        Some(Sign::Negative)
    } else if perm == 0.0 {
        Some(Sign::Zero)
    } else {
        None
    }
}

/// `(det, permanent)` of a 3x3 matrix, both by first-row Laplace expansion.
#[inline(always)]
fn det_perm3(m: &[[f64; 3]; 3]) -> (f64, f64) {
    let [[a0, a1, a2], [b0, b1, b2], [c0, c1, c2]] = *m;
    let m0 = b1 * c2 - b2 * c1;
    let m1 = b0 * c2 - b2 * c0;
    let m2 = b0 * c1 - b1 * c0;
    let d = (a0 * m0 - a1 * m1) + a2 * m2;
    let [[a0, a1, a2], [b0, b1, b2], [c0, c1, c2]] = m.map(|r| r.map(f64::abs));
    let p0 = b1 * c2 + b2 * c1;
    let p1 = b0 * c2 + b2 * c0;
    let p2 = b0 * c1 + b1 * c0;
    let p = (a0 * p0 + a1 * p1) + a2 * p2;
    (d, p)
}

/// `(det, permanent)` of a 4x4 matrix by Laplace expansion along rows 0,1.
#[inline(always)]
fn det_perm4(m: &[[f64; 4]; 4]) -> (f64, f64) {
    #[inline(always)]
    fn pairs(r: [f64; 4], s: [f64; 4], sub: bool) -> [f64; 6] {
        let f = |i: usize, j: usize| {
            if sub {
                r[i] * s[j] - r[j] * s[i]
            } else {
                r[i] * s[j] + r[j] * s[i]
            }
        };
        [f(0, 1), f(0, 2), f(0, 3), f(1, 2), f(1, 3), f(2, 3)]
    }
    let s = pairs(m[0], m[1], true);
    let c = pairs(m[2], m[3], true);
    let d = ((s[0] * c[5] - s[1] * c[4]) + (s[2] * c[3] + s[3] * c[2])) + (s[5] * c[0] - s[4] * c[1]);
    let a = m.map(|r| r.map(f64::abs));
    let s = pairs(a[0], a[1], false);
    let c = pairs(a[2], a[3], false);
    let p = ((s[0] * c[5] + s[1] * c[4]) + (s[2] * c[3] + s[3] * c[2])) + (s[5] * c[0] + s[4] * c[1]);
    (d, p)
}

/// IA, N = 2: monotone comparison of the two rounded products.
#[inline(always)]
pub(crate) fn ia2(m: &[[f64; 2]; 2]) -> Option<Sign> {
    let p = m[0][0] * m[1][1];
    let q = m[0][1] * m[1][0];
    if p > q {
        Some(Sign::Positive)
    } else if p < q {
        Some(Sign::Negative)
    } else {
        None
    }
}

/// IA, N = 2, after `fl(ad) == fl(bc)`: exact zero products, or (inside the
/// window) the sign of the difference of the exact product tails.
#[cold]
pub(crate) fn ia2_tie(m: &[[f64; 2]; 2]) -> Outcome {
    let [[a, b], [c, d]] = *m;
    if (a == 0.0 || d == 0.0) && (b == 0.0 || c == 0.0) {
        return Outcome::Decided(Sign::Zero);
    }
    if in_window(m) {
        Outcome::Expansion
    } else {
        Outcome::Bignum
    }
}

/// IA, N = 3.
#[inline]
pub(crate) fn ia3(m: &[[f64; 3]; 3]) -> Outcome {
    let (d, p) = det_perm3(m);
    let ok = in_window(m);
    match decide(d, C_IA3 * p, p) {
        Some(s) if ok => Outcome::Decided(s),
        _ if ok => Outcome::Expansion,
        _ => Outcome::Bignum,
    }
}

/// IA, N = 4.
#[inline]
pub(crate) fn ia4(m: &[[f64; 4]; 4]) -> Outcome {
    let (d, p) = det_perm4(m);
    let ok = in_window(m);
    match decide(d, C_IA4 * p, p) {
        Some(s) if ok => Outcome::Decided(s),
        _ if ok => Outcome::Expansion,
        _ => Outcome::Bignum,
    }
}

/// MI tail shared by all sizes: the computed differences `x` passed the
/// window check or not; if not, the window on `a` and `b` also validates
/// the filter (their differences are multiples of the same unit) and the
/// expansion tier.
#[inline(always)]
fn mi_outcome<const N: usize>(decided: Option<Sign>, x_ok: bool, a: &[[f64; N]; N], b: &[[f64; N]; N]) -> Outcome {
    if x_ok {
        if let Some(s) = decided {
            return Outcome::Decided(s);
        }
    }
    mi_slow(decided, a, b)
}

#[cold]
fn mi_slow<const N: usize>(decided: Option<Sign>, a: &[[f64; N]; N], b: &[[f64; N]; N]) -> Outcome {
    if in_window(a) && in_window(b) {
        match decided {
            Some(s) => Outcome::Decided(s),
            None => Outcome::Expansion,
        }
    } else {
        Outcome::Bignum
    }
}

#[inline(always)]
fn diff<const N: usize>(a: &[[f64; N]; N], b: &[[f64; N]; N]) -> [[f64; N]; N] {
    std::array::from_fn(|i| std::array::from_fn(|j| a[i][j] - b[i][j]))
}

/// MI, N = 2.
#[inline]
pub(crate) fn mi2(a: &[[f64; 2]; 2], b: &[[f64; 2]; 2]) -> Outcome {
    let x = diff(a, b);
    let d = x[0][0] * x[1][1] - x[0][1] * x[1][0];
    let p = (x[0][0] * x[1][1]).abs() + (x[0][1] * x[1][0]).abs();
    mi_outcome(decide(d, C_MI2 * p, p), in_window(&x), a, b)
}

/// MI, N = 3.
#[inline]
pub(crate) fn mi3(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> Outcome {
    let x = diff(a, b);
    let (d, p) = det_perm3(&x);
    mi_outcome(decide(d, C_MI3 * p, p), in_window(&x), a, b)
}

/// MI, N = 4.
#[inline]
pub(crate) fn mi4(a: &[[f64; 4]; 4], b: &[[f64; 4]; 4]) -> Outcome {
    let x = diff(a, b);
    let (d, p) = det_perm4(&x);
    mi_outcome(decide(d, C_MI4 * p, p), in_window(&x), a, b)
}

/// The naive floating-point determinant (no filter), for the `--float`
/// variant of the stress test: same evaluation order as the filters.
#[inline]
pub(crate) fn det_f64<const N: usize>(m: &[[f64; N]; N]) -> f64 {
    match N {
        0 => 1.0,
        1 => m[0][0],
        2 => m[0][0] * m[1][1] - m[0][1] * m[1][0],
        3 => det_perm3(&fix(m)).0,
        4 => det_perm4(&fix(m)).0,
        _ => {
            // Laplace along the first row (not used by Septa; N <= 4 there).
            let mut acc = 0.0;
            for c in 0..N {
                let minor: Vec<Vec<f64>> =
                    (1..N).map(|i| (0..N).filter(|&j| j != c).map(|j| m[i][j]).collect()).collect();
                let t = m[0][c] * det_f64_dyn(&minor);
                acc += if c % 2 == 0 { t } else { -t };
            }
            acc
        }
    }
}

fn det_f64_dyn(m: &[Vec<f64>]) -> f64 {
    let n = m.len();
    if n == 0 {
        return 1.0;
    }
    let mut acc = 0.0;
    for c in 0..n {
        let minor: Vec<Vec<f64>> =
            m[1..].iter().map(|r| r.iter().enumerate().filter(|&(j, _)| j != c).map(|(_, &x)| x).collect()).collect();
        let t = m[0][c] * det_f64_dyn(&minor);
        acc += if c % 2 == 0 { t } else { -t };
    }
    acc
}

/// Re-types an `N x N` matrix as `K x K` once `N == K` is known (the copy
/// vanishes after monomorphisation).
#[inline(always)]
pub(crate) fn fix<const N: usize, const K: usize>(m: &[[f64; N]; N]) -> [[f64; K]; K] {
    debug_assert_eq!(N, K);
    std::array::from_fn(|i| std::array::from_fn(|j| m[i][j]))
}
