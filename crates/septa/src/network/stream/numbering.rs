//! Global vertex ids for a stream of blocks (docs/sparse.md), given in the order
//! the blocks come (x slabs outermost, as `grid.blocks` lists them).
//!
//! A vertex inside a block is that block's alone; a vertex on a block's
//! boundary (`shared`) may come again in up to 7 other blocks with the same
//! plane-based key (Du et al. Sec. 5.1) and keeps the id of its first
//! coming. Ids are given lazily, polygon by polygon, so a streamed file
//! lists vertices in the order faces first use them. A key whose grid
//! element lies left of the current slab can never come again and is
//! dropped: the map holds about two slabs' boundary vertices, which grow
//! like the surface's section, not like the grid.

use rustc_hash::FxHashMap;

use crate::complex::NONE;
use crate::grid::BoxGrid;
use crate::network::{NetworkError, VKey};

/// The numbering state (module doc).
pub(crate) struct VertexNumbering {
    /// Shared key -> (global id, payload of its first coming).
    shared: FxHashMap<VKey, (u32, u32)>,
    slab: usize,
    /// Grid vertices per x plane.
    plane: u64,
    next: u64,
    peak: usize,
}

/// The largest x index among the grid vertices of key `k`'s element.
pub(crate) fn max_x(plane: u64, k: &VKey) -> usize {
    k.grid.iter().filter(|&&v| v != u32::MAX).map(|&v| (v as u64 / plane) as usize).max().unwrap_or(0)
}

impl VertexNumbering {
    pub(crate) fn new(grid: &BoxGrid) -> VertexNumbering {
        VertexNumbering {
            shared: FxHashMap::default(),
            slab: 0,
            plane: (grid.res[1] as u64 + 1) * (grid.res[2] as u64 + 1),
            next: 0,
            peak: 0,
        }
    }

    /// Grid vertices per x plane (for [`max_x`]).
    pub(crate) fn plane(&self) -> u64 {
        self.plane
    }

    /// Vertices numbered so far.
    pub(crate) fn count(&self) -> u64 {
        self.next
    }

    /// Most shared keys held at once.
    pub(crate) fn peak(&self) -> usize {
        self.peak
    }

    /// Numbers the vertices of the polygons of a block whose cubes start at
    /// x index `lo_x`: `ids[v]` for block vertex `v` (`NONE`: on no polygon).
    /// `payload(v)` is stored with a shared vertex's first coming; when a
    /// shared vertex comes again, `repeat(first payload, v)` is called.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn block(
        &mut self,
        lo_x: usize,
        keys: &[VKey],
        shared: &[bool],
        poly_verts: &[u32],
        ids: &mut Vec<u32>,
        payload: impl Fn(u32) -> u32,
        mut repeat: impl FnMut(u32, u32),
    ) -> Result<(), NetworkError> {
        if lo_x > self.slab {
            // No later block reaches left of x = lo_x: those keys are done.
            self.slab = lo_x;
            let (slab, plane) = (self.slab, self.plane);
            self.shared.retain(|k, _| max_x(plane, k) >= slab);
        }
        ids.clear();
        ids.resize(keys.len(), NONE);
        for &v in poly_verts {
            let v = v as usize;
            if ids[v] != NONE {
                continue;
            }
            let next = self.next;
            if next >= u32::MAX as u64 {
                return Err(NetworkError::TooManyVertices);
            }
            let id = if shared[v] {
                match self.shared.entry(keys[v]) {
                    std::collections::hash_map::Entry::Occupied(o) => {
                        let (id, first) = *o.get();
                        repeat(first, v as u32);
                        id
                    }
                    std::collections::hash_map::Entry::Vacant(e) => {
                        e.insert((next as u32, payload(v as u32)));
                        next as u32
                    }
                }
            } else {
                next as u32
            };
            if id as u64 == next {
                self.next += 1;
            }
            ids[v] = id;
        }
        self.peak = self.peak.max(self.shared.len());
        Ok(())
    }
}
