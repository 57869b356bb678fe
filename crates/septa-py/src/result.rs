//! Results between Rust and Python as numpy arrays, never JSON text:
//! [`view_dict`] hands a `ResultView` (the one result model of
//! `septa::io::result`) to `septa.Network`, and [`write_result`] writes a
//! Python `Network` with the same Rust writers the command line uses.
use std::borrow::Cow;

use numpy::{IntoPyArray, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use septa::io::{write_file, Format, ResultView};

use crate::InputError;

/// The arrays of `r` under the names `septa.Network._from_core` reads.
pub(crate) fn view_dict<'py>(py: Python<'py>, r: &ResultView) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let (np, nf) = (r.points.len(), r.num_faces());
    d.set_item("mode", r.mode)?;
    d.set_item("functions", r.functions)?;
    let pts: Vec<f64> = r.points.iter().flatten().copied().collect();
    d.set_item("points", pts.into_pyarray(py).reshape([np, 3])?)?;
    let i64s = |xs: &[u32]| xs.iter().map(|&x| x as i64).collect::<Vec<i64>>();
    d.set_item("offsets", i64s(&r.face_start).into_pyarray(py))?;
    d.set_item("indices", i64s(&r.face_verts).into_pyarray(py))?;
    d.set_item("face_patch", i64s(&r.patch).into_pyarray(py))?;
    let pairs = |xs: &[[i32; 2]]| xs.iter().flatten().map(|&x| x as i64).collect::<Vec<i64>>();
    d.set_item("face_label", pairs(&r.labels).into_pyarray(py).reshape([nf, 2])?)?;
    d.set_item("face_cells", pairs(&r.cells).into_pyarray(py).reshape([nf, 2])?)?;
    d.set_item("patch_labels", pairs(&r.patch_labels).into_pyarray(py).reshape([r.patch_labels.len(), 2])?)?;
    let mut per_patch = vec![0i64; r.patch_labels.len()];
    for &p in r.patch.iter() {
        if let Some(n) = per_patch.get_mut(p as usize) {
            *n += 1;
        }
    }
    d.set_item("patch_faces", per_patch.into_pyarray(py))?;
    let lists = |ls: &[Vec<u32>]| -> PyResult<Bound<'py, PyList>> {
        PyList::new(py, ls.iter().map(|l| i64s(l).into_pyarray(py)))
    };
    d.set_item("chains", lists(&r.chains)?)?;
    d.set_item("chain_patches", lists(&r.chain_patches)?)?;
    d.set_item("corners", i64s(&r.corners).into_pyarray(py))?;
    d.set_item("shells", lists(&r.shells)?)?;
    let cells = PyList::empty(py);
    for (s, l) in r.cell_shells.iter().zip(&r.cell_labels) {
        let c = PyDict::new(py);
        c.set_item("shells", s.clone())?;
        if r.mode == "ia" {
            c.set_item("label", l.iter().map(|&b| b != 0).collect::<Vec<bool>>())?;
        } else {
            c.set_item("label", l.clone())?;
        }
        cells.append(c)?;
    }
    d.set_item("cells", cells)?;
    notes_items(py, &d, &r.names, &r.measures)?;
    Ok(d)
}

/// `cell_volume`, `patch_area`, `chain_length` (float64 arrays, empty when
/// not measured) and `names` (`{"functions": [..], "regions": {r: name}}`).
pub(crate) fn notes_items<'py>(
    py: Python<'py>,
    d: &Bound<'py, PyDict>,
    names: &septa::io::Names,
    m: &septa::measure::Measures,
) -> PyResult<()> {
    d.set_item("cell_volume", m.cell_volume.clone().into_pyarray(py))?;
    d.set_item("patch_area", m.patch_area.clone().into_pyarray(py))?;
    d.set_item("chain_length", m.chain_length.clone().into_pyarray(py))?;
    let n = PyDict::new(py);
    n.set_item("functions", names.functions.clone())?;
    let regions = PyDict::new(py);
    for (k, v) in &names.regions {
        regions.set_item(*k, v)?;
    }
    n.set_item("regions", regions)?;
    d.set_item("names", n)?;
    Ok(())
}

/// Names from their JSON (`{"functions": [..], "regions": {"r": name}}`);
/// anything else is no names.
pub(crate) fn names_of(v: Option<&serde_json::Value>) -> septa::io::Names {
    let mut n = septa::io::Names::default();
    let Some(v) = v else { return n };
    if let Some(fs) = v.get("functions").and_then(|f| f.as_array()) {
        n.functions = fs.iter().map(|f| f.as_str().map_or_else(|| f.to_string(), str::to_string)).collect();
    }
    if let Some(rs) = v.get("regions").and_then(|r| r.as_object()) {
        for (k, name) in rs {
            if let (Ok(r), Some(name)) = (k.trim().parse::<i64>(), name.as_str()) {
                n.regions.insert(r, name.to_string());
            }
        }
    }
    n
}

/// A ragged list given as (offsets, indices).
fn ragged(name: &str, offsets: &[i64], indices: &[i64], points: usize) -> PyResult<Vec<Vec<u32>>> {
    let mut out = Vec::with_capacity(offsets.len().saturating_sub(1));
    for (i, w) in offsets.windows(2).enumerate() {
        let (a, b) = (w[0], w[1]);
        if a < 0 || b < a || b as usize > indices.len() {
            return Err(InputError::new_err(format!("{name} {i}: offsets {a}..{b} out of range")));
        }
        out.push(to_u32(name, &indices[a as usize..b as usize], points)?);
    }
    Ok(out)
}

fn to_u32(name: &str, xs: &[i64], below: usize) -> PyResult<Vec<u32>> {
    xs.iter()
        .enumerate()
        .map(|(i, &x)| {
            if x < 0 || x >= u32::MAX as i64 || (below != usize::MAX && x as usize >= below) {
                Err(InputError::new_err(format!("{name}[{i}]: {x} out of range")))
            } else {
                Ok(x as u32)
            }
        })
        .collect()
}

fn slice<'a, T: numpy::Element>(name: &str, a: &'a PyReadonlyArray1<'_, T>) -> PyResult<&'a [T]> {
    a.as_slice().map_err(|_| InputError::new_err(format!("{name}: array must be C-contiguous")))
}

fn pairs(name: &str, a: &PyReadonlyArray2<'_, i64>) -> PyResult<Vec<[i32; 2]>> {
    if a.shape()[1] != 2 && a.shape()[0] > 0 {
        return Err(InputError::new_err(format!("{name}: expected shape (n, 2), got {:?}", a.shape())));
    }
    let s = a.as_slice().map_err(|_| InputError::new_err(format!("{name}: array must be C-contiguous")))?;
    Ok(s.chunks_exact(2).map(|c| [c[0] as i32, c[1] as i32]).collect())
}

/// write_result(path, format, mode, functions, points, offsets, indices, patch, labels, cells, patch_labels, chain_offsets, chain_indices, chain_patch_offsets, chain_patch_indices, corners, shell_offsets, shell_indices, cell_shell_offsets, cell_shell_indices, cell_labels, meta, cell_volume=None, patch_area=None, chain_length=None)
/// --
///
/// Writes a result with the command line's writers (`network.ply`, `.obj`,
/// `.vtu`, `.vtm`, `.npz`, `.plain.ply`); `format` is one of those names.
/// Integer arrays are int64; ragged lists come as offsets / indices. Every
/// index is checked (the error names the array and the element). The
/// measures (float64, one per cell, patch, chain) and `meta["names"]` are
/// written where the format holds them. The GIL is released while writing.
#[pyfunction]
#[pyo3(signature = (path, format, mode, functions, points, offsets, indices, patch, labels, cells, patch_labels,
    chain_offsets, chain_indices, chain_patch_offsets, chain_patch_indices, corners, shell_offsets, shell_indices,
    cell_shell_offsets, cell_shell_indices, cell_labels, meta, cell_volume = None, patch_area = None,
    chain_length = None))]
#[allow(clippy::too_many_arguments)]
pub fn write_result(
    py: Python<'_>,
    path: std::path::PathBuf,
    format: &str,
    mode: &str,
    functions: usize,
    points: PyReadonlyArray2<'_, f64>,
    offsets: PyReadonlyArray1<'_, i64>,
    indices: PyReadonlyArray1<'_, i64>,
    patch: PyReadonlyArray1<'_, i64>,
    labels: PyReadonlyArray2<'_, i64>,
    cells: PyReadonlyArray2<'_, i64>,
    patch_labels: PyReadonlyArray2<'_, i64>,
    chain_offsets: PyReadonlyArray1<'_, i64>,
    chain_indices: PyReadonlyArray1<'_, i64>,
    chain_patch_offsets: PyReadonlyArray1<'_, i64>,
    chain_patch_indices: PyReadonlyArray1<'_, i64>,
    corners: PyReadonlyArray1<'_, i64>,
    shell_offsets: PyReadonlyArray1<'_, i64>,
    shell_indices: PyReadonlyArray1<'_, i64>,
    cell_shell_offsets: PyReadonlyArray1<'_, i64>,
    cell_shell_indices: PyReadonlyArray1<'_, i64>,
    cell_labels: PyReadonlyArray2<'_, i64>,
    meta: &str,
    cell_volume: Option<PyReadonlyArray1<'_, f64>>,
    patch_area: Option<PyReadonlyArray1<'_, f64>>,
    chain_length: Option<PyReadonlyArray1<'_, f64>>,
) -> PyResult<()> {
    let format = Format::parse_list(format).map_err(InputError::new_err)?;
    let [format] = format[..] else { return Err(InputError::new_err("write_result: one format")) };
    let mode: &'static str = match mode {
        "ia" => "ia",
        "mi" => "mi",
        "regions" => "regions",
        m => return Err(InputError::new_err(format!("mode must be ia, mi or regions, not {m:?}"))),
    };
    if points.shape()[1] != 3 {
        return Err(InputError::new_err(format!("points: expected shape (n, 3), got {:?}", points.shape())));
    }
    let pts = points.as_slice().map_err(|_| InputError::new_err("points: array must be C-contiguous"))?;
    let pts: Vec<[f64; 3]> = pts.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    let np = pts.len();
    let any = usize::MAX;
    let width = cell_labels.shape()[1];
    let cl = cell_labels.as_slice().map_err(|_| InputError::new_err("cell_labels: array must be C-contiguous"))?;
    let meta: serde_json::Value =
        serde_json::from_str(meta).map_err(|e| InputError::new_err(format!("meta: not JSON: {e}")))?;
    let floats = |name: &str, a: &Option<PyReadonlyArray1<'_, f64>>| -> PyResult<Vec<f64>> {
        match a {
            None => Ok(Vec::new()),
            Some(a) => Ok(slice(name, a)?.to_vec()),
        }
    };
    let measures = septa::measure::Measures {
        cell_volume: floats("cell_volume", &cell_volume)?,
        patch_area: floats("patch_area", &patch_area)?,
        chain_length: floats("chain_length", &chain_length)?,
    };
    let names = names_of(meta.get("names"));
    let view = ResultView {
        names: Cow::Owned(names),
        measures: Cow::Owned(measures),
        mode,
        functions,
        face_start: Cow::Owned(to_u32("offsets", slice("offsets", &offsets)?, any)?),
        face_verts: Cow::Owned(to_u32("indices", slice("indices", &indices)?, np)?),
        patch: Cow::Owned(to_u32("face_patch", slice("face_patch", &patch)?, any)?),
        labels: pairs("face_label", &labels)?,
        cells: pairs("face_cells", &cells)?,
        patch_labels: pairs("patch_labels", &patch_labels)?,
        chains: Cow::Owned(ragged(
            "chain",
            slice("chain_offsets", &chain_offsets)?,
            slice("chain_indices", &chain_indices)?,
            np,
        )?),
        chain_patches: Cow::Owned(ragged(
            "chain_patches",
            slice("chain_patch_offsets", &chain_patch_offsets)?,
            slice("chain_patch_indices", &chain_patch_indices)?,
            any,
        )?),
        corners: Cow::Owned(to_u32("corners", slice("corners", &corners)?, np)?),
        shells: Cow::Owned(ragged(
            "shell",
            slice("shell_offsets", &shell_offsets)?,
            slice("shell_indices", &shell_indices)?,
            any,
        )?),
        cell_shells: ragged(
            "cell_shells",
            slice("cell_shell_offsets", &cell_shell_offsets)?,
            slice("cell_shell_indices", &cell_shell_indices)?,
            any,
        )?,
        cell_labels: if width == 0 {
            vec![Vec::new(); cell_labels.shape()[0]]
        } else {
            cl.chunks_exact(width).map(|c| c.to_vec()).collect()
        },
        points: Cow::Owned(pts),
    };
    view.validate().map_err(InputError::new_err)?;
    let shown = path.display().to_string();
    // A failing write is the file system's error, not bad input: OSError.
    py.detach(|| write_file(&view, &path, format, &meta))
        .map_err(|e| pyo3::exceptions::PyOSError::new_err((e.raw_os_error().unwrap_or(0), format!("{shown}: {e}"))))
}
