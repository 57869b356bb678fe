//! `septa.continuation`: networks of a Python callable (a function without
//! bounds) by continuation from seeds (Bloomenthal 4.5.1), with
//! `septa::network::compute_continuation`. The callable gets `(n, 3) float64`
//! points, one block (or the coarse scan's corners) per call, and returns
//! `(n, k)` values; the GIL is taken per call and released otherwise, so
//! the per-tet work of other blocks runs meanwhile.
use crate::InputError;
use numpy::{IntoPyArray, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use pyo3::types::{PyDict, PyDictMethods};
use septa::grid::{BoxGrid, Split};
use septa::network::BlockResult;
use septa::network::{
    compute_continuation, continuation_block, continuation_seeds, finish_continuation, ContinuationStats, Field, Seeds,
};
use septa::network::{Network, NetworkOptions};

/// A Python callable as a [`Field`].
struct PyField {
    f: Py<PyAny>,
    k: usize,
}

impl Field for PyField {
    fn functions(&self) -> usize {
        self.k
    }

    fn eval(&self, points: &[[f64; 3]], out: &mut Vec<f64>) -> Result<(), String> {
        Python::attach(|py| -> Result<(), String> {
            let n = points.len();
            let flat: Vec<f64> = points.iter().flatten().copied().collect();
            let arr = flat.into_pyarray(py).reshape([n, 3]).map_err(|e| e.to_string())?;
            let r = self.f.bind(py).call1((arr,)).map_err(|e| format!("the function raised {e}"))?;
            let np = py.import("numpy").map_err(|e| e.to_string())?;
            let kw = PyDict::new(py);
            kw.set_item("dtype", "float64").map_err(|e| e.to_string())?;
            let a = np
                .call_method("ascontiguousarray", (r,), Some(&kw))
                .map_err(|e| format!("the function's result is not a float array: {e}"))?;
            let a = a
                .cast_into::<numpy::PyArrayDyn<f64>>()
                .map_err(|_| "the function's result is not a float array".to_string())?;
            let shape = a.shape().to_vec();
            let ok = shape == [n, self.k] || (self.k == 1 && shape == [n]);
            if !ok {
                return Err(format!(
                    "the function returned shape {shape:?} for {n} points, expected ({n}, {})",
                    self.k
                ));
            }
            let ro = a.readonly();
            out.extend_from_slice(ro.as_slice().map_err(|e| e.to_string())?);
            Ok(())
        })
    }
}

/// continuation(f, k, mode, resolution, bounds, split=5, block=8, seeds=None, dense=False, threads=None)
/// --
///
/// The IA (`mode="ia"`) or MI network of the `k` functions computed by the
/// callable `f(points (n, 3)) -> (n, k)` on a box grid, by continuation from
/// the blocks holding `seeds` (a list of points), or from a coarse scan of
/// the block corners when `seeds` is None. `dense=True` samples every
/// vertex instead (the reference). Returns the network dict (as `network`)
/// with `counts["blocks"]` (total, skipped, sampled, active, seeds, rounds).
#[pyfunction]
#[pyo3(signature = (f, k, mode, resolution, bounds, split = 5, block = 8, seeds = None, dense = false, threads = None))]
#[allow(clippy::too_many_arguments)]
pub fn continuation<'py>(
    py: Python<'py>,
    f: Py<PyAny>,
    k: usize,
    mode: &str,
    resolution: [usize; 3],
    bounds: [[f64; 3]; 2],
    split: u8,
    block: usize,
    seeds: Option<Vec<[f64; 3]>>,
    dense: bool,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let mode = crate::parse_mode(mode).map_err(InputError::new_err)?;
    let split = match split {
        5 => Split::Five,
        6 => Split::Six,
        s => return Err(InputError::new_err(format!("split must be 5 or 6, not {s}"))),
    };
    let grid = BoxGrid::new(resolution, bounds, split).map_err(crate::failure)?;
    let field = PyField { f, k };
    let mut options = NetworkOptions::new(mode);
    options.block = block.max(1);
    let cancel = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    options.cancel = Some(cancel.clone());
    let r: Result<(Network, Option<ContinuationStats>), String> =
        crate::interrupt::run_interruptible(py, &cancel, || {
            let run = || {
                if dense {
                    // Every vertex sampled, the dense path (the reference the tests compare to).
                    let g = septa::grid::Grid::Box(grid.clone());
                    let pts = g.vertices();
                    let mut values = Vec::with_capacity(pts.len() * k);
                    for chunk in pts.chunks(1 << 16) {
                        field.eval(chunk, &mut values)?;
                    }
                    if values.len() != pts.len() * k {
                        return Err(format!(
                            "the function returned {} values, expected {}",
                            values.len(),
                            pts.len() * k
                        ));
                    }
                    let net = septa::network::compute(&g, &values, k, &options).map_err(|e| e.to_string())?;
                    return Ok((net, None));
                }
                let seeds = match &seeds {
                    Some(p) => Seeds::Points(p),
                    None => Seeds::CoarseScan,
                };
                compute_continuation(&grid, &field, seeds, &options)
                    .map(|(n, s)| (n, Some(s)))
                    .map_err(|e| e.to_string())
            };
            let (mut net, stats) = crate::on_threads(threads, run)?;
            septa::mesh::certify_network(&mut net, Some(&grid));
            Ok((net, stats))
        })?;
    let (net, stats) = r.map_err(InputError::new_err)?;
    let notes = py.detach(|| crate::network::box_notes(&net, &grid));
    let d = crate::network::to_dict(py, &net, &notes)?;
    if let (Some(s), Some(counts)) = (stats, d.get_item("counts")?) {
        let b = crate::distributed::stats_dict(py, &s.blocks)?;
        b.set_item("seeds", s.seeds)?;
        b.set_item("rounds", s.rounds)?;
        counts.set_item("blocks", b)?;
    }
    Ok(d)
}

/// A continuation job's grid and options: `(mode, resolution, bounds, split, block)`.
type JobTuple = (String, [usize; 3], [[f64; 3]; 2], u8, usize);

fn job_of(job: &JobTuple) -> Result<(BoxGrid, NetworkOptions), String> {
    let mode = crate::parse_mode(&job.0)?;
    let split = match job.3 {
        5 => Split::Five,
        6 => Split::Six,
        s => return Err(format!("split must be 5 or 6, not {s}")),
    };
    let grid = BoxGrid::new(job.1, job.2, split).map_err(|e| e.to_string())?;
    let mut options = NetworkOptions::new(mode);
    options.block = job.4.max(1);
    Ok((grid, options))
}

/// continuation_seeds(f, k, job, seeds=None)
/// --
///
/// Seed blocks of a continuation job `(mode, resolution, bounds, split,
/// block)`: the blocks holding `seeds`, or the coarse scan's.
#[pyfunction]
#[pyo3(name = "continuation_seeds", signature = (f, k, job, seeds = None))]
pub fn continuation_seeds_py(
    py: Python<'_>,
    f: Py<PyAny>,
    k: usize,
    job: JobTuple,
    seeds: Option<Vec<[f64; 3]>>,
) -> PyResult<Vec<usize>> {
    let field = PyField { f, k };
    let r: Result<Vec<usize>, String> = py.detach(|| {
        let (grid, options) = job_of(&job)?;
        let s = match &seeds {
            Some(p) => Seeds::Points(p),
            None => Seeds::CoarseScan,
        };
        continuation_seeds(&grid, &field, &s, &options).map_err(|e| e.to_string())
    });
    r.map_err(InputError::new_err)
}

/// continuation_blocks(f, k, job, indices)
/// --
///
/// One round of the search on this worker: per block, `(bytes, next)`: its
/// part of the network (Septa's block layout) and the neighbour blocks
/// across the faces the network touches.
#[pyfunction]
pub fn continuation_blocks<'py>(
    py: Python<'py>,
    f: Py<PyAny>,
    k: usize,
    job: JobTuple,
    indices: Vec<usize>,
) -> PyResult<Vec<(Bound<'py, PyBytes>, Vec<usize>)>> {
    let field = PyField { f, k };
    let r: Result<Vec<(Vec<u8>, Vec<usize>)>, String> = py.detach(|| {
        let (grid, options) = job_of(&job)?;
        indices
            .iter()
            .map(|&i| {
                continuation_block(&grid, &field, &options, i)
                    .map(|(b, next)| (b.to_bytes(), next))
                    .map_err(|e| format!("block {i}: {e}"))
            })
            .collect()
    });
    Ok(r.map_err(InputError::new_err)?.into_iter().map(|(b, n)| (PyBytes::new(py, &b), n)).collect())
}

/// continuation_finish(f, k, job, results)
/// --
///
/// The end of a continuation job from its block results (any order): the
/// network dict, with `counts["blocks"]`.
#[pyfunction]
pub fn continuation_finish<'py>(
    py: Python<'py>,
    f: Py<PyAny>,
    k: usize,
    job: JobTuple,
    results: Vec<Bound<'py, PyBytes>>,
) -> PyResult<Bound<'py, PyDict>> {
    let field = PyField { f, k };
    let slices: Vec<&[u8]> = results.iter().map(|b| b.as_bytes()).collect();
    let r: Result<(Network, septa::network::SparseStats, septa::io::Annotations), String> = py.detach(|| {
        let (grid, options) = job_of(&job)?;
        let blocks = slices
            .iter()
            .enumerate()
            .map(|(i, b)| BlockResult::from_bytes(b).map_err(|e| format!("result {i}: {e}")))
            .collect::<Result<Vec<_>, _>>()?;
        let (mut net, s) = finish_continuation(&grid, &field, &options, blocks).map_err(|e| e.to_string())?;
        septa::mesh::certify_network(&mut net, Some(&grid));
        let notes = crate::network::box_notes(&net, &grid);
        Ok((net, s, notes))
    });
    let (net, s, notes) = r.map_err(InputError::new_err)?;
    let d = crate::network::to_dict(py, &net, &notes)?;
    if let Some(counts) = d.get_item("counts")? {
        counts.set_item("blocks", crate::distributed::stats_dict(py, &s)?)?;
    }
    Ok(d)
}
