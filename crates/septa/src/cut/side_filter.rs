//! A floating-point filter with a proven bound for the vertex-face
//! sidedness of the embedding (TopoCut Sec. 6.1, the orders of Eq. (13)):
//! most (cut-vertex, supporting plane) pairs of a cell are far apart, and
//! for them one bound shows at once that the rounded position and the
//! exact cut-vertex lie strictly on the same side, so neither the exact
//! side nor the exact orientation of the rounded point is needed.
//!
//! Derivation. A supporting plane is `f*(y) = n* . y + d*`, exact. Its
//! floating-point copy `(n, d)` satisfies `|n*_i - n_i| <= dn_i` and
//! `|d* - d| <= dd` (both zero for an input cut plane; for a triangle `n*`
//! is enclosed by the interval normal of [`Ctx::tn`] and `d* = -n* . a`).
//! For a box of centre `c` and half-widths `w_i`, every `y` in it has
//! `|f*(y) - f*(c)| <= sum (|n_i| + dn_i) w_i` and `|f*(c) - (n . c + d)|
//! <= sum dn_i |c_i| + dd`; the rounded evaluation `g = fl(n . c + d)` of
//! 3 products and 3 sums errs by at most `6u (1 + 6u) (sum |n_i c_i| + |d|)
//! <= 4 eps (...)` plus `6 * 2^-1074` of underflow (Higham, Thm. 3.1). So
//! when `|g|` exceeds the sum `B` of these terms (computed with rounding
//! and enlarged by a factor `1 + 2^-40` that covers the ~20 roundings of
//! `B` itself, plus `1e-300` that covers every underflow), `f*` has the
//! strict sign of `g` on the whole box. The box of a vertex is its rounded
//! position widened by `r_v >= |x_v - x*_v|` (from the interval enclosure
//! of its homogeneous coordinates), so both the rounded and the exact point
//! are in it; a cluster's box covers the boxes of its vertices.

use super::cells::Support;
use super::geom::Ctx;
use septa_exact::Interval;

/// Relative enlargement of every computed bound (see the module doc).
const GROW: f64 = 1.0 + 1.0 / (1u64 << 40) as f64;
/// Absolute term covering underflow in any of the bounded evaluations.
const TINY: f64 = 1e-300;

/// Floating-point copy of an exact supporting plane with error bounds.
#[derive(Clone, Copy, Debug)]
pub struct FloatPlane {
    /// Normal (rounded).
    pub n: [f64; 3],
    /// Offset (rounded).
    pub d: f64,
    /// `|n*_i - n_i| <= dn_i`.
    pub dn: [f64; 3],
    /// `|d* - d| <= dd`.
    pub dd: f64,
}

impl FloatPlane {
    /// The plane of an input cut plane (exact in doubles) or of an input
    /// triangle (normal enclosed by intervals).
    pub fn of(c: &Ctx, s: Support) -> FloatPlane {
        match s {
            Support::Plane(p) => {
                let q = c.planes[p as usize];
                FloatPlane { n: [q[0], q[1], q[2]], d: q[3], dn: [0.0; 3], dd: 0.0 }
            }
            Support::Tri(t) => {
                let iv: [Interval; 3] = c.tn(t);
                let n = iv.map(|x| x.mid());
                let dn = [0, 1, 2].map(|k| (iv[k].hi - n[k]).max(n[k] - iv[k].lo) * GROW);
                let a = c.verts[c.tris[t as usize][0] as usize];
                let na = n[0] * a[0] + n[1] * a[1] + n[2] * a[2];
                let abs_na = (n[0] * a[0]).abs() + (n[1] * a[1]).abs() + (n[2] * a[2]).abs();
                let err = dn[0] * a[0].abs() + dn[1] * a[1].abs() + dn[2] * a[2].abs() + 4.0 * f64::EPSILON * abs_na;
                FloatPlane { n, d: -na, dn, dd: err * GROW + TINY }
            }
        }
    }

    /// The strict sign (`+1` / `-1`) that the exact plane has on the whole
    /// box of centre `c` and half-widths `w`, if the bound proves one.
    #[inline]
    pub fn box_sign(&self, c: &[f64; 3], w: &[f64; 3]) -> Option<i8> {
        let n = &self.n;
        let g = n[0] * c[0] + n[1] * c[1] + n[2] * c[2] + self.d;
        let mut b = self.dd + 4.0 * f64::EPSILON * self.d.abs();
        for k in 0..3 {
            b += (n[k].abs() + self.dn[k]) * w[k] + self.dn[k] * c[k].abs() + 4.0 * f64::EPSILON * (n[k] * c[k]).abs();
        }
        let b = b * GROW + TINY;
        if g > b {
            Some(1)
        } else if g < -b {
            Some(-1)
        } else {
            None
        }
    }
}

/// Upper bound of `|x - x*|` per coordinate (as one number) for a rounded
/// position `x` and the interval box `bx` that encloses the exact point;
/// infinite when there is no box.
pub fn radius(x: &[f64; 3], bx: &Option<[Interval; 3]>) -> f64 {
    match bx {
        None => f64::INFINITY,
        Some(b) => {
            let mut r: f64 = 0.0;
            for k in 0..3 {
                r = r.max(b[k].hi - x[k]).max(x[k] - b[k].lo);
            }
            r * GROW + TINY
        }
    }
}

/// Interval box enclosing the exact point `H / W` of a cut-vertex.
pub fn exact_box(h: &[Interval; 3], w: &Interval) -> Option<[Interval; 3]> {
    Some([h[0].div(w)?, h[1].div(w)?, h[2].div(w)?])
}

/// A bounding-volume hierarchy over the boxes of a cell's vertices (in
/// Morton order, halves split recursively), to find the vertices near a
/// face without visiting every vertex of the cell.
pub struct BoxTree {
    items: Vec<u32>,
    nodes: Vec<TreeNode>,
}

struct TreeNode {
    lo: [f64; 3],
    hi: [f64; 3],
    start: u32,
    end: u32,
    /// Child node ids, or `u32::MAX` for a leaf.
    kids: [u32; 2],
}

/// Items per leaf of a [`BoxTree`].
const LEAF: usize = 4;

/// True when the boxes `[alo, ahi]` and `[blo, bhi]` meet.
#[inline]
pub fn overlap(alo: &[f64; 3], ahi: &[f64; 3], blo: &[f64; 3], bhi: &[f64; 3]) -> bool {
    (0..3).all(|k| alo[k] <= bhi[k] && blo[k] <= ahi[k])
}

impl BoxTree {
    /// The tree over `items` (already in a spatially coherent order) with
    /// boxes `lo[i], hi[i]` indexed by item.
    pub fn new(items: Vec<u32>, lo: &[[f64; 3]], hi: &[[f64; 3]]) -> BoxTree {
        let mut t = BoxTree { items, nodes: Vec::new() };
        if !t.items.is_empty() {
            t.build(0, t.items.len(), lo, hi);
        }
        t
    }

    fn build(&mut self, start: usize, end: usize, lo: &[[f64; 3]], hi: &[[f64; 3]]) -> u32 {
        let id = self.nodes.len() as u32;
        self.nodes.push(TreeNode {
            lo: [f64::INFINITY; 3],
            hi: [f64::NEG_INFINITY; 3],
            start: start as u32,
            end: end as u32,
            kids: [u32::MAX; 2],
        });
        let (mut blo, mut bhi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        if end - start <= LEAF {
            for &v in &self.items[start..end] {
                for k in 0..3 {
                    blo[k] = blo[k].min(lo[v as usize][k]);
                    bhi[k] = bhi[k].max(hi[v as usize][k]);
                }
            }
        } else {
            let mid = (start + end) / 2;
            let a = self.build(start, mid, lo, hi);
            let b = self.build(mid, end, lo, hi);
            for c in [a, b] {
                let n = &self.nodes[c as usize];
                for k in 0..3 {
                    blo[k] = blo[k].min(n.lo[k]);
                    bhi[k] = bhi[k].max(n.hi[k]);
                }
            }
            self.nodes[id as usize].kids = [a, b];
        }
        self.nodes[id as usize].lo = blo;
        self.nodes[id as usize].hi = bhi;
        id
    }

    /// Calls `f` on every item whose leaf box meets `[qlo, qhi]` (a superset
    /// of the items whose own box meets it; callers test those boxes).
    /// `stack` is scratch space (kept by the caller across queries).
    pub fn query(&self, qlo: &[f64; 3], qhi: &[f64; 3], stack: &mut Vec<u32>, mut f: impl FnMut(u32)) {
        if self.nodes.is_empty() {
            return;
        }
        stack.clear();
        stack.push(0);
        while let Some(i) = stack.pop() {
            let n = &self.nodes[i as usize];
            if !overlap(&n.lo, &n.hi, qlo, qhi) {
                continue;
            }
            if n.kids[0] == u32::MAX {
                self.items[n.start as usize..n.end as usize].iter().for_each(|&v| f(v));
            } else {
                stack.extend(n.kids);
            }
        }
    }
}

/// Morton key of a point in the box `[lo, lo + ext]` (10 bits per axis).
pub fn morton(p: &[f64; 3], lo: &[f64; 3], ext: &[f64; 3]) -> u32 {
    let mut key = 0u32;
    let q = [0, 1, 2].map(|k| {
        let t = if ext[k] > 0.0 { (p[k] - lo[k]) / ext[k] } else { 0.0 };
        (t.clamp(0.0, 1.0) * 1023.0) as u32
    });
    for bit in (0..10).rev() {
        for v in q {
            key = (key << 1) | ((v >> bit) & 1);
        }
    }
    key
}
