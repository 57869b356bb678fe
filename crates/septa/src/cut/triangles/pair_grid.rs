//! The uniform grid that gives `selfx` its candidate triangle pairs (TopoCut
//! App. A tests "all pairs of triangles whose bounding boxes overlap"): each
//! triangle is entered in every grid cell its bounding box touches, and a
//! cell's triangles are then swept along x. The grid only chooses which pairs
//! reach the exact test; a pair of overlapping boxes always shares the cell of
//! the low corner of their overlap, so no pair is missed whatever the sizing.
//!
//! The entries are ordered without comparison sorts: the triangles are put in
//! order of the low x of their boxes once, and their entries are grouped by
//! cell in that order, so each cell's run is already in sweep order (the
//! comparison sorts of all entries by cell and of every cell by x were a
//! sixth of the exact check on the large meshes). The grouping is a counting
//! sort with one counter per cell (two passes over the triangles' cells)
//! unless the cells far outnumber the entries; then (cell key, triangle)
//! pairs are radix-sorted by key. The counting sort replaced the radix sort
//! everywhere the cells allow: on nefertiti R20 it moved and faulted in
//! 16-byte pairs twice (13 MB each way) where it now writes 4-byte ids once,
//! and the grid of the exact check went from 50 to 25 ms.

use crate::cut::triangles::radix::{radix_sort_keys, radix_sort_stable, total_order_key};

/// A triangle's bounding box, as `(lo, hi)` corners.
pub(crate) type Aabb = ([f64; 3], [f64; 3]);

/// The grid of one set of boxes: every cell's boxes in sweep order.
pub(crate) struct PairGrid {
    /// Each box's low grid cell per axis.
    pub low_cell: Vec<[u32; 3]>,
    /// The boxes entered in each cell, cell after cell in key order, each
    /// cell's in order of the boxes' low x (ties in any order).
    pub ids: Vec<u32>,
    /// The non-empty cells: `(key, start, end)`, the cell's boxes being
    /// `ids[start..end]`, in key order.
    pub groups: Vec<(u64, u32, u32)>,
    res: u64,
    /// Whether the boxes were grouped by one counter per cell (else by
    /// sorting (key, box) pairs).
    #[cfg_attr(not(test), allow(dead_code))]
    pub dense: bool,
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
        drop(extents);
        let ext = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        let mut res = ((ext / (1.5 * median).max(f64::MIN_POSITIVE)).ceil() as usize).clamp(1, 1 << 20);
        let cell_of = |res: usize| {
            let size: [f64; 3] = std::array::from_fn(|k| ((hi[k] - lo[k]) / res as f64).max(f64::MIN_POSITIVE));
            move |b: &Aabb| -> [[u32; 3]; 2] {
                let cell = |p: f64, k: usize| (((p - lo[k]) / size[k]) as usize).min(res - 1) as u32;
                [std::array::from_fn(|k| cell(b.0[k], k)), std::array::from_fn(|k| cell(b.1[k], k))]
            }
        };
        let span = |[l, h]: [[u32; 3]; 2]| (0..3).map(|k| (h[k] - l[k]) as usize + 1).product::<usize>();
        // the budget is checked by counting alone; the cells are formed once
        let mut total: usize = boxes.iter().map(|b| span(cell_of(res)(b))).sum();
        while res > 1 && total > 8 * n {
            res = res * 3 / 4;
            let at = cell_of(res);
            total = boxes.iter().map(|b| span(at(b))).sum();
        }
        let cells: Vec<[[u32; 3]; 2]> = boxes.iter().map(cell_of(res)).collect();
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
        let cells_total = r * r * r;
        // one counter per cell when the cells are not many more than the
        // entries (else sorted (key, box) pairs)
        let dense = cells_total <= 4 * total as u64 + (1 << 16);
        // with `fresh`, the cells holding a fresh box: a flag per cell, or
        // their sorted keys
        let (mut hot_flags, mut hot_keys) = (Vec::new(), Vec::new());
        if let Some(fresh) = fresh {
            if dense {
                hot_flags = vec![false; cells_total as usize];
            }
            for t in (0..n).filter(|&t| fresh[t]) {
                for_each_cell(cells[t], &mut |k| {
                    if dense {
                        hot_flags[k as usize] = true;
                    } else {
                        hot_keys.push(k);
                    }
                });
            }
            hot_keys.sort_unstable();
            hot_keys.dedup();
        }
        let wanted = |t: u32, k: u64| match fresh {
            None => true,
            Some(f) => f[t as usize] || if dense { hot_flags[k as usize] } else { hot_keys.binary_search(&k).is_ok() },
        };
        let low_cell = cells.iter().map(|c| c[0]).collect();
        let (ids, groups) = if dense {
            // a counting sort by cell: one count per cell, then each box
            // entered in order of low x, so every cell's run comes out in
            // sweep order without moving (key, box) pairs around
            let mut start = vec![0u32; cells_total as usize + 1];
            for &(_, t) in &order {
                for_each_cell(cells[t as usize], &mut |k| {
                    if wanted(t, k) {
                        start[k as usize + 1] += 1;
                    }
                });
            }
            for k in 0..cells_total as usize {
                start[k + 1] += start[k];
            }
            let mut ids = vec![0u32; start[cells_total as usize] as usize];
            // `start[k]` is the cursor of cell k, and ends at its end
            for &(_, t) in &order {
                for_each_cell(cells[t as usize], &mut |k| {
                    if wanted(t, k) {
                        ids[start[k as usize] as usize] = t;
                        start[k as usize] += 1;
                    }
                });
            }
            let groups = (0..cells_total as usize)
                .filter_map(|k| {
                    let s = if k == 0 { 0 } else { start[k - 1] };
                    (s < start[k]).then_some((k as u64, s, start[k]))
                })
                .collect();
            (ids, groups)
        } else {
            // a key space far larger than the entries (a few long boxes
            // forced a fine grid): (key, box) pairs sorted by key
            let mut entries: Vec<(u64, u32)> = Vec::with_capacity(if fresh.is_none() { total } else { 0 });
            for &(_, t) in &order {
                for_each_cell(cells[t as usize], &mut |k| {
                    if wanted(t, k) {
                        entries.push((k, t))
                    }
                });
            }
            radix_sort_stable(&mut entries, 64 - (cells_total - 1).leading_zeros());
            let mut groups: Vec<(u64, u32, u32)> = Vec::new();
            let mut s = 0;
            while s < entries.len() {
                let mut e = s + 1;
                while e < entries.len() && entries[e].0 == entries[s].0 {
                    e += 1;
                }
                groups.push((entries[s].0, s as u32, e as u32));
                s = e;
            }
            (entries.into_iter().map(|e| e.1).collect(), groups)
        };
        PairGrid { low_cell, ids, groups, res: r, dense }
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
