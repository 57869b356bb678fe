//! The exact triangle-pair test of the self-intersection check (TopoCut
//! App. A): do two triangles of doubles meet anywhere besides their shared
//! vertices and edges? Quick sufficient tests first (one triangle strictly
//! on one side of the other's plane by orient3d's static filter, projections
//! separated by an edge line), then edge-against-triangle tests whose
//! every decision is an exact orientation sign. `selfx` finds the candidate
//! pairs.

use crate::cut::triangles::orient::{dot2, orient, orient2, orient_filtered, orient_slow, proj_axis, proven_sign};
use septa_exact::{filtered_sign_bounded, Bounded, Exact, Interval, Ring, Sign};

/// The orientations one triangle pair's test asks for, remembered while it
/// runs: the edge-against-triangle tests ask for the same determinant
/// several times (each corner against the other triangle's plane once per
/// edge through it; an edge against an edge from both triangles' sides),
/// and on nearly degenerate pairs (rounded cut-vertices along a nearly
/// straight chain next to a nearly perpendicular face: plate_genus9,
/// staircase) each of them went through intervals and the exact
/// determinant again. Only signs the static filter cannot decide are kept,
/// under the sorted vertex ids (the sign flips with the permutation's
/// parity, exactly).
///
/// A corner against the other triangle's plane, asked with that triangle's
/// corners in their order, first goes through the prepared plane's filter
/// ([`TriPlane::side`]: `orient(a, b, c, d)` is the sign of
/// `det(b - a, c - a, d - a)`, which `side` bounds), cheaper than the
/// general one (instead of it: when it cannot decide, the exact sign is
/// computed, as after the general filter).
struct PairOrients<'a> {
    x: &'a [[f64; 3]],
    planes: [(&'a [u32; 3], Option<&'a TriPlane>); 2],
    keys: [[u32; 4]; 16],
    signs: [Sign; 16],
    n: usize,
}

impl<'a> PairOrients<'a> {
    fn new(x: &'a [[f64; 3]], planes: [(&'a [u32; 3], Option<&'a TriPlane>); 2]) -> Self {
        PairOrients { x, planes, keys: [[0; 4]; 16], signs: [Sign::Zero; 16], n: 0 }
    }

    fn orient(&mut self, a: u32, b: u32, c: u32, d: u32) -> Sign {
        let plane = self.planes.iter().find(|(t, p)| p.is_some() && **t == [a, b, c]).and_then(|q| q.1);
        let filtered = match plane {
            Some(p) => p.side(&self.x[d as usize]),
            None => orient_filtered(self.x, a, b, c, d),
        };
        if let Some(s) = filtered {
            return s;
        }
        let mut k = [a, b, c, d];
        let mut odd = false;
        for i in 0..3 {
            for j in 0..3 - i {
                if k[j] > k[j + 1] {
                    k.swap(j, j + 1);
                    odd = !odd;
                }
            }
        }
        let s = match self.keys[..self.n].iter().position(|q| *q == k) {
            Some(i) => self.signs[i],
            None => {
                let s = orient_slow(self.x, k[0], k[1], k[2], k[3]);
                if self.n < self.keys.len() {
                    (self.keys[self.n], self.signs[self.n]) = (k, s);
                    self.n += 1;
                }
                s
            }
        };
        if odd {
            s.flip()
        } else {
            s
        }
    }
}

/// A triangle's plane prepared once for many [`TriPlane::side`] queries:
/// the corner `a`, the edge vectors' cross product `n = (b - a) x (c - a)`
/// and the three partial permanents of Shewchuk's orient3d bound, all in
/// floating point exactly as `orient_filtered` forms them.
#[derive(Clone, Copy)]
pub(crate) struct TriPlane {
    a: [f64; 3],
    n: [f64; 3],
    perm: [f64; 3],
}

impl TriPlane {
    pub(crate) fn new(x: &[[f64; 3]], t: &[u32; 3]) -> Self {
        let (a, b, c) = (x[t[0] as usize], x[t[1] as usize], x[t[2] as usize]);
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let (yz, zy) = (u[1] * v[2], u[2] * v[1]);
        let (zx, xz) = (u[2] * v[0], u[0] * v[2]);
        let (xy, yx) = (u[0] * v[1], u[1] * v[0]);
        TriPlane {
            a,
            n: [yz - zy, zx - xz, xy - yx],
            perm: [yz.abs() + zy.abs(), zx.abs() + xz.abs(), xy.abs() + yx.abs()],
        }
    }

    /// The floating-point normal `(b - a) x (c - a)` (a direction for
    /// heuristics; no sign is read from it).
    pub(crate) fn normal(&self) -> [f64; 3] {
        self.n
    }

    /// Side of `q`: the sign of `det(b - a, c - a, q - a)` when the static
    /// filter proves it, else `None` (never an exact fallback). This is
    /// Shewchuk's orient3d filter (`o3derrboundA = 7u + 56u^2`) on the
    /// transposed matrix: the nine entries are the same kind of rounded
    /// differences, the determinant is expanded along `q - a` with the 2x2
    /// minors of `b - a, c - a` in the same order of operations, and the
    /// permanent is formed alike, so the bound carries over unchanged.
    /// Only the strict sign is used (a zero is never claimed).
    #[inline]
    pub(crate) fn side(&self, q: &[f64; 3]) -> Option<Sign> {
        let w = [q[0] - self.a[0], q[1] - self.a[1], q[2] - self.a[2]];
        let det = w[0] * self.n[0] + w[1] * self.n[1] + w[2] * self.n[2];
        let perm = self.perm[0] * w[0].abs() + self.perm[1] * w[1].abs() + self.perm[2] * w[2].abs();
        proven_sign(det, perm)
    }
}

/// Closed 2D segment-segment intersection (coplanar points, axis `k` dropped).
pub(crate) fn seg_seg2(x: &[[f64; 3]], k: usize, p: u32, q: u32, a: u32, b: u32) -> bool {
    let (o1, o2) = (orient2(x, k, p, q, a), orient2(x, k, p, q, b));
    let (o3, o4) = (orient2(x, k, a, b, p), orient2(x, k, a, b, q));
    if o1 != Sign::Zero && o1 == o2 || o3 != Sign::Zero && o3 == o4 {
        return false;
    }
    if o1 == Sign::Zero && o2 == Sign::Zero {
        // collinear: overlap of projections on the axis with most spread
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        let ax = if x[p as usize][i] != x[q as usize][i] { i } else { j };
        let (l1, h1) = (x[p as usize][ax].min(x[q as usize][ax]), x[p as usize][ax].max(x[q as usize][ax]));
        let (l2, h2) = (x[a as usize][ax].min(x[b as usize][ax]), x[a as usize][ax].max(x[b as usize][ax]));
        return l1 <= h2 && l2 <= h1;
    }
    true
}

/// Closed 2D point-in-triangle (coplanar, axis `k` dropped).
pub(crate) fn in_tri2(x: &[[f64; 3]], k: usize, p: u32, t: &[u32; 3]) -> bool {
    let s = [orient2(x, k, t[0], t[1], p), orient2(x, k, t[1], t[2], p), orient2(x, k, t[2], t[0], p)];
    !(s.contains(&Sign::Positive) && s.contains(&Sign::Negative))
}

/// Closed segment `pq` against closed triangle `t`.
fn seg_tri(o: &mut PairOrients, p: u32, q: u32, t: &[u32; 3]) -> bool {
    let x = o.x;
    let o1 = o.orient(t[0], t[1], t[2], p);
    let o2 = o.orient(t[0], t[1], t[2], q);
    if o1 != Sign::Zero && o1 == o2 {
        return false;
    }
    if o1 == Sign::Zero && o2 == Sign::Zero {
        let k = proj_axis(x, t);
        return in_tri2(x, k, p, t)
            || in_tri2(x, k, q, t)
            || (0..3).any(|e| seg_seg2(x, k, p, q, t[e], t[(e + 1) % 3]));
    }
    let s = [o.orient(p, q, t[0], t[1]), o.orient(p, q, t[1], t[2]), o.orient(p, q, t[2], t[0])];
    !(s.contains(&Sign::Positive) && s.contains(&Sign::Negative))
}

/// Are `c` and `d` on the same side of the line `ab` (positive dot product
/// of their components perpendicular to `ab`)?
fn same_side_of_edge(x: &[[f64; 3]], a: u32, b: u32, c: u32, d: u32) -> bool {
    fn f<R: Ring>(x: &[[f64; 3]], a: u32, b: u32, c: u32, d: u32) -> R {
        let p = |i: u32| [R::of(x[i as usize][0]), R::of(x[i as usize][1]), R::of(x[i as usize][2])];
        let (pa, pb, pc, pd) = (p(a), p(b), p(c), p(d));
        let e: [R; 3] = std::array::from_fn(|k| pb[k].sub(&pa[k]));
        let u: [R; 3] = std::array::from_fn(|k| pc[k].sub(&pa[k]));
        let w: [R; 3] = std::array::from_fn(|k| pd[k].sub(&pa[k]));
        let dot = |p: &[R; 3], q: &[R; 3]| p[0].mul(&q[0]).add(&p[1].mul(&q[1])).add(&p[2].mul(&q[2]));
        // (u.w)|e|^2 - (u.e)(w.e) = |e|^2 (u_perp . w_perp)
        dot(&u, &w).mul(&dot(&e, &e)).sub(&dot(&u, &e).mul(&dot(&w, &e)))
    }
    filtered_sign_bounded(|| f::<Bounded>(x, a, b, c, d), || f::<Interval>(x, a, b, c, d), || f::<Exact>(x, a, b, c, d))
        == Sign::Positive
}

/// Sufficient test that two triangles meet at most in shared vertices:
/// their projections along a coordinate axis are separated by an edge line
/// of one of them (all other corners outside, shared corners on the line).
/// Exact (2D orientations of input coordinates), and cheap where the 3D
/// predicates are nearly degenerate (flat fans of nearly coplanar
/// triangles).
///
/// Corners of the other triangle may lie on the line itself (grids of
/// axis-aligned cut-faces are full of such collinear corners): both
/// projections then meet the line in segments, the edge and the hull of
/// the corners on it, and the projections share at most a shared vertex
/// when these segments are apart or meet in a shared vertex only (compared
/// along a coordinate in which the line is not constant, where collinear
/// points keep their order). The projection of the first triangle is not
/// degenerate, so only its own points project onto its projection: a
/// common point of the triangles projects into both, hence is a shared
/// vertex.
fn projections_separated(x: &[[f64; 3]], t1: &[u32; 3], n: &[f64; 3], t2: &[u32; 3]) -> bool {
    // `n`: t1's floating-point normal; it only picks the projection axis
    let k = (0..3).max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs())).unwrap();
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    for (ta, tb) in [(t1, t2), (t2, t1)] {
        let inner = orient2(x, k, ta[0], ta[1], ta[2]);
        if inner == Sign::Zero {
            return false;
        }
        'edge: for e in 0..3 {
            let (a, b) = (ta[e], ta[(e + 1) % 3]);
            // the free corners of tb on the line, if any
            let mut on_line = [false; 3];
            for (q, &w) in tb.iter().enumerate() {
                if w != a && w != b {
                    if ta.contains(&w) {
                        continue 'edge;
                    }
                    match orient2(x, k, a, b, w) {
                        s if s == inner.flip() => {}
                        Sign::Zero => on_line[q] = true,
                        _ => continue 'edge,
                    }
                }
            }
            if on_line == [false; 3] {
                return true;
            }
            // the hull of tb's points on the line (its free corners there and
            // the shared ends of the edge) along `c`
            let c = if x[a as usize][i] != x[b as usize][i] { i } else { j };
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for (q, &w) in tb.iter().enumerate() {
                if on_line[q] || w == a || w == b {
                    let v = x[w as usize][c];
                    (lo, hi) = (lo.min(v), hi.max(v));
                }
            }
            let (va, vb) = (x[a as usize][c], x[b as usize][c]);
            let (from, to) = (lo.max(va.min(vb)), hi.min(va.max(vb)));
            if from > to {
                return true;
            }
            // one common point, at a shared end of the edge
            let shared_end = |v: u32| tb.contains(&v) && x[v as usize][c] == from;
            if from == to && (shared_end(a) || shared_end(b)) {
                return true;
            }
        }
    }
    false
}

/// Quick sufficient test that two triangles meet at most in shared
/// vertices: the corners of `t2` that `t1` does not share lie strictly on
/// one side of `t1`'s plane, as proven by orient3d's static filter (`false`
/// when the filter cannot tell; no exact fallback). `t2` then meets `t1`'s
/// plane only in the shared vertices (none, one, or the shared edge).
/// Most candidate pairs of a cut-cell mesh (triangles of different faces
/// in one grid cell) end here, before the 2D projection tests.
#[inline(always)]
pub(crate) fn plane_separated(x: &[[f64; 3]], t1: &[u32; 3], p1: &TriPlane, t2: &[u32; 3]) -> bool {
    // the free corners counted by the side the filter proves (an undecided
    // corner ends the test); the same answer as stopping at the first
    // corner on another side, without a branch per corner
    let (mut free, mut pos, mut neg) = (0u32, 0u32, 0u32);
    for &w in t2 {
        if w == t1[0] || w == t1[1] || w == t1[2] {
            continue;
        }
        free += 1;
        match p1.side(&x[w as usize]) {
            Some(Sign::Positive) => pos += 1,
            Some(Sign::Negative) => neg += 1,
            _ => return false,
        }
    }
    free >= 1 && (pos == free || neg == free)
}

/// Do two triangles meet anywhere besides their shared vertices?
pub(crate) fn pair_intersects(x: &[[f64; 3]], t1: &[u32; 3], t2: &[u32; 3]) -> bool {
    pair_intersects_planes(x, t1, &TriPlane::new(x, t1), t2, &TriPlane::new(x, t2))
}

/// [`pair_intersects`] with both triangles' planes prepared (inlined into
/// the sweep of candidate pairs: most pairs end at the plane sides, where
/// a call's prologue was a sixth of their cost).
#[inline(always)]
pub(crate) fn pair_intersects_planes(
    x: &[[f64; 3]],
    t1: &[u32; 3],
    p1: &TriPlane,
    t2: &[u32; 3],
    p2: &TriPlane,
) -> bool {
    if plane_separated(x, t1, p1, t2) || plane_separated(x, t2, p2, t1) {
        return false;
    }
    pair_intersects_unseparated(x, t1, p1, t2, p2)
}

/// [`pair_intersects_planes`] after the plane-side rejections (out of line:
/// most pairs end there, and this part's frame is large).
#[inline(never)]
fn pair_intersects_unseparated(x: &[[f64; 3]], t1: &[u32; 3], p1: &TriPlane, t2: &[u32; 3], p2: &TriPlane) -> bool {
    if projections_separated(x, t1, &p1.n, t2) {
        return false;
    }
    let mut o = PairOrients::new(x, [(t1, Some(p1)), (t2, Some(p2))]);
    if let Some(meet) = general_position(&mut o, t1, t2) {
        return meet;
    }
    edge_tests(&mut o, t1, t2)
}

/// Exact sides of the corners of `t` against the plane of `u` (corners
/// shared with `u` left `Zero`).
fn sides(o: &mut PairOrients, u: &[u32; 3], t: &[u32; 3]) -> [Sign; 3] {
    std::array::from_fn(|k| if u.contains(&t[k]) { Sign::Zero } else { o.orient(u[0], u[1], u[2], t[k]) })
}

/// The pair decided from exact orientations unless the two triangles are
/// coplanar or share an edge and lie in one plane (`None`: the edge tests
/// decide those). `s1` / `s2` below are the sides of each triangle's corners
/// against the other's plane; `L` is the line where the planes meet. Each
/// case is a proof:
///
/// - two shared corners, the third corner of `t2` off `t1`'s plane:
///   `t2 ∩ plane(t1)` is the shared edge and `t1` lies in that plane, so
///   the triangles meet exactly in the shared edge;
/// - one triangle's free corners strictly on one side of the other's plane:
///   it meets that plane only in the shared vertices (or nowhere);
/// - no shared corner, one corner of a triangle exactly on the other's
///   plane and its other two strictly on one side: the pair meets iff that
///   corner lies in the other triangle ([`lone_contact`]);
/// - one shared vertex `v`, `t1 = (v, a, b)`, `t2 = (v, c, d)`, each
///   triangle reaching both sides of the other's plane or lying on it along
///   an edge, `d` off `t1`'s plane (renamed so), and `a` off `t2`'s unless
///   `b` is (`e`, `f` below are `a`, `b` or swapped so that `e` is off it):
///   both triangles meet `L` in segments from `v` (to a point of `ab`, or to
///   the corner on `L`; likewise `cd`), which share more than `v` iff they
///   leave `v` in one direction. The plane `(v, e, d)` meets `t1`'s plane in
///   the line `ve` (`d` is off it), so it meets `L` only at `v`: the two
///   segments leave `v` on one side of it iff `orient(v, e, d, c) =
///   orient(v, e, d, f)` (`t2`'s segment ends between `c` and `d`, or at
///   `c`, and `d` is on the plane; `t1`'s between `e` and `f`, or at `f`).
///   Neither sign is zero (the segments' ends are off that plane);
/// - no shared corner: the closed triangles meet iff their segments on `L`
///   overlap. Each triangle is turned so that its first corner `p` is alone
///   on its side (the other two on the opposite side or on the plane; or,
///   when two corners are on one side and the third on the plane, that
///   third one, counted on the opposite side), then the other triangle's
///   last two corners are swapped unless `p` counts as positive; the pair
///   meets iff `orient(p1, q1, p2, q2) <= 0` and `orient(p1, r1, r2, p2) <= 0`
///   (Devillers and Guigue, "Faster triangle-triangle intersection tests",
///   INRIA RR-4488, 2002, Sec. 3).
///
/// The last two rules, in this sign convention (`orient(a, b, c, d) = sign
/// det(b - a, c - a, d - a)`), were checked against the exact rational
/// segments on `L` for 300,000 random pairs of small integer triangles each
/// (every pattern of zero sides), and `tri_pair_tests` compares the whole
/// test with the edge tests. On cut-cell meshes most pairs that reach this
/// point are nearly degenerate (a cut-face strip against a surface piece it
/// meets along a rounded chain) or touch along axis planes; the edge tests
/// asked for up to 30 orientations there, this for at most 8.
fn general_position(o: &mut PairOrients, t1: &[u32; 3], t2: &[u32; 3]) -> Option<bool> {
    let ns = t1.iter().filter(|v| t2.contains(v)).count();
    let s2 = sides(o, t1, t2);
    let free2 = (0..3).filter(|&k| !t1.contains(&t2[k]));
    if free2.clone().all(|k| s2[k] == Sign::Zero) {
        return None; // coplanar (or a shared triangle)
    }
    if ns == 2 {
        return Some(false);
    }
    if ns == 0 {
        if let Some(k) = lone_contact(&s2) {
            return Some(in_tri2(o.x, proj_axis(o.x, t1), t2[k], t1));
        }
    }
    let s1 = sides(o, t2, t1);
    let one_side = |t: &[u32; 3], u: &[u32; 3], s: &[Sign; 3]| {
        let mut free = (0..3).filter(|&k| !u.contains(&t[k])).map(|k| s[k]);
        let first = free.next();
        first != Some(Sign::Zero) && free.all(|x| Some(x) == first)
    };
    if one_side(t1, t2, &s1) || one_side(t2, t1, &s2) {
        return Some(false);
    }
    if ns == 0 {
        if let Some(k) = lone_contact(&s1) {
            return Some(in_tri2(o.x, proj_axis(o.x, t2), t1[k], t2));
        }
    }
    if ns == 1 {
        let k1 = (0..3).find(|&k| t2.contains(&t1[k]))?;
        let k2 = (0..3).find(|&k| t1.contains(&t2[k]))?;
        let (v, a, b) = (t1[k1], t1[(k1 + 1) % 3], t1[(k1 + 2) % 3]);
        let (sa, sb) = (s1[(k1 + 1) % 3], s1[(k1 + 2) % 3]);
        let (mut c, mut d) = (t2[(k2 + 1) % 3], t2[(k2 + 2) % 3]);
        if s2[(k2 + 2) % 3] == Sign::Zero {
            std::mem::swap(&mut c, &mut d);
        }
        if sa == Sign::Zero && sb == Sign::Zero {
            return None;
        }
        let (e, f) = if sa == Sign::Zero { (b, a) } else { (a, b) };
        let (g, h) = (o.orient(v, e, d, c), o.orient(v, e, d, f));
        return (g != Sign::Zero && h != Sign::Zero).then_some(g == h);
    }
    // the corner alone on its side, and the side it counts on
    let lone = |s: &[Sign; 3]| -> Option<(usize, Sign)> {
        let others = |k: usize| [s[(k + 1) % 3], s[(k + 2) % 3]];
        (0..3).find(|&k| s[k] != Sign::Zero && !others(k).contains(&s[k])).map(|k| (k, s[k])).or_else(|| {
            (0..3).find_map(|k| {
                let [p, q] = others(k);
                (s[k] == Sign::Zero && p == q && p != Sign::Zero).then(|| (k, p.flip()))
            })
        })
    };
    let ((k1, g1), (k2, g2)) = (lone(&s1)?, lone(&s2)?);
    let (p1, mut q1, mut r1) = (t1[k1], t1[(k1 + 1) % 3], t1[(k1 + 2) % 3]);
    let (p2, mut q2, mut r2) = (t2[k2], t2[(k2 + 1) % 3], t2[(k2 + 2) % 3]);
    // a cyclic turn of a triangle keeps its orientations
    if g1 == Sign::Negative {
        std::mem::swap(&mut q2, &mut r2);
    }
    if g2 == Sign::Negative {
        std::mem::swap(&mut q1, &mut r1);
    }
    Some(o.orient(p1, q1, p2, q2) != Sign::Positive && o.orient(p1, r1, r2, p2) != Sign::Positive)
}

/// The corner of a triangle sharing no corner with the other that lies
/// exactly on the other's plane while its two other corners lie strictly on
/// one side (`s`: the sides of its corners): the triangle then meets that
/// plane in this corner alone (any other point of it mixes in a corner off
/// the plane with a positive weight), so the pair meets iff the corner lies
/// in the other (closed) triangle, a 2D question in its plane. Cut-cell
/// meshes of axis-aligned planes are full of such touching pairs (a
/// surface piece's corner on the plane of a cut-face next to its own); the
/// rules below would ask for five more orientations each.
fn lone_contact(s: &[Sign; 3]) -> Option<usize> {
    let k = (0..3).find(|&k| s[k] == Sign::Zero)?;
    let (a, b) = (s[(k + 1) % 3], s[(k + 2) % 3]);
    (a != Sign::Zero && a == b).then_some(k)
}

/// The pair decided edge by edge: each edge of one triangle against the
/// other triangle (closed), with the cases of shared corners; every
/// decision an exact orientation sign. Correct in every configuration,
/// the degenerate ones included.
fn edge_tests(o: &mut PairOrients, t1: &[u32; 3], t2: &[u32; 3]) -> bool {
    let x = o.x;
    let mut shared = [0u32; 3];
    let mut ns = 0;
    for &v in t1 {
        if t2.contains(&v) {
            shared[ns] = v;
            ns += 1;
        }
    }
    match ns {
        0 => {
            (0..3).any(|e| seg_tri(o, t1[e], t1[(e + 1) % 3], t2))
                || (0..3).any(|e| seg_tri(o, t2[e], t2[(e + 1) % 3], t1))
        }
        1 => {
            let v = shared[0];
            let other = |t: &[u32; 3]| -> [u32; 2] {
                let k = t.iter().position(|&w| w == v).unwrap();
                [t[(k + 1) % 3], t[(k + 2) % 3]]
            };
            let (o1, o2) = (other(t1), other(t2));
            if seg_tri(o, o1[0], o1[1], t2) || seg_tri(o, o2[0], o2[1], t1) {
                return true;
            }
            // an edge from v lying in the other triangle's plane may run into it
            for (os, t) in [(&o1, t2), (&o2, t1)] {
                for &w in os.iter() {
                    if o.orient(t[0], t[1], t[2], w) == Sign::Zero {
                        let k = proj_axis(x, t);
                        let opp = other(t);
                        if in_tri2(x, k, w, t) || seg_seg2(x, k, v, w, opp[0], opp[1]) {
                            return true;
                        }
                        // the edge v-w starts inside the angle of t at v
                        let s1 = orient2(x, k, v, opp[0], w);
                        let s2 = orient2(x, k, v, opp[1], w);
                        let inside = orient2(x, k, v, opp[0], opp[1]);
                        if s1 == inside && s2 == inside.flip() {
                            return true;
                        }
                        // the edge v-w runs along an edge v-opp of t: overlap
                        for (sk, o) in [(s1, opp[0]), (s2, opp[1])] {
                            if sk == Sign::Zero && dot2(x, k, v, w, o) == Sign::Positive {
                                return true;
                            }
                        }
                    }
                }
            }
            false
        }
        2 => {
            // folded onto each other: the other apex on the same side of the
            // shared edge (checked first: it is rarely so) and coplanar
            let shared = [shared[0], shared[1]];
            let c = *t1.iter().find(|w| !shared.contains(w)).unwrap();
            let d = *t2.iter().find(|w| !shared.contains(w)).unwrap();
            if !same_side_of_edge(x, shared[0], shared[1], c, d) {
                return false;
            }
            if orient(x, shared[0], shared[1], c, d) != Sign::Zero {
                return false;
            }
            let k = proj_axis(x, t1);
            orient2(x, k, shared[0], shared[1], c) == orient2(x, k, shared[0], shared[1], d)
        }
        _ => true,
    }
}

#[cfg(test)]
#[path = "tri_pair_tests.rs"]
mod tests;
