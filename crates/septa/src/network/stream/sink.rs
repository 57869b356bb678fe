//! What a stream hands out: finished blocks ([`StreamBlock`]) to a
//! [`StreamSink`], and what a streamed run reports ([`StreamStats`]).

use crate::network::{NetworkError, VKey};

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
    /// Per polygon: its patch piece ([`stream_topology`](crate::network::stream_topology) only, else empty);
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
