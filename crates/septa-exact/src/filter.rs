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
//! ## Validity without a window: underflow as an absolute error (hot path)
//!
//! With gradual underflow every product obeys
//! `fl(xy) = xy(1 + d) + e`, `|e| <= eta = 2^-1075`, while sums keep the
//! plain model (a sum that lands in the subnormal range is exact): Higham,
//! *Accuracy and Stability*, Sec. 2.1, model with underflow. Each `e` reaches the result
//! multiplied only by the factors still to come on its path:
//! * N = 3: an `e` inside minor `k` is multiplied by the row-0 entry
//!   `x_0k`; one at the top product by 1. So the extra error is
//!   `F <= eta (1+u)^5 (2 S + 3)`, `S = |x_00| + |x_01| + |x_02|`.
//! * N = 4: an `e` inside `s_k` (`c_k`) is multiplied by the other computed
//!   minor, which is at most its computed permanent; so
//!   `F <= eta (1+u)^6 (2 S + 6)` with `S = sum_k (ps_k + pc_k)`, itself at
//!   most `R0 R1 + R2 R3` (`R_i` the absolute row sums), which is what is
//!   computed.
//! * N = 2 (MI): `F <= 2 eta (1+u)`.
//!
//! The permanent tree has the same structure, so `P^ >= (1-u)^mP P - F`
//! too. Requiring `P^ >= 2^-700` (then `B` is a normal number) and
//! `S <= 2^300` bounds `r = F / P^ <= 2^-73`, and it suffices that
//! `c_hot (1-u) / (1+u) >= gamma_{m'} (1 + r) / (1-u)^mP + r`, met by
//! `c_hot = c (1 + 2^-16)` (checked with `r = 2^-72` in exact rationals by
//! `filter_tests.rs`). Overflow needs no check: if `P^` is finite, every node
//! of the permanent tree is, and by monotone rounding every node of the
//! determinant tree is bounded by its permanent counterpart; if `P^` is
//! infinite, `B` is and nothing is decided. This hot criterion costs a few
//! additions and two comparisons, instead of a scan of all entries.
//!
//! ## Validity with an exponent window (cold path: zeros, tiny scales)
//!
//! When the hot criterion fails, the filter is retried under the *exponent
//! window*: every nonzero `|x|` in `[2^-W, 2^W]`, `W = 400, 250, 180` for
//! `N = 2, 3, 4`. Then every entry is an integer multiple of `2^(-W-52)`,
//! every nonzero intermediate of degree `k` is a multiple of, hence at
//! least, `2^(-k(W+52)) >= 2^-960` (no product underflows, `B` is normal)
//! and at most `N! 2^(N(W+1)) < 2^990` (nothing overflows), so the plain
//! bound `c` applies. Inside the window a computed permanent `P^ == 0` means
//! every monomial is exactly zero, so the determinant is exactly zero: zero
//! rows and columns, common on degenerate grids, are decided here. The same
//! window makes the expansion tier exact; outside it the integer or bignum
//! tier decides.

use crate::Sign;

const U: f64 = f64::EPSILON / 2.0;
const C_IA3: f64 = 4.0 * U + 64.0 * U * U;
const C_IA4: f64 = 7.0 * U + 128.0 * U * U;
const C_MI2: f64 = 3.0 * U + 32.0 * U * U;
const C_MI3: f64 = 7.0 * U + 128.0 * U * U;
const C_MI4: f64 = 11.0 * U + 512.0 * U * U;

/// Hot-path constants `c (1 + 2^-16)` (see "Validity without a window").
const HOT: f64 = 1.0 + 1.0 / (1u64 << 16) as f64;
const H_IA3: f64 = C_IA3 * HOT;
const H_IA4: f64 = C_IA4 * HOT;
const H_MI2: f64 = C_MI2 * HOT;
const H_MI3: f64 = C_MI3 * HOT;
const H_MI4: f64 = C_MI4 * HOT;
/// Smallest permanent and largest magnification sum for the hot path.
const P_MIN: f64 = f64::from_bits((1023 - 700) << 52);
const S_MAX: f64 = f64::from_bits((1023 + 300) << 52);

/// `(name, N, m', mP, c, c_hot)` for every bounded filter: checked in
/// exact rational arithmetic by the tests in `filter_tests.rs`.
#[cfg(test)]
pub(crate) const BOUNDS: [(&str, usize, u32, u32, f64, f64); 5] = [
    ("IA3", 3, 4, 5, C_IA3, H_IA3),
    ("IA4", 4, 7, 8, C_IA4, H_IA4),
    ("MI2", 2, 3, 4, C_MI2, H_MI2),
    ("MI3", 3, 7, 8, C_MI3, H_MI3),
    ("MI4", 4, 11, 12, C_MI4, H_MI4),
];
#[cfg(test)]
pub(crate) const HOT_LIMITS: (f64, f64) = (P_MIN, S_MAX);

/// Exponent window `[2^-W, 2^W]` per size (see the module doc).
pub(crate) const fn window(n: usize) -> (f64, f64) {
    match n {
        0..=2 => (f64::from_bits((1023 - 400) << 52), f64::from_bits((1023 + 400) << 52)),
        3 => (f64::from_bits((1023 - 250) << 52), f64::from_bits((1023 + 250) << 52)),
        _ => (f64::from_bits((1023 - 180) << 52), f64::from_bits((1023 + 180) << 52)),
    }
}

/// What the filter concluded. The three signs share [`Sign`]'s values so
/// the hot path builds and reads it without branches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(i8)]
pub(crate) enum Outcome {
    /// Proven negative.
    Negative = -1,
    /// Proven zero.
    Zero = 0,
    /// Proven positive.
    Positive = 1,
    /// Undecided, inputs inside the window: the expansion tier is exact.
    Expansion = 2,
    /// Inputs outside the window: only the bignum tier is exact.
    Bignum = 3,
}

impl Outcome {
    /// The proven sign, if any.
    #[inline(always)]
    pub(crate) fn sign(self) -> Option<Sign> {
        match self {
            Outcome::Negative => Some(Sign::Negative),
            Outcome::Zero => Some(Sign::Zero),
            Outcome::Positive => Some(Sign::Positive),
            _ => None,
        }
    }

    #[inline(always)]
    fn from_code(c: i8) -> Outcome {
        match c {
            -1 => Outcome::Negative,
            0 => Outcome::Zero,
            1 => Outcome::Positive,
            2 => Outcome::Expansion,
            _ => Outcome::Bignum,
        }
    }
}

/// True if every nonzero `|x|` lies in the window for size `n`.
///
/// Written as integer flags OR-ed together (integer OR reassociates freely,
/// so the reduction is a shallow tree of packed compares, not a serial chain
/// of floating-point min/max).
#[inline(always)]
pub(crate) fn in_window(x: &[f64], n: usize) -> bool {
    let (lo, hi) = window(n);
    let mut bad = 0u32;
    for &v in x {
        let a = v.abs();
        bad |= ((a > hi) as u32) | (((a < lo) & (a != 0.0)) as u32);
    }
    bad == 0
}

/// The entries of an `N x N` matrix as a flat `K`-array reference
/// (`K == N * N`); the length check folds away after monomorphisation.
#[inline(always)]
pub(crate) fn flat<const N: usize, const K: usize>(m: &[[f64; N]; N]) -> &[f64; K] {
    <&[f64; K]>::try_from(m.as_flattened()).expect("K == N * N")
}

/// Branch-free verdict: `|d| > bound` proves `sign(d)`; a zero permanent
/// proves zero; `ok` says whether the exponent window (and thereby the
/// error bound) holds.
#[inline(always)]
fn decide(d: f64, bound: f64, perm: f64, ok: bool) -> Outcome {
    let pos = d > bound;
    let neg = -d > bound;
    let decided = pos | neg | (perm == 0.0);
    let code = if !ok {
        3
    } else if !decided {
        2
    } else {
        pos as i8 - neg as i8
    };
    Outcome::from_code(code)
}

/// `(det, permanent, S)` of a 3x3 matrix (row-major), both by first-row
/// Laplace expansion; `S` is the row-0 magnification sum of the hot path.
#[inline(always)]
fn det_perm3(m: &[f64; 9]) -> (f64, f64, f64) {
    let [a0, a1, a2, b0, b1, b2, c0, c1, c2] = *m;
    let m0 = b1 * c2 - b2 * c1;
    let m1 = b0 * c2 - b2 * c0;
    let m2 = b0 * c1 - b1 * c0;
    let d = (a0 * m0 - a1 * m1) + a2 * m2;
    let [a0, a1, a2, b0, b1, b2, c0, c1, c2] = m.map(f64::abs);
    let p0 = b1 * c2 + b2 * c1;
    let p1 = b0 * c2 + b2 * c0;
    let p2 = b0 * c1 + b1 * c0;
    let p = (a0 * p0 + a1 * p1) + a2 * p2;
    (d, p, (a0 + a1) + a2)
}

/// `(det, permanent, S)` of a 4x4 matrix (row-major) by Laplace expansion
/// along rows 0,1; `S` bounds the sum of the 2x2 minor permanents (hot path).
#[inline(always)]
fn det_perm4(m: &[f64; 16]) -> (f64, f64, f64) {
    #[inline(always)]
    fn pairs(m: &[f64; 16], r: usize, sub: bool) -> [f64; 6] {
        let f = |i: usize, j: usize| {
            let (x, y) = (m[4 * r + i] * m[4 * r + 4 + j], m[4 * r + j] * m[4 * r + 4 + i]);
            if sub {
                x - y
            } else {
                x + y
            }
        };
        [f(0, 1), f(0, 2), f(0, 3), f(1, 2), f(1, 3), f(2, 3)]
    }
    let s = pairs(m, 0, true);
    let c = pairs(m, 2, true);
    let d = ((s[0] * c[5] - s[1] * c[4]) + (s[2] * c[3] + s[3] * c[2])) + (s[5] * c[0] - s[4] * c[1]);
    let a = m.map(f64::abs);
    let s = pairs(&a, 0, false);
    let c = pairs(&a, 2, false);
    let p = ((s[0] * c[5] + s[1] * c[4]) + (s[2] * c[3] + s[3] * c[2])) + (s[5] * c[0] + s[4] * c[1]);
    // Magnification sum of the twelve 2x2 minor permanents, bounded by row
    // sums: sum_{i<j} (|r_i||s_j| + |r_j||s_i|) <= (sum |r|)(sum |s|).
    let row = |k: usize| (a[4 * k] + a[4 * k + 1]) + (a[4 * k + 2] + a[4 * k + 3]);
    let mag = row(0) * row(1) + row(2) * row(3);
    (d, p, mag)
}

/// Hot path: the sign if `|d| > c_hot p` and the magnitudes allow the
/// absolute underflow term to be absorbed (module doc), else `None`.
#[inline(always)]
fn hot(d: f64, p: f64, s: f64, c_hot: f64) -> Option<Sign> {
    let bound = c_hot * p;
    let pos = d > bound;
    let neg = -d > bound;
    if (pos | neg) & (p >= P_MIN) & (s <= S_MAX) {
        Some(Sign::from_i8(pos as i8 - neg as i8))
    } else {
        None
    }
}

/// IA, N = 2: monotone comparison of the two rounded products.
#[inline(always)]
pub(crate) fn ia2(m: &[f64; 4]) -> Option<Sign> {
    let p = m[0] * m[3];
    let q = m[1] * m[2];
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
pub(crate) fn ia2_tie(m: &[f64; 4]) -> Outcome {
    let [a, b, c, d] = *m;
    if (a == 0.0 || d == 0.0) && (b == 0.0 || c == 0.0) {
        return Outcome::Zero;
    }
    if in_window(m, 2) {
        Outcome::Expansion
    } else {
        Outcome::Bignum
    }
}

/// IA cold path: the windowed filter, then the tier to use.
#[cold]
#[inline(never)]
fn cold_ia(d: f64, p: f64, c: f64, m: &[f64], n: usize) -> Outcome {
    decide(d, c * p, p, in_window(m, n))
}

#[inline(always)]
fn from_hot(s: Option<Sign>) -> Option<Outcome> {
    s.map(|s| Outcome::from_code(s.as_i8()))
}

/// IA, N = 3.
#[inline]
pub(crate) fn ia3(m: &[f64; 9]) -> Outcome {
    let (d, p, s) = det_perm3(m);
    from_hot(hot(d, p, s, H_IA3)).unwrap_or_else(|| cold_ia(d, p, C_IA3, m, 3))
}

/// IA, N = 4.
#[inline]
pub(crate) fn ia4(m: &[f64; 16]) -> Outcome {
    let (d, p, s) = det_perm4(m);
    from_hot(hot(d, p, s, H_IA4)).unwrap_or_else(|| cold_ia(d, p, C_IA4, m, 4))
}

/// MI cold path. The windowed filter is valid if the computed differences
/// `x` lie in the window, or if `a` and `b` do (their differences are then
/// multiples of the same unit); the expansion tier needs the latter.
#[cold]
#[inline(never)]
fn cold_mi(d: f64, p: f64, c: f64, x: &[f64], a: &[f64], b: &[f64], n: usize) -> Outcome {
    let ab = in_window(a, n) && in_window(b, n);
    if !(ab || in_window(x, n)) {
        return Outcome::Bignum;
    }
    match decide(d, c * p, p, true) {
        o @ (Outcome::Negative | Outcome::Zero | Outcome::Positive) => o,
        _ if ab => Outcome::Expansion,
        _ => Outcome::Bignum,
    }
}

#[inline(always)]
fn diff<const K: usize>(a: &[f64; K], b: &[f64; K]) -> [f64; K] {
    std::array::from_fn(|i| a[i] - b[i])
}

/// MI, N = 2.
#[inline]
pub(crate) fn mi2(a: &[f64; 4], b: &[f64; 4]) -> Outcome {
    let x = diff(a, b);
    let (l, r) = (x[0] * x[3], x[1] * x[2]);
    let d = l - r;
    let p = l.abs() + r.abs();
    // No magnification at N = 2: S = 0.
    from_hot(hot(d, p, 0.0, H_MI2)).unwrap_or_else(|| cold_mi(d, p, C_MI2, &x, a, b, 2))
}

/// MI, N = 3.
#[inline]
pub(crate) fn mi3(a: &[f64; 9], b: &[f64; 9]) -> Outcome {
    let x = diff(a, b);
    let (d, p, s) = det_perm3(&x);
    from_hot(hot(d, p, s, H_MI3)).unwrap_or_else(|| cold_mi(d, p, C_MI3, &x, a, b, 3))
}

/// MI, N = 4.
#[inline]
pub(crate) fn mi4(a: &[f64; 16], b: &[f64; 16]) -> Outcome {
    let x = diff(a, b);
    let (d, p, s) = det_perm4(&x);
    from_hot(hot(d, p, s, H_MI4)).unwrap_or_else(|| cold_mi(d, p, C_MI4, &x, a, b, 4))
}

/// The naive floating-point determinant (no filter), for the `--float`
/// variant of the stress test: same evaluation order as the filters.
#[inline]
pub(crate) fn det_f64<const N: usize>(m: &[[f64; N]; N]) -> f64 {
    match N {
        0 => 1.0,
        1 => m[0][0],
        2 => m[0][0] * m[1][1] - m[0][1] * m[1][0],
        3 => det_perm3(flat(m)).0,
        4 => det_perm4(flat(m)).0,
        _ => det_f64_dyn(&m.iter().map(|r| r.to_vec()).collect::<Vec<_>>()),
    }
}

/// Laplace along the first row (not used by Septa, where N <= 4).
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

#[cfg(test)]
#[path = "filter_tests.rs"]
mod tests;
