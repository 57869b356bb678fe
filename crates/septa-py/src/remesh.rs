//! `Network.remesh(L)`: a result's polygons remeshed by
//! `septa::mesh::remesh_written` (the same as `septa remesh OUT L`), handed
//! back as numpy arrays.
use numpy::{IntoPyArray, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use septa::mesh::{remesh_written, RemeshOptions, Written};

use crate::InputError;

fn c<'a, T: numpy::Element>(name: &str, a: &'a PyReadonlyArray1<'_, T>) -> PyResult<&'a [T]> {
    a.as_slice().map_err(|_| InputError::new_err(format!("{name}: array must be C-contiguous")))
}

fn u32s(name: &str, xs: &[i64]) -> PyResult<Vec<u32>> {
    xs.iter()
        .enumerate()
        .map(|(i, &x)| u32::try_from(x).map_err(|_| InputError::new_err(format!("{name}[{i}]: {x} out of range"))))
        .collect()
}

fn rows2(name: &str, a: &PyReadonlyArray2<'_, i64>) -> PyResult<Vec<[i64; 2]>> {
    if a.shape()[1] != 2 && a.shape()[0] > 0 {
        return Err(InputError::new_err(format!("{name}: expected shape (n, 2), got {:?}", a.shape())));
    }
    let s = a.as_slice().map_err(|_| InputError::new_err(format!("{name}: array must be C-contiguous")))?;
    Ok(s.chunks_exact(2).map(|c| [c[0], c[1]]).collect())
}

/// remesh(points, offsets, indices, face_patch, face_cells, face_label, patches, cells, chain_offsets, chain_indices, corners, cell_volume, length, iterations=8)
/// --
///
/// Remeshes a result's polygons to triangles of edge length about `length`
/// (`septa::mesh::remesh_written`: chains and corners kept, vertices on the
/// unremeshed patches, certified by the exact check, refused when a
/// violation remains). Integer arrays int64 (`face_cells` -1: none). The
/// GIL is released while remeshing. Returns a dict: `points`, `offsets`,
/// `indices`, `face_patch`, `face_cells`, `face_label`, `chains` (list),
/// `corners`, `cell_volume`, `patch_area`, `chain_length`, `report` and
/// `embedding` (JSON text; `embedding` None when refused).
#[pyfunction]
#[pyo3(signature = (points, offsets, indices, face_patch, face_cells, face_label, patches, cells, chain_offsets,
    chain_indices, corners, cell_volume, length, iterations = 8))]
#[allow(clippy::too_many_arguments)]
pub fn remesh<'py>(
    py: Python<'py>,
    points: PyReadonlyArray2<'py, f64>,
    offsets: PyReadonlyArray1<'py, i64>,
    indices: PyReadonlyArray1<'py, i64>,
    face_patch: PyReadonlyArray1<'py, i64>,
    face_cells: PyReadonlyArray2<'py, i64>,
    face_label: PyReadonlyArray2<'py, i64>,
    patches: usize,
    cells: usize,
    chain_offsets: PyReadonlyArray1<'py, i64>,
    chain_indices: PyReadonlyArray1<'py, i64>,
    corners: PyReadonlyArray1<'py, i64>,
    cell_volume: PyReadonlyArray1<'py, f64>,
    length: f64,
    iterations: usize,
) -> PyResult<Bound<'py, PyDict>> {
    if points.shape()[1] != 3 {
        return Err(InputError::new_err(format!("points: expected shape (n, 3), got {:?}", points.shape())));
    }
    let pts = points.as_slice().map_err(|_| InputError::new_err("points: array must be C-contiguous"))?;
    let pts: Vec<[f64; 3]> = pts.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    let face_start = u32s("offsets", c("offsets", &offsets)?)?;
    let face_verts = u32s("indices", c("indices", &indices)?)?;
    let fp = u32s("face_patch", c("face_patch", &face_patch)?)?;
    let fc: Vec<[u32; 2]> = rows2("face_cells", &face_cells)?
        .iter()
        .map(|r| r.map(|x| if x < 0 { u32::MAX } else { u32::try_from(x).unwrap_or(u32::MAX - 1) }))
        .collect();
    let fl: Vec<[i32; 2]> = rows2("face_label", &face_label)?.iter().map(|r| r.map(|x| x as i32)).collect();
    let co = c("chain_offsets", &chain_offsets)?;
    let ci = u32s("chain_indices", c("chain_indices", &chain_indices)?)?;
    let mut chains = Vec::with_capacity(co.len().saturating_sub(1));
    for (i, w) in co.windows(2).enumerate() {
        if w[0] < 0 || w[1] < w[0] || w[1] as usize > ci.len() {
            return Err(InputError::new_err(format!("chain {i}: offsets {}..{} out of range", w[0], w[1])));
        }
        chains.push(ci[w[0] as usize..w[1] as usize].to_vec());
    }
    let corners = u32s("corners", c("corners", &corners)?)?;
    let volumes = c("cell_volume", &cell_volume)?.to_vec();
    let w = Written {
        points: &pts,
        face_start: &face_start,
        face_verts: &face_verts,
        face_patch: &fp,
        face_cells: &fc,
        face_label: &fl,
        patches,
        cells,
        chains: &chains,
        corners: &corners,
        cell_volume: &volumes,
    };
    let mut opts = RemeshOptions::new(length);
    opts.iterations = iterations;
    let r = py.detach(|| remesh_written(&w, &opts)).map_err(InputError::new_err)?;
    let d = PyDict::new(py);
    let np = r.points.len();
    let flat: Vec<f64> = r.points.iter().flatten().copied().collect();
    d.set_item("points", flat.into_pyarray(py).reshape([np, 3])?)?;
    let i64s = |xs: &[u32]| xs.iter().map(|&x| x as i64).collect::<Vec<i64>>();
    d.set_item("offsets", i64s(&r.face_start).into_pyarray(py))?;
    d.set_item("indices", i64s(&r.face_verts).into_pyarray(py))?;
    d.set_item("face_patch", i64s(&r.face_patch).into_pyarray(py))?;
    let nf = r.face_patch.len();
    let cells2: Vec<i64> = r.face_cells.iter().flatten().map(|&x| if x == u32::MAX { -1 } else { x as i64 }).collect();
    d.set_item("face_cells", cells2.into_pyarray(py).reshape([nf, 2])?)?;
    let labels2: Vec<i64> = r.face_label.iter().flatten().map(|&x| x as i64).collect();
    d.set_item("face_label", labels2.into_pyarray(py).reshape([nf, 2])?)?;
    d.set_item("chains", PyList::new(py, r.chains.iter().map(|ch| i64s(ch).into_pyarray(py)))?)?;
    d.set_item("corners", i64s(&r.corners).into_pyarray(py))?;
    d.set_item("cell_volume", r.measures.cell_volume.clone().into_pyarray(py))?;
    d.set_item("patch_area", r.measures.patch_area.clone().into_pyarray(py))?;
    d.set_item("chain_length", r.measures.chain_length.clone().into_pyarray(py))?;
    let err = |e: serde_json::Error| InputError::new_err(e.to_string());
    d.set_item("report", serde_json::to_string(&r.report).map_err(err)?)?;
    match &r.embedding {
        Some(e) => d.set_item("embedding", serde_json::to_string(e).map_err(err)?)?,
        None => d.set_item("embedding", py.None())?,
    }
    Ok(d)
}
