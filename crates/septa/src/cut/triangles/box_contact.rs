//! Pairs of triangles whose bounding boxes only touch: decided from the
//! boxes and a few coordinate comparisons, before the orientation tests of
//! `tri_pair`.
//!
//! Cut-cell meshes of axis-aligned planes are full of them: the faces of
//! neighbouring cells lie on perpendicular or identical axis planes and
//! their triangles' boxes meet in a rectangle, a segment or a point. On cube
//! A10, 131k of the exact check's 134k candidate pairs are of this kind;
//! half of all pairs used to go on to the 2D projection test and an eighth
//! to the general-position test, each asking for several orientations that
//! are mostly exact zeros, past the floating-point filters. Any mesh has
//! some: two triangles sharing a corner that is the highest point of one
//! and the lowest of the other along an axis (bunny R20: 129k of 357k).
//!
//! Why the boxes decide. Two closed triangles meet only inside the overlap
//! `B` of their boxes. Call an axis `k` *flat* when `B` is a single value
//! `c_k` on it that is the least or the greatest coordinate `k` of each
//! triangle. A linear function reaches its extreme over a triangle on a face
//! (a corner, an edge or the whole triangle), the hull of the corners
//! reaching it; faces of a triangle meet in the face of their common corners.
//! So the points of a triangle `T` with `p_k = c_k` on every flat axis are
//! exactly the hull `conv(C)` of its corners `C` there, and
//! `T1 ∩ T2 = conv(C1) ∩ conv(C2)`. The pair is allowed to meet in the hull
//! of its shared corners `S` (a vertex or the shared edge), itself a face of
//! `T1`; as `T1 ∩ T2 ⊆ conv(C1)`, it stays there iff it stays in
//! `conv(S ∩ C1)`.
//!
//! With two or three flat axes every point of `C1` and `C2` lies on one
//! axis-parallel line, where hulls are intervals of the remaining
//! coordinate: comparisons of doubles decide everything. With one flat axis
//! the hulls lie in one axis plane; corners, edges and a triangle there are
//! decided by exact 2D orientations, and two whole triangles (coplanar faces
//! on one axis plane) are left to `tri_pair`, as is an edge that neither
//! meets a triangle at an end nor is separated from it by a line. Every
//! answer is exact: no arithmetic is done on the coordinates, only
//! comparisons and `orient2`.

use crate::cut::triangles::orient::orient2;
use crate::cut::triangles::pair_grid::Aabb;
use crate::cut::triangles::tri_pair::{in_tri2, seg_seg2};
use septa_exact::Sign;

/// Whether the triangles `t1` and `t2` (corners in `x`, boxes `b1` and
/// `b2`) meet anywhere besides their shared vertices and edges, when the
/// way their boxes touch decides it (see the module doc); `None`
/// otherwise. The same answer as `tri_pair::pair_intersects` whenever it
/// answers.
///
/// `e1` and `e2` are the triangles' [`extreme_corners`] (read instead of
/// the corners' coordinates: most pairs of this kind are decided from them
/// and the corner ids alone).
#[inline(always)]
pub(crate) fn box_contact(
    x: &[[f64; 3]],
    t1: &[u32; 3],
    b1: &Aabb,
    e1: u32,
    t2: &[u32; 3],
    b2: &Aabb,
    e2: u32,
) -> Option<bool> {
    // the flat axes and their common value (no branch per axis: most
    // pairs of a curved surface have none and leave at once)
    let (mut flat, mut c) = ([false; 3], [0.0f64; 3]);
    for k in 0..3 {
        let (lo, hi) = (b1.0[k].max(b2.0[k]), b1.1[k].min(b2.1[k]));
        let ends = |b: &Aabb| (lo == b.0[k]) | (lo == b.1[k]);
        flat[k] = (lo == hi) & ends(b1) & ends(b2);
        c[k] = lo;
    }
    if !(flat[0] | flat[1] | flat[2]) {
        return None;
    }
    // the corners of each triangle on every flat plane, as bit masks: on a
    // flat axis `c_k` is the triangle's least or greatest coordinate, so its
    // corners there are those reaching that extreme
    let on = |b: &Aabb, e: u32| -> u32 {
        let mut m = 7;
        for k in 0..3 {
            if flat[k] {
                let shift = 6 * k + if c[k] == b.0[k] { 0 } else { 3 };
                m &= e >> shift & 7;
            }
        }
        m
    };
    let (m1, m2) = (on(b1, e1), on(b2, e2));
    if m1 == 0 || m2 == 0 {
        return Some(false);
    }
    // the commonest contact, a corner against a corner: they meet iff at
    // one point, allowed iff one vertex
    if m1.is_power_of_two() && m2.is_power_of_two() {
        let (v1, v2) = (t1[m1.trailing_zeros() as usize], t2[m2.trailing_zeros() as usize]);
        return Some(v1 != v2 && x[v1 as usize] == x[v2 as usize]);
    }
    // the next commonest, an edge of both (faces of neighbouring cells
    // along one cut-edge): they meet in it, as allowed
    if m1.count_ones() == 2 && m2.count_ones() == 2 {
        let edge = |t: &[u32; 3], m: u32| {
            let (a, b) = (t[m.trailing_zeros() as usize], t[(31 - m.leading_zeros()) as usize]);
            (a.min(b), a.max(b))
        };
        if edge(t1, m1) == edge(t2, m2) {
            return Some(false);
        }
    }
    hulls_meet(x, flat, t1, m1, t2, m2)
}

/// Which corners of triangle `t` reach the ends of its box `b` on each
/// axis: bits `6k..6k+3` the corners with the least coordinate `k`, bits
/// `6k+3..6k+6` those with the greatest (a bit per corner, in `t`'s order).
pub(crate) fn extreme_corners(x: &[[f64; 3]], t: &[u32; 3], b: &Aabb) -> u32 {
    let mut e = 0;
    for k in 0..3 {
        for (q, &v) in t.iter().enumerate() {
            let p = x[v as usize][k];
            e |= ((p == b.0[k]) as u32) << (6 * k + q) | ((p == b.1[k]) as u32) << (6 * k + 3 + q);
        }
    }
    e
}

/// Up to three corner ids of one triangle.
#[derive(Clone, Copy)]
struct Corners {
    ids: [u32; 3],
    n: usize,
}

impl Corners {
    /// The corners `v` (at position `q`) of `t` for which `f(q, v)`.
    fn keep(t: &[u32], f: impl Fn(usize, u32) -> bool) -> Corners {
        let mut s = Corners { ids: [0; 3], n: 0 };
        for (q, &v) in t.iter().enumerate() {
            if f(q, v) {
                s.ids[s.n] = v;
                s.n += 1;
            }
        }
        s
    }

    fn ids(&self) -> &[u32] {
        &self.ids[..self.n]
    }
}

/// Whether the faces of `t1` and `t2` on the flat planes (their corners
/// with bits set in `m1` and `m2`, both non-zero) meet outside the hull of
/// the shared corners; `None` when one of them is a whole triangle lying
/// in the one flat plane.
#[inline(never)]
fn hulls_meet(x: &[[f64; 3]], flat: [bool; 3], t1: &[u32; 3], m1: u32, t2: &[u32; 3], m2: u32) -> Option<bool> {
    // the shared corners among them: those of `t1`'s face that `t2` has
    // (a shared corner on the flat planes is on `t2`'s face too)
    let ms = (0..3).fold(0, |m, q| m | (((m1 >> q & 1 == 1) && t2.contains(&t1[q])) as u32) << q);
    if flat.iter().filter(|&&f| f).count() == 1 {
        let k = (0..3).find(|&k| flat[k]).unwrap_or(0);
        let c = |t: &[u32; 3], m: u32| Corners::keep(t, |q, _| m >> q & 1 == 1);
        return in_axis_plane(x, k, &c(t1, m1), &c(t2, m2), &c(t1, ms));
    }
    // one axis-parallel line (or a point): faces are intervals of the
    // remaining coordinate `a`
    let a = (0..3).find(|&k| !flat[k]).unwrap_or(0);
    let span = |t: &[u32; 3], m: u32| {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for q in 0..3 {
            if m >> q & 1 == 1 {
                let v = x[t[q] as usize][a];
                (lo, hi) = (lo.min(v), hi.max(v));
            }
        }
        (lo, hi)
    };
    let ((l1, h1), (l2, h2)) = (span(t1, m1), span(t2, m2));
    let (lo, hi) = (l1.max(l2), h1.min(h2));
    if lo > hi {
        return Some(false);
    }
    if ms == 0 {
        return Some(true);
    }
    let (ls, hs) = span(t1, ms);
    Some(!(ls <= lo && hi <= hs))
}

/// The faces `c1` and `c2` in the axis plane dropping axis `k` (corners,
/// edges or whole triangles) against each other, with `shared` the shared
/// corners among them; `None` for two whole triangles (coplanar faces:
/// `tri_pair` separates them by an edge line).
fn in_axis_plane(x: &[[f64; 3]], k: usize, c1: &Corners, c2: &Corners, shared: &Corners) -> Option<bool> {
    let (s1, s2) = (c1.ids(), c2.ids());
    let tri = |s: &[u32]| [s[0], s[1], s[2]];
    match (s1.len(), s2.len()) {
        // a corner meets the other face only in itself: allowed iff shared
        (1, 2) => Some(shared.n == 0 && on_segment(x, k, s1[0], s2[0], s2[1])),
        (2, 1) => Some(shared.n == 0 && on_segment(x, k, s2[0], s1[0], s1[1])),
        (1, 3) => Some(shared.n == 0 && in_tri2(x, k, s1[0], &tri(s2))),
        (3, 1) => Some(shared.n == 0 && in_tri2(x, k, s2[0], &tri(s1))),
        (2, 2) => match shared.n {
            // the same edge: they meet in it
            2 => Some(false),
            // edges from one shared corner: they overlap beyond it iff
            // they run along one line in one direction
            1 => {
                let v = shared.ids[0];
                let p = if s1[0] == v { s1[1] } else { s1[0] };
                let q = if s2[0] == v { s2[1] } else { s2[0] };
                Some(orient2(x, k, v, p, q) == Sign::Zero && same_direction(x, k, v, p, q))
            }
            _ => Some(seg_seg2(x, k, s1[0], s1[1], s2[0], s2[1])),
        },
        (2, 3) => edge_meets_triangle(x, k, [s1[0], s1[1]], &tri(s2), shared),
        (3, 2) => edge_meets_triangle(x, k, [s2[0], s2[1]], &tri(s1), shared),
        _ => None,
    }
}

/// Does the edge `e` meet the closed triangle `t` (both in the axis plane
/// dropping axis `k`) outside the hull of `shared`, the corners of `e`
/// that `t` has? `None` when it cannot tell.
fn edge_meets_triangle(x: &[[f64; 3]], k: usize, e: [u32; 2], t: &[u32; 3], shared: &Corners) -> Option<bool> {
    match shared.n {
        // an edge of `t`: inside it
        2 => Some(false),
        // from the corner `a` of `t`: it goes beyond `a` iff it leaves `a`
        // into the closed angle of `t` there
        1 => {
            let a = shared.ids[0];
            let b = if e[0] == a { e[1] } else { e[0] };
            let q = t.iter().position(|&v| v == a).unwrap_or(0);
            let (c, d) = (t[(q + 1) % 3], t[(q + 2) % 3]);
            let inner = orient2(x, k, a, c, d);
            let (s1, s2) = (orient2(x, k, a, c, b), orient2(x, k, a, b, d));
            Some(if s1 == Sign::Zero {
                same_direction(x, k, a, c, b)
            } else if s2 == Sign::Zero {
                same_direction(x, k, a, d, b)
            } else {
                s1 == inner && s2 == inner
            })
        }
        // disjoint or a violation: an edge line of `t` with both ends of
        // `e` strictly outside, or the line of `e` with `t` strictly on one
        // side, proves them apart (what a valid mesh shows); an end in `t`
        // proves a meeting; the rest is left to `tri_pair`
        _ => {
            let (a, b) = (e[0], e[1]);
            let inner = orient2(x, k, t[0], t[1], t[2]);
            let outside = inner.flip();
            for q in 0..3 {
                let (u, v) = (t[q], t[(q + 1) % 3]);
                if orient2(x, k, u, v, a) == outside && orient2(x, k, u, v, b) == outside {
                    return Some(false);
                }
            }
            let s0 = orient2(x, k, a, b, t[0]);
            if s0 != Sign::Zero && (1..3).all(|q| orient2(x, k, a, b, t[q]) == s0) {
                return Some(false);
            }
            (in_tri2(x, k, a, t) || in_tri2(x, k, b, t)).then_some(true)
        }
    }
}

/// Is `p` on the closed segment `ab` (all three in one axis plane, axis
/// `k` dropped)?
fn on_segment(x: &[[f64; 3]], k: usize, p: u32, a: u32, b: u32) -> bool {
    orient2(x, k, a, b, p) == Sign::Zero && between(x, k, p, a, b)
}

/// For `p` on the line `ab` (axis `k` dropped): is it between `a` and `b`?
/// Collinear points keep their order in each coordinate in which the line
/// is not constant.
fn between(x: &[[f64; 3]], k: usize, p: u32, a: u32, b: u32) -> bool {
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    let (pa, pb, pp) = (x[a as usize], x[b as usize], x[p as usize]);
    let d = if pa[i] != pb[i] { i } else { j };
    pa[d].min(pb[d]) <= pp[d] && pp[d] <= pa[d].max(pb[d])
}

/// For `p` and `q` on one line through `v`, both distinct from it (axis `k`
/// dropped): do they lie on the same side of `v`?
fn same_direction(x: &[[f64; 3]], k: usize, v: u32, p: u32, q: u32) -> bool {
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    let (pv, pp, pq) = (x[v as usize], x[p as usize], x[q as usize]);
    let d = if pp[i] != pv[i] { i } else { j };
    (pp[d] > pv[d]) == (pq[d] > pv[d]) && pq[d] != pv[d]
}

#[cfg(test)]
#[path = "box_contact_tests.rs"]
mod tests;
