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

/// Proves `sum_{g in W} g(v) > |W| f(v)` at every corner `v`, for the rows
/// `winners` (`|W| >= 2`) and a row `f`. Recursive summation of `n`
/// doubles errs by at most `gamma_{n-1} sum |x_j|` (Higham, Accuracy and
/// Stability of Numerical Algorithms, eq. 4.4), `gamma_m = m u / (1 - m u)`,
/// `u = 2^-53`; the product `|W| f` adds one relative `u` and the final
/// difference one more. `(|W| + 3) * EPSILON = (|W| + 3) 2u` times the sum of
/// magnitudes covers all of them with room for `|W|` up to 2^40, and
/// `MIN_POSITIVE` covers underflow. Non-finite sums prove nothing.
///
/// The sums depend on the winners alone, so they are formed once per tet
/// rather than once per tested function.
pub(crate) struct WinnerSums {
    w: usize,
    /// Per corner: the sum of the winners and the sum of their magnitudes.
    sum: [f64; 4],
    mag: [f64; 4],
}

impl WinnerSums {
    pub(crate) fn new(winners: &[[f64; 4]]) -> WinnerSums {
        let (mut sum, mut mag) = ([0.0f64; 4], [0.0f64; 4]);
        for i in 0..4 {
            for g in winners {
                sum[i] += g[i];
                mag[i] += g[i].abs();
            }
        }
        WinnerSums { w: winners.len(), sum, mag }
    }

    /// Whether the winners' average strictly exceeds `f` at all four corners, proven.
    pub(crate) fn dominates(&self, f: &[f64; 4]) -> bool {
        let w = self.w;
        if w < 2 {
            return false;
        }
        (0..4).all(|i| {
            let p = w as f64 * f[i];
            let d = self.sum[i] - p;
            let bound = (w as f64 + 3.0) * f64::EPSILON * (self.mag[i] + p.abs()) + f64::MIN_POSITIVE;
            d.is_finite() && bound.is_finite() && d > bound
        })
    }
}

#[cfg(test)]
mod tests {
    use super::WinnerSums;

    #[test]
    fn average_of_winners_dominates_only_when_strictly_above() {
        // Average of the two winners: [0.5, 0.5, 0.5, 1.0].
        let w = [[1.0, 0.0, 0.5, 2.0], [0.0, 1.0, 0.5, 0.0]];
        let s = WinnerSums::new(&w);
        assert!(s.dominates(&[0.4, 0.4, 0.4, 0.9]));
        assert!(!s.dominates(&[0.5, 0.4, 0.4, 0.9]), "a tie at a corner proves nothing");
        assert!(!s.dominates(&[0.4, 0.4, 0.4, 1.1]));
        assert!(!s.dominates(&[f64::NAN, 0.0, 0.0, 0.0]));
        assert!(!WinnerSums::new(&w[..1]).dominates(&[-9.0; 4]), "one winner is no average");
        // Below the average by less than the rounding bound: not proven.
        assert!(!s.dominates(&[0.5 - 1e-17, 0.4, 0.4, 0.9]));
    }
}
