//! The library's one input layer and its output checks, for the Python
//! package's own readers and writers (`septa.load`, `Network.save`): regular
//! files only, a size cap, no link or special file replaced
//! (`septa::io::read_input`, `septa::io::check_output_file`).

use pyo3::prelude::*;
use pyo3::types::PyBytes;
use std::path::Path;

use crate::InputError;

/// read_input(path) -> bytes
/// --
///
/// The bytes of the input file `path`: a regular file (a FIFO, device or
/// folder is refused; `-` is standard input) no larger than the input
/// limit. Raises `septa.InputError` naming the file.
#[pyfunction]
pub fn read_input<'py>(py: Python<'py>, path: &str) -> PyResult<Bound<'py, PyBytes>> {
    let bytes = py
        .detach(|| septa::io::read_input(Path::new(path)))
        .map_err(|e| InputError::new_err(format!("{path}: cannot read: {e}")))?;
    Ok(PyBytes::new(py, &bytes))
}

/// check_input_file(path) -> int
/// --
///
/// Checks that `path` is a regular file (or a link to one) that may be
/// read, and returns the input limit in bytes. Raises `septa.InputError`
/// naming the file.
#[pyfunction]
pub fn check_input_file(path: &str) -> PyResult<u64> {
    septa::io::open_regular(Path::new(path)).map_err(|e| InputError::new_err(format!("{path}: cannot read: {e}")))?;
    Ok(septa::io::input_limit())
}

/// check_output_file(path) -> None
/// --
///
/// Checks that `path` may be replaced by a new regular file: absent or a
/// regular file; a link, FIFO, device or folder is refused with
/// `septa.InputError` naming it.
#[pyfunction]
pub fn check_output_file(path: &str) -> PyResult<()> {
    septa::io::check_output_file(Path::new(path)).map_err(|e| InputError::new_err(e.to_string()))
}
