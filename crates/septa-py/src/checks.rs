//! Input validation shared by every job: the checks run in Rust, without
//! the GIL, on the arrays exactly as the jobs will read them.
use crate::InputError;
use numpy::{PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;

/// check_values(values, name="values")
/// --
///
/// Checks a `(#V, k) float64` C-contiguous array of function values: every
/// value finite (the exact predicates are defined on finite numbers only).
/// Raises `septa.InputError` naming the vertex and function of the first
/// NaN or infinity.
#[pyfunction]
#[pyo3(signature = (values, name = "values"))]
pub fn check_values(py: Python<'_>, values: PyReadonlyArray2<'_, f64>, name: &str) -> PyResult<()> {
    let k = values.shape()[1].max(1);
    let slice = values.as_slice().map_err(|_| InputError::new_err(format!("{name}: array must be C-contiguous")))?;
    match py.detach(|| septa_exact::check_finite(slice)) {
        Ok(()) => Ok(()),
        Err(e) => Err(InputError::new_err(format!(
            "{name}: value {} of function {} at vertex {} is not finite",
            e.value,
            e.index % k,
            e.index / k
        ))),
    }
}

/// check_tets(tets, n_vertices)
/// --
///
/// Checks a `(#T, 4) int64` C-contiguous array of tetrahedra: every index in
/// `0..n_vertices` and the four vertices of a tet distinct. Raises
/// `septa.InputError` naming the first bad tet.
#[pyfunction]
pub fn check_tets(py: Python<'_>, tets: PyReadonlyArray2<'_, i64>, n_vertices: usize) -> PyResult<()> {
    if tets.shape()[1] != 4 {
        return Err(InputError::new_err(format!("tets: expected shape (#T, 4), got (#T, {})", tets.shape()[1])));
    }
    let slice = tets.as_slice().map_err(|_| InputError::new_err("tets: array must be C-contiguous"))?;
    let bad = py.detach(|| {
        slice.chunks_exact(4).enumerate().find_map(|(t, tet)| {
            if let Some(v) = tet.iter().find(|&&v| v < 0 || v as usize >= n_vertices) {
                return Some(format!("tets: tet {t} refers to vertex {v}, but there are {n_vertices} vertices"));
            }
            let mut s = [tet[0], tet[1], tet[2], tet[3]];
            s.sort_unstable();
            s.windows(2).any(|w| w[0] == w[1]).then(|| format!("tets: tet {t} repeats a vertex: {tet:?}"))
        })
    });
    match bad {
        None => Ok(()),
        Some(msg) => Err(InputError::new_err(msg)),
    }
}
