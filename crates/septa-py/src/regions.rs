//! `septa.region_surfaces`: the surfaces and curves of interest of a scene's
//! region rule (Bloomenthal's non-manifold model on the exact network).
use crate::InputError;
use numpy::{IntoPyArray, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use septa::io::ResultView;
use septa::regions::{region_surfaces, RegionOptions, RegionSurfaces};
use septa::scene::Scene;

/// regions(scene, normals=False, clean=None, progress=None, certify=True, project=False)
/// --
///
/// `scene` is a scene file path, `builtin:NAME`, or scene JSON text
/// (starting with `{`). Returns a dict of numpy arrays (`septa.Network`'s
/// names: `patches` are the surfaces with their region pairs, `chains` the
/// curves, `cells` the regions) with `summary` (JSON text: counts, surfaces,
/// curves) and, with normals, `normal_vertex`, `normal_regions`,
/// `normal_vectors` and `indices_normal`; the GIL is released while it is
/// computed. With `certify` the kept polygons' written doubles are checked
/// exactly and repaired (`septa::mesh::certify_regions`; `embedding` in the
/// summary). With `project` (and `certify`) the vertices are first moved
/// onto the true zero sets of the scene's functions
/// (`septa::mesh::certify_regions_on`, `septa regions --project`).
#[pyfunction]
#[pyo3(signature = (scene, normals = false, clean = None, progress = None, certify = true, project = false))]
pub fn regions<'py>(
    py: Python<'py>,
    scene: &str,
    normals: bool,
    clean: Option<f64>,
    progress: Option<Py<PyAny>>,
    certify: bool,
    project: bool,
) -> PyResult<Bound<'py, PyDict>> {
    if project && !certify {
        return Err(InputError::new_err("project: needs certify (moves are checked exactly)"));
    }
    if let Some(f) = clean {
        if !(f.is_finite() && f >= 0.0) {
            return Err(InputError::new_err(format!("clean: expected a factor >= 0, not {f}")));
        }
    }
    let result: Result<RegionSurfaces, String> = py.detach(|| {
        let s = if scene.trim_start().starts_with('{') {
            Scene::from_json(scene, "<scene>", None)
        } else {
            Scene::load(scene)
        }
        .map_err(|e| e.to_string())?;
        let progress = progress.map(crate::network::py_progress);
        let mut r = region_surfaces(&s, &RegionOptions { normals, clean, progress, ..Default::default() })
            .map_err(|e| e.to_string())?;
        if certify {
            let grid = s.grid.box_grid().map_err(|e| e.to_string())?;
            if project {
                septa::mesh::certify_regions_on(&mut r, &grid, &s.functions);
            } else {
                septa::mesh::certify_regions(&mut r, Some(&grid), Some(grid.bounds));
            }
        }
        Ok(r)
    });
    region_dict(py, &result.map_err(InputError::new_err)?)
}

/// The arrays of region surfaces (`result::view_dict`) with their summary and normals.
pub(crate) fn region_dict<'py>(py: Python<'py>, r: &RegionSurfaces) -> PyResult<Bound<'py, PyDict>> {
    let d = crate::result::view_dict(py, &ResultView::of_regions(r))?;
    d.set_item("summary", septa::io::regions_summary(r).to_string())?;
    if !r.normals.is_empty() {
        let v: Vec<i64> = r.normals.iter().map(|n| n.0 as i64).collect();
        d.set_item("normal_vertex", v.into_pyarray(py))?;
        let g: Vec<i64> = r.normals.iter().flat_map(|n| n.1).collect();
        d.set_item("normal_regions", g.into_pyarray(py).reshape([r.normals.len(), 2])?)?;
        let x: Vec<f64> = r.normals.iter().flat_map(|n| n.2).collect();
        d.set_item("normal_vectors", x.into_pyarray(py).reshape([r.normals.len(), 3])?)?;
        let c: Vec<i64> = septa::io::regions_face_normals(r).into_iter().flatten().map(|c| c as i64).collect();
        d.set_item("indices_normal", c.into_pyarray(py))?;
    }
    Ok(d)
}

/// labels(volume, sigma=0.0, progress=None, affine=None, names=None, certify=True)
/// --
///
/// Exact surfaces between the labels of a segmented volume (`septa labels`):
/// `volume` a 3-axis int64 array (C order, index `[i, j, k]` at grid point
/// `(i, j, k)`), `sigma` an optional Gaussian smoothing of the indicator
/// functions in voxels, `progress(done, total)` called as blocks of the
/// network finish, `affine` the voxel-to-world map (3 rows `[M | t]`; default
/// the identity; the points, the box and so the measures are placed by it, as
/// `septa labels` does), `names` a dict label -> name, `certify` the exact
/// check and repair of the placed doubles (`septa::mesh::place_labels`).
/// Returns the arrays of `regions`; the GIL is released while it is computed.
#[pyfunction]
#[pyo3(signature = (volume, sigma = 0.0, progress = None, affine = None, names = None, certify = true))]
pub fn labels<'py>(
    py: Python<'py>,
    volume: numpy::PyReadonlyArray3<'_, i64>,
    sigma: f64,
    progress: Option<Py<PyAny>>,
    affine: Option<[[f64; 4]; 3]>,
    names: Option<std::collections::BTreeMap<i64, String>>,
    certify: bool,
) -> PyResult<Bound<'py, PyDict>> {
    use numpy::PyUntypedArrayMethods;
    let shape = volume.shape();
    let shape = [shape[0], shape[1], shape[2]];
    let data: Vec<i64> = volume.as_array().iter().copied().collect();
    let progress = progress.map(crate::network::py_progress);
    let affine = affine.unwrap_or([[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]]);
    let result = py.detach(|| {
        let mut r =
            septa::regions::label_surfaces_with_progress(&data, shape, sigma, progress).map_err(|e| e.to_string())?;
        septa::mesh::place_labels(&mut r, shape, &affine, certify)?;
        r.names.regions = names.unwrap_or_default();
        Ok::<_, String>(r)
    });
    region_dict(py, &result.map_err(InputError::new_err)?)
}
