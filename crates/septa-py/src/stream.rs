//! `septa.stream_ply`: the polygons of a sparse job streamed block by block
//! into one PLY (or, for a path ending in .vtu, one VTK file) in bounded memory (docs/sparse.md: networks larger than memory),
//! with the topology assembled from block summaries on the way (written to
//! `<path>.topology.json`, as `septa ia --stream` does).
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

use crate::Failure;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use rayon::prelude::*;
use septa::io::PlyStreamStats;
use septa::io::StreamFile;
use septa::network::{stream_sparse, stream_topology, StreamFeeder, StreamStats};
use septa::network::{BlockResult, NetworkSummary, SparsePlan};

use crate::InputError;

/// Streams job `job` (the JSON of `septa.distributed.job_spec`) to the PLY
/// `path`; returns a summary dict. `progress(done, total)` is called as
/// blocks finish.
#[pyfunction]
#[pyo3(signature = (job, path, window = 0, triangles = false, threads = None, topology = true, progress = None))]
#[allow(clippy::too_many_arguments)]
pub fn stream_ply<'py>(
    py: Python<'py>,
    job: &str,
    path: &str,
    window: usize,
    triangles: bool,
    threads: Option<usize>,
    topology: bool,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let progress = progress.map(crate::network::py_progress);
    let cancel = Arc::new(AtomicBool::new(false));
    type Out = (StreamStats, PlyStreamStats, Option<NetworkSummary>);
    let topo_path = Path::new(path).with_extension("topology.json");
    let r: Result<Out, Failure> = crate::interrupt::run_interruptible(py, &cancel, || {
        let mut j = crate::distributed::parse_job(job)?;
        j.options.cancel = Some(cancel.clone());
        j.options.progress = progress;
        let run = || -> Result<Out, Failure> {
            // (its errors name the file)
            let mut sink = StreamFile::create(Path::new(path), &j.grid, j.options.mode, j.functions.len(), triangles)
                .map_err(|e| e.to_string())?;
            let (stats, summary) = if topology {
                let (s, t) =
                    stream_topology(&j.grid, &j.functions, &j.options, window, &mut sink).map_err(crate::failure)?;
                (s, Some(t))
            } else {
                (stream_sparse(&j.grid, &j.functions, &j.options, window, &mut sink).map_err(crate::failure)?, None)
            };
            let ply = sink.finish_with(summary.as_ref()).map_err(|e| format!("{path}: {e}"))?;
            if let Some(t) = &summary {
                septa::io::write_summary_json(t, &topo_path, &[])
                    .map_err(|e| format!("{}: {e}", topo_path.display()))?;
            }
            Ok((stats, ply, summary))
        };
        crate::on_threads(threads, run)
    })?;
    let (stats, ply, summary) = r?;
    result_dict(py, path, &stats, &ply, summary.as_ref(), &topo_path)
}

/// The dict both ways of streaming return.
fn result_dict<'py>(
    py: Python<'py>,
    path: &str,
    stats: &StreamStats,
    ply: &PlyStreamStats,
    summary: Option<&NetworkSummary>,
    topo_path: &Path,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("path", path)?;
    d.set_item("faces", ply.polygons)?;
    d.set_item("ply_faces", ply.faces)?;
    d.set_item("vertices", ply.vertices)?;
    d.set_item("active_tets", stats.active_tets)?;
    let b = PyDict::new(py);
    b.set_item("total", stats.blocks)?;
    b.set_item("skipped", stats.skipped)?;
    b.set_item("sampled", stats.sampled)?;
    b.set_item("active", stats.active)?;
    d.set_item("blocks", b)?;
    if let Some(t) = summary {
        let c = PyDict::new(py);
        for (k, v) in t.counts() {
            c.set_item(k, v)?;
        }
        d.set_item("counts", c)?;
        d.set_item("topology", topo_path.display().to_string())?;
    }
    Ok(d)
}

/// StreamWriter(job, path, plan, triangles, topology)
/// --
///
/// The in-order half of a stream whose blocks are computed elsewhere (on a
/// Dask cluster: `septa.distributed.stream_ply`): `feed(results)` takes
/// block results as bytes (`sparse_blocks`), in the plan's order, numbers
/// their vertices, writes their polygons to the PLY `path` and assembles the
/// topology from their summaries; `finish()` shoots the rays, writes
/// `<path>.topology.json` and returns the same dict as `stream_ply`. Dropped
/// unfinished (an error, Ctrl-C), it leaves no file.
#[pyclass(module = "septa._septa")]
pub struct StreamWriter {
    state: Option<(StreamFeeder<'static>, StreamFile)>,
    path: String,
}

#[pymethods]
impl StreamWriter {
    #[new]
    fn new(job: &str, path: &str, plan: (usize, Vec<usize>, bool), triangles: bool, topology: bool) -> PyResult<Self> {
        let r = (|| -> Result<StreamWriter, String> {
            let j = crate::distributed::parse_job(job)?;
            let plan = SparsePlan { blocks: plan.0, kept: plan.1, dense: plan.2 };
            let feeder = StreamFeeder::new(&j.grid, j.functions.clone(), &j.options, &plan, topology)
                .map_err(|e| e.to_string())?;
            let sink = StreamFile::create(Path::new(path), &j.grid, j.options.mode, j.functions.len(), triangles)
                .map_err(|e| e.to_string())?;
            Ok(StreamWriter { state: Some((feeder, sink)), path: path.to_string() })
        })();
        r.map_err(InputError::new_err)
    }

    /// Feeds block results (bytes, in the plan's order).
    fn feed(&mut self, py: Python<'_>, results: Vec<Bound<'_, PyBytes>>) -> PyResult<()> {
        let slices: Vec<&[u8]> = results.iter().map(|b| b.as_bytes()).collect();
        let Some((feeder, sink)) = self.state.as_mut() else {
            return Err(InputError::new_err("the stream is finished"));
        };
        // Decoded and summarised in parallel here; only the assembly and
        // the file are in order (the client's share of a distributed stream).
        let r: Result<(), String> = py.detach(|| {
            let blocks = slices
                .par_iter()
                .enumerate()
                .map(|(i, b)| BlockResult::from_bytes(b).map_err(|e| format!("result {i}: {e}")))
                .collect::<Result<Vec<_>, _>>()?;
            feeder.feed_all(blocks, sink).map_err(|e| e.to_string())
        });
        if r.is_err() {
            self.state = None; // drops the sink: no file is left
        }
        r.map_err(InputError::new_err)
    }

    /// Finishes the stream (module doc) and returns its summary dict.
    fn finish<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let Some((feeder, sink)) = self.state.take() else {
            return Err(InputError::new_err("the stream is finished"));
        };
        let path = self.path.clone();
        let topo_path = Path::new(&path).with_extension("topology.json");
        type Out = (StreamStats, PlyStreamStats, Option<NetworkSummary>);
        let r: Result<Out, String> = py.detach(|| {
            let (stats, summary) = feeder.finish().map_err(|e| e.to_string())?;
            let ply = sink.finish_with(summary.as_ref()).map_err(|e| format!("{path}: {e}"))?;
            if let Some(t) = &summary {
                septa::io::write_summary_json(t, &topo_path, &[])
                    .map_err(|e| format!("{}: {e}", topo_path.display()))?;
            }
            Ok((stats, ply, summary))
        });
        let (stats, ply, summary) = r.map_err(InputError::new_err)?;
        result_dict(py, &path, &stats, &ply, summary.as_ref(), &topo_path)
    }
}
