//! A floating-point static filter for the sign of a cell's volume
//! (`volume.rs`), run before its interval evaluation: the fan sum
//! `sum +-det[p_a - o, p_b - o, p_c - o]` on the midpoints of the
//! cut-vertices' boxes in plain doubles, with a proven bound on its distance
//! from the exact sum for *any* exact points inside the boxes (the style of
//! Shewchuk 1997, Sec. 4.2's static error bounds, with the boxes' radii as
//! an input error). When the float sum is farther from zero than the bound
//! its sign is the exact sign; otherwise the interval path (then the exact
//! one) decides, so no sign is ever taken from an undecided filter.
//! (The check of the written doubles has its own, tighter filter in
//! `verify_volume.rs`: there the points are exact doubles, not boxes.)
//!
//! The bound. For each vertex let `P = fl(m - o)` (`m` the box midpoint)
//! and `R >= |p - o - P|` componentwise (`p` the exact point: the box
//! radius plus the rounding of the difference, `|x - fl(x)| <= u |fl(x)|`
//! for round-to-nearest, `u = 2^-53`). `det` is trilinear, so with
//! `perm(x, y, z) = sum over the 6 permutations of |x_i y_j z_k|` (which
//! bounds `|det|`, is multilinear and increasing on non-negative vectors):
//!
//! `|det(P_a + D_a, P_b + D_b, P_c + D_c) - det(P_a, P_b, P_c)|
//!    <= perm(R_a, |P_b| + R_b, |P_c| + R_c) + perm(|P_a|, R_b, |P_c| + R_c)
//!     + perm(|P_a|, |P_b|, R_c)`                               (telescoping)
//!
//! `det(P_a, P_b, P_c)` evaluated as `a . (b x c)` has error at most
//! `8u perm(|P_a|, |P_b|, |P_c|)` (two roundings per cross component, one
//! per product and two for the sum of three: at most 5 on any path, each
//! relative to the permanent's terms; 8u leaves room for the higher-order
//! terms), and the recursive sum of `n` such values adds at most
//! `1.01 (n - 1) u sum |value|` (`gamma_(n-1)` for `n <= 2^20`), with
//! `|value| <= (1 + 8u) perm`. So with `E = sum pert_t` and
//! `S = sum perm_t`, `|exact - float| <= E + (n + 16) 2u S`. The bound
//! itself is computed in doubles from non-negative terms (each rounding
//! at most a relative `u`, at most `n + 20` of them on any path), so it is
//! taken times `1 + 2^-30`, and `n 2^-1000` is added for products that
//! underflow (absolute error at most `2^-1074` each, fewer than `2^26`
//! of them).

use septa_exact::{Interval, Sign};

/// `u = 2^-53`, the unit roundoff of round-to-nearest doubles.
const U: f64 = f64::EPSILON / 2.0;

/// Largest fan the bound's constants are stated for.
const MAX_TRIS: usize = 1 << 20;

/// The smallest double above `x >= 0` (finite).
fn up(x: f64) -> f64 {
    f64::from_bits(x.to_bits() + 1)
}

/// A vertex as the filter sees it: `P = fl(m - o)`, `|P|`, and the radius
/// `R` with `|p - o - P| <= R` for the exact point `p` in its box.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FilterPoint {
    p: [f64; 3],
    abs: [f64; 3],
    r: [f64; 3],
}

impl FilterPoint {
    /// From the box enclosing the exact point and the float origin `o`.
    pub(crate) fn new(b: &[Interval; 3], o: &[f64; 3]) -> FilterPoint {
        let mut f = FilterPoint { p: [0.0; 3], abs: [0.0; 3], r: [0.0; 3] };
        for k in 0..3 {
            let (lo, hi) = (b[k].lo, b[k].hi);
            let m = 0.5 * lo + 0.5 * hi;
            // |p - m| <= max(hi - m, m - lo), both rounded, so one step up
            let rad = up((hi - m).max(m - lo).max(0.0));
            let p = m - o[k];
            f.p[k] = p;
            f.abs[k] = p.abs();
            // the rounding of m - o: |(m - o) - p| <= u |p|
            f.r[k] = up(rad + up(U * p.abs()));
        }
        f
    }

    fn finite(&self) -> bool {
        (0..3).all(|k| self.p[k].is_finite() && self.r[k].is_finite())
    }
}

/// `sum over permutations (i, j, k) of x_i y_j z_k` for non-negative vectors.
#[inline]
fn perm(x: &[f64; 3], y: &[f64; 3], z: &[f64; 3]) -> f64 {
    x[0] * (y[1] * z[2] + y[2] * z[1]) + x[1] * (y[0] * z[2] + y[2] * z[0]) + x[2] * (y[0] * z[1] + y[1] * z[0])
}

#[inline]
fn add(x: &[f64; 3], y: &[f64; 3]) -> [f64; 3] {
    [x[0] + y[0], x[1] + y[1], x[2] + y[2]]
}

/// The sign of `sum +-det[p_a - o, p_b - o, p_c - o]` over the fan
/// triangles `tris` (indices into `pts`, `true` for `+`), when the float
/// evaluation decides it; `None` otherwise (the caller then evaluates
/// exactly). Never returns [`Sign::Zero`].
pub(crate) fn fan_sign(pts: &[FilterPoint], tris: &[([usize; 3], bool)]) -> Option<Sign> {
    let n = tris.len();
    if n == 0 || n > MAX_TRIS || !pts.iter().all(FilterPoint::finite) {
        return None;
    }
    let (mut v, mut e, mut s) = (0.0f64, 0.0f64, 0.0f64);
    for &([a, b, c], positive) in tris {
        let (a, b, c) = (&pts[a], &pts[b], &pts[c]);
        let cr =
            [b.p[1] * c.p[2] - b.p[2] * c.p[1], b.p[2] * c.p[0] - b.p[0] * c.p[2], b.p[0] * c.p[1] - b.p[1] * c.p[0]];
        let d = a.p[0] * cr[0] + a.p[1] * cr[1] + a.p[2] * cr[2];
        v = if positive { v + d } else { v - d };
        let (bb, cc) = (add(&b.abs, &b.r), add(&c.abs, &c.r));
        e += perm(&a.r, &bb, &cc) + perm(&a.abs, &b.r, &cc) + perm(&a.abs, &b.abs, &c.r);
        s += perm(&a.abs, &b.abs, &c.abs);
    }
    let bound = (e + (n as f64 + 16.0) * 2.0 * U * s) * (1.0 + 2f64.powi(-30)) + n as f64 * 2f64.powi(-1000);
    if !bound.is_finite() || !v.is_finite() {
        return None;
    }
    if v > bound {
        Some(Sign::Positive)
    } else if v < -bound {
        Some(Sign::Negative)
    } else {
        None
    }
}

#[cfg(test)]
#[path = "volume_filter_tests.rs"]
mod tests;
