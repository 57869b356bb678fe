//! Sparse evaluation (docs/sparse.md): work and memory follow the surface.
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
//! the dense samples. Values exactly 0 (IA) or tied (MI) at grid vertices
//! need nothing special: polygons lying in tet faces pair by key in the
//! merge on both paths, and ray shooting works on the merged network
//! either way (network vertices at grid vertices start and stop rays like
//! edge-points: `topology/raytrace.rs`). Only where ray shooting declines
//! (pieces of one component touching only at points, as tangent spheres)
//! or cell volumes are asked for, which need cell grouping across every tet
//! face, does the sparse path fall back to the dense one, and it says so
//! (`dense_fallback`).

use std::time::Instant;

use rayon::prelude::*;

use super::sample::{may_be_active, sample_block, Sampled};
use crate::complex::{Mode, Options};
use crate::grid::{Block, BoxGrid, Grid};
use crate::network::block::{BlockOut, Ctx, PointValues, Values, Worker};
use crate::network::dense::{assemble, label_free_cells};
use crate::network::field::{BoundedField, ByRef};
use crate::network::topology::{canonicalize_merged, canonicalize_topology, merge, topology, Merged, Merger};
use crate::network::{CellMethod, Network, NetworkError, NetworkOptions};

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

pub(crate) fn ctx<'a>(grid: &'a Grid, k: usize, options: &NetworkOptions, values: &'a dyn Values) -> Ctx<'a> {
    Ctx {
        grid,
        values: &[],
        k,
        mode: options.mode,
        options: {
            let mut o = Options::with_float(options.float);
            o.lookup = options.lookup;
            o
        },
        average_domination: options.mi_average_domination,
        volumes: false,
        grouping: false,
        sparse: Some(values),
        block_rows: values.block_rows(),
        lookup: Ctx::lookup_of(grid),
    }
}

/// The dense path on the same functions (every vertex sampled).
fn dense(grid: &BoxGrid, functions: &dyn BoundedField, options: &NetworkOptions) -> Result<Network, NetworkError> {
    let g = Grid::Box(grid.clone());
    let values = functions.sample(&g.vertices());
    crate::network::compute(&g, &values, functions.functions(), options)
}

/// The first step of a sparse job: which blocks may hold a part of the
/// network (classified by bounds, nothing sampled).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SparsePlan {
    /// Blocks of the grid, `grid.blocks(options.block).len()`.
    pub blocks: usize,
    /// Indices (into `grid.blocks(options.block)`) of the blocks to sample, ascending.
    pub kept: Vec<usize>,
    /// The options ask for cell grouping (volumes, or ray shooting off):
    /// the job runs on the dense path and no block is run.
    pub dense: bool,
}

/// What identifies a sparse job, carried by every [`BlockResult`] so that
/// results of another job (another grid, mode, function count or block
/// size) are refused at [`finish_sparse`] instead of merged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JobKey {
    /// IA or MI.
    pub mode: Mode,
    /// Number of functions.
    pub functions: usize,
    /// Grid resolution.
    pub res: [usize; 3],
    /// Grid bounds.
    pub bounds: [[f64; 3]; 2],
    /// Tets per cube (5 or 6).
    pub split: u8,
    /// Block edge in cubes.
    pub block: usize,
}

impl JobKey {
    /// The key of a job.
    pub fn of(grid: &BoxGrid, functions: usize, options: &NetworkOptions) -> JobKey {
        JobKey {
            mode: options.mode,
            functions,
            res: grid.res,
            bounds: grid.bounds,
            split: grid.split.tets_per_cube() as u8,
            block: options.block.max(1),
        }
    }

    /// Equality with floats compared bit for bit.
    pub(crate) fn same(&self, o: &JobKey) -> bool {
        let bits = |b: &[[f64; 3]; 2]| b.map(|c| c.map(f64::to_bits));
        self.mode == o.mode
            && self.functions == o.functions
            && self.res == o.res
            && bits(&self.bounds) == bits(&o.bounds)
            && self.split == o.split
            && self.block == o.block
    }
}

/// One sampled block's part of the network (the second step of a sparse
/// job), mergeable with the others by [`finish_sparse`] in block order.
/// It crosses machines as bytes: [`BlockResult::to_bytes`] and
/// [`BlockResult::from_bytes`] (see `wire.rs`).
#[derive(Debug)]
pub struct BlockResult {
    pub(crate) job: JobKey,
    pub(crate) index: usize,
    pub(crate) out: BlockOut,
    /// Whether ray shooting's precondition holds on the block (module doc).
    pub(crate) clean: bool,
    pub(crate) sampled_vertices: usize,
}

impl BlockResult {
    /// The block's index in `grid.blocks(block)`.
    pub fn index(&self) -> usize {
        self.index
    }

    /// The job it belongs to.
    pub fn job(&self) -> JobKey {
        self.job
    }

    /// Whether ray shooting applies on this block (IA: no value exactly 0;
    /// MI: a unique maximum at every vertex); if any block is not clean the
    /// job falls back to the dense path.
    pub fn clean(&self) -> bool {
        self.clean
    }

    /// Grid vertices sampled for the block.
    pub fn sampled_vertices(&self) -> usize {
        self.sampled_vertices
    }

    /// Tets of the block with a part of the network.
    pub fn active_tets(&self) -> usize {
        self.out.active_tets
    }
}

/// Checks the function count, as the dense path does.
pub(crate) fn check_functions(k: usize) -> Result<(), NetworkError> {
    if k == 0 {
        return Err(NetworkError::NoFunctions);
    }
    if k > u16::MAX as usize - 1 {
        return Err(NetworkError::TooManyFunctions(k));
    }
    Ok(())
}

pub(crate) fn cubes(b: &Block) -> ([usize; 3], [usize; 3]) {
    match b {
        Block::Cubes { lo, hi } => (*lo, *hi),
        Block::Tets(_) => unreachable!("a box grid has cube blocks"),
    }
}

/// Blocks of edge `size` cubes in `grid`.
pub(crate) fn block_count(grid: &BoxGrid, size: usize) -> usize {
    grid.res.map(|r| r.div_ceil(size.max(1))).iter().product()
}

/// Block `index` of `grid.blocks(size)` without listing them all (same
/// order: i outermost, k innermost).
pub(crate) fn block_at(grid: &BoxGrid, size: usize, index: usize) -> Option<Block> {
    let size = size.max(1);
    let n = grid.res.map(|r| r.div_ceil(size));
    if index >= n[0] * n[1] * n[2] {
        return None;
    }
    let ijk = [index / (n[1] * n[2]), index / n[2] % n[1], index % n[2]];
    let lo = [0, 1, 2].map(|a| ijk[a] * size);
    let hi = [0, 1, 2].map(|a| (lo[a] + size).min(grid.res[a]));
    Some(Block::Cubes { lo, hi })
}

/// Step 1 of a sparse job: classifies the blocks by the functions' bounds
/// (in parallel) and lists those to sample.
pub fn plan_sparse<F: BoundedField + ?Sized>(
    grid: &BoxGrid,
    functions: &F,
    options: &NetworkOptions,
) -> Result<SparsePlan, NetworkError> {
    let functions: &dyn BoundedField = &ByRef(functions);
    check_functions(functions.functions())?;
    let blocks = grid.blocks(options.block);
    if options.volumes || !options.raytrace {
        return Ok(SparsePlan { blocks: blocks.len(), kept: Vec::new(), dense: true });
    }
    let kept: Vec<usize> = (0..blocks.len())
        .into_par_iter()
        .filter(|&i| {
            let (lo, hi) = cubes(&blocks[i]);
            may_be_active(grid, functions, options.mode, lo, hi)
        })
        .collect();
    Ok(SparsePlan { blocks: blocks.len(), kept, dense: false })
}

/// Samples block `index` and builds its part of the network with `w`.
pub(crate) fn run_block_with(
    w: &mut Worker,
    g: &Grid,
    grid: &BoxGrid,
    functions: &dyn BoundedField,
    options: &NetworkOptions,
    index: usize,
) -> Result<BlockResult, NetworkError> {
    let k = functions.functions();
    let b = block_at(grid, options.block, index)
        .ok_or_else(|| NetworkError::NoSuchBlock { index, blocks: block_count(grid, options.block) })?;
    let (lo, hi) = cubes(&b);
    let (sampled, clean) = sample_block(grid, functions, options.mode, lo, hi)?;
    let (values, sampled_vertices): (&dyn Values, usize) = match &sampled {
        Sampled::Rows(bv) => (bv, bv.data.len() / k),
        Sampled::Labels(bl) => (bl, bl.labels.len()),
    };
    let c = ctx(g, k, options, values);
    let out = w.run(&c, &b)?;
    Ok(BlockResult { job: JobKey::of(grid, k, options), index, out, clean, sampled_vertices })
}

/// Step 2 of a sparse job: samples block `index` (of `grid.blocks(options.block)`)
/// and builds its part of the network. Independent of every other block,
/// so it may run anywhere (another thread, process or machine).
pub fn run_block<F: BoundedField + ?Sized>(
    grid: &BoxGrid,
    functions: &F,
    options: &NetworkOptions,
    index: usize,
) -> Result<BlockResult, NetworkError> {
    let functions: &dyn BoundedField = &ByRef(functions);
    check_functions(functions.functions())?;
    let g = Grid::Box(grid.clone());
    run_block_with(&mut Worker::default(), &g, grid, functions, options, index)
}

/// Step 3 of a sparse job: merges the block results in block order (so the
/// numbering never depends on which block finished first), puts the
/// network in the dense path's canonical order, identifies cells by ray
/// shooting (values outside the sampled blocks computed on demand) and
/// assembles the [`Network`]. Falls back to the dense path, here, when the
/// plan says so, a block is not clean, or ray shooting does not apply.
/// `results` must be exactly the plan's kept blocks of this job.
pub fn finish_sparse<F: BoundedField + ?Sized>(
    grid: &BoxGrid,
    functions: &F,
    options: &NetworkOptions,
    plan: &SparsePlan,
    results: Vec<BlockResult>,
) -> Result<(Network, SparseStats), NetworkError> {
    let functions: &dyn BoundedField = &ByRef(functions);
    check_functions(functions.functions())?;
    let pv = PointValues { grid, functions };
    finish_with(grid, functions.functions(), options, plan, results, &pv, || dense(grid, functions, options))
}

/// [`finish_sparse`] with values on demand from `pv` and the dense path
/// given as `dense` (shared with continuation).
pub(crate) fn finish_with(
    grid: &BoxGrid,
    k: usize,
    options: &NetworkOptions,
    plan: &SparsePlan,
    mut results: Vec<BlockResult>,
    pv: &dyn Values,
    dense: impl FnOnce() -> Result<Network, NetworkError>,
) -> Result<(Network, SparseStats), NetworkError> {
    let t0 = Instant::now();
    let mut stats = SparseStats { blocks: plan.blocks, ..SparseStats::default() };
    if plan.dense {
        return dense_fallback(grid, stats, dense);
    }
    let job = JobKey::of(grid, k, options);
    if let Some(r) = results.iter().find(|r| !r.job.same(&job)) {
        return Err(NetworkError::ForeignBlock {
            index: r.index,
            job: format!("{:?}", r.job),
            expected: format!("{job:?}"),
        });
    }
    results.sort_by_key(|r| r.index);
    if results.len() != plan.kept.len() || results.iter().zip(&plan.kept).any(|(r, &i)| r.index != i) {
        let have: std::collections::BTreeSet<usize> = results.iter().map(|r| r.index).collect();
        let missing: Vec<usize> = plan.kept.iter().copied().filter(|i| !have.contains(i)).take(5).collect();
        return Err(NetworkError::BlockCount { given: results.len(), planned: plan.kept.len(), missing });
    }
    stats.sampled = plan.kept.len();
    stats.skipped = plan.blocks - plan.kept.len();
    stats.sampled_vertices = results.iter().map(|r| r.sampled_vertices).sum();
    stats.active = results.iter().filter(|r| r.out.active_tets > 0).count();
    // Blocks with a value exactly 0 (IA) or a tie (MI) at a grid vertex
    // are merged like the others: their polygons on tet faces pair by key
    // in the merge, and ray shooting decides whether it can identify the
    // cells (it declines only where the dense path would group them).
    let outs: Vec<BlockOut> = results.into_iter().map(|r| r.out).collect();
    let t1 = Instant::now();
    let m = merge(options.mode, outs);
    finish_merged(grid, k, options, m, stats, pv, [t1 - t0, t1.elapsed()], dense)
}

/// The dense path's network, with the stats saying so.
fn dense_fallback(
    grid: &BoxGrid,
    mut stats: SparseStats,
    dense: impl FnOnce() -> Result<Network, NetworkError>,
) -> Result<(Network, SparseStats), NetworkError> {
    stats.dense_fallback = true;
    stats.skipped = 0;
    stats.sampled = stats.blocks;
    stats.sampled_vertices = grid.num_vertices();
    // The dense path holds every vertex: refuse with the estimate rather
    // than abort in the allocator (before: regions at resolution 1600).
    crate::grid::memory::check_dense(
        grid.num_vertices(),
        1,
        "this job falls back to the dense path (a function vanishes at a grid vertex or cells need grouping); use a coarser grid or shift the grid bounds slightly",
    )?;
    Ok((dense()?, stats))
}

/// The tail of a sparse job once its blocks are merged: canonical order,
/// cells by ray shooting, labels, assembly (or the dense fallback).
#[allow(clippy::too_many_arguments)]
fn finish_merged(
    grid: &BoxGrid,
    k: usize,
    options: &NetworkOptions,
    mut m: Merged,
    stats: SparseStats,
    pv: &dyn Values,
    [tets, merged]: [std::time::Duration; 2],
    dense: impl FnOnce() -> Result<Network, NetworkError>,
) -> Result<(Network, SparseStats), NetworkError> {
    let t_merged = Instant::now();
    // The same canonical order as the dense path (identical output).
    canonicalize_merged(&mut m);
    let t2 = Instant::now();
    let g = Grid::Box(grid.clone());
    let c = ctx(&g, k, options, pv);
    // Cells come from ray shooting here, or the dense path runs instead.
    m.drop_region_groups();
    let mut topo = topology(&mut m, Some(&c));
    if topo.cells_method != CellMethod::Raytrace {
        return dense_fallback(grid, stats, dense);
    }
    canonicalize_topology(&mut topo);
    let row: Vec<f64> = (0..k).map(|f| pv.val(0, f)).collect();
    label_free_cells(&mut topo.cells, options.mode, &row);
    let t3 = Instant::now();
    let mut net = assemble(options.mode, k, m, topo, [tets, merged, t3 - t2]);
    net.seconds.insert(2, ("canon", (t2 - t_merged).as_secs_f64()));
    Ok((net, stats))
}

/// A block worker taken from `pool` for one task of the parallel loop and
/// put back when the task ends, so the next window's tasks reuse its
/// tables and its record of the last block's lengths (the parallel loop
/// makes a fresh state for every piece of work it splits off).
struct Pooled<'a>(Worker, &'a std::sync::Mutex<Vec<Worker>>);

impl<'a> Pooled<'a> {
    fn take(pool: &'a std::sync::Mutex<Vec<Worker>>) -> Pooled<'a> {
        let w = pool.lock().ok().and_then(|mut p| p.pop()).unwrap_or_default();
        Pooled(w, pool)
    }
}

impl Drop for Pooled<'_> {
    fn drop(&mut self) {
        if let Ok(mut p) = self.1.lock() {
            p.push(std::mem::take(&mut self.0));
        }
    }
}

/// Merges a window of block results (in block order) and counts them;
/// returns the time it took.
fn merge_window(merger: &mut Merger, stats: &mut SparseStats, results: Vec<BlockResult>) -> std::time::Duration {
    let t = Instant::now();
    for r in results {
        stats.sampled_vertices += r.sampled_vertices;
        stats.active += (r.out.active_tets > 0) as usize;
        merger.add(r.out);
    }
    t.elapsed()
}

/// Computes the IA or MI network of analytic functions on a box grid by
/// sparse evaluation (see the module doc); the result equals
/// [`compute`](crate::network::compute) on the functions sampled at every vertex.
///
/// It is [`plan_sparse`], [`run_block`] on every kept block (in parallel
/// on the current rayon pool) and [`finish_sparse`]: a distributed run of
/// the same three steps is identical by construction.
pub fn compute_sparse<F: BoundedField + ?Sized>(
    grid: &BoxGrid,
    functions: &F,
    options: &NetworkOptions,
) -> Result<(Network, SparseStats), NetworkError> {
    let functions: &dyn BoundedField = &ByRef(functions);
    let t0 = Instant::now();
    let plan = plan_sparse(grid, functions, options)?;
    if plan.dense {
        return finish_sparse(grid, functions, options, &plan, Vec::new());
    }
    let g = Grid::Box(grid.clone());
    let done = std::sync::atomic::AtomicUsize::new(0);
    let mut stats = SparseStats { blocks: plan.blocks, sampled: plan.kept.len(), ..SparseStats::default() };
    stats.skipped = plan.blocks - plan.kept.len();
    // Blocks run in windows, in parallel, and are merged in block order as
    // each window completes, so only a window's block outputs are alive
    // next to the merged network (the same result as merging all at once).
    // The merge of one window runs beside the blocks of the next: `join`
    // starts the merge on this thread while the other threads may take the
    // blocks; on one thread it merges first, so then still only one
    // window's outputs are alive at a time.
    let window = 4 * rayon::current_num_threads().max(1);
    let mut merger = Merger::new(options.mode);
    let mut merge_time = std::time::Duration::ZERO;
    let mut pending: Vec<BlockResult> = Vec::new();
    let pool = std::sync::Mutex::new(Vec::new());
    for chunk in plan.kept.chunks(window) {
        let (merged, results) = rayon::join(
            || merge_window(&mut merger, &mut stats, std::mem::take(&mut pending)),
            || {
                chunk
                    .par_iter()
                    .map_init(
                        || Pooled::take(&pool),
                        |w, &i| {
                            if options.cancelled() {
                                return Err(NetworkError::Cancelled);
                            }
                            let r = run_block_with(&mut w.0, &g, grid, functions, options, i)?;
                            if let Some(p) = &options.progress {
                                p.tick(&done, plan.kept.len());
                            }
                            Ok(r)
                        },
                    )
                    .collect::<Result<Vec<BlockResult>, NetworkError>>()
            },
        );
        merge_time += merged;
        pending = results?;
    }
    merge_time += merge_window(&mut merger, &mut stats, pending);
    // The workers' tables go before the merged network's topology.
    drop(pool);
    crate::heap::release_free_memory();
    let t = Instant::now();
    let m = merger.finish();
    merge_time += t.elapsed();
    let tets = t0.elapsed() - merge_time;
    let pv = PointValues { grid, functions };
    finish_merged(grid, functions.functions(), options, m, stats, &pv, [tets, merge_time], || {
        dense(grid, functions, options)
    })
}
