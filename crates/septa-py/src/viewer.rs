//! The built browser viewer, embedded (the same committed bundle that the
//! `septa view` command embeds), so `septa.view` needs no node.
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};

const INDEX_HTML: &str = include_str!("../../../viewer/dist/index.html");
const VIEWER_JS: &str = include_str!("../../../viewer/dist/viewer.js");

/// viewer_assets()
/// --
///
/// The viewer's static files as `{file name: bytes}`: `index.html` and the
/// bundled `viewer.js` (three.js included). `septa.view` adds `data.js`.
#[pyfunction]
pub fn viewer_assets(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("index.html", PyBytes::new(py, INDEX_HTML.as_bytes()))?;
    d.set_item("viewer.js", PyBytes::new(py, VIEWER_JS.as_bytes()))?;
    Ok(d)
}
