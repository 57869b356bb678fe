//! What a streamed run with topology returns: the network's topology
//! (Du et al. Sec. 7) without its polygons, which went to the sink; made by
//! the assembly (`assembly.rs`).

use crate::complex::Mode;
use crate::network::{named_counts, CellInfo, Patch};

/// The topology of a streamed network, without its polygons (they went to
/// the stream's sink, each with its patch piece: [`NetworkSummary::piece_patch`]
/// and [`NetworkSummary::piece_cells`] map pieces to patches and cells).
#[derive(Clone, Debug)]
pub struct NetworkSummary {
    /// IA or MI.
    pub mode: Mode,
    /// Number of functions.
    pub functions: usize,
    /// Network vertices (numbered as streamed).
    pub vertices: usize,
    /// Polygons.
    pub faces: usize,
    /// Network edges.
    pub edges: usize,
    /// Patches, numbered by their first piece.
    pub patches: Vec<Patch>,
    /// Chains as paths of streamed vertex ids (a closed chain repeats its first vertex).
    pub chains: Vec<Vec<u32>>,
    /// Per chain, the patches around it in cyclic order, from the wedges of
    /// a per-tet complex at one of its edges (empty if the chain has none inside a tet).
    pub chain_patches: Vec<Vec<u32>>,
    /// Corner vertices (streamed ids, ascending).
    pub corners: Vec<u32>,
    /// Shells as lists of half-patches (`2p` positive side of patch `p`, `2p + 1` negative).
    pub shells: Vec<Vec<u32>>,
    /// Cells (volumes are not computed: 0).
    pub cells: Vec<CellInfo>,
    /// Connected components of the network.
    pub components: usize,
    /// Tets with a part of the network.
    pub active_tets: usize,
    /// Patch of each patch piece.
    pub piece_patch: Vec<u32>,
    /// `[cell on the positive side, cell on the negative side]` of each patch piece.
    pub piece_cells: Vec<[u32; 2]>,
}

impl NetworkSummary {
    /// The counts the reference reports, by name (as [`Network::counts`](crate::network::Network::counts)).
    pub fn counts(&self) -> Vec<(&'static str, usize)> {
        named_counts([
            self.vertices,
            self.faces,
            self.edges,
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
