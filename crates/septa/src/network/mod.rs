//! Surface networks on tetrahedral grids (Du et al. 2022, Sec. 3, 6, 7):
//! per-tet complexes assembled into polygons with global plane-based keys,
//! then patches, chains, corners, shells and cells.
//!
//! The grid is processed in blocks (in parallel with rayon); every vertex
//! key names a grid element and functions (Sec. 5.1), so duplicates across
//! tets and blocks unify exactly and independently of processing order.
//! Regions are joined across tet faces by (face, region label) keys, and
//! shells by wedges around edges, so block summaries merge in any order.

mod block;
mod dense;
pub mod embedding;
mod field;
mod sparse;
mod stream;
mod topology;

pub use dense::compute;
pub use field::{BoundedField, Field};
pub use sparse::continuation::{
    compute_continuation, continuation_block, continuation_seeds, finish_continuation, ContinuationStats, Seeds,
};
pub use sparse::wire::{WireError, VERSION as WIRE_VERSION};
pub use sparse::{compute_sparse, finish_sparse, plan_sparse, run_block, BlockResult, JobKey, SparsePlan, SparseStats};
pub use stream::{
    stream_sparse, stream_topology, NetworkSummary, StreamBlock, StreamError, StreamFeeder, StreamSink, StreamStats,
};

use crate::Progress;
use smallvec::SmallVec;

use crate::complex::Mode;

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
    /// A block index that the job's grid does not have (a caller that
    /// hands out block indices may branch on it).
    #[error("block results: block {index} does not exist (the grid has {blocks} blocks)")]
    NoSuchBlock {
        /// The index asked for.
        index: usize,
        /// Blocks in the grid.
        blocks: usize,
    },
    /// A block result computed for another job (grid, functions, mode or
    /// options differ): `job` and `expected` describe the two jobs.
    #[error("block results: block {index} belongs to another job ({job}, expected {expected})")]
    ForeignBlock {
        /// The block.
        index: usize,
        /// The job the result was computed for.
        job: String,
        /// This job.
        expected: String,
    },
    /// Block results handed to [`finish_sparse`] are not the planned blocks,
    /// once each: `missing` lists (up to five of) the planned blocks without
    /// a result, so a caller can run them again.
    #[error("block results: {given} block results for the {planned} planned blocks (missing e.g. {missing:?}, or a block given twice or not planned)")]
    BlockCount {
        /// Results given.
        given: usize,
        /// Blocks planned.
        planned: usize,
        /// Up to five planned blocks without a result.
        missing: Vec<usize>,
    },
    /// A stream was asked for a plan that takes the dense path (cell
    /// volumes or cell grouping asked for): there is nothing to stream.
    #[error("block results: the plan asks for the dense path (volumes or cell grouping): nothing to stream")]
    DensePlanStreamed,
    /// A stream was fed block `index` where the plan's next block is
    /// `expected` (`None`: every planned block was fed already).
    #[error("block results: block {index} fed out of order (expected {})", expected_block(.expected))]
    BlockOutOfOrder {
        /// The block fed.
        index: usize,
        /// The plan's next block.
        expected: Option<usize>,
    },
    /// A stream was finished after `fed` of its `planned` blocks.
    #[error("block results: {fed} of the plan's {planned} blocks fed")]
    BlocksMissing {
        /// Blocks fed.
        fed: usize,
        /// Blocks planned.
        planned: usize,
    },
    /// A stream numbers its vertices in 32 bits.
    #[error("block results: more than 2^32 - 1 network vertices")]
    TooManyVertices,
    /// The streamed topology numbers its polygons in 31 bits.
    #[error("block results: more than 2^31 polygons: too many for the streamed topology")]
    TooManyPolygons,
    /// IA stream: a network face in a tet face was found by the block on
    /// one side only (the block across it was not sampled), so its sides
    /// cannot be joined; `face` holds the tet face's grid vertices.
    #[error(
        "block results: the network face lying in the tet face at grid vertices {face:?} was found from one side \
         only (the block across it was not sampled): run in memory (without --stream)"
    )]
    FaceFromOneSide {
        /// Grid vertices of the tet face.
        face: [u32; 3],
    },
    /// Streamed topology: a ray ran along the network, so cells cannot be
    /// found by ray shooting (Sec. 7.1).
    #[error(
        "block results: cells could not be found by ray shooting (a ray running along the network): stream the \
         polygons only, or run in memory (cell grouping)"
    )]
    RayAlongNetwork,
    /// Streamed topology: sheets of one component touch only at points
    /// where their shells cannot be linked, so cells cannot be found by ray
    /// shooting; in-memory runs group cells there.
    #[error(
        "block results: cells could not be found by ray shooting: the surfaces of {} {labels:?} touch only at \
         points{}, {}: stream the polygons only (--polygons-only), or run in memory (without --stream), which \
         groups cells there",
        labels_word(*.mode), contact_text(.at), touch_reason(*.cracked)
    )]
    SheetsTouchAtPoints {
        /// IA (labels are functions) or MI (labels are materials).
        mode: Mode,
        /// The functions or materials whose surfaces touch (sorted).
        labels: Vec<u16>,
        /// A point where they touch, when one was found.
        at: Option<[f64; 3]>,
        /// Whether the network is not closed near them (a crack: an edge of
        /// one face off the grid boundary, which the point-only naming of
        /// tied vertices rules out) rather than unreadable around the point.
        cracked: bool,
    },
    /// Continuation: the caller's field failed; its own message (a Python
    /// function's exception, for example).
    #[error("continuation: {0}")]
    FieldFailed(String),
    /// Continuation: the field gave a wrong number of values.
    #[error("continuation: the field returned {values} values for {points} points x {functions} functions")]
    FieldValues {
        /// Values returned.
        values: usize,
        /// Points asked for.
        points: usize,
        /// Functions of the field.
        functions: usize,
    },
    /// Continuation: a seed point outside the grid's box.
    #[error("continuation: seed point {seed} {point:?} is outside the grid")]
    SeedOutside {
        /// The seed's index.
        seed: usize,
        /// The point.
        point: [f64; 3],
    },
    /// The per-tet construction failed (an internal error: inputs are
    /// checked before; Python raises it as `RuntimeError`).
    #[error("tet {tet}: {source}")]
    Tet {
        /// Tet id.
        tet: usize,
        /// What failed.
        source: crate::complex::BuildError,
    },
}

fn expected_block(e: &Option<usize>) -> String {
    e.map_or("no more blocks".to_string(), |i| format!("block {i}"))
}

fn labels_word(mode: Mode) -> &'static str {
    match mode {
        Mode::Ia => "functions",
        Mode::Mi => "materials",
    }
}

fn contact_text(at: &Option<[f64; 3]>) -> String {
    at.map_or(String::new(), |q| format!(", e.g. at ({}, {}, {})", q[0], q[1], q[2]))
}

fn touch_reason(cracked: bool) -> &'static str {
    if cracked {
        "and the network is not closed near them (an edge of one face off the grid boundary; vertex keys name \
         each point by the point alone, so this is a defect: please report the input)"
    } else {
        "and the shells meeting there could not be read from the tets around them"
    }
}

impl NetworkError {
    /// Whether this is a failure of the library itself, which checked input
    /// cannot cause (front ends report it as a bug, not as bad input).
    pub fn is_internal(&self) -> bool {
        matches!(self, NetworkError::Tet { .. })
    }
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
    /// MI: a function is inactive in a tet also when the average of the
    /// functions maximal at some corner is proven above it at all four
    /// corners (complex/dominated.rs), not only when one function is.
    /// Label indicators need it: the materials absent from a tet tie at 0
    /// and no single material dominates them. The output is the same either
    /// way (a function that never wins changes no complex); `false` only
    /// for the test that shows it. Default value: `true`.
    #[doc(hidden)]
    pub mi_average_domination: bool,
}

impl NetworkOptions {
    /// Whether [`NetworkOptions::cancel`] has been set.
    pub(crate) fn cancelled(&self) -> bool {
        self.cancel.as_ref().is_some_and(|c| c.load(std::sync::atomic::Ordering::Relaxed))
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
            mi_average_domination: true,
        }
    }
}

/// How the cells of a network were identified (Du et al. Sec. 7.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CellMethod {
    /// Topological ray shooting from each component (the default).
    Raytrace,
    /// Regions joined across every tet face (when ray shooting declines,
    /// cell volumes are asked for, or ray shooting is turned off).
    Grouping,
}

impl CellMethod {
    /// `"raytrace"` or `"grouping"`, as written in `network.json`.
    pub fn as_str(self) -> &'static str {
        match self {
            CellMethod::Raytrace => "raytrace",
            CellMethod::Grouping => "grouping",
        }
    }
}

impl std::fmt::Display for CellMethod {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl PartialEq<&str> for CellMethod {
    fn eq(&self, other: &&str) -> bool {
        self.as_str() == *other
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

impl CellInfo {
    /// IA: whether function `f` is positive on the cell (its sign bit).
    pub fn positive(&self, f: usize) -> bool {
        sign_bit(&self.label, f)
    }
}

/// Bit `f` of an IA sign label (set iff function `f` is positive); the one
/// reader of the label layout.
pub fn sign_bit(label: &[u64], f: usize) -> bool {
    label.get(f / 64).is_some_and(|w| w >> (f % 64) & 1 == 1)
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
    /// How cells were identified.
    pub cells_method: CellMethod,
    /// Seconds per stage.
    pub seconds: Vec<(&'static str, f64)>,
    /// What the certification of the written doubles found and changed
    /// (`septa::mesh::certify_network`; `None`: not certified).
    pub embedding: Option<embedding::Embedding>,
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
