//! Where a block reads function values: the whole grid's array (dense),
//! one block's samples (sparse), or values computed on demand at single
//! grid vertices (ray shooting across skipped blocks).

use std::sync::atomic::{AtomicU64, Ordering};

use super::mask::CubeMask;
use crate::complex::{Mode, Options};
use crate::grid::{BoxGrid, Grid, VertexLookup};
use crate::network::field::BoundedField;

/// Function values at grid vertices, for the block worker and ray shooting.
pub(crate) trait Values: Sync {
    /// Value of function `f` at grid vertex `v`.
    fn val(&self, v: u32, f: usize) -> f64;
    /// The `k` values at grid vertex `v` where they are held as one row
    /// (`None`: ask [`Values::val`] per function).
    fn row(&self, _v: u32) -> Option<&[f64]> {
        None
    }
    /// When every function is an indicator (1 for one function at each
    /// vertex, 0 for the others: a label volume), the function that is 1
    /// at grid vertex `v`; `None` otherwise.
    fn label(&self, _v: u32) -> Option<u32> {
        None
    }
    /// [`Values::label`] of every vertex of the block `lo..lo + vn` (grid
    /// coordinates), in local order (`(i * vn[1] + j) * vn[2] + k`), when
    /// held as such: read as a slice, not vertex by vertex from grid ids.
    fn block_labels(&self, _lo: [usize; 3], _vn: [usize; 3]) -> Option<&[u32]> {
        None
    }
    /// The block's cubes that may hold a part of the network, when the
    /// vertices of the others were not sampled (`mask.rs`).
    fn mask(&self) -> Option<&CubeMask> {
        None
    }
    /// One box block's samples as rows, when held so: a caller that walks
    /// the block's vertices by their local index reads a row without
    /// locating grid vertex ids ([`Values::val`]'s divisions and cache).
    fn block_rows(&self) -> Option<BlockRows<'_>> {
        None
    }
}

/// The samples of the box block `lo..lo + vn` (grid coordinates) as rows of
/// `k` values: function `f` at the vertex of row `r` is `data[r * k + f]`.
#[derive(Clone, Copy)]
pub(crate) struct BlockRows<'a> {
    pub data: &'a [f64],
    pub lo: [usize; 3],
    pub vn: [usize; 3],
    mask: Option<&'a CubeMask>,
}

impl BlockRows<'_> {
    /// The row of block-local vertex `local` (`(i * vn[1] + j) * vn[2] + k`),
    /// or [`super::mask::NO_ROW`] for a vertex the mask left unsampled.
    #[inline]
    pub(crate) fn row_of(&self, local: usize) -> u32 {
        match self.mask {
            None => local as u32,
            Some(m) => m.row(local),
        }
    }
}

/// Run-wide inputs.
pub(crate) struct Ctx<'a> {
    pub grid: &'a Grid,
    pub values: &'a [f64],
    pub k: usize,
    pub mode: Mode,
    pub options: Options,
    pub volumes: bool,
    /// Join regions across tet faces (cell grouping); off when ray shooting
    /// is sure to apply.
    pub grouping: bool,
    /// Sparse evaluation (docs/sparse.md): values come from here, not `values`.
    pub sparse: Option<&'a dyn Values>,
    /// `sparse`'s [`Values::block_rows`], asked once per block instead of
    /// once per tet.
    pub block_rows: Option<BlockRows<'a>>,
    /// MI: also drop functions below the average of the corner winners
    /// ([`crate::network::NetworkOptions::mi_average_domination`]).
    pub average_domination: bool,
    /// Box grids: vertex ids to indices and positions without division.
    pub lookup: Option<VertexLookup>,
}

impl Ctx<'_> {
    /// The lookup of a box grid (for [`Ctx::lookup`]).
    pub(crate) fn lookup_of(grid: &Grid) -> Option<VertexLookup> {
        match grid {
            Grid::Box(g) => Some(VertexLookup::new(g)),
            Grid::Mesh(_) => None,
        }
    }

    /// Position of grid vertex `v` (the same bits as `grid.vertex(v)`).
    #[inline]
    pub(crate) fn vertex(&self, v: u32) -> [f64; 3] {
        match &self.lookup {
            Some(l) => l.position(v),
            None => self.grid.vertex(v),
        }
    }
    /// Value of function `f` at grid vertex `v`.
    #[inline]
    pub(crate) fn val(&self, v: u32, f: usize) -> f64 {
        match self.sparse {
            None => self.values[v as usize * self.k + f],
            Some(s) => s.val(v, f),
        }
    }

    /// The `k` values at grid vertex `v` (copied into `buf` when sparse).
    #[inline]
    pub(crate) fn row<'b>(&'b self, v: u32, buf: &'b mut Vec<f64>) -> &'b [f64] {
        match self.sparse {
            None => &self.values[v as usize * self.k..(v as usize + 1) * self.k],
            Some(s) => match s.row(v) {
                Some(row) => row,
                None => {
                    buf.clear();
                    buf.extend((0..self.k).map(|f| s.val(v, f)));
                    buf
                }
            },
        }
    }

    /// The function that is 1 at grid vertex `v` when the values are
    /// indicators ([`Values::label`]).
    #[inline]
    pub(crate) fn label(&self, v: u32) -> Option<u32> {
        self.sparse.and_then(|s| s.label(v))
    }
}

/// The values of one block's vertices, `lo..=hi` in grid coordinates: every
/// vertex, or those the mask gives a row.
pub(crate) struct BlockValues {
    k: usize,
    pub(crate) data: Vec<f64>,
    at: LocalIndex,
    mask: Option<CubeMask>,
}

/// Grid vertex id to a block's local vertex index, with a small cache.
struct LocalIndex {
    lo: [usize; 3],
    vn: [usize; 3],
    /// Vertex id strides of i and j.
    stride: [u32; 2],
    /// Recently looked-up rows, `v << 32 | local row`, hashed by `v`: the
    /// block worker reads the same few tet vertices over and over (MI reads
    /// up to `4 k^2` values per tet) and the integer divisions that locate
    /// a row dominated. Relaxed atomics are plain loads and stores here;
    /// every entry is self-validating, so sharing could never give a wrong row.
    cache: [AtomicU64; 16],
}

impl BlockValues {
    pub(crate) fn new(grid: &BoxGrid, lo: [usize; 3], vn: [usize; 3], k: usize, data: Vec<f64>) -> BlockValues {
        BlockValues { k, data, at: LocalIndex::new(grid, lo, vn), mask: None }
    }

    /// The values of the vertices `mask` gives a row, in row order.
    pub(crate) fn masked(
        grid: &BoxGrid,
        lo: [usize; 3],
        vn: [usize; 3],
        k: usize,
        data: Vec<f64>,
        mask: CubeMask,
    ) -> BlockValues {
        debug_assert_eq!(data.len(), mask.sampled() * k);
        BlockValues { k, data, at: LocalIndex::new(grid, lo, vn), mask: Some(mask) }
    }
}

impl LocalIndex {
    fn new(grid: &BoxGrid, lo: [usize; 3], vn: [usize; 3]) -> LocalIndex {
        let b = grid.res[2] as u32 + 1;
        let a = (grid.res[1] as u32 + 1) * b;
        LocalIndex { lo, vn, stride: [a, b], cache: std::array::from_fn(|_| AtomicU64::new(u64::MAX)) }
    }

    /// The row of grid vertex `v`: its block-local index, renumbered by
    /// `mask` when given (a vertex without a row is never read: the worker
    /// skips the cubes the mask rules out).
    #[inline]
    fn local(&self, v: u32, mask: Option<&CubeMask>) -> usize {
        let slot = &self.cache[(v.wrapping_mul(0x9E37_79B1) >> 28) as usize];
        let e = slot.load(Ordering::Relaxed);
        if e >> 32 == v as u64 {
            return (e & 0xFFFF_FFFF) as usize;
        }
        let (i, r) = (v / self.stride[0], v % self.stride[0]);
        let (j, l) = (r / self.stride[1], r % self.stride[1]);
        let local = ((i as usize - self.lo[0]) * self.vn[1] + (j as usize - self.lo[1])) * self.vn[2]
            + (l as usize - self.lo[2]);
        let local = match mask {
            None => local,
            Some(m) => m.row(local) as usize,
        };
        slot.store((v as u64) << 32 | local as u64, Ordering::Relaxed);
        local
    }
}

impl Values for BlockValues {
    #[inline]
    fn val(&self, v: u32, f: usize) -> f64 {
        self.data[self.at.local(v, self.mask.as_ref()) * self.k + f]
    }

    #[inline]
    fn row(&self, v: u32) -> Option<&[f64]> {
        let at = self.at.local(v, self.mask.as_ref()) * self.k;
        Some(&self.data[at..at + self.k])
    }

    fn mask(&self) -> Option<&CubeMask> {
        self.mask.as_ref()
    }

    fn block_rows(&self) -> Option<BlockRows<'_>> {
        Some(BlockRows { data: &self.data, lo: self.at.lo, vn: self.at.vn, mask: self.mask.as_ref() })
    }
}

/// One block's vertices of a label volume: the index of the label at each
/// vertex, `lo..=hi` in grid coordinates, instead of `k` values per vertex
/// (the label indicators: 1 for that label, 0 for the others, every value
/// exact). 4 bytes a vertex where the rows took `8 k`.
pub(crate) struct BlockLabels {
    pub(crate) labels: Vec<u32>,
    at: LocalIndex,
}

impl BlockLabels {
    pub(crate) fn new(grid: &BoxGrid, lo: [usize; 3], vn: [usize; 3], labels: Vec<u32>) -> BlockLabels {
        BlockLabels { labels, at: LocalIndex::new(grid, lo, vn) }
    }
}

impl Values for BlockLabels {
    #[inline]
    fn val(&self, v: u32, f: usize) -> f64 {
        (self.labels[self.at.local(v, None)] as usize == f) as u8 as f64
    }

    #[inline]
    fn label(&self, v: u32) -> Option<u32> {
        Some(self.labels[self.at.local(v, None)])
    }

    fn block_labels(&self, lo: [usize; 3], vn: [usize; 3]) -> Option<&[u32]> {
        (self.at.lo == lo && self.at.vn == vn).then_some(&self.labels[..])
    }
}

/// Values computed on demand at any grid vertex (for the few vertices ray
/// shooting looks at, possibly in skipped blocks).
pub(crate) struct PointValues<'a> {
    pub(crate) grid: &'a BoxGrid,
    pub(crate) functions: &'a dyn BoundedField,
}

impl Values for PointValues<'_> {
    fn val(&self, v: u32, f: usize) -> f64 {
        self.functions.value(f, self.grid.vertex(v))
    }
}
