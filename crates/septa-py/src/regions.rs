//! `septa.region_surfaces`: the surfaces and curves of interest of a scene's
//! region rule (Bloomenthal's non-manifold model on the exact network).
use crate::InputError;
use pyo3::prelude::*;
use septa::regions::{region_surfaces, RegionOptions};
use septa::scene::Scene;

/// regions(scene, normals=False, clean=None)
/// --
///
/// `scene` is a scene file path, `builtin:NAME`, or scene JSON text
/// (starting with `{`). Returns the `network.json` document as JSON text
/// (`mode` "regions"; `patches` are the surfaces with their region pairs,
/// `chains` the curves); the GIL is released while it is computed.
#[pyfunction]
#[pyo3(signature = (scene, normals = false, clean = None))]
pub fn regions(py: Python<'_>, scene: &str, normals: bool, clean: Option<f64>) -> PyResult<String> {
    if let Some(f) = clean {
        if !(f.is_finite() && f >= 0.0) {
            return Err(InputError::new_err(format!("clean: expected a factor >= 0, not {f}")));
        }
    }
    let result: Result<String, String> = py.detach(|| {
        let s = if scene.trim_start().starts_with('{') {
            Scene::from_json(scene, "<scene>", None)
        } else {
            Scene::load(scene)
        }
        .map_err(|e| e.to_string())?;
        let r =
            region_surfaces(&s, &RegionOptions { normals, clean, ..Default::default() }).map_err(|e| e.to_string())?;
        Ok(septa::io::regions_out::document(&r).to_string())
    });
    result.map_err(InputError::new_err)
}

/// labels(volume, sigma=0.0)
/// --
///
/// Exact surfaces between the labels of a segmented volume (`septa labels`):
/// `volume` a 3-axis int64 array (C order, index `[i, j, k]` at grid point
/// `(i, j, k)`), `sigma` an optional Gaussian smoothing of the indicator
/// functions in voxels. Returns the region-surfaces `network.json` document
/// as JSON text; the GIL is released while it is computed.
#[pyfunction]
#[pyo3(signature = (volume, sigma = 0.0))]
pub fn labels(py: Python<'_>, volume: numpy::PyReadonlyArray3<'_, i64>, sigma: f64) -> PyResult<String> {
    use numpy::PyUntypedArrayMethods;
    let shape = volume.shape();
    let shape = [shape[0], shape[1], shape[2]];
    let data: Vec<i64> = volume.as_array().iter().copied().collect();
    let result: Result<String, String> = py.detach(|| {
        let r = septa::regions::label_surfaces(&data, shape, sigma).map_err(|e| e.to_string())?;
        Ok(septa::io::regions_out::document(&r).to_string())
    });
    result.map_err(InputError::new_err)
}
