//! MI: functions that never win anywhere in a tet (Du et al. Sec. 4.2).
//!
//! Inserting a function that is strictly below the current maximum at every
//! vertex of the complex changes nothing (no vertex has the negative sign
//! that starts a split), so the MI of a tet's functions equals the MI
//! without such a function. The network leaves them out of a tet's active
//! functions (network/block/active.rs); with fewer active functions, tets
//! reach the single-polygon templates and the look-up tables (label
//! volumes: the materials absent from a tet are 0 at its four corners and
//! tie with each other, so no single material dominates them).
//!
//! A function `f` counts as dominated only when it is *proven*: with `W` the
//! functions attaining the maximum at some corner, the average of `W` is
//! strictly greater than `f` at all four corners. The maximum is at least
//! the average, which is linear like `f`, so `max > f` in the whole tet.
//! The sums are floating point; a corner counts only when the computed
//! difference exceeds a bound on its rounding error. When not proven the
//! function stays active, which is always correct.

/// Whether `sum_{g in W} g(v) > |W| f(v)` at every corner `v` is proven,
/// for the rows `winners` (`|W| >= 2`) and `f`. Recursive summation of `n`
/// doubles errs by at most `gamma_{n-1} sum |x_j|` (Higham, Accuracy and
/// Stability of Numerical Algorithms, eq. 4.4), `gamma_m = m u / (1 - m u)`,
/// `u = 2^-53`; the product `|W| f` adds one relative `u` and the final
/// difference one more. `(|W| + 3) * EPSILON = (|W| + 3) 2u` times the sum of
/// magnitudes covers all of them with room for `|W|` up to 2^40, and
/// `MIN_POSITIVE` covers underflow. Non-finite sums prove nothing.
pub(crate) fn average_dominates(winners: &[[f64; 4]], f: &[f64; 4]) -> bool {
    let w = winners.len();
    if w < 2 {
        return false;
    }
    (0..4).all(|i| {
        let (mut s, mut mag) = (0.0f64, 0.0f64);
        for g in winners {
            s += g[i];
            mag += g[i].abs();
        }
        let p = w as f64 * f[i];
        let d = s - p;
        let bound = (w as f64 + 3.0) * f64::EPSILON * (mag + p.abs()) + f64::MIN_POSITIVE;
        d.is_finite() && bound.is_finite() && d > bound
    })
}
