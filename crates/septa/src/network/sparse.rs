//! Sparse evaluation (issue 6): work and memory follow the surface.
//!
//! Blocks of a box grid are first classified by the functions' guaranteed
//! bounds over the block's box, before anything is sampled (IA: a block is
//! skipped when every function keeps one strict sign on it; MI: when one
//! function exceeds every other on it). Only the vertices of the other
//! blocks are sampled, block by block and in parallel; a block's values live
//! while the block is processed and are dropped with it, so no `N x k`
//! array of the whole grid is ever allocated.
//!
//! Why the output is identical to the dense path: a skipped block holds no
//! part of the network, so on the dense path its cubes are all empty and,
//! with ray shooting (Du et al. Sec. 7.1), contribute nothing to the merge.
//! Rays do cross skipped blocks; the few values they look at are computed
//! on demand by the same formula at the same point, hence bit-identical to
//! the dense samples. Where the dense path would group cells instead of
//! shooting rays (volumes asked for, a value exactly 0 in IA, a tie for the
//! maximum in MI), the sparse path falls back to the dense one and says so.

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

use rayon::prelude::*;

use super::block::{BlockOut, Ctx, Worker};
use super::{merge, topology, Network, NetworkError, NetworkOptions};
use crate::complex::{Mode, Options};
use crate::grid::{Block, BoxGrid, Grid};
use crate::scene::{block_may_be_active_ia, block_may_be_active_mi, sample_grid, Primitive};

/// Function values at grid vertices, for the block worker and ray shooting.
pub(crate) trait Values: Sync {
    /// Value of function `f` at grid vertex `v`.
    fn val(&self, v: u32, f: usize) -> f64;
}

/// What sparse evaluation did, for the JSON summary.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SparseStats {
    /// Blocks of the grid.
    pub blocks: usize,
    /// Blocks proven empty by bounds and never sampled.
    pub skipped: usize,
    /// Blocks whose vertices were sampled.
    pub sampled: usize,
    /// Sampled blocks with at least one active tet.
    pub active: usize,
    /// Grid vertices sampled (vertices on block boundaries count once per block).
    pub sampled_vertices: usize,
    /// The dense path was used instead (cells needed grouping: volumes,
    /// an IA value exactly 0 or an MI tie; see the module doc).
    pub dense_fallback: bool,
}

/// The values of one block's vertices, `lo..=hi` in grid coordinates.
struct BlockValues {
    lo: [usize; 3],
    vn: [usize; 3],
    k: usize,
    data: Vec<f64>,
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
    fn new(grid: &BoxGrid, lo: [usize; 3], vn: [usize; 3], k: usize, data: Vec<f64>) -> BlockValues {
        let b = grid.res[2] as u32 + 1;
        let a = (grid.res[1] as u32 + 1) * b;
        BlockValues { lo, vn, k, data, stride: [a, b], cache: std::array::from_fn(|_| AtomicU64::new(u64::MAX)) }
    }

    #[inline]
    fn local(&self, v: u32) -> usize {
        let slot = &self.cache[(v.wrapping_mul(0x9E37_79B1) >> 28) as usize];
        let e = slot.load(Ordering::Relaxed);
        if e >> 32 == v as u64 {
            return (e & 0xFFFF_FFFF) as usize;
        }
        let (i, r) = (v / self.stride[0], v % self.stride[0]);
        let (j, l) = (r / self.stride[1], r % self.stride[1]);
        let local = ((i as usize - self.lo[0]) * self.vn[1] + (j as usize - self.lo[1])) * self.vn[2]
            + (l as usize - self.lo[2]);
        slot.store((v as u64) << 32 | local as u64, Ordering::Relaxed);
        local
    }
}

impl Values for BlockValues {
    #[inline]
    fn val(&self, v: u32, f: usize) -> f64 {
        self.data[self.local(v) * self.k + f]
    }
}

/// Values computed on demand at any grid vertex (for the few vertices ray
/// shooting looks at, possibly in skipped blocks).
struct PointValues<'a> {
    grid: &'a BoxGrid,
    functions: &'a [Primitive],
}

impl Values for PointValues<'_> {
    fn val(&self, v: u32, f: usize) -> f64 {
        self.functions[f].eval(self.grid.vertex(v))
    }
}

/// Whether a block may hold a part of the network, by the functions' bounds
/// over its box (no sampling).
fn may_be_active(grid: &BoxGrid, functions: &[Primitive], mode: Mode, lo: [usize; 3], hi: [usize; 3]) -> bool {
    let a = grid.vertex(grid.vertex_index(lo));
    let b = grid.vertex(grid.vertex_index(hi));
    match mode {
        Mode::Ia => block_may_be_active_ia(functions, a, b),
        Mode::Mi => block_may_be_active_mi(functions, a, b),
    }
}

/// Samples the vertices of cubes `lo..hi`; also says whether ray shooting's
/// precondition holds there (IA no value 0, MI a unique strict maximum).
fn sample_block(
    grid: &BoxGrid,
    functions: &[Primitive],
    mode: Mode,
    lo: [usize; 3],
    hi: [usize; 3],
) -> Result<(BlockValues, bool), NetworkError> {
    let k = functions.len();
    let vn = [hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1];
    let mut data = Vec::with_capacity(vn[0] * vn[1] * vn[2] * k);
    let mut clean = true;
    for i in lo[0]..=hi[0] {
        for j in lo[1]..=hi[1] {
            for l in lo[2]..=hi[2] {
                let v = grid.vertex_index([i, j, l]);
                let p = grid.vertex(v);
                let start = data.len();
                for (f, func) in functions.iter().enumerate() {
                    let x = func.eval(p);
                    if !x.is_finite() {
                        return Err(NetworkError::NonFinite { vertex: v as usize, function: f, value: x });
                    }
                    data.push(x);
                }
                let row = &data[start..];
                clean &= match mode {
                    Mode::Ia => row.iter().all(|&x| x != 0.0),
                    Mode::Mi => {
                        let m = row.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                        row.iter().filter(|&&x| x == m).count() == 1
                    }
                };
            }
        }
    }
    Ok((BlockValues::new(grid, lo, vn, k, data), clean))
}

fn ctx<'a>(grid: &'a Grid, k: usize, options: &NetworkOptions, values: &'a dyn Values) -> Ctx<'a> {
    Ctx {
        grid,
        values: &[],
        k,
        mode: options.mode,
        options: Options::with_float(options.float),
        volumes: false,
        grouping: false,
        sparse: Some(values),
    }
}

/// The dense path on the same functions (every vertex sampled).
fn dense(grid: &BoxGrid, functions: &[Primitive], options: &NetworkOptions) -> Result<Network, NetworkError> {
    let g = Grid::Box(grid.clone());
    let values = sample_grid(functions, &g.vertices());
    super::compute(&g, &values, functions.len(), options)
}

/// Computes the IA or MI network of analytic functions on a box grid by
/// sparse evaluation (see the module doc); the result equals
/// [`compute`](super::compute) on the functions sampled at every vertex.
pub fn compute_sparse(
    grid: &BoxGrid,
    functions: &[Primitive],
    options: &NetworkOptions,
) -> Result<(Network, SparseStats), NetworkError> {
    let t0 = Instant::now();
    let k = functions.len();
    if k == 0 {
        return Err(NetworkError::NoFunctions);
    }
    if k > u16::MAX as usize - 1 {
        return Err(NetworkError::TooManyFunctions(k));
    }
    let blocks = grid.blocks(options.block);
    let mut stats = SparseStats { blocks: blocks.len(), ..SparseStats::default() };
    let fallback = |mut stats: SparseStats| {
        stats.dense_fallback = true;
        stats.skipped = 0;
        stats.sampled = stats.blocks;
        stats.sampled_vertices = grid.num_vertices();
        Ok((dense(grid, functions, options)?, stats))
    };
    if options.volumes || !options.raytrace {
        return fallback(stats);
    }
    let cubes = |b: &Block| match b {
        Block::Cubes { lo, hi } => (*lo, *hi),
        Block::Tets(_) => unreachable!("a box grid has cube blocks"),
    };
    // 1. Classify by bounds, before any sampling.
    let keep: Vec<&Block> = blocks
        .par_iter()
        .filter(|b| {
            let (lo, hi) = cubes(b);
            may_be_active(grid, functions, options.mode, lo, hi)
        })
        .collect();
    stats.sampled = keep.len();
    stats.skipped = blocks.len() - keep.len();
    // 2. Sample and process each kept block; its values die with it.
    let g = Grid::Box(grid.clone());
    let done = std::sync::atomic::AtomicUsize::new(0);
    let outs: Vec<(BlockOut, bool, usize)> = keep
        .par_iter()
        .map_init(Worker::default, |w, b| {
            if options.cancelled() {
                return Err(NetworkError::Cancelled);
            }
            let (lo, hi) = cubes(b);
            let (bv, clean) = sample_block(grid, functions, options.mode, lo, hi)?;
            let nv = bv.data.len() / k;
            let c = ctx(&g, k, options, &bv);
            let out = w.run(&c, b)?;
            if let Some(p) = &options.progress {
                p.tick(&done, keep.len());
            }
            Ok((out, clean, nv))
        })
        .collect::<Result<_, NetworkError>>()?;
    stats.sampled_vertices = outs.iter().map(|o| o.2).sum();
    stats.active = outs.iter().filter(|o| o.0.active_tets > 0).count();
    if !outs.iter().all(|o| o.1) {
        return fallback(stats);
    }
    let outs: Vec<BlockOut> = outs.into_iter().map(|o| o.0).collect();
    let t1 = Instant::now();
    let mut m = merge::merge(options.mode, outs);
    // The same canonical order as the dense path (identical output).
    super::canon::canonicalize_merged(&mut m);
    let t2 = Instant::now();
    let pv = PointValues { grid, functions };
    let c = ctx(&g, k, options, &pv);
    let mut topo = topology::topology(&mut m, Some(&c));
    if topo.cells_method != "raytrace" {
        return fallback(stats);
    }
    super::canon::canonicalize_topology(&mut topo);
    let row: Vec<f64> = (0..k).map(|f| pv.val(0, f)).collect();
    super::label_free_cells(&mut topo, options.mode, &row);
    let t3 = Instant::now();
    let net = super::assemble(options.mode, k, m, topo, [t1 - t0, t2 - t1, t3 - t2]);
    Ok((net, stats))
}
