//! The in-order half of a stream (docs/sparse.md): block results, in the plan's
//! order, get their vertices' streamed ids (`numbering.rs`), go to the sink,
//! and, for topology, their summaries to the assembly (`assembly.rs`);
//! [`StreamFeeder::finish`] shoots the rays (`rerun.rs`).
//!
//! [`stream_sparse`](crate::network::stream_sparse) and
//! [`stream_topology`](crate::network::stream_topology) compute the blocks on
//! this machine and feed them here; a caller whose blocks were computed
//! elsewhere (on a Dask cluster, as bytes: [`BlockResult::from_bytes`])
//! feeds them the same way, so the stream and its topology are the same
//! wherever the blocks ran.

use super::assembly::{Assembler, NetworkSummary};
use super::numbering::VertexNumbering;
use super::sink::{StreamBlock, StreamError, StreamSink, StreamStats};
use super::summary::BlockSummary;
use crate::grid::{BoxGrid, Grid};
use crate::network::block::PointValues;
use crate::network::field::BoundedField;
use crate::network::sparse::{block_at, check_functions, ctx, cubes, BlockResult, JobKey, SparsePlan};
use crate::network::topology::ray_cells;
use crate::network::{NetworkError, NetworkOptions};

/// Feeds block results to a sink in plan order (module doc).
pub struct StreamFeeder<'a> {
    grid: BoxGrid,
    functions: Box<dyn BoundedField + Send + 'a>,
    options: NetworkOptions,
    job: JobKey,
    kept: Vec<usize>,
    next: usize,
    numbering: VertexNumbering,
    assembler: Option<Assembler>,
    ids: Vec<u32>,
    pieces: Vec<u32>,
    stats: StreamStats,
}

/// The summary of a block (an error naming the block if it has network
/// faces lying in tet faces, which only the in-memory merge pairs yet).
pub(crate) fn summary_of(r: &BlockResult) -> Result<BlockSummary, NetworkError> {
    super::summary::summarize(&r.out).map_err(|_| face_on_tet_face(r))
}

/// Values exactly 0 (IA) or tied (MI) at grid vertices stream like any
/// others; a network face lying in a tet face (a function vanishing on a
/// whole tet face, two materials tied on one) does not yet.
fn face_on_tet_face(r: &BlockResult) -> NetworkError {
    let face = match r.out.halves.first() {
        Some(h) => format!(" (grid vertices {:?}, function {})", h.face, h.zero),
        None => String::new(),
    };
    NetworkError::BlockResults(format!(
        "block {}: a network face lies in a tet face{face}: a function vanishes on a whole tet face \
         (IA) or two materials tie on one (MI); streaming cannot pair such faces across blocks yet: \
         run in memory (without --stream), which handles them",
        r.index
    ))
}

impl<'a> StreamFeeder<'a> {
    /// A feeder for the blocks `plan.kept` of a sparse job
    /// ([`plan_sparse`](crate::network::plan_sparse) on the same grid, functions and
    /// options); with `topology`, the assembly runs too.
    pub fn new<F: BoundedField + Send + 'a>(
        grid: &BoxGrid,
        functions: F,
        options: &NetworkOptions,
        plan: &SparsePlan,
        topology: bool,
    ) -> Result<StreamFeeder<'a>, NetworkError> {
        let k = functions.functions();
        check_functions(k)?;
        if plan.dense {
            return Err(NetworkError::BlockResults(
                "the plan asks for the dense path (volumes or cell grouping): nothing to stream".into(),
            ));
        }
        let numbering = VertexNumbering::new(grid);
        let assembler = topology.then(|| Assembler::new(options.mode, k, numbering.plane()));
        let stats = StreamStats {
            blocks: plan.blocks,
            sampled: plan.kept.len(),
            skipped: plan.blocks - plan.kept.len(),
            ..StreamStats::default()
        };
        Ok(StreamFeeder {
            grid: grid.clone(),
            functions: Box::new(functions),
            options: options.clone(),
            job: JobKey::of(grid, k, options),
            kept: plan.kept.clone(),
            next: 0,
            numbering,
            assembler,
            ids: Vec::new(),
            pieces: Vec::new(),
            stats,
        })
    }

    /// Feeds the next block's result (it must be block `plan.kept[i]` for
    /// the `i`-th call, of this job) to `sink`, then drops it.
    pub fn feed<S: StreamSink + ?Sized>(&mut self, result: BlockResult, sink: &mut S) -> Result<(), StreamError> {
        let summary = match &self.assembler {
            Some(_) => Some(summary_of(&result)?),
            None => None,
        };
        self.feed_with(result, summary, sink)
    }

    /// Feeds several consecutive block results, making their summaries in
    /// parallel on the current rayon pool first (the assembly itself is in
    /// order): what a client receiving batches from many workers should call.
    pub fn feed_all<S: StreamSink + ?Sized>(
        &mut self,
        results: Vec<BlockResult>,
        sink: &mut S,
    ) -> Result<(), StreamError> {
        use rayon::prelude::*;
        let topology = self.assembler.is_some();
        let summaries: Vec<Option<BlockSummary>> = results
            .par_iter()
            .map(|r| if topology { summary_of(r).map(Some) } else { Ok(None) })
            .collect::<Result<_, _>>()?;
        for (r, s) in results.into_iter().zip(summaries) {
            self.feed_with(r, s, sink)?;
        }
        Ok(())
    }

    /// [`StreamFeeder::feed`] with the block's summary already made (in parallel).
    pub(crate) fn feed_with<S: StreamSink + ?Sized>(
        &mut self,
        r: BlockResult,
        summary: Option<BlockSummary>,
        sink: &mut S,
    ) -> Result<(), StreamError> {
        if !r.job.same(&self.job) {
            return Err(NetworkError::BlockResults(format!(
                "block {} belongs to another job ({:?}, expected {:?})",
                r.index, r.job, self.job
            ))
            .into());
        }
        match self.kept.get(self.next) {
            Some(&i) if i == r.index => self.next += 1,
            want => {
                return Err(NetworkError::BlockResults(format!(
                    "block {} fed out of order (expected {})",
                    r.index,
                    want.map_or("no more blocks".to_string(), |i| format!("block {i}"))
                ))
                .into())
            }
        }
        if !r.out.halves.is_empty() {
            return Err(face_on_tet_face(&r).into());
        }
        let b = block_at(&self.grid, self.options.block, r.index).expect("a planned block exists");
        let (lo, hi) = cubes(&b);
        let out = &r.out;
        let stats = &mut self.stats;
        stats.sampled_vertices += r.sampled_vertices;
        stats.active += (out.active_tets > 0) as usize;
        stats.active_tets += out.active_tets;
        stats.faces += out.poly_label.len();
        stats.block_vertices += out.keys.len();
        let base = self.assembler.as_ref().map_or(0, |a| a.pieces());
        let vertex_piece: &[u32] = summary.as_ref().map_or(&[], |s| &s.vertex_piece);
        // Shared vertices seen before join components, once the block's
        // pieces exist in the assembly.
        let mut repeats: Vec<(u32, u32)> = Vec::new();
        self.numbering
            .block(
                lo[0],
                &out.keys,
                &out.shared,
                &out.poly_verts,
                &mut self.ids,
                |v| vertex_piece.get(v as usize).map_or(0, |p| base + p),
                |first, v| {
                    if let Some(p) = vertex_piece.get(v as usize) {
                        repeats.push((first, base + p));
                    }
                },
            )
            .map_err(NetworkError::BlockResults)?;
        self.pieces.clear();
        if let (Some(a), Some(s)) = (self.assembler.as_mut(), &summary) {
            a.add(r.index, lo[0], out, s, &self.ids)?;
            for (x, y) in repeats {
                a.same_vertex(x, y);
            }
            self.pieces.extend(s.poly_piece.iter().map(|&p| base + p));
        }
        sink.block(&StreamBlock {
            index: r.index,
            lo,
            hi,
            keys: &out.keys,
            shared: &out.shared,
            points: &out.points,
            poly_start: &out.poly_start,
            poly_verts: &out.poly_verts,
            poly_label: &out.poly_label,
            vertex_ids: &self.ids,
            poly_piece: &self.pieces,
            active_tets: out.active_tets,
        })?;
        Ok(())
    }

    /// After the last block: the stream's statistics and, with topology,
    /// the network's topology (cells by ray shooting, running the few
    /// blocks a ray looks at again on the current rayon pool's thread).
    pub fn finish(self) -> Result<(StreamStats, Option<NetworkSummary>), StreamError> {
        if self.next != self.kept.len() {
            return Err(NetworkError::BlockResults(format!(
                "{} of the plan's {} blocks fed",
                self.next,
                self.kept.len()
            ))
            .into());
        }
        let mut stats = self.stats;
        stats.vertices = self.numbering.count();
        stats.peak_shared_keys = self.numbering.peak();
        let Some(mut asm) = self.assembler else { return Ok((stats, None)) };
        stats.peak_open = asm.peak_open;
        let (grid, functions, options) = (&self.grid, &*self.functions as &dyn BoundedField, &self.options);
        let g = Grid::Box(grid.clone());
        let pv = PointValues { grid, functions };
        let ctx = ctx(&g, functions.functions(), options, &pv);
        let row0: Vec<f64> = (0..functions.functions()).map(|f| functions.value(f, grid.vertex(0))).collect();
        let block_pieces = std::mem::take(&mut asm.block_pieces);
        let mut reruns = 0;
        let summary = asm.finish(
            stats.vertices as usize,
            |a| {
                let mut index = super::rerun::RerunIndex::new(grid, &g, functions, options, &block_pieces, a);
                let r = ray_cells(&ctx, &mut index, &a.starts, a.num_shells);
                reruns = index.reruns;
                r
            },
            &row0,
        )?;
        stats.reruns = reruns;
        Ok((stats, Some(summary)))
    }
}
