//! `septa.distributed`: the three steps of a sparse job (docs/distributed.md) as separate calls, so that a Dask cluster can run the
//! middle one anywhere: plan the blocks, run blocks into bytes, finish from
//! the bytes. A job travels as JSON text (never Rust objects), so a worker
//! only needs `pip install septa`.
//!
//! Job JSON: `{"mode": "ia"|"mi", "block": 16, "grid": {"resolution": n or
//! [nx, ny, nz], "bounds": [[..], [..]], "split": 5|6}, "functions": [..]}`
//! (a reference-format primitive list), or `{"scene": {..} or
//! "builtin:NAME", "block": 16}` where mode and grid come from the scene
//! unless given. `"base_dir"` resolves relative mesh paths.
use crate::{failure, Failure, InputError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use rayon::prelude::*;
use septa::complex::Mode;
use septa::grid::BoxGrid;
use septa::io::Annotations;
use septa::network::{
    compute, compute_sparse, finish_sparse, plan_sparse, run_block, BlockResult, Network, NetworkOptions, SparsePlan,
    SparseStats,
};
use septa::scene::{sample_grid, Primitive, Scene};

/// A parsed job.
pub(crate) struct Job {
    pub(crate) grid: BoxGrid,
    pub(crate) functions: Vec<Primitive>,
    pub(crate) options: NetworkOptions,
    scene: Option<Scene>,
}

/// The job JSON (module doc), read by the library's one job model
/// (`septa::job::Job::from_job_json`): a formulas-on-a-box-grid job.
pub(crate) fn parse_job(text: &str) -> Result<Job, String> {
    let (job, block) = septa::job::Job::from_job_json(text).map_err(|e| e.to_string())?;
    let mut options = NetworkOptions::new(job.mode.unwrap_or(Mode::Ia));
    if let Some(b) = block {
        options.block = b;
    }
    let (grid, functions) = match (job.grid, job.functions) {
        (septa::grid::Grid::Box(g), septa::job::Functions::Formulas(f)) => (g, f),
        _ => return Err("job: the distributed path needs formulas on a box grid".into()),
    };
    Ok(Job { grid, functions, options, scene: job.scene })
}

fn plan_of(p: (usize, Vec<usize>, bool)) -> SparsePlan {
    SparsePlan { blocks: p.0, kept: p.1, dense: p.2 }
}

/// A sparse run's block statistics as the dict Python results carry, with
/// the command line's `--json` names (`total`, not `blocks`: one name).
pub(crate) fn stats_dict<'py>(py: Python<'py>, s: &SparseStats) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("total", s.blocks)?;
    d.set_item("skipped", s.skipped)?;
    d.set_item("sampled", s.sampled)?;
    d.set_item("active", s.active)?;
    d.set_item("sampled_vertices", s.sampled_vertices)?;
    d.set_item("dense_fallback", s.dense_fallback)?;
    Ok(d)
}

/// A job's network's names and measures (its box grid is the domain).
fn notes_of(j: &Job, net: &Network) -> Annotations {
    Annotations {
        names: j.scene.as_ref().map(|s| s.result_names()).unwrap_or_default(),
        measures: septa::measure::network_measures(net, Some(&septa::measure::BoxDomain::of_box(&j.grid))),
    }
}

fn network_dict<'py>(
    py: Python<'py>,
    net: &Network,
    stats: Option<&SparseStats>,
    notes: &Annotations,
) -> PyResult<Bound<'py, PyDict>> {
    let d = crate::network::to_dict(py, net, notes)?;
    if let (Some(s), Some(counts)) = (stats, d.get_item("counts")?) {
        counts.set_item("blocks", stats_dict(py, s)?)?;
    }
    Ok(d)
}

/// sparse_plan(job)
/// --
///
/// Step 1: `(blocks, kept, dense)`: the number of blocks, the indices of
/// those that may hold a part of the network (by the functions' bounds,
/// nothing sampled), and whether the job runs on the dense path instead.
#[pyfunction]
pub fn sparse_plan(py: Python<'_>, job: &str) -> PyResult<(usize, Vec<usize>, bool)> {
    let r: Result<_, String> = py.detach(|| {
        let j = parse_job(job)?;
        let p = plan_sparse(&j.grid, &j.functions, &j.options).map_err(|e| e.to_string())?;
        Ok((p.blocks, p.kept, p.dense))
    });
    r.map_err(InputError::new_err)
}

/// sparse_blocks(job, indices)
/// --
///
/// Step 2: samples and processes the given blocks one after the other on
/// this thread (the GIL released) and returns one `bytes` per block: the
/// block's part of the network in Septa's versioned binary layout.
#[pyfunction]
pub fn sparse_blocks<'py>(py: Python<'py>, job: &str, indices: Vec<usize>) -> PyResult<Vec<Bound<'py, PyBytes>>> {
    let r: Result<Vec<Vec<u8>>, String> = py.detach(|| {
        let j = parse_job(job)?;
        indices
            .iter()
            .map(|&i| {
                run_block(&j.grid, &j.functions, &j.options, i)
                    .map(|b| b.to_bytes())
                    .map_err(|e| format!("block {i}: {e}"))
            })
            .collect()
    });
    Ok(r.map_err(InputError::new_err)?.iter().map(|b| PyBytes::new(py, b)).collect())
}

fn finish(job: &Job, plan: SparsePlan, results: &[&[u8]]) -> Result<(Network, SparseStats), Failure> {
    // Decoded in parallel: the client's share of the work besides the merge.
    let blocks = results
        .par_iter()
        .enumerate()
        .map(|(i, b)| BlockResult::from_bytes(b).map_err(|e| format!("result {i}: {e}")))
        .collect::<Result<Vec<_>, String>>()?;
    finish_sparse(&job.grid, &job.functions, &job.options, &plan, blocks).map_err(failure)
}

/// sparse_finish(job, plan, results)
/// --
///
/// Step 3: merges the block results (in block order, whatever order they
/// come in), finds the topology, certifies the written doubles (as
/// `network` does by default) and returns the network dict (as `network`),
/// with the sparse statistics in `counts["blocks"]`.
#[pyfunction]
pub fn sparse_finish<'py>(
    py: Python<'py>,
    job: &str,
    plan: (usize, Vec<usize>, bool),
    results: Vec<Bound<'py, PyBytes>>,
) -> PyResult<Bound<'py, PyDict>> {
    let slices: Vec<&[u8]> = results.iter().map(|b| b.as_bytes()).collect();
    let r = py.detach(|| -> Result<_, Failure> {
        let j = parse_job(job)?;
        let (mut net, stats) = finish(&j, plan_of(plan), &slices)?;
        septa::mesh::certify_network(&mut net, Some(&j.grid));
        let notes = notes_of(&j, &net);
        Ok((net, stats, notes))
    });
    let (net, stats, notes) = r?;
    network_dict(py, &net, Some(&stats), &notes)
}

/// sparse_finish_regions(job, plan, results, normals=False)
/// --
///
/// Step 3 for a scene's region surfaces: as `sparse_finish`, then the
/// surfaces and curves of interest of the scene's region rule (and, with
/// `normals`, the per region pair vertex normals); returns the arrays of
/// `regions`.
#[pyfunction]
#[pyo3(signature = (job, plan, results, normals = false))]
pub fn sparse_finish_regions<'py>(
    py: Python<'py>,
    job: &str,
    plan: (usize, Vec<usize>, bool),
    results: Vec<Bound<'py, PyBytes>>,
    normals: bool,
) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
    let slices: Vec<&[u8]> = results.iter().map(|b| b.as_bytes()).collect();
    let r: Result<septa::regions::RegionSurfaces, Failure> = py.detach(|| {
        let j = parse_job(job)?;
        let scene =
            j.scene.as_ref().ok_or_else(|| "region surfaces need a scene (with its region rule)".to_string())?;
        let (net, stats) = finish(&j, plan_of(plan), &slices)?;
        let mut out = septa::regions::from_network(net, &scene.regions, &scene.interest);
        out.names = scene.result_names();
        out.domain = Some(septa::measure::BoxDomain::of_box(&j.grid));
        if normals {
            septa::regions::add_normals(&mut out, &scene.functions);
        }
        septa::mesh::certify_regions(&mut out, Some(&j.grid), Some(j.grid.bounds));
        out.sparse = Some(stats);
        Ok(out)
    });
    crate::regions::region_dict(py, &r?)
}

/// sparse_network(job, dense=False, threads=None)
/// --
///
/// The same job in this process: `compute_sparse` (the three steps with
/// blocks on the rayon pool), or with `dense=True` every vertex sampled
/// and the dense path. Returns the network dict (as `sparse_finish`).
#[pyfunction]
#[pyo3(signature = (job, dense = false, threads = None))]
pub fn sparse_network<'py>(
    py: Python<'py>,
    job: &str,
    dense: bool,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let cancel = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let r: Result<(Network, Option<SparseStats>, Annotations), Failure> =
        crate::interrupt::run_interruptible(py, &cancel, || {
            let mut j = parse_job(job)?;
            j.options.cancel = Some(cancel.clone());
            let run = || -> Result<(Network, Option<SparseStats>), Failure> {
                if dense {
                    let g = septa::grid::Grid::Box(j.grid.clone());
                    let values = sample_grid(&j.functions, &g.vertices());
                    let net = compute(&g, &values, j.functions.len(), &j.options).map_err(failure)?;
                    Ok((net, None))
                } else {
                    compute_sparse(&j.grid, &j.functions, &j.options).map(|(n, s)| (n, Some(s))).map_err(failure)
                }
            };
            let (mut net, stats) = crate::on_threads(threads, run)?;
            septa::mesh::certify_network(&mut net, Some(&j.grid));
            let notes = notes_of(&j, &net);
            Ok((net, stats, notes))
        })?;
    let (net, stats, notes) = r?;
    network_dict(py, &net, stats.as_ref(), &notes)
}
