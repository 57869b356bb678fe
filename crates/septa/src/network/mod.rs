//! Surface networks on tetrahedral grids (Du et al. 2022, Sec. 3, 6, 7):
//! per-tet complexes assembled into polygons with global plane-based keys,
//! then patches, chains, corners, shells and cells.
//!
//! The grid is processed in blocks (in parallel with rayon); every vertex
//! key names a grid element and functions (Sec. 5.1), so duplicates across
//! tets and blocks unify exactly and independently of processing order.
//! Regions are joined across tet faces by (face, region label) keys, and
//! shells by wedges around edges, so block summaries merge in any order.

mod active;
mod assembly;
pub mod bench;
mod block;
mod boxfast;
mod canon;
pub mod continuation;
mod feeder;
mod keys;
mod merge;
mod numbering;
mod program;
mod raytrace;
mod rerun;
mod simple;
pub mod sparse;
pub mod stream;
mod summary;
pub use assembly::NetworkSummary;
pub use sparse::{compute_sparse, finish_sparse, plan_sparse, run_block, BlockResult, JobKey, SparsePlan, SparseStats};
mod topology;
pub mod uf;
pub mod wire;

use std::time::Instant;

use rayon::prelude::*;
use smallvec::SmallVec;

pub use crate::complex::Mode;
use crate::complex::Options;
use crate::grid::Grid;

/// Global key of a network vertex: the sorted grid vertices of the grid
/// element it lies in (padded with `u32::MAX`), and the sorted global ids of
/// the functions defining it (padded with `u16::MAX`; none for grid vertices).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct VKey {
    /// Grid vertices of the element.
    pub grid: [u32; 4],
    /// Functions.
    pub funcs: [u16; 4],
}

/// Why a network could not be computed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum NetworkError {
    /// The value array does not match the grid.
    #[error("expected {expected} values ({vertices} vertices x {functions} functions), got {got}")]
    ValueCount {
        /// Needed.
        expected: usize,
        /// Grid vertices.
        vertices: usize,
        /// Functions.
        functions: usize,
        /// Given.
        got: usize,
    },
    /// A value is NaN or infinite.
    #[error("value of function {function} at vertex {vertex} is not finite ({value})")]
    NonFinite {
        /// Grid vertex.
        vertex: usize,
        /// Function.
        function: usize,
        /// Value.
        value: f64,
    },
    /// No functions given.
    #[error("no functions given")]
    NoFunctions,
    /// More than 65535 functions.
    #[error("{0} functions: at most 65535 are supported")]
    TooManyFunctions(usize),
    /// IA: a function is zero on a whole tet (its zero set is not a surface there).
    #[error("function {function} vanishes on the whole tet {tet}")]
    VanishesOnTet {
        /// Tet id.
        tet: usize,
        /// Function.
        function: usize,
    },
    /// The run was cancelled through [`NetworkOptions::cancel`].
    #[error("cancelled")]
    Cancelled,
    /// The job would need more memory than the machine has (estimated
    /// before allocating; `grid::memory`).
    #[error(transparent)]
    Memory(#[from] crate::grid::memory::MemoryError),
    /// Block results handed to [`finish_sparse`] do not match its plan
    /// (missing, repeated, or from another job).
    #[error("block results: {0}")]
    BlockResults(String),
    /// Continuation: a seed or the field's values are wrong (the message says which).
    #[error("continuation: {0}")]
    Continuation(String),
    /// The per-tet construction failed.
    #[error("tet {tet}: {message}")]
    Tet {
        /// Tet id.
        tet: usize,
        /// What failed.
        message: String,
    },
}

/// How to compute the network.
#[derive(Clone, Debug)]
pub struct NetworkOptions {
    /// IA or MI.
    pub mode: Mode,
    /// Naive floating-point predicates (for measuring only).
    pub float: bool,
    /// Use the complex's look-up tables for few active functions (Sec. 6).
    pub lookup: bool,
    /// Block edge in cubes.
    pub block: usize,
    /// Compute cell volumes (floating point, for invariant checks); they
    /// come from cell grouping, so this selects grouping over ray shooting.
    pub volumes: bool,
    /// Identify cells by topological ray shooting (Sec. 7.1) when the grid
    /// allows it (a box, no network vertex at a grid vertex); otherwise, or
    /// when false, by cell grouping.
    pub raytrace: bool,
    /// Called with `(blocks done, blocks in all)` as blocks finish, from
    /// worker threads (for progress bars). Default value: none.
    pub progress: Option<Progress>,
    /// Set it to stop the run: blocks not yet started are skipped and the
    /// run returns [`NetworkError::Cancelled`] (never a panic). Default value: none.
    pub cancel: Option<std::sync::Arc<std::sync::atomic::AtomicBool>>,
}

impl NetworkOptions {
    /// Whether [`NetworkOptions::cancel`] has been set.
    pub(crate) fn cancelled(&self) -> bool {
        self.cancel.as_ref().is_some_and(|c| c.load(std::sync::atomic::Ordering::Relaxed))
    }
}

/// A progress callback `(done, total)`; see [`NetworkOptions::progress`].
#[derive(Clone)]
pub struct Progress(pub std::sync::Arc<dyn Fn(usize, usize) + Send + Sync>);

impl std::fmt::Debug for Progress {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Progress(..)")
    }
}

impl Progress {
    /// Counts one finished block out of `total` and reports it.
    pub(crate) fn tick(&self, done: &std::sync::atomic::AtomicUsize, total: usize) {
        let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        (self.0)(n, total);
    }
}

impl NetworkOptions {
    /// Defaults for a mode: exact, 16^3-cube blocks, no volumes.
    pub fn new(mode: Mode) -> NetworkOptions {
        NetworkOptions {
            mode,
            float: false,
            lookup: true,
            block: 16,
            volumes: false,
            raytrace: true,
            progress: None,
            cancel: None,
        }
    }
}

/// A patch: a maximal connected manifold piece of the network.
#[derive(Clone, Debug, PartialEq)]
pub struct Patch {
    /// IA `[f, f]`; MI `[a, b]`, `a < b`, the two materials (positive side: `f_a > f_b`).
    pub label: [u16; 2],
    /// Number of polygons.
    pub faces: usize,
}

/// A cell: a connected 3D region of the complement of the network.
#[derive(Clone, Debug, PartialEq)]
pub struct CellInfo {
    /// Its bounding shells.
    pub shells: Vec<u32>,
    /// IA: sign bits (bit `f` set iff `f > 0`); MI: the material in word 0.
    pub label: SmallVec<[u64; 2]>,
    /// Volume (only with [`NetworkOptions::volumes`], else 0).
    pub volume: f64,
}

/// A complete surface network.
#[derive(Clone, Debug)]
pub struct Network {
    /// IA or MI.
    pub mode: Mode,
    /// Number of functions.
    pub functions: usize,
    /// Vertex positions (floating point, output only).
    pub points: Vec<[f64; 3]>,
    /// Vertex keys (exact identity of each vertex).
    pub keys: Vec<VKey>,
    /// Polygon `f` is `face_verts[face_start[f]..face_start[f+1]]`,
    /// counter-clockwise seen from its positive side.
    pub face_start: Vec<u32>,
    /// See `face_start`.
    pub face_verts: Vec<u32>,
    /// Per polygon: IA `[f, f]`, MI `[a, b]`.
    pub face_label: Vec<[u16; 2]>,
    /// Per polygon: `[cell on the positive side, cell on the negative side]` (`u32::MAX`: outside the grid).
    pub face_cells: Vec<[u32; 2]>,
    /// Per polygon: its patch.
    pub face_patch: Vec<u32>,
    /// Network edges (vertex pairs, ascending).
    pub edges: Vec<[u32; 2]>,
    /// Patches.
    pub patches: Vec<Patch>,
    /// Chains as vertex paths (a closed chain repeats its first vertex).
    pub chains: Vec<Vec<u32>>,
    /// Per chain, the patches around it in cyclic order, one per face
    /// around the chain (`topology.rs` says how it is found on tet faces;
    /// empty only where a cell fills two wedges at every chain edge).
    pub chain_patches: Vec<Vec<u32>>,
    /// Corner vertices.
    pub corners: Vec<u32>,
    /// Shells as lists of half-patches (`2p` positive side of patch `p`, `2p + 1` negative).
    pub shells: Vec<Vec<u32>>,
    /// Cells.
    pub cells: Vec<CellInfo>,
    /// Connected components of the network.
    pub components: usize,
    /// Tets with a part of the network.
    pub active_tets: usize,
    /// How cells were identified: "raytrace" or "grouping".
    pub cells_method: &'static str,
    /// Seconds per stage.
    pub seconds: Vec<(&'static str, f64)>,
}

impl Network {
    /// Number of polygons.
    pub fn num_faces(&self) -> usize {
        self.face_label.len()
    }

    /// Vertices of polygon `f`.
    pub fn face(&self, f: usize) -> &[u32] {
        &self.face_verts[self.face_start[f] as usize..self.face_start[f + 1] as usize]
    }

    /// The counts the reference reports, by name.
    pub fn counts(&self) -> Vec<(&'static str, usize)> {
        named_counts([
            self.points.len(),
            self.num_faces(),
            self.edges.len(),
            self.patches.len(),
            self.chains.len(),
            self.corners.len(),
            self.shells.len(),
            self.cells.len(),
            self.components,
            self.active_tets,
        ])
    }
}

/// The reference's counts in its order, named (one list for the in-memory
/// network and the streamed summary).
pub(crate) fn named_counts(c: [usize; 10]) -> Vec<(&'static str, usize)> {
    const NAMES: [&str; 10] =
        ["vertices", "faces", "edges", "patches", "chains", "corners", "shells", "cells", "components", "active_tets"];
    NAMES.into_iter().zip(c).collect()
}

/// Whether ray shooting is sure to apply: a box grid and no network vertex
/// at a grid vertex (IA: no value is exactly 0; MI: no tie for the maximum).
fn ray_applies(grid: &Grid, values: &[f64], k: usize, mode: Mode) -> bool {
    if !matches!(grid, Grid::Box(_)) {
        return false;
    }
    match mode {
        Mode::Ia => values.iter().all(|&x| x != 0.0),
        Mode::Mi => values.chunks_exact(k).all(|r| {
            // One pass: the running maximum and whether it is tied.
            let (mut m, mut tied) = (r[0], false);
            for &x in &r[1..] {
                if x > m {
                    (m, tied) = (x, false);
                } else if x == m {
                    tied = true;
                }
            }
            !tied
        }),
    }
}

/// Computes the IA or MI network of `k` functions given by their values at
/// the grid vertices (`values[v * k + f]`), on the current rayon pool.
pub fn compute(grid: &Grid, values: &[f64], k: usize, options: &NetworkOptions) -> Result<Network, NetworkError> {
    let t0 = Instant::now();
    let n = grid.num_vertices();
    if k == 0 {
        return Err(NetworkError::NoFunctions);
    }
    if k > u16::MAX as usize - 1 {
        return Err(NetworkError::TooManyFunctions(k));
    }
    if values.len() != n * k {
        return Err(NetworkError::ValueCount { expected: n * k, vertices: n, functions: k, got: values.len() });
    }
    // One branch-free pass (it vectorises) for NaN/inf and IA zeros; the
    // position of a bad value is searched only when there is one.
    let (mut nonfinite, mut zero) = (false, false);
    for chunk in values.chunks(4096) {
        for &x in chunk {
            nonfinite |= !x.is_finite();
            zero |= x == 0.0;
        }
    }
    if nonfinite {
        let i = values.iter().position(|x| !x.is_finite()).unwrap_or(0);
        return Err(NetworkError::NonFinite { vertex: i / k, function: i % k, value: values[i] });
    }
    let ray = options.raytrace
        && !options.volumes
        && match options.mode {
            Mode::Ia => !zero && matches!(grid, Grid::Box(_)),
            Mode::Mi => ray_applies(grid, values, k, options.mode),
        };
    let t_check = Instant::now();
    let ctx = block::Ctx {
        grid,
        values,
        k,
        mode: options.mode,
        options: {
            let mut o = Options::with_float(options.float);
            o.lookup = options.lookup;
            o
        },
        volumes: options.volumes,
        grouping: !ray,
        sparse: None,
    };
    let blocks = grid.blocks(options.block);
    let done = std::sync::atomic::AtomicUsize::new(0);
    // Blocks run in windows and merge in block order as each window
    // completes: only a window's block outputs live beside the merged network.
    let window = 16 * rayon::current_num_threads().max(1);
    let mut merger = merge::Merger::new(options.mode);
    let mut merge_time = std::time::Duration::ZERO;
    for chunk in blocks.chunks(window) {
        let outs: Vec<block::BlockOut> = chunk
            .par_iter()
            .map_init(block::Worker::default, |w, b| {
                if options.cancelled() {
                    return Err(NetworkError::Cancelled);
                }
                let out = w.run(&ctx, b);
                if let Some(p) = &options.progress {
                    p.tick(&done, blocks.len());
                }
                out
            })
            .collect::<Result<_, _>>()?;
        let t = Instant::now();
        for out in outs {
            merger.add(out);
        }
        merge_time += t.elapsed();
    }
    let t = Instant::now();
    let mut m = merger.finish();
    merge_time += t.elapsed();
    let t1 = Instant::now() - merge_time;
    let t_merged = Instant::now();
    canon::canonicalize_merged(&mut m);
    let t2 = Instant::now();
    let mut topo = topology::topology(&mut m, (options.raytrace && !options.volumes).then_some(&ctx));
    canon::canonicalize_topology(&mut topo);
    label_free_cells(&mut topo.cells, options.mode, &values[..k]);
    let t3 = Instant::now();
    if !ctx.grouping && topo.cells_method != "raytrace" {
        // Cannot happen when the preconditions hold; never answer without cells.
        let mut o = options.clone();
        o.raytrace = false;
        return compute(grid, values, k, &o);
    }
    let mut net = assemble(options.mode, k, m, topo, [t1 - t_check, t_merged - t1, t3 - t2]);
    // Input checks and canonical numbering are neither extraction nor
    // topology: report them apart (`septa bench grid` sums tets + merge).
    net.seconds.insert(0, ("check", (t_check - t0).as_secs_f64()));
    net.seconds.insert(3, ("canon", (t2 - t_merged).as_secs_f64()));
    Ok(net)
}

/// A cell bounded by no face (no network at all) takes the label of the
/// values `row` of one grid vertex (IA sign bits; MI argmax).
pub(crate) fn label_free_cells(cells: &mut [CellInfo], mode: Mode, row: &[f64]) {
    let k = row.len();
    for cell in cells.iter_mut().filter(|c| c.label.is_empty()) {
        cell.label = match mode {
            Mode::Ia => {
                let mut l: SmallVec<[u64; 2]> = SmallVec::from_elem(0, k.div_ceil(64));
                for (f, &x) in row.iter().enumerate() {
                    if x > 0.0 {
                        l[f / 64] |= 1 << (f % 64);
                    }
                }
                l
            }
            Mode::Mi => {
                let m = (0..k).fold(0, |b, f| if row[f] > row[b] { f } else { b });
                SmallVec::from_elem(m as u64, 1)
            }
        };
    }
}

/// The network from merged polygons and their topology; `stages` are the
/// durations of the tets, merge and topology stages.
pub(crate) fn assemble(
    mode: Mode,
    k: usize,
    m: merge::Merged,
    topo: topology::Topology,
    stages: [std::time::Duration; 3],
) -> Network {
    Network {
        mode,
        functions: k,
        points: m.points,
        keys: m.keys,
        face_start: m.face_start,
        face_verts: m.face_verts,
        face_label: m.face_label,
        face_cells: topo.face_cells,
        face_patch: topo.face_patch,
        edges: topo.edges,
        patches: topo.patches,
        chains: topo.chains,
        chain_patches: topo.chain_patches,
        corners: topo.corners,
        shells: topo.shells,
        cells: topo.cells,
        components: topo.components,
        active_tets: m.active_tets,
        cells_method: topo.cells_method,
        seconds: vec![
            ("tets", stages[0].as_secs_f64()),
            ("merge", stages[1].as_secs_f64()),
            ("topology", stages[2].as_secs_f64()),
        ],
    }
}
