//! Sides of points against the supporting plane of a cut-face (a cut plane,
//! or an input triangle's plane with its outward normal): the exact side of a
//! cut-vertex from its face triple, and the exact side of a rounded point
//! from its doubles (the plane is exact in doubles, so an orientation test).
//! The embedding's vertex-face orders (TopoCut Eq. (13)) compare the two.

use crate::cut::base::geom::{dot3, v3, Ctx, Def};
use crate::cut::Support;
use septa_exact::{det_sign_diff, filtered_sign_bounded, plane_point_sign, Bounded, Exact, Interval, Ring, Sign};

/// Exact side of cut-vertex `d` with respect to the supporting plane of `s`
/// (for a triangle, the sign of `n_t . (x - a)`, `n_t` its outward normal).
pub(crate) fn exact_side(c: &Ctx, d: Def, s: Support) -> Sign {
    // A triple that names the support lies on it: no arithmetic needed.
    let named = match (d, s) {
        (Def::EP(_, p), Support::Plane(q)) => p == q,
        (Def::TPP(_, p, q), Support::Plane(r)) => p == r || q == r,
        (Def::PPP(p, q, r), Support::Plane(x)) => p == x || q == x || r == x,
        (Def::V(v), Support::Tri(t)) => c.tris[t as usize].contains(&v),
        (Def::EP(e, _), Support::Tri(t)) => c.tri_edges[t as usize].contains(&e),
        (Def::TPP(u, _, _), Support::Tri(t)) => u == t,
        _ => false,
    };
    if named {
        return Sign::Zero;
    }
    if let Support::Tri(t) = s {
        if let Some(side) = side_by_corners(c, d, t) {
            return side;
        }
    }
    exact_side_full(c, d, s)
}

/// Exact side of a cut-vertex on the surface with respect to the plane of
/// triangle `t`, from the corners of the mesh element it lies strictly
/// inside: an input vertex is its own corner, `EP(e, p)` is
/// `lu u + lv v` on edge `e = (u, v)` and `TPP(s, p, q)` is `la a + lb b +
/// lc c` inside triangle `s = (a, b, c)`, all weights positive and summing
/// to 1. The orientation `det[b' - a', c' - a', x - a']` is affine in `x`,
/// so when the corners' exact orientations (input doubles) share one sign
/// or are 0, so does the vertex's. Nearly coplanar neighbouring triangles
/// (plate_genus9) are the pairs the interval filter cannot decide; this
/// decides them with three orientations instead of the cut-vertex's
/// rational coordinates. `None`: corners on both sides (or a vertex
/// inside the domain), left to [`exact_side_full`].
fn side_by_corners(c: &Ctx, d: Def, t: u32) -> Option<Sign> {
    let corners: &[u32] = match &d {
        Def::V(v) => std::slice::from_ref(v),
        Def::EP(e, _) => &c.edges[*e as usize],
        Def::TPP(u, _, _) => &c.tris[*u as usize],
        Def::PPP(..) => return None,
    };
    let (mut pos, mut neg) = (false, false);
    for &v in corners {
        match float_side(c, &c.verts[v as usize], Support::Tri(t)) {
            Sign::Positive => pos = true,
            Sign::Negative => neg = true,
            Sign::Zero => {}
        }
    }
    match (pos, neg) {
        (true, true) => None,
        (true, false) => Some(Sign::Positive),
        (false, true) => Some(Sign::Negative),
        (false, false) => Some(Sign::Zero),
    }
}

/// [`exact_side`] from the cut-vertex's homogeneous coordinates (no
/// shortcut).
pub(crate) fn exact_side_full(c: &Ctx, d: Def, s: Support) -> Sign {
    match s {
        Support::Plane(p) => c.side(d, p),
        Support::Tri(t) => {
            fn f<R: Ring>(c: &Ctx, d: Def, t: u32) -> R {
                let (h, w) = c.hom::<R>(d);
                let n = c.tn::<R>(t);
                let a = v3::<R>(&c.verts[c.tris[t as usize][0] as usize]);
                // n . (h / w - a) has the sign of (n . h - (n . a) w) w
                dot3(&n, &h).sub(&dot3(&n, &a).mul(&w)).mul(&w)
            }
            filtered_sign_bounded(|| f::<Bounded>(c, d, t), || f::<Interval>(c, d, t), || f::<Exact>(c, d, t))
        }
    }
}

/// Exact side of the double point `x` with respect to the supporting plane
/// of `s` (the plane is exact in doubles, so this is an orientation test).
pub fn float_side(c: &Ctx, x: &[f64; 3], s: Support) -> Sign {
    match s {
        Support::Plane(p) => plane_point_sign(&c.planes[p as usize], x),
        Support::Tri(t) => {
            let [a, b, cc] = c.tris[t as usize].map(|i| c.verts[i as usize]);
            // det[b - a, c - a, x - a] = ((b - a) x (c - a)) . (x - a)
            det_sign_diff(&[b, cc, *x], &[a, a, a])
        }
    }
}
