//! The browser viewer: the library's one writer (`septa::io::write_viewer`,
//! the one `septa view` uses), with the bundle embedded in the library, so
//! `septa.view` needs no node.
use crate::InputError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use septa::io::ViewerError;
use std::path::PathBuf;

/// A viewer failure: I/O as `OSError` (with its errno), bad results as `septa.InputError`.
fn raise(e: ViewerError) -> PyErr {
    match e {
        ViewerError::Io { path, source } => {
            let msg = format!("{}: {source}", path.display());
            match source.raw_os_error() {
                Some(errno) => pyo3::exceptions::PyOSError::new_err((errno, msg)),
                None => pyo3::exceptions::PyOSError::new_err(msg),
            }
        }
        e => InputError::new_err(e.to_string()),
    }
}

fn parse(network: &str) -> PyResult<serde_json::Value> {
    serde_json::from_str(network).map_err(|e| InputError::new_err(format!("network: invalid JSON: {e}")))
}

/// viewer_assets()
/// --
///
/// The viewer's static files as `{file name: bytes}`: `index.html` and the
/// bundled `viewer.js` (three.js included).
#[pyfunction]
pub fn viewer_assets(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("index.html", PyBytes::new(py, septa::io::VIEWER_INDEX_HTML.as_bytes()))?;
    d.set_item("viewer.js", PyBytes::new(py, septa::io::VIEWER_JS.as_bytes()))?;
    Ok(d)
}

/// viewer_write(folder, network, title)
/// --
///
/// Writes `folder/{data.js, viewer.js, index.html}` for `network` (the
/// `network.json` contract as JSON text); returns the path of index.html.
#[pyfunction]
pub fn viewer_write(py: Python<'_>, folder: PathBuf, network: &str, title: &str) -> PyResult<PathBuf> {
    let network = parse(network)?;
    py.detach(|| septa::io::write_viewer(&folder, title, &network, None)).map_err(raise)
}

/// viewer_write_result(result, title, folder=None)
/// --
///
/// Writes the viewer of a result folder (or a stream's `OUT.ply` / `OUT.vtu`)
/// exactly as `septa view` does, into `folder` (default: `viewer/` beside
/// the result); returns the path of index.html.
#[pyfunction]
#[pyo3(signature = (result, title, folder = None))]
pub fn viewer_write_result(py: Python<'_>, result: PathBuf, title: &str, folder: Option<PathBuf>) -> PyResult<PathBuf> {
    py.detach(|| septa::io::write_result_viewer(&result, title, folder.as_deref())).map_err(raise)
}

/// viewer_page(network, title)
/// --
///
/// The viewer for `network` (JSON text) as one self-contained HTML page.
#[pyfunction]
pub fn viewer_page(network: &str, title: &str) -> PyResult<String> {
    Ok(septa::io::viewer_inline_page(title, &parse(network)?, None))
}
