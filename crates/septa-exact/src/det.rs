//! Exact signs of small determinants (N = 1..=4) of `f64` data, in three
//! tiers: a floating-point filter with a proven bound (`filter.rs`); an
//! allocation-free exact tier, first `i128` arithmetic for low-precision rows
//! (`integer_det.rs`, any magnitude), then expansions (`expansion_det.rs`)
//! inside an exponent window; and a bignum tier ([`Exact`](crate::Exact))
//! for everything else.
//! Each call bumps exactly one per-thread counter in [`crate::stats`].
//!
//! Inputs must be finite (see [`crate::check_finite`]); a NaN or infinity
//! is a precondition violation: an unspecified sign in release builds, a
//! debug assertion in [`Exact::from_f64`](crate::Exact::from_f64) in debug
//! builds if it reaches the bignum tier.

use crate::filter::{self, flat, Outcome};
use crate::{bignum, expansion_det, integer_det, stats, Sign};

/// Sign of `det(m)` for an `N x N` matrix of input values, `N` in `1..=4`
/// (larger `N` works too, on the slow exact tier only).
///
/// ```
/// use septa_exact::{det_sign, Sign};
/// assert_eq!(det_sign(&[[1.0, 2.0], [3.0, 4.0]]), Sign::Negative);
/// // Rows 1 and 2 are proportional: exactly singular.
/// assert_eq!(det_sign(&[[0.1, 0.2, 0.3], [1.0, 2.0, 3.0], [2.0, 4.0, 6.0]]), Sign::Zero);
/// ```
#[inline]
pub fn det_sign<const N: usize>(m: &[[f64; N]; N]) -> Sign {
    match N {
        1 => {
            stats::count_filter();
            Sign::of_f64(m[0][0])
        }
        2 => {
            let m2: &[f64; 4] = flat(m);
            match filter::ia2(m2) {
                Some(s) => {
                    stats::count_filter();
                    s
                }
                None => finish_ia(filter::ia2_tie(m2), m),
            }
        }
        3 => finish_ia(filter::ia3(flat(m)), m),
        4 => finish_ia(filter::ia4(flat(m)), m),
        _ => {
            stats::count_bignum();
            bignum::det_sign(m)
        }
    }
}

#[inline(always)]
fn finish_ia<const N: usize>(o: Outcome, m: &[[f64; N]; N]) -> Sign {
    match o.sign() {
        Some(s) => {
            stats::count_filter();
            s
        }
        None => slow_ia(o, m),
    }
}

#[cold]
#[inline(never)]
fn slow_ia<const N: usize>(o: Outcome, m: &[[f64; N]; N]) -> Sign {
    let exact = match o {
        Outcome::Expansion if N == 2 => Some(expansion_det::ia2_tie_sign(flat(m))),
        Outcome::Expansion => integer_det::det_sign_ia(m).or_else(|| expansion_det::det_sign_ia(m)),
        Outcome::Bignum => integer_det::det_sign_ia(m),
        decided => {
            // A zero proven on the tie path of N = 2.
            stats::count_filter();
            return decided.sign().unwrap_or(Sign::Zero);
        }
    };
    match exact {
        Some(s) => {
            stats::count_expansion();
            s
        }
        None => {
            stats::count_bignum();
            bignum::det_sign(m)
        }
    }
}

/// Sign of `det(a - b)` for `N x N` matrices, `N` in `1..=4`, where the
/// differences are formed *inside* the predicate so their rounding is
/// accounted for (the MI form of the barycentric predicate).
///
/// ```
/// use septa_exact::{det_sign_diff, det_sign_diff_f64_naive, Sign};
/// // det(a - b) = (1 + 2^-60) - 1 = 2^-60 > 0, but the rounded difference
/// // 1 + 2^-60 is 1.0, so naive floating point sees an exact zero.
/// let t = 2f64.powi(-60);
/// let a = [[1.0, 1.0], [1.0, 1.0]];
/// let b = [[-t, 0.0], [0.0, 0.0]];
/// assert_eq!(det_sign_diff(&a, &b), Sign::Positive);
/// assert_eq!(det_sign_diff_f64_naive(&a, &b), Sign::Zero);
/// ```
#[inline]
pub fn det_sign_diff<const N: usize>(a: &[[f64; N]; N], b: &[[f64; N]; N]) -> Sign {
    let o = match N {
        1 => {
            stats::count_filter();
            // Comparison of two doubles is exact.
            let (x, y) = (a[0][0], b[0][0]);
            return if x > y {
                Sign::Positive
            } else if x < y {
                Sign::Negative
            } else {
                Sign::Zero
            };
        }
        2 => filter::mi2(flat(a), flat(b)),
        3 => filter::mi3(flat(a), flat(b)),
        4 => filter::mi4(flat(a), flat(b)),
        _ => Outcome::Bignum,
    };
    match o.sign() {
        Some(s) => {
            stats::count_filter();
            s
        }
        None => slow_mi(o, a, b),
    }
}

#[cold]
#[inline(never)]
fn slow_mi<const N: usize>(o: Outcome, a: &[[f64; N]; N], b: &[[f64; N]; N]) -> Sign {
    let exact = match o {
        Outcome::Expansion => integer_det::det_sign_mi(a, b).or_else(|| expansion_det::det_sign_mi(a, b)),
        Outcome::Bignum => integer_det::det_sign_mi(a, b),
        decided => return decided.sign().unwrap_or(Sign::Zero),
    };
    match exact {
        Some(s) => {
            stats::count_expansion();
            s
        }
        None => {
            stats::count_bignum();
            bignum::det_sign_diff(a, b)
        }
    }
}

/// The naive floating-point sign of `det(m)`: the filter's evaluation
/// without the error bound. **Not exact**; it exists for the `--float`
/// variant of the stress test (the paper's floating-point baseline, Sec. 8.1).
#[inline]
pub fn det_sign_f64_naive<const N: usize>(m: &[[f64; N]; N]) -> Sign {
    Sign::of_f64(filter::det_f64(m))
}

/// The naive floating-point sign of `det(a - b)`, differences rounded first.
/// **Not exact**; see [`det_sign_f64_naive`].
#[inline]
pub fn det_sign_diff_f64_naive<const N: usize>(a: &[[f64; N]; N], b: &[[f64; N]; N]) -> Sign {
    let x: [[f64; N]; N] = std::array::from_fn(|i| std::array::from_fn(|j| a[i][j] - b[i][j]));
    Sign::of_f64(filter::det_f64(&x))
}
