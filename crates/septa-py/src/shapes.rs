//! `septa.grid.box` and `septa.shapes`: the library's box grid and the
//! library's primitives, so that a grid, a plane or a sphere is the same
//! numbers in Python as in a scene file or on the command line (before,
//! Python rebuilt both in numpy, and a value could differ in its last bit from
//! the one a scene file samples).
use crate::InputError;
use numpy::{IntoPyArray, PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use septa::grid::{BoxGrid, Split};
use septa::scene::{load_function_list, sample_grid};

type Arrays<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<i64>>);

/// box_grid(resolution, bounds, split)
/// --
///
/// The library's box grid (`septa::grid::BoxGrid`): `(vertices (#V, 3)
/// float64, tets (#T, 4) int64)`, vertex `(i, j, k)` at index
/// `i*(ny+1)*(nz+1) + j*(nz+1) + k`, cube by cube `split` tets each, every
/// tet positively oriented. Raises `septa.InputError` for a zero resolution,
/// bounds that are not increasing, too many vertices or a split other than
/// 5 or 6.
#[pyfunction]
pub fn box_grid<'py>(
    py: Python<'py>,
    resolution: [usize; 3],
    bounds: [[f64; 3]; 2],
    split: u8,
) -> PyResult<Arrays<'py>> {
    let split = Split::try_from(split).map_err(|e| InputError::new_err(e.to_string()))?;
    let grid = BoxGrid::new(resolution, bounds, split).map_err(|e| InputError::new_err(e.to_string()))?;
    let (vertices, tets) = py.detach(|| {
        let v: Vec<f64> = (0..grid.num_vertices() as u32).flat_map(|v| grid.vertex(v)).collect();
        let t: Vec<i64> = (0..grid.num_tets()).flat_map(|t| grid.tet(t)).map(i64::from).collect();
        (v, t)
    });
    let (nv, nt) = (vertices.len() / 3, tets.len() / 4);
    Ok((vertices.into_pyarray(py).reshape([nv, 3])?, tets.into_pyarray(py).reshape([nt, 4])?))
}

/// sample_functions(functions, points)
/// --
///
/// Values of the primitives in `functions` (a JSON list of scene /
/// reference primitive objects, read by the library's one reader) at the
/// rows of `points` (`(N, 3) float64`, C-contiguous): `(N, k) float64`, the
/// numbers a scene file with these primitives samples, bit for bit. Raises
/// `septa.InputError` naming the primitive and field of a bad entry.
#[pyfunction]
pub fn sample_functions<'py>(
    py: Python<'py>,
    functions: &str,
    points: PyReadonlyArray2<'_, f64>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    if points.shape()[1] != 3 {
        return Err(InputError::new_err(format!("points: expected shape (N, 3), got (N, {})", points.shape()[1])));
    }
    let flat = points.as_slice().map_err(|_| InputError::new_err("points: array must be C-contiguous"))?;
    let n = points.shape()[0];
    let values = py.detach(|| {
        let fs = load_function_list(functions, "<functions>", None).map_err(|e| e.to_string())?;
        let pts: Vec<[f64; 3]> = flat.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
        Ok::<_, String>((fs.len(), sample_grid(&fs, &pts)))
    });
    let (k, values) = values.map_err(InputError::new_err)?;
    values.into_pyarray(py).reshape([n, k])
}
