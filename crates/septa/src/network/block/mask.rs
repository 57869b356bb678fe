//! Which cubes of a sampled block may hold a part of the network, at the
//! granularity of sub-boxes of a few cubes, and where the samples of the
//! vertices that are needed sit (docs/sparse.md, "Sub-boxes").
//!
//! A block is sampled because the bounds over its whole box could not prove
//! it empty, yet most of its cubes are far from every surface. The same
//! bounds over each sub-box prove most of them empty. A cube of such a
//! sub-box has one region label at its 8 corners (IA: every function keeps
//! one strict sign; MI: one function is the strict maximum), so the worker
//! would skip it anyway (`boxfast.rs`, without cell grouping): its vertices
//! need no values unless a cube of another sub-box uses them.

use crate::complex::Mode;

/// Whether a block may be masked: the worker's one-label cube path
/// (`boxfast.rs`), the only reader of masks, applies to the block.
pub(crate) fn applies(mode: Mode, k: usize) -> bool {
    mode == Mode::Mi || k <= 63
}

/// Cubes per sub-box edge. A block of 16^3 cubes has 64 sub-boxes; smaller
/// sub-boxes prove more cubes empty but cost a bound test each.
pub(crate) const SUB_BOX: usize = 4;

/// No sample: the vertex is used by no cube that may be active.
pub(crate) const NO_ROW: u32 = u32::MAX;

/// A block's sub-boxes that may hold a part of the network, and the sample
/// row of each vertex.
pub(crate) struct CubeMask {
    /// Cubes of the block per axis.
    n: [usize; 3],
    /// Sub-boxes per axis (`ceil(n / SUB_BOX)`).
    m: [usize; 3],
    /// Per sub-box (row-major): may hold a part of the network.
    active: Vec<bool>,
    /// Per block vertex (row-major, `(n + 1)^3`): its row among the samples,
    /// or [`NO_ROW`].
    rows: Vec<u32>,
    /// Vertices with a row.
    sampled: usize,
}

impl CubeMask {
    /// The mask of a block of `n` cubes per axis whose sub-box `(a, b, c)`
    /// may be active iff `may_be_active(lo, hi)` with `lo`, `hi` its first
    /// and last vertex (block-local). `None` when every sub-box may be
    /// active (the mask would save nothing).
    pub(crate) fn build(
        n: [usize; 3],
        mut may_be_active: impl FnMut([usize; 3], [usize; 3]) -> bool,
    ) -> Option<CubeMask> {
        let m = n.map(|c| c.div_ceil(SUB_BOX));
        let range = |s: usize, a: usize| (s * SUB_BOX, ((s + 1) * SUB_BOX).min(n[a]));
        let mut active = Vec::with_capacity(m[0] * m[1] * m[2]);
        for a in 0..m[0] {
            for b in 0..m[1] {
                for c in 0..m[2] {
                    let (r0, r1, r2) = (range(a, 0), range(b, 1), range(c, 2));
                    active.push(may_be_active([r0.0, r1.0, r2.0], [r0.1, r1.1, r2.1]));
                }
            }
        }
        if active.iter().all(|&x| x) {
            return None;
        }
        let vn = n.map(|c| c + 1);
        let mut used = vec![false; vn[0] * vn[1] * vn[2]];
        for a in 0..m[0] {
            for b in 0..m[1] {
                for c in 0..m[2] {
                    if !active[(a * m[1] + b) * m[2] + c] {
                        continue;
                    }
                    let (r0, r1, r2) = (range(a, 0), range(b, 1), range(c, 2));
                    for i in r0.0..=r0.1 {
                        for j in r1.0..=r1.1 {
                            let row = (i * vn[1] + j) * vn[2];
                            used[row + r2.0..=row + r2.1].fill(true);
                        }
                    }
                }
            }
        }
        let mut sampled = 0;
        let rows = used
            .iter()
            .map(|&u| {
                if u {
                    sampled += 1;
                    sampled as u32 - 1
                } else {
                    NO_ROW
                }
            })
            .collect();
        Some(CubeMask { n, m, active, rows, sampled })
    }

    /// Whether block-local cube `(i, j, k)` may hold a part of the network.
    #[inline]
    pub(crate) fn cube(&self, [i, j, k]: [usize; 3]) -> bool {
        debug_assert!(i < self.n[0] && j < self.n[1] && k < self.n[2]);
        self.active[((i / SUB_BOX) * self.m[1] + j / SUB_BOX) * self.m[2] + k / SUB_BOX]
    }

    /// The sample row of block-local vertex number `local` (row-major), or
    /// [`NO_ROW`].
    #[inline]
    pub(crate) fn row(&self, local: usize) -> u32 {
        self.rows[local]
    }

    /// Vertices with a sample row, in block vertex order.
    pub(crate) fn sampled(&self) -> usize {
        self.sampled
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sub_box_needs_its_closed_vertex_range_only() {
        // 8 x 4 x 5 cubes: sub-boxes 2 x 1 x 2, the last ones partial.
        let n = [8, 4, 5];
        let mask = CubeMask::build(n, |lo, hi| lo == [4, 0, 4] && hi == [8, 4, 5]).unwrap();
        assert!(mask.cube([4, 0, 4]) && mask.cube([7, 3, 4]));
        assert!(!mask.cube([3, 3, 4]) && !mask.cube([7, 3, 3]));
        assert_eq!(mask.sampled(), 5 * 5 * 2);
        let vn = [9, 5, 6];
        let local = |i: usize, j: usize, k: usize| (i * vn[1] + j) * vn[2] + k;
        assert_eq!(mask.row(local(4, 0, 4)), 0);
        assert_eq!(mask.row(local(8, 4, 5)), 49);
        assert_eq!(mask.row(local(3, 0, 4)), NO_ROW);
        assert_eq!(mask.row(local(4, 0, 3)), NO_ROW);
        assert!(CubeMask::build(n, |_, _| true).is_none());
    }
}
