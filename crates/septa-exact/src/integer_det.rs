//! Exact shortcut for *low-precision* data: determinants in `i128`.
//!
//! Exactly degenerate inputs (small integers, dyadic grid values, repeated
//! rows) are where the filter must give up, and they are common on
//! degenerate grids. Such rows use few significant bits, so after scaling
//! each row by a power of two (a positive factor: the sign of the
//! determinant is unchanged) every entry is a small integer and the whole
//! Laplace expansion fits in `i128`. This works at any magnitude, subnormals
//! included, because only each row's *span* of bits matters, not its
//! exponent. When the spans are too wide the caller moves on to expansions.
//!
//! Bound: with row `i` spanning `b_i` bits, every partial sum of the
//! expansion is at most the matching partial permanent, hence below
//! `N! 2^(b_1 + .. + b_N)`; requiring `sum b_i + log2(N!) <= 126` keeps all
//! intermediates inside `i128`.

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
    let (m, e) = if biased == 0 {
        (frac, -1074)
    } else {
        (frac | (1u64 << 52), biased - 1075)
    };
    let tz = m.trailing_zeros();
    let m = m >> tz;
    let len = 64 - m.leading_zeros() as i32;
    let m = if bits >> 63 == 1 {
        -(m as i64)
    } else {
        m as i64
    };
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
    let top = d
        .iter()
        .filter(|&&(m, _, _)| m != 0)
        .map(|&(_, e, l)| e + l)
        .max()
        .unwrap_or(emin);
    let span = top - emin;
    if span > max_bits {
        return None;
    }
    Some((
        d.map(|(m, e, _)| if m == 0 { 0 } else { m << (e - emin) }),
        span,
    ))
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
            let (c01, c02, c03, c12, c13, c23) =
                (c(0, 1), c(0, 2), c(0, 3), c(1, 2), c(1, 3), c(2, 3));
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

/// Exact sign of `det(m)` if every row is narrow enough, else `None`.
pub(crate) fn det_sign_ia<const N: usize>(m: &[[f64; N]; N]) -> Option<Sign> {
    if N == 0 || N > 4 {
        return None;
    }
    let mut out = [[0i128; N]; N];
    let mut total = LOG_FACT[N];
    for (row, o) in m.iter().zip(out.iter_mut()) {
        let (ints, span) = row_ints(row, 62)?;
        total += span;
        *o = ints.map(i128::from);
    }
    (total <= BUDGET).then(|| sign_i128(det_i128(&out)))
}

/// Exact sign of `det(a - b)` if every row pair is narrow enough, else `None`.
pub(crate) fn det_sign_mi<const N: usize>(a: &[[f64; N]; N], b: &[[f64; N]; N]) -> Option<Sign> {
    if N == 0 || N > 4 {
        return None;
    }
    let mut out = [[0i128; N]; N];
    let mut total = LOG_FACT[N];
    for i in 0..N {
        // One scale for the row of a and the row of b together, so the
        // integer difference is the exact difference, scaled.
        let mut both = [0.0f64; 8];
        both[..N].copy_from_slice(&a[i]);
        both[4..4 + N].copy_from_slice(&b[i]);
        let (ints, span) = row_ints(&both, 61)?;
        total += span + 1;
        for j in 0..N {
            out[i][j] = i128::from(ints[j]) - i128::from(ints[4 + j]);
        }
    }
    (total <= BUDGET).then(|| sign_i128(det_i128(&out)))
}
