//! `septa.arrangement` / `septa.material_interface`: the grid surface
//! network (Du et al. 2022) computed by `septa::network::compute`, handed
//! back as numpy arrays (no file round trip).
use crate::{failure, Failure, InputError};
use numpy::{IntoPyArray, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use septa::complex::Mode;
use septa::grid::{BoxGrid, Grid, Split, TetMesh};
use septa::io::Annotations;
use septa::measure::{network_measures, BoxDomain};
use septa::network::{compute, Network, NetworkOptions};

fn id(x: u32) -> i64 {
    if x == u32::MAX {
        -1
    } else {
        x as i64
    }
}

/// network(mode, vertices, tets, values, box=None, lookup=True, raytrace=True, threads=None, progress=None, certify=True)
/// --
///
/// Computes the IA (`mode="ia"`) or MI (`mode="mi"`) network of the `k`
/// functions in `values` `(#V, k) float64` on the grid `vertices`
/// `(#V, 3) float64`, `tets` `(#T, 4) int64`. With `box=((nx, ny, nz),
/// ((x0, y0, z0), (x1, y1, z1)), split)` the grid is the built-in box (whose
/// vertices and tets must be the ones given). The GIL is released while the
/// network is computed. `progress(done, total)` is called as blocks finish
/// (from worker threads, with the GIL taken for the call; an exception in it
/// is printed and ignored). With `certify` the written doubles are checked
/// exactly and repaired (`septa::mesh::certify_network`; `embedding` holds
/// the report as JSON text). Returns a dict of arrays (see `septa.Network`).
#[pyfunction]
#[pyo3(signature = (mode, vertices, tets, values, r#box = None, lookup = true, raytrace = true, threads = None, progress = None, certify = true))]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub fn network<'py>(
    py: Python<'py>,
    mode: &str,
    vertices: PyReadonlyArray2<'py, f64>,
    tets: PyReadonlyArray2<'py, i64>,
    values: PyReadonlyArray2<'py, f64>,
    r#box: Option<([usize; 3], [[f64; 3]; 2], u8)>,
    lookup: bool,
    raytrace: bool,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
    certify: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let mode = crate::parse_mode(mode).map_err(InputError::new_err)?;
    let k = values.shape()[1];
    let vs = vertices.as_slice().map_err(|_| InputError::new_err("vertices: array must be C-contiguous"))?;
    let ts = tets.as_slice().map_err(|_| InputError::new_err("tets: array must be C-contiguous"))?;
    let fs = values.as_slice().map_err(|_| InputError::new_err("values: array must be C-contiguous"))?;
    let mut options = NetworkOptions::new(mode);
    options.lookup = lookup;
    options.raytrace = raytrace;
    options.progress = progress.map(py_progress);
    let cancel = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    options.cancel = Some(cancel.clone());
    let result: Result<(Network, Annotations), Failure> = crate::interrupt::run_interruptible(py, &cancel, || {
        let grid = match r#box {
            Some((res, bounds, split)) => {
                let split = match split {
                    5 => Split::Five,
                    6 => Split::Six,
                    s => return Err(format!("split must be 5 or 6, not {s}").into()),
                };
                Grid::Box(BoxGrid::new(res, bounds, split).map_err(failure)?)
            }
            None => {
                let pts: Vec<[f64; 3]> = vs.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
                let tt: Vec<[i64; 4]> = ts.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect();
                Grid::Mesh(TetMesh::new(pts, &tt).map_err(failure)?)
            }
        };
        let run = || {
            let mut net = compute(&grid, fs, k, &options).map_err(failure)?;
            if certify {
                let b = match &grid {
                    Grid::Box(b) => Some(b),
                    Grid::Mesh(_) => None,
                };
                septa::mesh::certify_network(&mut net, b);
            }
            Ok::<_, Failure>(net)
        };
        let net = crate::on_threads(threads, run)?;
        let domain = match &grid {
            Grid::Box(g) => Some(BoxDomain::of_box(g)),
            Grid::Mesh(_) => None,
        };
        let notes = Annotations { names: Default::default(), measures: network_measures(&net, domain.as_ref()) };
        Ok((net, notes))
    })?;
    let (net, notes) = result?;
    to_dict(py, &net, &notes)
}

/// The measures of a network on a box grid (no names).
pub(crate) fn box_notes(net: &Network, grid: &BoxGrid) -> Annotations {
    Annotations { names: Default::default(), measures: network_measures(net, Some(&BoxDomain::of_box(grid))) }
}

/// The arrays of a network (`septa.Network._from_core`), with its names and
/// measures.
pub(crate) fn to_dict<'py>(py: Python<'py>, net: &Network, notes: &Annotations) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let n = net.points.len();
    d.set_item("mode", if net.mode == Mode::Ia { "ia" } else { "mi" })?;
    d.set_item("functions", net.functions)?;
    let pts: Vec<f64> = net.points.iter().flatten().copied().collect();
    d.set_item("points", pts.into_pyarray(py).reshape([n, 3])?)?;
    let offsets: Vec<i64> = net.face_start.iter().map(|&x| x as i64).collect();
    d.set_item("offsets", offsets.into_pyarray(py))?;
    let indices: Vec<i64> = net.face_verts.iter().map(|&x| x as i64).collect();
    d.set_item("indices", indices.into_pyarray(py))?;
    let nf = net.num_faces();
    let fp: Vec<i64> = net.face_patch.iter().map(|&x| x as i64).collect();
    d.set_item("face_patch", fp.into_pyarray(py))?;
    let fc: Vec<i64> = net.face_cells.iter().flat_map(|c| [id(c[0]), id(c[1])]).collect();
    d.set_item("face_cells", fc.into_pyarray(py).reshape([nf, 2])?)?;
    let fl: Vec<i64> = net.face_label.iter().flat_map(|l| [l[0] as i64, l[1] as i64]).collect();
    d.set_item("face_label", fl.into_pyarray(py).reshape([nf, 2])?)?;
    let pl: Vec<i64> = net.patches.iter().flat_map(|p| [p.label[0] as i64, p.label[1] as i64]).collect();
    d.set_item("patch_labels", pl.into_pyarray(py).reshape([net.patches.len(), 2])?)?;
    let pf: Vec<i64> = net.patches.iter().map(|p| p.faces as i64).collect();
    d.set_item("patch_faces", pf.into_pyarray(py))?;
    let as_arrays = |lists: &[Vec<u32>]| -> PyResult<Bound<'py, PyList>> {
        PyList::new(py, lists.iter().map(|c| c.iter().map(|&x| x as i64).collect::<Vec<_>>().into_pyarray(py)))
    };
    d.set_item("chains", as_arrays(&net.chains)?)?;
    d.set_item("chain_patches", as_arrays(&net.chain_patches)?)?;
    let corners: Vec<i64> = net.corners.iter().map(|&x| x as i64).collect();
    d.set_item("corners", corners.into_pyarray(py))?;
    d.set_item("shells", as_arrays(&net.shells)?)?;
    let cells = PyList::empty(py);
    for c in &net.cells {
        let cd = PyDict::new(py);
        cd.set_item("shells", c.shells.clone())?;
        match net.mode {
            // Sign vector as booleans (bit f set iff f > 0), as network.json.
            Mode::Ia => cd.set_item("label", (0..net.functions).map(|f| c.positive(f)).collect::<Vec<bool>>())?,
            Mode::Mi => cd.set_item("label", vec![c.label.first().copied().unwrap_or(0)])?,
        }
        cells.append(cd)?;
    }
    d.set_item("cells", cells)?;
    let counts = PyDict::new(py);
    for (k, v) in net.counts() {
        counts.set_item(k, v)?;
    }
    counts.set_item("components", net.components)?;
    counts.set_item("active_tets", net.active_tets)?;
    d.set_item("counts", counts)?;
    d.set_item("cells_method", net.cells_method.as_str())?;
    if let Some(e) = &net.embedding {
        d.set_item("embedding", serde_json::to_string(e).map_err(|e| InputError::new_err(e.to_string()))?)?;
    }
    let seconds = PyDict::new(py);
    for (k, v) in &net.seconds {
        seconds.set_item(*k, *v)?;
    }
    d.set_item("seconds", seconds)?;
    crate::result::notes_items(py, &d, &notes.names, &notes.measures)?;
    Ok(d)
}

/// A Python `progress(done, total)` as the library's block progress (an
/// exception in it is printed, not raised: the computation goes on).
pub(crate) fn py_progress(cb: Py<PyAny>) -> septa::Progress {
    septa::Progress(std::sync::Arc::new(move |done, total| {
        Python::attach(|py| {
            if let Err(e) = cb.call1(py, (done, total)) {
                e.print(py);
            }
        })
    }))
}
