//! The uniform grid that gives `selfx` its candidate triangle pairs (TopoCut
//! App. A tests "all pairs of triangles whose bounding boxes overlap"): each
//! triangle is entered in every grid cell its bounding box touches, and a
//! cell's triangles are then swept along x. The grid only chooses which pairs
//! reach the exact test; a pair of overlapping boxes always shares the cell of
//! the low corner of their overlap, so no pair is missed whatever the sizing.
//!
//! The entries are ordered without comparison sorts: the triangles are put in
//! order of the low x of their boxes once, their entries are made in that
//! order, and a stable least-significant-digit radix sort on the cell keys
//! groups them by cell. Each cell's run is then already in sweep order (the
//! comparison sorts of all entries by cell and of every cell by x were a
//! sixth of the exact check on the large meshes).

use super::radix::{radix_sort_keys, radix_sort_stable, total_order_key};

/// A triangle's bounding box, as `(lo, hi)` corners.
pub(super) type Aabb = ([f64; 3], [f64; 3]);

/// The grid of one set of boxes: every cell's entries in sweep order.
pub(super) struct PairGrid {
    /// Each box's low grid cell per axis.
    pub low_cell: Vec<[u32; 3]>,
    /// (cell key, box) entries, grouped by key, each group in order of the
    /// boxes' low x (ties in any order).
    pub entries: Vec<(u64, u32)>,
    /// The runs `[s, e)` of `entries` with one key, in key order.
    pub groups: Vec<(u32, u32)>,
    res: u64,
}

impl PairGrid {
    /// The grid over `boxes`; with `fresh`, only the cells that hold a
    /// fresh box are filled (a re-check of the pairs with a fresh box).
    pub fn new(boxes: &[Aabb], fresh: Option<&[bool]>) -> PairGrid {
        let n = boxes.len();
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for b in boxes {
            for k in 0..3 {
                lo[k] = lo[k].min(b.0[k]);
                hi[k] = hi[k].max(b.1[k]);
            }
        }
        // cells about the size of a typical (median) triangle: a surface mesh
        // then puts a few triangles in each occupied cell. The mean would let
        // the long triangles of a large cut-face's triangulation coarsen the
        // grid for all; they enter many cells instead, as long as the entries
        // stay within a budget (else the grid is coarsened).
        let mut extents: Vec<f64> = boxes.iter().map(|b| (0..3).map(|k| b.1[k] - b.0[k]).fold(0.0, f64::max)).collect();
        let median = match extents.len() {
            0 => 0.0,
            len => *extents.select_nth_unstable_by(len / 2, f64::total_cmp).1,
        };
        let ext = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        let mut res = ((ext / (1.5 * median).max(f64::MIN_POSITIVE)).ceil() as usize).clamp(1, 1 << 20);
        let cells_at = |res: usize| -> Vec<[[u32; 3]; 2]> {
            let size: [f64; 3] = std::array::from_fn(|k| ((hi[k] - lo[k]) / res as f64).max(f64::MIN_POSITIVE));
            let cell = |p: f64, k: usize| (((p - lo[k]) / size[k]) as usize).min(res - 1) as u32;
            boxes
                .iter()
                .map(|b| [std::array::from_fn(|k| cell(b.0[k], k)), std::array::from_fn(|k| cell(b.1[k], k))])
                .collect()
        };
        let count = |c: &[[[u32; 3]; 2]]| -> usize {
            c.iter().map(|[l, h]| (0..3).map(|k| (h[k] - l[k]) as usize + 1).product::<usize>()).sum()
        };
        let mut cells = cells_at(res);
        let mut total = count(&cells);
        while res > 1 && total > 8 * n {
            res = res * 3 / 4;
            cells = cells_at(res);
            total = count(&cells);
        }
        let r = res as u64;
        let key = |i: u32, j: u32, l: u32| (i as u64 * r + j as u64) * r + l as u64;
        // the boxes in order of their low x, then their entries in that order
        // (radix-sorted on the bits of the low x mapped to an unsigned key
        // in the order of `f64::total_cmp`: only the order of equal low x
        // is left open, which the sweep does not depend on)
        let mut order: Vec<(u64, u32)> =
            boxes.iter().enumerate().map(|(t, b)| (total_order_key(b.0[0]), t as u32)).collect();
        radix_sort_keys(&mut order);
        let for_each_cell = |[c0, c1]: [[u32; 3]; 2], f: &mut dyn FnMut(u64)| {
            for i in c0[0]..=c1[0] {
                for j in c0[1]..=c1[1] {
                    for l in c0[2]..=c1[2] {
                        f(key(i, j, l));
                    }
                }
            }
        };
        let mut entries: Vec<(u64, u32)> = Vec::new();
        match fresh {
            None => {
                entries.reserve_exact(total);
                for &(_, t) in &order {
                    for_each_cell(cells[t as usize], &mut |k| entries.push((k, t)));
                }
            }
            Some(fresh) => {
                // the cells of the fresh boxes, then every box in them
                let mut hot: rustc_hash::FxHashSet<u64> = Default::default();
                (0..n).filter(|&t| fresh[t]).for_each(|t| {
                    for_each_cell(cells[t], &mut |k| {
                        hot.insert(k);
                    })
                });
                for &(_, t) in &order {
                    let is_fresh = fresh[t as usize];
                    for_each_cell(cells[t as usize], &mut |k| {
                        if is_fresh || hot.contains(&k) {
                            entries.push((k, t))
                        }
                    });
                }
            }
        }
        let cells_total = r * r * r;
        radix_sort_stable(&mut entries, 64 - (cells_total - 1).leading_zeros());
        let mut groups: Vec<(u32, u32)> = Vec::new();
        let mut s = 0;
        while s < entries.len() {
            let mut e = s + 1;
            while e < entries.len() && entries[e].0 == entries[s].0 {
                e += 1;
            }
            groups.push((s as u32, e as u32));
            s = e;
        }
        let low_cell = cells.into_iter().map(|c| c[0]).collect();
        PairGrid { low_cell, entries, groups, res: r }
    }

    /// The cell of the key `k`.
    #[inline]
    pub fn coords(&self, k: u64) -> [u32; 3] {
        [(k / (self.res * self.res)) as u32, (k / self.res % self.res) as u32, (k % self.res) as u32]
    }
}

#[cfg(test)]
#[path = "pair_grid_tests.rs"]
mod tests;
