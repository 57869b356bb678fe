//! A static floating-point filter for the sign of a cell's volume in the
//! exact check of the written mesh (`verify`): the sum over the cell's
//! triangles of `det(b - o, c - o, d - o)` (divergence theorem), evaluated
//! in doubles with an error bound proven a priori, so that only cells whose
//! volume is within the bound go to the interval and exact sums (which
//! formed nine interval products per triangle for every cell).
//!
//! Its sibling `volume_filter.rs` decides the same kind of sum for the
//! cut's own cells, whose points are exact rationals known only to lie in
//! boxes (hence a bound with the boxes' radii); here the points are the
//! written doubles themselves, so Shewchuk's orient3d bound applies as is.

use septa_exact::{filtered_sign_bounded, Bounded, Exact, Interval, Ring, Sign};

/// The sign of `sum det(x[t0] - o, x[t1] - o, x[t2] - o)` over `tris` when
/// the floating-point sum proves it, else `None` (the caller then evaluates
/// it exactly). Never claims zero.
///
/// Bound (u = 2^-53, m triangles, `D_i` the exact determinant of triangle
/// i, `d_i` its floating-point value, `p_i` the floating-point permanent of
/// absolute values of the same products):
/// - each `d_i` is formed like Shewchuk's orient3d (rounded differences,
///   2x2 minors of two rows expanded along the third), so `|d_i - D_i| <=
///   (7u + 56u^2) p_i` (Shewchuk 1997, "Adaptive precision floating-point
///   arithmetic and fast robust geometric predicates", Sec. 4.3,
///   `o3derrboundA`);
/// - rounding is monotonic, so `|d_i| <= p_i` term by term;
/// - the recursive sums `s` of the `d_i` and `p` of the `p_i` err by at
///   most `gamma_{m-1}` times the sum of absolute values (Higham 2002,
///   "Accuracy and Stability of Numerical Algorithms", eq. 4.4; `gamma_k =
///   k u / (1 - k u)`), so `|s - sum D_i| <= (7u + 56u^2 + gamma_{m-1})
///   sum p_i` and `sum p_i <= p / (1 - gamma_{m-1})`;
/// - for `m u <= 2^-27` that is at most `(8 + 2m) u p`, and the rounded
///   product `fl((9 + 2m) u * p)` is at least that (the integer times a
///   power of two is exact; one rounding loses at most a factor `1 - u`).
///
/// The bound assumes no underflow: with `p > 1e-280` the slack of at least
/// `0.9 u p > 1e-297` in the coefficient exceeds the absolute error of
/// every underflowing operation together (at most ~30 m of 2^-1075 each).
/// An infinite `s` comes with `p = inf` and NaNs compare false: `None`.
pub(crate) fn volume_sign_static(x: &[[f64; 3]], o: [f64; 3], tris: &[[u32; 3]]) -> Option<Sign> {
    let m = tris.len();
    if m == 0 || m > 1 << 26 {
        return None;
    }
    let (mut s, mut p) = (0.0f64, 0.0f64);
    for t in tris {
        let r = |i: u32| {
            let q = &x[i as usize];
            [q[0] - o[0], q[1] - o[1], q[2] - o[2]]
        };
        let (a, b, c) = (r(t[0]), r(t[1]), r(t[2]));
        let (b1c2, b2c1) = (b[1] * c[2], b[2] * c[1]);
        let (b0c2, b2c0) = (b[0] * c[2], b[2] * c[0]);
        let (b0c1, b1c0) = (b[0] * c[1], b[1] * c[0]);
        // the same expression as the exact sum in `verify`
        s += a[0] * (b1c2 - b2c1) - a[1] * (b0c2 - b2c0) + a[2] * (b0c1 - b1c0);
        p += a[0].abs() * (b1c2.abs() + b2c1.abs())
            + a[1].abs() * (b0c2.abs() + b2c0.abs())
            + a[2].abs() * (b0c1.abs() + b1c0.abs());
    }
    if !(p > 1e-280) {
        return None;
    }
    let bound = ((9 + 2 * m) as f64 * (f64::EPSILON / 2.0)) * p;
    if s > bound {
        Some(Sign::Positive)
    } else if -s > bound {
        Some(Sign::Negative)
    } else {
        None
    }
}

/// Exact sign of the volume enclosed by oriented triangles (six times the
/// volume: `sum det(b - o, c - o, d - o)`).
pub(crate) fn volume_sign(x: &[[f64; 3]], tris: &[[u32; 3]]) -> Sign {
    let Some(t0) = tris.first() else { return Sign::Zero };
    let o = x[t0[0] as usize];
    if let Some(s) = volume_sign_static(x, o, tris) {
        return s;
    }
    filtered_sign_bounded(
        || volume_sum::<Bounded>(x, o, tris),
        || volume_sum::<Interval>(x, o, tris),
        || volume_sum::<Exact>(x, o, tris),
    )
}

/// `sum det(b - o, c - o, d - o)` over the triangles `(b, c, d)` in `R`.
pub(crate) fn volume_sum<R: Ring>(x: &[[f64; 3]], o: [f64; 3], tris: &[[u32; 3]]) -> R {
    let mut s = R::of(0.0);
    for t in tris {
        let p = |i: u32| -> [R; 3] { std::array::from_fn(|k| R::of(x[i as usize][k]).sub(&R::of(o[k]))) };
        let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
        let d = a[0]
            .mul(&b[1].mul(&c[2]).sub(&b[2].mul(&c[1])))
            .sub(&a[1].mul(&b[0].mul(&c[2]).sub(&b[2].mul(&c[0]))))
            .add(&a[2].mul(&b[0].mul(&c[1]).sub(&b[1].mul(&c[0]))));
        s = s.add(&d);
    }
    s
}

#[cfg(test)]
#[path = "verify_volume_tests.rs"]
mod tests;
