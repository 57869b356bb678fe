//! Streaming: outputs written to disk block by block for networks larger
//! than memory.
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
//! Network faces lying in tet faces (a function vanishing on a whole tet
//! face, two materials tied on one) are paired inside a block and across
//! block boundaries by the merge's rules (`halves.rs`). Cells come from ray
//! shooting. Sheets touching only at points (tangent spheres) have their
//! shells linked at the contact points, found by running again the blocks
//! that hold them (`rerun.rs`, `topology/contact.rs`). A network that is not
//! closed near such points (a crack: one point under two keys, which the
//! point-only naming of tied vertices, complex/ties.rs, rules out; the
//! in-memory path would group cells there) stops the run with
//! [`NetworkError::SheetsTouchAtPoints`] rather than guess.

mod assembly;
mod feeder;
mod halves;
mod numbering;
mod prepare;
mod rerun;
mod run;
mod sink;
mod summary;
mod summary_result;

pub use feeder::StreamFeeder;
pub use run::{stream_sparse, stream_topology};
pub use sink::{StreamBlock, StreamError, StreamSink, StreamStats};
pub use summary_result::NetworkSummary;
