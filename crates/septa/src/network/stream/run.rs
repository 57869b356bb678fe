//! The stream's drivers: blocks computed a window at a time and handed
//! in order to the feeder, which numbers, summarises and sinks them.

use std::sync::atomic::AtomicUsize;
use std::sync::Mutex;

use rayon::prelude::*;

use super::feeder::StreamFeeder;
use super::prepare::{prepare, Prepared};
use super::sink::{StreamError, StreamSink, StreamStats};
use super::summary_result::NetworkSummary;
use crate::grid::{BoxGrid, Grid};
use crate::network::block::Worker;
use crate::network::field::{BoundedField, ByRef};
use crate::network::sparse::{check_functions, plan_sparse, run_block_with, BlockResult};
use crate::network::{NetworkError, NetworkOptions};

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
/// [`compute_sparse`](crate::network::compute_sparse) on the same input (its
/// network's polygons are these, merged by key and renumbered).
pub fn stream_sparse<S: StreamSink + Send, F: BoundedField + ?Sized>(
    grid: &BoxGrid,
    functions: &F,
    options: &NetworkOptions,
    window: usize,
    sink: &mut S,
) -> Result<StreamStats, StreamError> {
    Ok(drive(grid, &ByRef(functions), options, window, sink, false)?.0)
}

/// [`stream_sparse`] plus the topology, assembled from block summaries
/// while the polygons stream (module doc): memory follows the blocks in
/// flight, the blocks' boundaries and the number of patch pieces, never the
/// polygons. Its counts, patches, shells and cells are those of
/// [`compute_sparse`](crate::network::compute_sparse) up to numbering (tested face by
/// face); cells come from ray shooting, so a network whose pieces meet only
/// at points is refused (the in-memory path groups cells there).
pub fn stream_topology<S: StreamSink + Send, F: BoundedField + ?Sized>(
    grid: &BoxGrid,
    functions: &F,
    options: &NetworkOptions,
    window: usize,
    sink: &mut S,
) -> Result<(StreamStats, NetworkSummary), StreamError> {
    let (stats, summary) = drive(grid, &ByRef(functions), options, window, sink, true)?;
    Ok((stats, summary.expect("topology was asked for")))
}

/// Runs the kept blocks a window at a time and feeds them in order to a
/// [`StreamFeeder`] (summaries are made in the parallel part).
fn drive<S: StreamSink + Send>(
    grid: &BoxGrid,
    functions: &dyn BoundedField,
    options: &NetworkOptions,
    window: usize,
    sink: &mut S,
    topology: bool,
) -> Result<(StreamStats, Option<NetworkSummary>), StreamError> {
    check_functions(functions.functions())?;
    let mut o = options.clone();
    o.volumes = false;
    o.raytrace = true;
    let plan = plan_sparse(grid, functions, &o)?;
    let window = if window == 0 { 4 * rayon::current_num_threads() } else { window };
    let mut feeder = StreamFeeder::new(grid, ByRef(functions), &o, &plan, topology)?;
    let g = Grid::Box(grid.clone());
    let pool: Mutex<Vec<Worker>> = Mutex::new(Vec::new());
    let done = AtomicUsize::new(0);
    let run_window = |ids: &[usize]| -> Result<Vec<(BlockResult, Prepared)>, NetworkError> {
        ids.par_iter()
            .map_init(
                || Lease { worker: Some(pool.lock().ok().and_then(|mut p| p.pop()).unwrap_or_default()), pool: &pool },
                |lease, &i| {
                    if o.cancelled() {
                        return Err(NetworkError::Cancelled);
                    }
                    let w = lease.worker.as_mut().expect("a leased worker");
                    let mut r = run_block_with(w, &g, grid, functions, &o, i)?;
                    // Halves are paired inside the block and summaries made
                    // here, in parallel; only their assembly runs in block order.
                    let summary = prepare(grid, &o, &mut r, topology)?;
                    if let Some(p) = &o.progress {
                        p.tick(&done, plan.kept.len());
                    }
                    Ok((r, summary))
                },
            )
            .collect()
    };
    // Window w + 1 is computed while window w goes to the sink.
    let mut pending: Option<Vec<(BlockResult, Prepared)>> = None;
    let mut feed = |rs: Vec<(BlockResult, Prepared)>, sink: &mut S| -> Result<(), StreamError> {
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
