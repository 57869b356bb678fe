//! Streaming (issue 6): "outputs can be streamed to disk block by block for
//! networks larger than memory".
//!
//! [`stream_sparse`] classifies the blocks as sparse evaluation does
//! ([`plan_sparse`]), runs the kept blocks a window at a time (in parallel
//! on the current rayon pool) and hands every finished block, in block
//! index order, to a [`StreamSink`], then drops it. While one window is
//! handed to the sink the next one is computed, so at most two windows of
//! block results are alive: memory is bounded by the window, not by the grid.
//!
//! What this mode gives: the polygons of the network (Du et al. Sec. 6),
//! each with its label (IA `[f, f]`, MI `[a, b]`) and its vertices' global
//! plane-based keys ([`VKey`], Sec. 5.1) and streamed ids; with
//! [`stream_topology`] also the topology (Sec. 7: patches, chains, corners,
//! shells, cells), assembled from per-block summaries while the polygons
//! stream (`summary.rs`, `assembly.rs`): each polygon carries its patch
//! piece, which the returned [`NetworkSummary`] maps to its patch and cells.
//! Blocks computed elsewhere (on a Dask cluster, shipped as bytes) go
//! through the same in-order half, [`StreamFeeder`] (`feeder.rs`).
//!
//! Vertices: a block numbers its own vertices. A vertex on a block's
//! boundary (flagged `shared`) repeats in every block that touches it
//! (up to 8); its key is the same in each, and so is its streamed id
//! ([`StreamBlock::vertex_ids`], `numbering.rs`: given at its first coming,
//! in polygon order). Its position, computed in floating point per tet, may
//! differ in the last bits between blocks; the in-memory merge keeps the
//! first block's, and so does the PLY sink. A vertex inside a block is in
//! that block only. Polygons never repeat: each lies in one tet of one block. Orientation: as in the
//! block (counter-clockwise seen from the positive side), before the
//! in-memory path's canonical renumbering.
//!
//! Streaming needs ray shooting's precondition (IA: no value exactly 0;
//! MI: a unique maximum at every vertex) on every sampled block: otherwise
//! network faces may lie on tet faces and are paired only by the merge. A
//! block without it stops the run with [`NetworkError::BlockResults`].

use std::sync::atomic::AtomicUsize;
use std::sync::Mutex;

use rayon::prelude::*;

use super::assembly::NetworkSummary;
use super::block::Worker;
pub use super::feeder::StreamFeeder;
use super::feeder::{summary_of, BlockSummary};
use super::sparse::{check_functions, plan_sparse, run_block_with, BlockResult};
use super::{NetworkError, NetworkOptions, VKey};
use crate::grid::{BoxGrid, Grid};
use crate::scene::Primitive;

/// One finished block, as handed to a [`StreamSink`] (borrowed: it is
/// dropped once the sink returns).
#[derive(Clone, Copy, Debug)]
pub struct StreamBlock<'a> {
    /// Index of the block in `grid.blocks(options.block)`.
    pub index: usize,
    /// First cube of the block (grid coordinates).
    pub lo: [usize; 3],
    /// One past the last cube of the block.
    pub hi: [usize; 3],
    /// Global key of each block vertex.
    pub keys: &'a [VKey],
    /// Per vertex: whether it lies on the block's boundary and may repeat
    /// in other blocks (with the same key).
    pub shared: &'a [bool],
    /// Vertex positions (floating point, output only).
    pub points: &'a [[f64; 3]],
    /// Polygon `p` is `poly_verts[poly_start[p]..poly_start[p + 1]]` (block vertex ids).
    pub poly_start: &'a [u32],
    /// See `poly_start`.
    pub poly_verts: &'a [u32],
    /// Per polygon: IA `[f, f]`; MI `[a, b]`, `a < b`.
    pub poly_label: &'a [[u16; 2]],
    /// Streamed id of each block vertex (`u32::MAX`: on no polygon): a
    /// vertex on block boundaries has the same id in every block.
    pub vertex_ids: &'a [u32],
    /// Per polygon: its patch piece ([`stream_topology`] only, else empty);
    /// [`NetworkSummary::piece_patch`] and [`NetworkSummary::piece_cells`] map it.
    pub poly_piece: &'a [u32],
    /// Tets of the block with a part of the network.
    pub active_tets: usize,
}

impl StreamBlock<'_> {
    /// Number of polygons.
    pub fn num_polygons(&self) -> usize {
        self.poly_label.len()
    }

    /// Block vertex ids of polygon `p`.
    pub fn polygon(&self, p: usize) -> &[u32] {
        &self.poly_verts[self.poly_start[p] as usize..self.poly_start[p + 1] as usize]
    }
}

/// Where streamed blocks go (a file writer, a counter, a test's collector).
pub trait StreamSink {
    /// Takes one block; blocks arrive in ascending index order, each once,
    /// sampled blocks only (a block with no polygon included).
    fn block(&mut self, block: &StreamBlock) -> std::io::Result<()>;
}

/// Why a streamed run stopped.
#[derive(Debug, thiserror::Error)]
pub enum StreamError {
    /// Computing a block failed (or the run was cancelled).
    #[error(transparent)]
    Network(#[from] NetworkError),
    /// The sink failed (its message names the file).
    #[error("stream output: {0}")]
    Sink(#[from] std::io::Error),
}

/// What a streamed run did, for the JSON summary.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StreamStats {
    /// Blocks of the grid.
    pub blocks: usize,
    /// Blocks proven empty by bounds and never sampled.
    pub skipped: usize,
    /// Blocks sampled (handed to the sink).
    pub sampled: usize,
    /// Sampled blocks with at least one active tet.
    pub active: usize,
    /// Grid vertices sampled (vertices on block boundaries count once per block).
    pub sampled_vertices: usize,
    /// Polygons handed to the sink.
    pub faces: usize,
    /// Block vertices handed to the sink (boundary vertices once per block).
    pub block_vertices: usize,
    /// Distinct network vertices (streamed ids `0..vertices`).
    pub vertices: u64,
    /// Most block-boundary vertex keys held at once (`numbering.rs`).
    pub peak_shared_keys: usize,
    /// With topology: most open edges and tet-face pieces held at once, and blocks run again for ray shooting.
    pub peak_open: usize,
    /// See `peak_open`.
    pub reruns: usize,
    /// Tets with a part of the network.
    pub active_tets: usize,
    /// Blocks computed at a time.
    pub window: usize,
}

/// A worker borrowed from a pool for one rayon job and given back on drop,
/// so look-up programs and maps are built once per thread, not per window.
struct Lease<'a> {
    worker: Option<Worker>,
    pool: &'a Mutex<Vec<Worker>>,
}

impl Drop for Lease<'_> {
    fn drop(&mut self) {
        if let (Some(w), Ok(mut pool)) = (self.worker.take(), self.pool.lock()) {
            pool.push(w);
        }
    }
}

/// Streams the IA or MI polygons of analytic functions on a box grid to
/// `sink`, block by block (module doc). `window` is the number of blocks
/// computed at a time (`0`: four per thread of the current rayon pool).
/// `options.volumes` and `options.raytrace` do not apply (no cells).
///
/// The polygons, labels and keys are those of
/// [`compute_sparse`](super::compute_sparse) on the same input (its
/// network's polygons are these, merged by key and renumbered).
pub fn stream_sparse<S: StreamSink + Send>(
    grid: &BoxGrid,
    functions: &[Primitive],
    options: &NetworkOptions,
    window: usize,
    sink: &mut S,
) -> Result<StreamStats, StreamError> {
    Ok(drive(grid, functions, options, window, sink, false)?.0)
}

/// [`stream_sparse`] plus the topology, assembled from block summaries
/// while the polygons stream (module doc): memory follows the blocks in
/// flight, the blocks' boundaries and the number of patch pieces, never the
/// polygons. Its counts, patches, shells and cells are those of
/// [`compute_sparse`](super::compute_sparse) up to numbering (tested face by
/// face); cells come from ray shooting, so a network whose pieces meet only
/// at points is refused (the in-memory path groups cells there).
pub fn stream_topology<S: StreamSink + Send>(
    grid: &BoxGrid,
    functions: &[Primitive],
    options: &NetworkOptions,
    window: usize,
    sink: &mut S,
) -> Result<(StreamStats, NetworkSummary), StreamError> {
    let (stats, summary) = drive(grid, functions, options, window, sink, true)?;
    Ok((stats, summary.expect("topology was asked for")))
}

/// Runs the kept blocks a window at a time and feeds them in order to a
/// [`StreamFeeder`] (summaries are made in the parallel part).
fn drive<S: StreamSink + Send>(
    grid: &BoxGrid,
    functions: &[Primitive],
    options: &NetworkOptions,
    window: usize,
    sink: &mut S,
    topology: bool,
) -> Result<(StreamStats, Option<NetworkSummary>), StreamError> {
    check_functions(functions.len())?;
    let mut o = options.clone();
    o.volumes = false;
    o.raytrace = true;
    let plan = plan_sparse(grid, functions, &o)?;
    let window = if window == 0 { 4 * rayon::current_num_threads() } else { window };
    let mut feeder = StreamFeeder::new(grid, functions, &o, &plan, topology)?;
    let g = Grid::Box(grid.clone());
    let pool: Mutex<Vec<Worker>> = Mutex::new(Vec::new());
    let done = AtomicUsize::new(0);
    let run_window = |ids: &[usize]| -> Result<Vec<(BlockResult, Option<BlockSummary>)>, NetworkError> {
        ids.par_iter()
            .map_init(
                || Lease { worker: Some(pool.lock().ok().and_then(|mut p| p.pop()).unwrap_or_default()), pool: &pool },
                |lease, &i| {
                    if o.cancelled() {
                        return Err(NetworkError::Cancelled);
                    }
                    let w = lease.worker.as_mut().expect("a leased worker");
                    let r = run_block_with(w, &g, grid, functions, &o, i)?;
                    // Summaries are made here, in parallel; only their
                    // assembly runs in block order.
                    let summary = if topology && r.clean { Some(summary_of(&r)?) } else { None };
                    if let Some(p) = &o.progress {
                        p.tick(&done, plan.kept.len());
                    }
                    Ok((r, summary))
                },
            )
            .collect()
    };
    // Window w + 1 is computed while window w goes to the sink.
    let mut pending: Option<Vec<(BlockResult, Option<BlockSummary>)>> = None;
    let mut feed = |rs: Vec<(BlockResult, Option<BlockSummary>)>, sink: &mut S| -> Result<(), StreamError> {
        for (r, summary) in rs {
            feeder.feed_with(r, summary, sink)?;
        }
        Ok(())
    };
    for ids in plan.kept.chunks(window) {
        let (next, fed) = rayon::join(
            || run_window(ids),
            || match pending.take() {
                Some(rs) => feed(rs, sink),
                None => Ok(()),
            },
        );
        fed?;
        pending = Some(next?);
    }
    if let Some(rs) = pending {
        feed(rs, sink)?;
    }
    let (mut stats, summary) = feeder.finish()?;
    stats.window = window;
    Ok((stats, summary))
}
