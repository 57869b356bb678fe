//! The certified criterion on one tet (docs/adaptive.md has the argument).
//!
//! Let `L` be the piecewise linear interpolant of a function `f` on the
//! mesh (what the exact extraction partitions) and `f_t = (1 - t) L + t f`.
//! Every check below holds for every `t` in `[0, 1]` at once, because it
//! uses `gp`, a box of gradients holding both `grad f` and `grad L` (and so
//! every convex combination). Then along the homotopy no zero set changes
//! its topology or its contacts with the tet's faces and edges, so the true
//! network is isotopic to the extracted one; and the distances stated are
//! bounds between the two.
//!
//! - sheet: the gradient cone is bounded away from 0 (`u . g >= m > 0`),
//!   every edge is crossed at most once, every face in one arc; the zero
//!   sets of `f` and `L` are within `rad(G) diam / m` of each other;
//! - pair: the two gradients are independent on the tet and on each face
//!   both zero sets meet, and their crossings of each edge stay apart;
//! - triple: a Krawczyk test proves the three zero sets meet in no point of
//!   the tet, or in one that stays inside it.

use crate::scene::Interval;

use super::lattice::EDGES;
use super::term::{
    centred_combo, cross, cross_iv, dot, dot_iv, max_norm, mig, norm, radius, sub, Local, Term, Tet, V3,
};

/// Why a tet is not certified yet (kept for the refinement statistics).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Miss {
    /// No gradient enclosure (a primitive without one).
    NoBound,
    /// A gradient cone holds 0.
    Cone,
    /// An edge may be crossed twice, or a face in two arcs.
    Boundary,
    /// The zero sets of `f` and `L` may be farther apart than the tolerance.
    Distance,
    /// Two zero sets may be tangent, or their curve may touch a face or an
    /// edge along the homotopy.
    Pair,
    /// Three zero sets: no proof of at most one point inside.
    Triple,
    /// Too many zero sets meet the tet.
    Many,
}

/// The faces of a tet as corner slots, with the corner opposite.
pub const FACES: [([usize; 3], usize); 4] = [([1, 2, 3], 0), ([0, 2, 3], 1), ([0, 1, 3], 2), ([0, 1, 2], 3)];

/// Unit outward normal of a face.
pub fn outward(tet: &Tet, face: [usize; 3], opposite: usize) -> V3 {
    let p = &tet.p;
    let mut n = cross(sub(p[face[1]], p[face[0]]), sub(p[face[2]], p[face[0]]));
    if dot(n, sub(p[opposite], p[face[0]])) > 0.0 {
        n = n.map(|x| -x);
    }
    let l = norm(n);
    n.map(|x| x / l)
}

/// A sheet's certificate: the slack used by the pair bounds.
#[derive(Clone, Copy, Debug)]
pub struct Sheet {
    /// Bound on `|f - L|` over the tet.
    pub eps: f64,
}

/// The sheet test of one crossing term; `sub_bound(lo, hi)` encloses the
/// term's values on a sub-box (for edges and faces).
pub fn sheet(tet: &Tet, t: &Term, tolerance: f64, local: Local<'_>) -> Result<Sheet, Miss> {
    if t.affine {
        return Ok(Sheet { eps: t.rounding });
    }
    let mid = t.gp.map(|x| 0.5 * (x.lo + x.hi));
    let l = norm(mid);
    if !(l > 0.0) {
        return Err(Miss::Cone);
    }
    let u = mid.map(|x| x / l);
    let m = dot_iv(u, &t.gp).lo;
    if !(m > 0.0) {
        return Err(Miss::Cone);
    }
    // Edges: monotone along the edge, or no zero on it at all.
    for (a, b) in EDGES {
        let d = edge_slopes(tet, t, local, a, b);
        if !d.contains(0.0) {
            continue;
        }
        if !edge_keeps_sign(t, a, b, d) {
            return Err(Miss::Boundary);
        }
    }
    // Faces: monotone along the face's share of u, or no zero on it.
    for (face, opp) in FACES {
        let tri = face.map(|c| tet.p[c]);
        let signs_agree = same_sign(t.vals[face[0]], t.vals[face[1]]) && same_sign(t.vals[face[0]], t.vals[face[2]]);
        // No zero on the face: then none of any f_t either (between L's
        // positive values and f's).
        if signs_agree && !triangle_may_vanish(tri, local, 2) {
            continue;
        }
        let n = outward(tet, face, opp);
        let w = sub(u, n.map(|x| x * dot(u, n)));
        let lw = norm(w);
        if !(lw > 1e-6) || !(dot_iv(w.map(|x| x / lw), &t.gp).lo > 0.0) {
            return Err(Miss::Boundary);
        }
    }
    let eps = radius(&t.g) * tet.diameter() * (1.0 + 1e-12) + t.rounding;
    if eps / m > tolerance {
        return Err(Miss::Distance);
    }
    Ok(Sheet { eps })
}

/// Whether the values' enclosure on a triangle's box holds 0, after
/// `depth` rounds of splitting it in four at its edges' midpoints.
fn triangle_may_vanish(t: [V3; 3], local: Local<'_>, depth: u32) -> bool {
    let lo = [0, 1, 2].map(|k| t[0][k].min(t[1][k]).min(t[2][k]));
    let hi = [0, 1, 2].map(|k| t[0][k].max(t[1][k]).max(t[2][k]));
    if !local.bound(lo, hi).contains(0.0) {
        return false;
    }
    if depth == 0 {
        return true;
    }
    let m = |a: V3, b: V3| [0, 1, 2].map(|k| 0.5 * (a[k] + b[k]));
    let (ab, bc, ca) = (m(t[0], t[1]), m(t[1], t[2]), m(t[2], t[0]));
    [[t[0], ab, ca], [ab, t[1], bc], [ca, bc, t[2]], [ab, bc, ca]]
        .into_iter()
        .any(|s| triangle_may_vanish(s, local, depth - 1))
}

/// The slopes `d/ds f_t(p_a + s (p_b - p_a))` for every `t` and `s`: the
/// interpolant's is `v_b - v_a`, the function's lie in `e . G` over the
/// edge's own box (tighter than the tet's).
fn edge_slopes(tet: &Tet, t: &Term, local: Local<'_>, a: usize, b: usize) -> Interval {
    let e = sub(tet.p[b], tet.p[a]);
    if t.affine {
        return dot_iv(e, &t.gp);
    }
    let (lo, hi) = tet.sub_box(&[a, b]);
    let g = local.grad(lo, hi).map(|g| [0, 1, 2].map(|k| g[k].meet(t.g[k]))).unwrap_or(t.g);
    let dl = t.vals[b] - t.vals[a];
    let pad = 1e-12 * dl.abs() + 2.0 * t.rounding;
    dot_iv(e, &g).hull(Interval::new(dl - pad, dl + pad))
}

fn same_sign(a: f64, b: f64) -> bool {
    (a > 0.0 && b > 0.0) || (a < 0.0 && b < 0.0)
}

/// Whether `f_t` keeps the sign of both ends on edge `ab` for every `t`:
/// with slopes `d` in `[lo, hi]` along the edge, `f_t(s)` is at least
/// `max(v_a + s lo, v_b - (1 - s) hi)` (positive ends; the mirror for
/// negative ones), whose smallest value is where the two lines cross.
fn edge_keeps_sign(t: &Term, a: usize, b: usize, d: Interval) -> bool {
    let (va, vb) = (t.vals[a], t.vals[b]);
    if !same_sign(va, vb) {
        return false;
    }
    let (va, vb, lo, hi) = if va > 0.0 { (va, vb, d.lo, d.hi) } else { (-va, -vb, -d.hi, -d.lo) };
    // Lines v_a + s lo (falling when lo < 0) and v_b - (1 - s) hi (rising).
    if lo >= 0.0 || hi <= 0.0 {
        return true; // monotone: the ends' sign holds
    }
    let s = (vb - hi - va) / (lo - hi); // where they cross, in (0, 1) or not
    let s = s.clamp(0.0, 1.0);
    let low = (va + s * lo).max(vb - (1.0 - s) * hi);
    low > 1e-12 * (va.abs() + vb.abs()) + t.rounding
}

/// The pair test of two crossing terms with their sheets.
pub fn pair(
    tet: &Tet,
    (a, sa): (&Term, Sheet),
    (b, sb): (&Term, Sheet),
    tolerance: f64,
    la: Local<'_>,
    lb: Local<'_>,
) -> Result<(), Miss> {
    if a.affine && b.affine {
        return Ok(());
    }
    let c = cross_iv(&a.gp, &b.gp);
    let low = (mig(c[0]).powi(2) + mig(c[1]).powi(2) + mig(c[2]).powi(2)).sqrt() * (1.0 - 1e-15);
    if !(low > 0.0) {
        return Err(Miss::Pair);
    }
    // The curve of L is within |(eps_a, eps_b)| / sigma_min of the true one,
    // sigma_min >= |g_a x g_b| / (sqrt 2 max |g|).
    let sigma = low / (std::f64::consts::SQRT_2 * max_norm(&a.gp).max(max_norm(&b.gp)));
    if sa.eps.hypot(sb.eps) / sigma > tolerance {
        return Err(Miss::Distance);
    }
    // Each face both zero sets meet: independent within the face.
    for (face, opp) in FACES {
        if flat_on(a, la, &face) || flat_on(b, lb, &face) {
            continue;
        }
        let n = outward(tet, face, opp);
        let tri = face.map(|k| tet.p[k]);
        let (va, vb) = (face.map(|k| a.vals[k]), face.map(|k| b.vals[k]));
        if !pair_face_ok(&Pair2 { a, b, la, lb, n }, tri, va, vb, 3) {
            return Err(Miss::Pair);
        }
    }
    // Each edge both cross: their crossings stay apart.
    for (i, j) in EDGES {
        let (lo, hi) = tet.sub_box(&[i, j]);
        if apart(a, b, la, lb, &[i, j], lo, hi) || flat_on(a, la, &[i, j]) || flat_on(b, lb, &[i, j]) {
            continue;
        }
        let (da, db) = (edge_slopes(tet, a, la, i, j), edge_slopes(tet, b, lb, i, j));
        let (ra, rb) = match (root_range(a, da, i, j), root_range(b, db, i, j)) {
            (Some(ra), Some(rb)) => (ra, rb),
            _ => continue,
        };
        if !(ra.1 < rb.0 || rb.1 < ra.0) {
            return Err(Miss::Pair);
        }
    }
    Ok(())
}

/// A pair on one face of the tet.
struct Pair2<'a> {
    a: &'a Term,
    b: &'a Term,
    la: Local<'a>,
    lb: Local<'a>,
    n: V3,
}

/// Whether the curve of `f_t,a = f_t,b = 0` meets the triangle (part of a
/// face, with normal `n`, corner values `va`, `vb` of the interpolants)
/// only transversally for every `t`: no common zero on it (bounds or a
/// combination of one sign), or `det(g_a, g_b, n)` of one sign over the
/// part's box; else split in four, `depth` times. A curve tangent to a
/// face plane near its extreme is common (every closed curve has one per
/// direction), and there the face usually misses it by far more than
/// its parts' size.
fn pair_face_ok(p: &Pair2<'_>, tri: [V3; 3], va: [f64; 3], vb: [f64; 3], depth: u32) -> bool {
    let lo = [0, 1, 2].map(|k| tri[0][k].min(tri[1][k]).min(tri[2][k]));
    let hi = [0, 1, 2].map(|k| tri[0][k].max(tri[1][k]).max(tri[2][k]));
    let none_a = !p.la.bound(lo, hi).contains(0.0);
    let none_b = !p.lb.bound(lo, hi).contains(0.0);
    // The interpolants' values lie between the corners'; f's in the bound.
    let signed = |v: [f64; 3]| v.iter().all(|&x| x > 0.0) || v.iter().all(|&x| x < 0.0);
    if (none_a && signed(va)) || (none_b && signed(vb)) {
        return true;
    }
    for s in [-1.0, 1.0] {
        let at = [0, 1, 2].map(|i| va[i] + s * vb[i]);
        if signed(at) {
            if let Some(v) = centred_combo(p.la, p.lb, s, lo, hi) {
                if (at[0] > 0.0 && v.lo > 0.0) || (at[0] < 0.0 && v.hi < 0.0) {
                    return true;
                }
            }
        }
    }
    let g = |l: Local<'_>, t: &Term| {
        l.grad(lo, hi).map(|g| [0, 1, 2].map(|k| g[k].meet(t.g[k]).hull(t.gl[k]))).unwrap_or(t.gp)
    };
    let (ga, gb) = (g(p.la, p.a), g(p.lb, p.b));
    if !dot_iv(p.n, &cross_iv(&ga, &gb)).contains(0.0) {
        return true;
    }
    if depth == 0 {
        return false;
    }
    let m = |x: V3, y: V3| [0, 1, 2].map(|k| 0.5 * (x[k] + y[k]));
    let (ab, bc, ca) = (m(tri[0], tri[1]), m(tri[1], tri[2]), m(tri[2], tri[0]));
    let h = |v: [f64; 3]| (0.5 * (v[0] + v[1]), 0.5 * (v[1] + v[2]), 0.5 * (v[2] + v[0]));
    let (a01, a12, a20) = h(va);
    let (b01, b12, b20) = h(vb);
    pair_face_ok(p, [tri[0], ab, ca], [va[0], a01, a20], [vb[0], b01, b20], depth - 1)
        && pair_face_ok(p, [ab, tri[1], bc], [a01, va[1], a12], [b01, vb[1], b12], depth - 1)
        && pair_face_ok(p, [ca, bc, tri[2]], [a20, a12, va[2]], [b20, b12, vb[2]], depth - 1)
        && pair_face_ok(p, [ab, bc, ca], [a01, a12, a20], [b01, b12, b20], depth - 1)
}

/// An affine term vanishing at every corner of a face or edge vanishes on
/// all of it for every `t` (its interpolant is itself): there the pair's
/// curve is the other term's zero set in the face or edge, which its sheet
/// test already proved a single arc or point.
fn flat_on(t: &Term, l: Local<'_>, corners: &[usize]) -> bool {
    l.affine() && corners.iter().all(|&c| t.vals[c] == 0.0)
}

/// Whether `f_t,a` and `f_t,b` have no common zero on a face or edge (its
/// corners `corners`, its box `lo, hi`) for any `t`: `a - b` or `a + b`
/// keeps one sign there, both on the corners (so for the interpolants)
/// and in a centred enclosure of the functions.
fn apart(a: &Term, b: &Term, la: Local<'_>, lb: Local<'_>, corners: &[usize], lo: V3, hi: V3) -> bool {
    [-1.0, 1.0].into_iter().any(|s| {
        let at: Vec<f64> = corners.iter().map(|&c| a.vals[c] + s * b.vals[c]).collect();
        let pos = at.iter().all(|&v| v > 0.0);
        let neg = at.iter().all(|&v| v < 0.0);
        if !(pos || neg) {
            return false;
        }
        match centred_combo(la, lb, s, lo, hi) {
            Some(v) => (pos && v.lo > 0.0) || (neg && v.hi < 0.0),
            None => false,
        }
    })
}

/// Where along edge `ij` (as a fraction) the zero of `f_t` can be, for every
/// `t`, when the edge's ends have opposite signs and the term is monotone
/// along it; `None` when the edge has no zero. A zero corner is its own root.
fn root_range(t: &Term, d: Interval, i: usize, j: usize) -> Option<(f64, f64)> {
    let (vi, vj) = (t.vals[i], t.vals[j]);
    if vi == 0.0 {
        return Some((0.0, 0.0));
    }
    if vj == 0.0 {
        return Some((1.0, 1.0));
    }
    if (vi > 0.0) == (vj > 0.0) {
        return None;
    }
    // d/ds f_t(p_i + s e) lies in d, of one sign (the sheet test).
    let (dmin, dmax) = (mig(d), d.mag());
    if !(dmin > 0.0) {
        return Some((0.0, 1.0));
    }
    let (ai, aj) = (vi.abs(), vj.abs());
    let lo = (ai / dmax).max(1.0 - aj / dmin) * (1.0 - 1e-12) - 1e-15;
    let hi = (ai / dmin).min(1.0 - aj / dmax) * (1.0 + 1e-12) + 1e-15;
    Some((lo, hi))
}

/// The triple test (Krawczyk's operator on the tet's bounding box).
pub fn triple(tet: &Tet, terms: [&Term; 3], tolerance: f64) -> Result<(), Miss> {
    if terms.iter().all(|t| t.affine) {
        return Ok(());
    }
    let j: [[Interval; 3]; 3] = [terms[0].gp, terms[1].gp, terms[2].gp];
    let m: [[f64; 3]; 3] = j.map(|r| r.map(|x| 0.5 * (x.lo + x.hi)));
    let y = inverse(&m).ok_or(Miss::Triple)?;
    let c = tet.centre();
    let x: [Interval; 3] = [0, 1, 2].map(|k| Interval::new(tet.lo[k], tet.hi[k]));
    let xc: [Interval; 3] = [0, 1, 2].map(|k| x[k].sub(Interval::point(c[k])));
    let fc = [terms[0].at_centre, terms[1].at_centre, terms[2].at_centre];
    let mut k_box = [Interval::point(0.0); 3];
    for r in 0..3 {
        // c - Y F(c) + (I - Y J)(X - c)
        let mut s = Interval::point(c[r]);
        for q in 0..3 {
            s = s.sub(fc[q].scale(y[r][q]));
        }
        for col in 0..3 {
            let mut entry = Interval::point(if r == col { 1.0 } else { 0.0 });
            for q in 0..3 {
                entry = entry.sub(j[q][col].scale(y[r][q]));
            }
            s = s.add(entry.mul(xc[col]));
        }
        k_box[r] = s;
    }
    // No common zero in the box for any t.
    if (0..3).any(|r| k_box[r].hi < x[r].lo || k_box[r].lo > x[r].hi) {
        return Ok(());
    }
    // Two affine terms: the point moves along their exact line, where the
    // third is monotone (the Jacobian is regular), so it is never created,
    // lost or doubled; it may lie on the tet's faces or edges throughout
    // (lines through bisection vertices are the common case). Every zero
    // in the box lies in K, so within diam(K meet X) of each other.
    let affine = terms.iter().filter(|t| t.affine).count();
    if affine >= 2 && !dot_iv_iv(&j[0], &cross_iv(&j[1], &j[2])).contains(0.0) {
        let diam = norm([0, 1, 2].map(|r| k_box[r].hi.min(x[r].hi) - k_box[r].lo.max(x[r].lo)));
        return if diam <= tolerance { Ok(()) } else { Err(Miss::Distance) };
    }
    // A unique zero, inside K, for every t: K in the box's interior.
    if !(0..3).all(|r| k_box[r].lo > x[r].lo && k_box[r].hi < x[r].hi) {
        return Err(Miss::Triple);
    }

    let corners: Vec<V3> =
        (0..8).map(|b| [0, 1, 2].map(|r| if b >> r & 1 == 0 { k_box[r].lo } else { k_box[r].hi })).collect();
    let side = |face: [usize; 3], opp: usize| {
        let n = outward(tet, face, opp);
        let d: Vec<f64> = corners.iter().map(|q| dot(n, sub(*q, tet.p[face[0]]))).collect();
        let scale = norm(sub(tet.hi, tet.lo)) * 1e-12;
        (
            d.iter().cloned().fold(f64::INFINITY, f64::min) > scale,
            d.iter().cloned().fold(f64::NEG_INFINITY, f64::max) < -scale,
        )
    };
    let sides: Vec<(bool, bool)> = FACES.iter().map(|&(f, o)| side(f, o)).collect();
    if sides.iter().any(|s| s.0) {
        return Ok(()); // the point stays outside the tet
    }
    if sides.iter().all(|s| s.1) {
        let diam = norm([0, 1, 2].map(|r| k_box[r].hi - k_box[r].lo));
        return if diam <= tolerance { Ok(()) } else { Err(Miss::Distance) };
    }
    Err(Miss::Triple)
}

fn dot_iv_iv(a: &[Interval; 3], b: &[Interval; 3]) -> Interval {
    a[0].mul(b[0]).add(a[1].mul(b[1])).add(a[2].mul(b[2]))
}

fn inverse(m: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let det = dot(m[0], cross(m[1], m[2]));
    if !(det.abs() > 0.0) || !det.is_finite() {
        return None;
    }
    let c0 = cross(m[1], m[2]);
    let c1 = cross(m[2], m[0]);
    let c2 = cross(m[0], m[1]);
    // inverse = [c0 c1 c2] / det (columns).
    Some([0, 1, 2].map(|r| [c0[r] / det, c1[r] / det, c2[r] / det]))
}
