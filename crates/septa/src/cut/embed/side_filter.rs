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

use crate::cut::arrangement::nodes::FxMap;
use crate::cut::base::geom::Ctx;
use crate::cut::Support;
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

/// True when the boxes `[alo, ahi]` and `[blo, bhi]` meet.
#[inline]
pub fn overlap(alo: &[f64; 3], ahi: &[f64; 3], blo: &[f64; 3], bhi: &[f64; 3]) -> bool {
    (0..3).all(|k| alo[k] <= bhi[k] && blo[k] <= ahi[k])
}

/// A vertex id with its box `[lo, hi]`.
pub type GridItem = (u32, [f64; 3], [f64; 3]);

/// A uniform grid of buckets of vertices (by rounded position), to find
/// the vertices near a face without visiting every vertex of its cells.
pub struct VertexGrid {
    origin: [f64; 3],
    h: f64,
    /// Vertex ids sorted by bucket key, with their boxes (stored inline:
    /// a query reads them contiguously).
    items: Vec<GridItem>,
    /// Bucket key to its range in `items`.
    ranges: FxMap<u64, (u32, u32)>,
    /// Some item was out of range: no query can be answered by buckets.
    all: bool,
}

impl VertexGrid {
    /// Buckets of side `h` over items `(vertex, lo, hi)` (finite boxes),
    /// each in the bucket of its box centre.
    pub fn new(items: Vec<GridItem>, h: f64) -> VertexGrid {
        let centre = |it: &GridItem| [0, 1, 2].map(|k| 0.5 * it.1[k] + 0.5 * it.2[k]);
        let mut origin = [f64::INFINITY; 3];
        for it in &items {
            let p = centre(it);
            for k in 0..3 {
                origin[k] = origin[k].min(p[k]);
            }
        }
        let h = if h.is_finite() && h > 0.0 { h } else { 1.0 };
        let mut g = VertexGrid { origin, h, items: Vec::new(), ranges: FxMap::default(), all: false };
        let mut keyed: Vec<(u64, GridItem)> = Vec::with_capacity(items.len());
        for it in items {
            match g.cell(&centre(&it)) {
                Some(c) => keyed.push((g.key(&c), it)),
                None => g.all = true,
            }
        }
        if g.all {
            // out of the grid's range: queries fall back to every item
            g.items = keyed.into_iter().map(|(_, it)| it).collect();
            return g;
        }
        keyed.sort_unstable_by_key(|k| k.0);
        let mut start = 0;
        for i in 1..=keyed.len() {
            if i == keyed.len() || keyed[i].0 != keyed[start].0 {
                g.ranges.insert(keyed[start].0, (start as u32, i as u32));
                start = i;
            }
        }
        g.items = keyed.into_iter().map(|(_, it)| it).collect();
        g
    }

    /// Every item.
    pub fn items(&self) -> &[GridItem] {
        &self.items
    }

    fn cell(&self, p: &[f64; 3]) -> Option<[i64; 3]> {
        let c = [0, 1, 2].map(|k| ((p[k] - self.origin[k]) / self.h).floor());
        c.iter().all(|v| v.is_finite() && v.abs() < 1e6).then(|| c.map(|v| v as i64))
    }

    fn key(&self, c: &[i64; 3]) -> u64 {
        let f = |v: i64| ((v + (1 << 20)) as u64) & ((1 << 21) - 1);
        (f(c[0]) << 42) | (f(c[1]) << 21) | f(c[2])
    }

    /// Calls `f` on every item whose box centre lies in a bucket that the
    /// box `[lo, hi]` meets and returns true; returns false (calling
    /// nothing) when that is not cheaper than visiting every item.
    pub fn query(&self, lo: &[f64; 3], hi: &[f64; 3], mut f: impl FnMut(&GridItem)) -> bool {
        if self.all {
            return false;
        }
        let (Some(a), Some(b)) = (self.cell(lo), self.cell(hi)) else { return false };
        let span: u64 = (0..3).map(|k| (b[k] - a[k] + 1).max(0) as u64).product();
        if span > self.items.len() as u64 {
            return false;
        }
        for i in a[0]..=b[0] {
            for j in a[1]..=b[1] {
                for k in a[2]..=b[2] {
                    if let Some(&(s, e)) = self.ranges.get(&self.key(&[i, j, k])) {
                        self.items[s as usize..e as usize].iter().for_each(&mut f);
                    }
                }
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use septa_exact::{plane_point_sign, Sign};

    /// A small deterministic generator (xorshift) of doubles in [-1, 1).
    fn gen(state: &mut u64) -> f64 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        (*state >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    #[test]
    fn box_sign_agrees_with_the_exact_side_at_every_corner() {
        let mut s = 0x9e37_79b9_7f4a_7c15u64;
        let (mut decided, mut near) = (0, 0);
        for i in 0..20000 {
            let q = [gen(&mut s), gen(&mut s), gen(&mut s), gen(&mut s) * 0.1];
            let fp = FloatPlane { n: [q[0], q[1], q[2]], d: q[3], dn: [0.0; 3], dd: 0.0 };
            // a point on or next to the plane, and a box around it from 0
            // to a few ulps wide: the hard cases of the filter
            let mut c = [gen(&mut s), gen(&mut s), gen(&mut s)];
            let k = (0..3).max_by(|&a, &b| q[a].abs().total_cmp(&q[b].abs())).unwrap();
            c[k] = -(q[3] + (0..3).filter(|&j| j != k).map(|j| q[j] * c[j]).sum::<f64>()) / q[k];
            // half the points clearly off the plane (the filter must decide
            // them), half within a few ulps (it must not get them wrong)
            c[k] += if i % 2 == 0 { 1e-3 } else { (i % 7) as f64 * 1e-15 } * gen(&mut s);
            let w = [(i % 5) as f64 * 1e-16; 3];
            if let Some(sg) = fp.box_sign(&c, &w) {
                decided += 1;
                near += i % 2;
                for m in 0..8 {
                    let p = [0, 1, 2].map(|j| if m >> j & 1 == 1 { c[j] + w[j] } else { c[j] - w[j] });
                    let want = if sg > 0 { Sign::Positive } else { Sign::Negative };
                    // corners are rounded, so only check those that are
                    // exactly the box's corners
                    if (0..3).all(|j| (p[j] - c[j]).abs() == w[j]) {
                        assert_eq!(plane_point_sign(&q, &p), want, "plane {q:?} box {c:?} +- {w:?}");
                    }
                }
            }
        }
        // the filter decides the clear cases
        assert!(decided > 9000, "filter decided only {decided}");
        // and some of those within a few ulps of the plane (at its edge)
        assert!(near > 100, "filter decided only {near} near points");
    }
}
