//! Exact orientation signs of points given as indices into a list of
//! doubles, the predicates every triangle test of the cut and of the check
//! is made of: orient3d and its 2D projections, each behind Shewchuk's
//! static filter (Shewchuk 1997), exact shortcuts for the coplanar and
//! collinear cases that filter cannot see, then the exact determinant.

use septa_exact::{filtered_sign_bounded, Bounded, Exact, Interval, Ring, Sign};

/// Orientation of `d` against the plane through `a b c`: the sign of
/// `det(b - a, c - a, d - a)`.
pub(crate) fn orient(x: &[[f64; 3]], a: u32, b: u32, c: u32, d: u32) -> Sign {
    orient_filtered(x, a, b, c, d).unwrap_or_else(|| orient_slow(x, a, b, c, d))
}

/// [`orient`] after its static filter gave up.
pub(crate) fn orient_slow(x: &[[f64; 3]], a: u32, b: u32, c: u32, d: u32) -> Sign {
    // Four points with one coordinate exactly equal lie in one axis
    // plane: exactly coplanar. Cut-faces on axis-aligned planes (their
    // cut-vertices are snapped onto them) are all of this kind; without
    // this shortcut each of their planarity and coplanar-pair tests
    // went through the interval and exact determinants.
    let same = |k: usize| [b, c, d].iter().all(|&i| x[i as usize][k] == x[a as usize][k]);
    if (0..3).any(same) {
        return Sign::Zero;
    }
    // nearby points (the nearly degenerate pairs of neighbouring
    // triangles) subtract exactly: their determinant is then computed
    // exactly from the rounded differences, several times cheaper than
    // intervals followed by the general exact tiers
    let p = |i: u32| &x[i as usize];
    if let Some(s) = septa_exact::orient3d_exact_diffs(p(a), p(b), p(c), p(d)) {
        return s;
    }
    orient_exact(x, a, b, c, d)
}

/// The sign of a floating-point orient3d determinant `det` when Shewchuk's
/// static bound proves it (Shewchuk 1997, `o3derrboundA`: |det - fl(det)|
/// <= (7u + 56u^2) * permanent, u = 2^-53, `perm` the permanent of absolute
/// values of the same products), else `None`. Non-finite values and
/// permanents small enough for underflow to void the bound give `None`.
///
/// Non-finite values need no test of their own: rounding is monotonic, so
/// each rounded product and sum of `perm` is at least the absolute value of
/// the corresponding one of `det` (`|fl(a - b)| <= fl(|a| + |b|)`, `|fl(a b)|
/// = fl(|a| |b|)`), hence `|det| <= perm` in floating point: an infinite
/// `det` comes with `perm = inf`, so `bound = inf`, and comparisons with a
/// NaN (`det` or `perm`) are false; every such case gives `None`.
#[inline]
pub(crate) fn proven_sign(det: f64, perm: f64) -> Option<Sign> {
    const U: f64 = f64::EPSILON / 2.0;
    let bound = (7.0 * U + 56.0 * U * U) * perm;
    if !(perm > 1e-280) {
        return None;
    }
    if det > bound {
        Some(Sign::Positive)
    } else if -det > bound {
        Some(Sign::Negative)
    } else {
        None
    }
}

/// [`orient`] when its static filter decides it, else `None` (no exact
/// fallback: for quick rejections that may give up).
pub(crate) fn orient_filtered(x: &[[f64; 3]], a: u32, b: u32, c: u32, d: u32) -> Option<Sign> {
    // Shewchuk's static filter for orient3d ([`proven_sign`]).
    let (pa, pb, pc, pd) = (&x[a as usize], &x[b as usize], &x[c as usize], &x[d as usize]);
    let adx = pa[0] - pd[0];
    let bdx = pb[0] - pd[0];
    let cdx = pc[0] - pd[0];
    let ady = pa[1] - pd[1];
    let bdy = pb[1] - pd[1];
    let cdy = pc[1] - pd[1];
    let adz = pa[2] - pd[2];
    let bdz = pb[2] - pd[2];
    let cdz = pc[2] - pd[2];
    let bdxcdy = bdx * cdy;
    let cdxbdy = cdx * bdy;
    let cdxady = cdx * ady;
    let adxcdy = adx * cdy;
    let adxbdy = adx * bdy;
    let bdxady = bdx * ady;
    let det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
    let perm = (bdxcdy.abs() + cdxbdy.abs()) * adz.abs()
        + (cdxady.abs() + adxcdy.abs()) * bdz.abs()
        + (adxbdy.abs() + bdxady.abs()) * cdz.abs();
    // `det` is det(a - d, b - d, c - d), the opposite sign of
    // `orient(a, b, c, d)` = sign det(b - a, c - a, d - a).
    proven_sign(det, perm).map(|s| -s)
}

pub(crate) fn orient_exact(x: &[[f64; 3]], a: u32, b: u32, c: u32, d: u32) -> Sign {
    fn f(x: &[[f64; 3]], a: u32, b: u32, c: u32, d: u32) -> Interval {
        let p = |i: u32| {
            [Interval::point(x[i as usize][0]), Interval::point(x[i as usize][1]), Interval::point(x[i as usize][2])]
        };
        let (pa, pb, pc, pd) = (p(a), p(b), p(c), p(d));
        let u: [Interval; 3] = std::array::from_fn(|k| pb[k].sub(&pa[k]));
        let v: [Interval; 3] = std::array::from_fn(|k| pc[k].sub(&pa[k]));
        let w: [Interval; 3] = std::array::from_fn(|k| pd[k].sub(&pa[k]));
        u[0].mul(&v[1].mul(&w[2]).sub(&v[2].mul(&w[1])))
            .sub(&u[1].mul(&v[0].mul(&w[2]).sub(&v[2].mul(&w[0]))))
            .add(&u[2].mul(&v[0].mul(&w[1]).sub(&v[1].mul(&w[0]))))
    }
    if let Some(s) = f(x, a, b, c, d).sign() {
        return s;
    }
    // det(b - a, c - a, d - a), differences formed exactly inside septa-exact
    let p = |i: u32| x[i as usize];
    let pa = p(a);
    septa_exact::det_sign_diff::<3>(&[p(b), p(c), p(d)], &[pa, pa, pa])
}

/// 2D orientation of points projected by dropping axis `k`.
pub(crate) fn orient2(x: &[[f64; 3]], k: usize, a: u32, b: u32, c: u32) -> Sign {
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    // Shewchuk's static filter for orient2d (`ccwerrboundA` = (3u + 16u^2))
    let (pa, pb, pc) = (&x[a as usize], &x[b as usize], &x[c as usize]);
    let l = (pb[i] - pa[i]) * (pc[j] - pa[j]);
    let r = (pb[j] - pa[j]) * (pc[i] - pa[i]);
    let det = l - r;
    const U: f64 = f64::EPSILON / 2.0;
    let bound = (3.0 * U + 16.0 * U * U) * (l.abs() + r.abs());
    if det.is_finite() && (l.abs() + r.abs()) > 1e-280 {
        if det > bound {
            return Sign::Positive;
        }
        if -det > bound {
            return Sign::Negative;
        }
    }
    // Exact zeros the filter cannot see, common on axis-aligned cut-faces
    // (cube A10 used to send ~15k of them to the exact fallback): three
    // points on one axis-parallel line, or two of them the same projected
    // point, are exactly collinear.
    let eq = |p: &[f64; 3], q: &[f64; 3]| p[i] == q[i] && p[j] == q[j];
    if (pa[i] == pb[i] && pa[i] == pc[i]) || (pa[j] == pb[j] && pa[j] == pc[j]) {
        return Sign::Zero;
    }
    if eq(pa, pb) || eq(pa, pc) || eq(pb, pc) {
        return Sign::Zero;
    }
    // det [b - a; c - a] with the differences formed inside the exact
    // predicate (its own filter, then i128 or expansion arithmetic, bignums
    // only outside their exponent window): nearly collinear rounded rims of
    // flat cut-faces (plate_genus9: ~11k signs per check) used to go through
    // intervals and then allocating bignums.
    septa_exact::det_sign_diff::<2>(&[[pb[i], pb[j]], [pc[i], pc[j]]], &[[pa[i], pa[j]], [pa[i], pa[j]]])
}

/// Sign of `(w - v) . (o - v)` in the projection dropping axis `k`.
pub(crate) fn dot2(x: &[[f64; 3]], k: usize, v: u32, w: u32, o: u32) -> Sign {
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    fn f<R: Ring>(x: &[[f64; 3]], i: usize, j: usize, v: u32, w: u32, o: u32) -> R {
        let c = |t: u32, a: usize| R::of(x[t as usize][a]);
        let (wi, wj) = (c(w, i).sub(&c(v, i)), c(w, j).sub(&c(v, j)));
        let (oi, oj) = (c(o, i).sub(&c(v, i)), c(o, j).sub(&c(v, j)));
        wi.mul(&oi).add(&wj.mul(&oj))
    }
    filtered_sign_bounded(
        || f::<Bounded>(x, i, j, v, w, o),
        || f::<Interval>(x, i, j, v, w, o),
        || f::<Exact>(x, i, j, v, w, o),
    )
}

/// An axis along which the plane of triangle `t` projects without collapse.
pub(crate) fn proj_axis(x: &[[f64; 3]], t: &[u32; 3]) -> usize {
    (0..3)
        .find(|&k| {
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            let _ = (i, j);
            orient2(x, k, t[0], t[1], t[2]) != Sign::Zero
        })
        .unwrap_or(2)
}
