//! Exact tier for rows of *limited precision*: integer determinants.
//!
//! After scaling each row by a power of two (a positive factor: the sign of
//! the determinant is unchanged) every entry of a row whose nonzero values
//! span at most 62 bits is an `i64`. This holds at any magnitude,
//! subnormals included, because only each row's *span* of bits matters, not
//! its exponent: small integers and grid values (exactly degenerate data)
//! and rows of doubles of similar size (near-degenerate data) all qualify.
//!
//! The Laplace expansion then runs on integers: 2x2 minors are `i128`
//! (`< 2^125`), 3x3 minors and the 4x4 determinant use a 256-bit two's
//! complement accumulator ([`I256`]): `|3x3 minor| < 3 * 2^187`,
//! `|det4| < 4 * 2^251 < 2^255`. When all row spans sum to at most
//! `126 - log2(N!)` bits the whole expansion fits in `i128` and that
//! cheaper path is taken. Rows spanning more than 62 bits go to expansions.

use crate::Sign;

/// `x = m * 2^e` with `m` odd (or zero); returns `(m, e, bit length of m)`.
#[inline]
fn decompose(x: f64) -> (i64, i32, i32) {
    if x == 0.0 {
        return (0, i32::MAX, 0);
    }
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    let frac = bits & ((1u64 << 52) - 1);
    let (m, e) = if biased == 0 { (frac, -1074) } else { (frac | (1u64 << 52), biased - 1075) };
    let tz = m.trailing_zeros();
    let m = m >> tz;
    let len = 64 - m.leading_zeros() as i32;
    let m = if bits >> 63 == 1 { -(m as i64) } else { m as i64 };
    (m, e + tz as i32, len)
}

/// Per-row integer images of `values` (the entries of one row, or of the
/// matching rows of `a` and `b` for the MI form), scaled by a common power
/// of two; `None` if they span more than `max_bits` bits.
#[inline]
fn row_ints<const K: usize>(values: &[f64; K], max_bits: i32) -> Option<([i64; K], i32)> {
    let d = values.map(decompose);
    let emin = d.iter().map(|&(_, e, _)| e).min().unwrap_or(i32::MAX);
    if emin == i32::MAX {
        return Some(([0; K], 0));
    }
    let top = d.iter().filter(|&&(m, _, _)| m != 0).map(|&(_, e, l)| e + l).max().unwrap_or(emin);
    let span = top - emin;
    if span > max_bits {
        return None;
    }
    Some((d.map(|(m, e, _)| if m == 0 { 0 } else { m << (e - emin) }), span))
}

/// `ceil(log2(N!))` for N = 1..=4, and the `i128` budget (see module doc).
const LOG_FACT: [i32; 5] = [0, 0, 1, 3, 5];
const BUDGET: i32 = 126;

#[inline]
fn det_i128<const N: usize>(m: &[[i128; N]; N]) -> i128 {
    let m2 = |r: usize, s: usize, i: usize, j: usize| m[r][i] * m[s][j] - m[r][j] * m[s][i];
    match N {
        1 => m[0][0],
        2 => m2(0, 1, 0, 1),
        3 => m[0][0] * m2(1, 2, 1, 2) - m[0][1] * m2(1, 2, 0, 2) + m[0][2] * m2(1, 2, 0, 1),
        4 => {
            let c = |i, j| m2(2, 3, i, j);
            let (c01, c02, c03, c12, c13, c23) = (c(0, 1), c(0, 2), c(0, 3), c(1, 2), c(1, 3), c(2, 3));
            let r = &m[1];
            let m0 = r[1] * c23 - r[2] * c13 + r[3] * c12;
            let m1 = r[0] * c23 - r[2] * c03 + r[3] * c02;
            let m2_ = r[0] * c13 - r[1] * c03 + r[3] * c01;
            let m3 = r[0] * c12 - r[1] * c02 + r[2] * c01;
            m[0][0] * m0 - m[0][1] * m1 + m[0][2] * m2_ - m[0][3] * m3
        }
        _ => unreachable!("integer tier is only used for N <= 4"),
    }
}

fn sign_i128(x: i128) -> Sign {
    Sign::from_i8(x.signum() as i8)
}

/// A 256-bit two's complement integer (little-endian limbs), just enough
/// for sums of `i64 * i128` and `i64 * I256` products of bounded size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct I256([u64; 4]);

impl I256 {
    fn from_i128(v: i128) -> I256 {
        let ext = if v < 0 { u64::MAX } else { 0 };
        I256([v as u64, (v >> 64) as u64, ext, ext])
    }

    fn is_negative(self) -> bool {
        self.0[3] >> 63 == 1
    }

    fn add(self, o: I256) -> I256 {
        let mut r = [0u64; 4];
        let mut carry = false;
        for ((ri, &x), &y) in r.iter_mut().zip(&self.0).zip(&o.0) {
            let (s1, c1) = x.overflowing_add(y);
            let (s2, c2) = s1.overflowing_add(carry as u64);
            *ri = s2;
            carry = c1 | c2;
        }
        I256(r)
    }

    fn neg(self) -> I256 {
        I256(self.0.map(|l| !l)).add(I256([1, 0, 0, 0]))
    }

    /// `self * s`; the caller guarantees the product fits (module doc).
    fn mul_i64(self, s: i64) -> I256 {
        let negative = self.is_negative() != (s < 0);
        let mag = if self.is_negative() { self.neg() } else { self };
        let m = s.unsigned_abs() as u128;
        let mut r = [0u64; 4];
        let mut carry = 0u128;
        for (ri, &limb) in r.iter_mut().zip(&mag.0) {
            let t = limb as u128 * m + carry;
            *ri = t as u64;
            carry = t >> 64;
        }
        let r = I256(r);
        if negative {
            r.neg()
        } else {
            r
        }
    }

    fn sign(self) -> Sign {
        if self.is_negative() {
            Sign::Negative
        } else if self.0 == [0; 4] {
            Sign::Zero
        } else {
            Sign::Positive
        }
    }
}

/// `sum_k s_k x_k m_k` for `i64` entries `x_k` and wide minors `m_k`.
fn cofactor_sum(x: [i64; 4], m: [I256; 4], n: usize) -> I256 {
    let mut acc = I256::from_i128(0);
    for k in 0..n {
        let t = m[k].mul_i64(x[k]);
        acc = acc.add(if k % 2 == 0 { t } else { t.neg() });
    }
    acc
}

/// Exact sign of `det(m)` for rows of `i64` entries (any `N <= 4`).
fn det_sign_wide<const N: usize>(m: &[[i64; N]; N]) -> Sign {
    let w = |v: i128| I256::from_i128(v);
    let m2 =
        |r: usize, s: usize, i: usize, j: usize| m[r][i] as i128 * m[s][j] as i128 - m[r][j] as i128 * m[s][i] as i128;
    let row = |r: usize| -> [i64; 4] { std::array::from_fn(|j| if j < N { m[r][j] } else { 0 }) };
    match N {
        1 => Sign::from_i8(m[0][0].signum() as i8),
        2 => sign_i128(m2(0, 1, 0, 1)),
        3 => {
            let minors = [w(m2(1, 2, 1, 2)), w(m2(1, 2, 0, 2)), w(m2(1, 2, 0, 1)), w(0)];
            cofactor_sum(row(0), minors, 3).sign()
        }
        4 => {
            let c = |i, j| w(m2(2, 3, i, j));
            let (c01, c02, c03, c12, c13, c23) = (c(0, 1), c(0, 2), c(0, 3), c(1, 2), c(1, 3), c(2, 3));
            let r1 = row(1);
            let sub3 = |cols: [usize; 3], cof: [I256; 3]| {
                let x = [r1[cols[0]], r1[cols[1]], r1[cols[2]], 0];
                cofactor_sum(x, [cof[0], cof[1], cof[2], w(0)], 3)
            };
            let minors = [
                sub3([1, 2, 3], [c23, c13, c12]),
                sub3([0, 2, 3], [c23, c03, c02]),
                sub3([0, 1, 3], [c13, c03, c01]),
                sub3([0, 1, 2], [c12, c02, c01]),
            ];
            cofactor_sum(row(0), minors, 4).sign()
        }
        _ => unreachable!("integer tier is only used for N <= 4"),
    }
}

/// Exact sign of `det(m)` if every row spans at most 62 bits, else `None`.
pub(crate) fn det_sign_ia<const N: usize>(m: &[[f64; N]; N]) -> Option<Sign> {
    if N == 0 || N > 4 {
        return None;
    }
    let mut ints = [[0i64; N]; N];
    let mut total = LOG_FACT[N];
    for (row, o) in m.iter().zip(ints.iter_mut()) {
        let (r, span) = row_ints(row, 62)?;
        total += span;
        *o = r;
    }
    Some(finish(&ints, total))
}

/// Exact sign of `det(a - b)` if every row pair spans at most 61 bits
/// (so the differences fit in 62), else `None`.
pub(crate) fn det_sign_mi<const N: usize>(a: &[[f64; N]; N], b: &[[f64; N]; N]) -> Option<Sign> {
    if N == 0 || N > 4 {
        return None;
    }
    let mut ints = [[0i64; N]; N];
    let mut total = LOG_FACT[N];
    for i in 0..N {
        // One scale for the row of a and the row of b together, so the
        // integer difference is the exact difference, scaled.
        let mut both = [0.0f64; 8];
        both[..N].copy_from_slice(&a[i]);
        both[4..4 + N].copy_from_slice(&b[i]);
        let (r, span) = row_ints(&both, 61)?;
        total += span + 1;
        for j in 0..N {
            ints[i][j] = r[j] - r[4 + j];
        }
    }
    Some(finish(&ints, total))
}

/// `i128` when the spans allow it, else the 256-bit accumulator.
fn finish<const N: usize>(ints: &[[i64; N]; N], total: i32) -> Sign {
    if total <= BUDGET {
        sign_i128(det_i128(&ints.map(|r| r.map(i128::from))))
    } else {
        det_sign_wide(ints)
    }
}
