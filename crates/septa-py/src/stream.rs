//! `septa.stream_ply`: the polygons of a sparse job streamed block by block
//! into one PLY in bounded memory (issue 6: networks larger than memory),
//! with the topology assembled from block summaries on the way (written to
//! `<path>.topology.json`, as `septa ia --stream` does).
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

use pyo3::prelude::*;
use pyo3::types::PyDict;
use septa::io::ply_stream::{PlyStreamSink, PlyStreamStats};
use septa::network::stream::{stream_sparse, stream_topology, StreamStats};
use septa::network::NetworkSummary;

use crate::InputError;

/// Streams job `job` (the JSON of `septa.distributed.job_spec`) to the PLY
/// `path`; returns a summary dict.
#[pyfunction]
#[pyo3(signature = (job, path, window = 0, triangles = false, threads = None, topology = true))]
pub fn stream_ply<'py>(
    py: Python<'py>,
    job: &str,
    path: &str,
    window: usize,
    triangles: bool,
    threads: Option<usize>,
    topology: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let cancel = Arc::new(AtomicBool::new(false));
    type Out = (StreamStats, PlyStreamStats, Option<NetworkSummary>);
    let topo_path = Path::new(path).with_extension("topology.json");
    let r: Result<Out, String> = crate::interrupt::run_interruptible(py, &cancel, || {
        let mut j = crate::distributed::parse_job(job)?;
        j.options.cancel = Some(cancel.clone());
        let run = || -> Result<Out, String> {
            let mut sink = PlyStreamSink::create(Path::new(path), &j.grid, j.options.mode, j.functions.len())
                .map_err(|e| format!("{path}: {e}"))?
                .triangulated(triangles);
            let (stats, summary) = if topology {
                let (s, t) =
                    stream_topology(&j.grid, &j.functions, &j.options, window, &mut sink).map_err(|e| e.to_string())?;
                (s, Some(t))
            } else {
                (stream_sparse(&j.grid, &j.functions, &j.options, window, &mut sink).map_err(|e| e.to_string())?, None)
            };
            let ply = sink.finish_with(summary.as_ref()).map_err(|e| format!("{path}: {e}"))?;
            if let Some(t) = &summary {
                septa::io::summary_out::write_summary_json(t, &topo_path, &[])
                    .map_err(|e| format!("{}: {e}", topo_path.display()))?;
            }
            Ok((stats, ply, summary))
        };
        crate::on_threads(threads, run)
    })?;
    let (stats, ply, summary) = r.map_err(InputError::new_err)?;
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
