//! A block's output made ready for the in-order half of a stream: its
//! halves paired inside the block (`halves.rs`) and, for topology, its
//! summary (`summary.rs`). A pure function of the block, so the feeder
//! (`feeder.rs`) and the blocks re-run for ray shooting (`rerun.rs`) get
//! the same.

use super::halves::{pair_in_block, OpenHalf};
use super::summary::{summarize, BlockSummary};
use crate::grid::BoxGrid;
use crate::network::sparse::{block_at, cubes, BlockResult};
use crate::network::{NetworkError, NetworkOptions};

/// A block's output made ready for the in-order half: its halves paired
/// inside the block (`halves.rs`) and, for topology, its summary. A pure
/// function of the block, made in parallel.
pub(crate) struct Prepared {
    /// Halves left open at the block's boundary.
    pub open: Vec<OpenHalf>,
    pub summary: Option<BlockSummary>,
}

/// Prepares block result `r` of a job on `grid` with `options` (see [`Prepared`]).
pub(crate) fn prepare(
    grid: &BoxGrid,
    options: &NetworkOptions,
    r: &mut BlockResult,
    topology: bool,
) -> Result<Prepared, NetworkError> {
    let b = block_at(grid, options.block, r.index).ok_or_else(|| {
        let size = options.block.max(1);
        NetworkError::NoSuchBlock { index: r.index, blocks: grid.res.iter().map(|&n| n.div_ceil(size)).product() }
    })?;
    let (lo, hi) = cubes(&b);
    let open = pair_in_block(&mut r.out, options.mode, grid, lo, hi);
    let summary = topology.then(|| summarize(grid, &r.out, &open));
    Ok(Prepared { open, summary })
}
