//! The exact check around a few triangles, for repairs that move a vertex
//! or re-fan a polygon and keep a change only when the exact check around
//! it improves (certification, projection, remeshing). Triangles are found
//! through a uniform grid of their boxes; every decision is the exact one of
//! `check.rs` (`cut::collinear`, `cut::pair_intersects`, bitwise points).

use rustc_hash::FxHashMap;

use super::check::point_bits;
use crate::cut::{collinear, pair_intersects};

/// Triangles by the grid cells their boxes overlap. A triangle that moved
/// is inserted again where it is now; the entries where it was stay and are
/// skipped by the box test of [`TriGrid::near`].
pub(crate) struct TriGrid {
    size: f64,
    cells: FxHashMap<[i64; 3], Vec<u32>>,
    /// Per triangle, the last query that met it (no triangle twice).
    stamp: Vec<u32>,
    now: u32,
}

fn bbox(x: &[[f64; 3]], t: &[u32; 3]) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &v in t {
        for k in 0..3 {
            lo[k] = lo[k].min(x[v as usize][k]);
            hi[k] = hi[k].max(x[v as usize][k]);
        }
    }
    (lo, hi)
}

fn overlap(a: &([f64; 3], [f64; 3]), b: &([f64; 3], [f64; 3])) -> bool {
    (0..3).all(|k| a.0[k] <= b.1[k] && b.0[k] <= a.1[k])
}

impl TriGrid {
    /// A grid over `tris` with cells about twice their mean box extent.
    pub fn new(x: &[[f64; 3]], tris: &[[u32; 3]]) -> TriGrid {
        let mut ext = 0.0;
        for t in tris {
            let (lo, hi) = bbox(x, t);
            ext += (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        }
        let mean = if tris.is_empty() { 1.0 } else { ext / tris.len() as f64 };
        let size = if mean.is_finite() && mean > 0.0 { 2.0 * mean } else { 1.0 };
        let mut g = TriGrid { size, cells: FxHashMap::default(), stamp: vec![0; tris.len()], now: 0 };
        for (i, t) in tris.iter().enumerate() {
            g.insert(x, i as u32, t);
        }
        g
    }

    fn range(&self, b: &([f64; 3], [f64; 3])) -> Option<([i64; 3], [i64; 3])> {
        let lo = b.0.map(|c| (c / self.size).floor() as i64);
        let hi = b.1.map(|c| (c / self.size).floor() as i64);
        // a triangle spanning very many cells (none in a grid network) is
        // filed under its low cell only and found by [`TriGrid::near`]'s
        // scan of the large ones
        let n: i64 = (0..3).map(|k| hi[k] - lo[k] + 1).product();
        (n <= 4096).then_some((lo, hi))
    }

    /// Files triangle `t` (corners `tri`) where its box is now.
    pub fn insert(&mut self, x: &[[f64; 3]], t: u32, tri: &[u32; 3]) {
        if t as usize >= self.stamp.len() {
            self.stamp.resize(t as usize + 1, 0);
        }
        let b = bbox(x, tri);
        match self.range(&b) {
            Some((lo, hi)) => {
                for i in lo[0]..=hi[0] {
                    for j in lo[1]..=hi[1] {
                        for k in lo[2]..=hi[2] {
                            self.cells.entry([i, j, k]).or_default().push(t);
                        }
                    }
                }
            }
            None => self.cells.entry([i64::MAX; 3]).or_default().push(t),
        }
    }

    /// The triangles whose boxes meet the box `b` now, each once.
    pub fn near(&mut self, x: &[[f64; 3]], tris: &[[u32; 3]], b: &([f64; 3], [f64; 3]), out: &mut Vec<u32>) {
        out.clear();
        self.now = self.now.wrapping_add(1);
        if self.now == 0 {
            self.stamp.iter_mut().for_each(|s| *s = 0);
            self.now = 1;
        }
        let mut visit = |list: &Vec<u32>, stamp: &mut Vec<u32>, now: u32| {
            for &t in list {
                if stamp[t as usize] != now && overlap(&bbox(x, &tris[t as usize]), b) {
                    stamp[t as usize] = now;
                    out.push(t);
                }
            }
        };
        if let Some(list) = self.cells.get(&[i64::MAX; 3]) {
            visit(list, &mut self.stamp, self.now);
        }
        let Some((lo, hi)) = self.range(b) else {
            // a huge query box: every filed triangle
            let lists: Vec<&Vec<u32>> = self.cells.values().collect();
            for list in lists {
                visit(list, &mut self.stamp, self.now);
            }
            return;
        };
        for i in lo[0]..=hi[0] {
            for j in lo[1]..=hi[1] {
                for k in lo[2]..=hi[2] {
                    if let Some(list) = self.cells.get(&[i, j, k]) {
                        visit(list, &mut self.stamp, self.now);
                    }
                }
            }
        }
    }
}

/// Exact violations around the triangles `group` (ids into `tris`, all
/// live): degenerate ones among them, pairs of one of them with any
/// triangle meeting it besides shared vertices and edges (a pair inside the
/// group once), and, for each vertex of `points`, the other vertices in use
/// nearby at its very position. `live[t]` says which triangles exist.
pub(crate) fn violations_around(
    x: &[[f64; 3]],
    tris: &[[u32; 3]],
    live: &[bool],
    grid: &mut TriGrid,
    group: &[u32],
    points: &[u32],
) -> usize {
    let mut n = 0;
    let mut near = Vec::new();
    let degenerate = |t: &[u32; 3]| collinear(x, t[0], t[1], t[2]);
    for &t in group {
        let tri = tris[t as usize];
        if degenerate(&tri) {
            n += 1;
            continue;
        }
        grid.near(x, tris, &bbox(x, &tri), &mut near);
        for &u in &near {
            if u == t || !live[u as usize] || (group.contains(&u) && u < t) {
                continue;
            }
            let other = tris[u as usize];
            if !degenerate(&other) && pair_intersects(x, &tri, &other) {
                n += 1;
            }
        }
    }
    for &v in points {
        let p = x[v as usize];
        grid.near(x, tris, &(p, p), &mut near);
        let bits = point_bits(&p);
        let mut others: Vec<u32> = near
            .iter()
            .filter(|&&u| live[u as usize])
            .flat_map(|&u| tris[u as usize])
            .filter(|&w| w != v && point_bits(&x[w as usize]) == bits)
            .collect();
        others.sort_unstable();
        others.dedup();
        n += others.len();
    }
    n
}
