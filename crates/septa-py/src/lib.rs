//! `septa._septa`: the compiled core of the `septa` Python package.
//!
//! A thin layer (STYLE.md habit 12): one Rust file per idea, inputs coerced
//! once to contiguous numpy arrays of fixed dtype, the GIL released around
//! work, Rust errors raised as `septa.InputError` (a `ValueError`), internal
//! failures of the library as `RuntimeError` ([`Failure`]). The
//! user-facing API, docstrings and result classes live in `python/septa/`.
#![warn(missing_docs)]

use pyo3::prelude::*;

mod checks;
mod continuation;
mod cut;
mod distributed;
mod files;
mod interrupt;
mod network;
mod regions;
mod remesh;
mod result;
mod shapes;
mod stream;
mod viewer;

pyo3::create_exception!(
    _septa,
    InputError,
    pyo3::exceptions::PyValueError,
    "Bad input: the message names what is wrong and where (array, vertex, function, file, line)."
);

/// Why a call failed: bad input (raised as `septa.InputError`) or an
/// internal failure of the library that checked input cannot cause (raised
/// as `RuntimeError`, so that callers catching `ValueError` for their own
/// mistakes do not swallow a bug).
#[derive(Debug)]
pub(crate) enum Failure {
    /// Bad input; the message names it.
    Input(String),
    /// An internal failure.
    Internal(String),
}

impl From<String> for Failure {
    fn from(m: String) -> Failure {
        Failure::Input(m)
    }
}

impl From<Failure> for PyErr {
    fn from(f: Failure) -> PyErr {
        match f {
            Failure::Input(m) => InputError::new_err(m),
            Failure::Internal(m) => pyo3::exceptions::PyRuntimeError::new_err(m),
        }
    }
}

/// A library error as a [`Failure`]: the network's internal variant (and a
/// region or job error wrapping it) is internal, everything else input.
pub(crate) fn failure<E: std::error::Error + 'static>(e: E) -> Failure {
    let any: &dyn std::any::Any = &e;
    let net = any.downcast_ref::<septa::network::NetworkError>().or_else(|| match any.downcast_ref() {
        Some(septa::regions::RegionError::Network(n)) => Some(n),
        _ => None,
    });
    if net.is_some_and(|n| n.is_internal()) {
        Failure::Internal(e.to_string())
    } else {
        Failure::Input(e.to_string())
    }
}

/// `"ia"` or `"mi"` as a [`septa::complex::Mode`].
pub(crate) fn parse_mode(m: &str) -> Result<septa::complex::Mode, String> {
    match m {
        "ia" => Ok(septa::complex::Mode::Ia),
        "mi" => Ok(septa::complex::Mode::Mi),
        m => Err(format!("mode must be \"ia\" or \"mi\", not {m:?}")),
    }
}

/// Runs `work` on a pool of `threads` threads, or on rayon's global pool.
pub(crate) fn on_threads<T: Send, E: From<String> + Send>(
    threads: Option<usize>,
    work: impl FnOnce() -> Result<T, E> + Send,
) -> Result<T, E> {
    match threads {
        // Checked here as well as in Python: `threads=10**6` must not try
        // to start a million threads.
        Some(t) if t == 0 || t > 1024 => Err(format!("threads: {t} is out of range 1..=1024").into()),
        Some(t) => rayon::ThreadPoolBuilder::new()
            .num_threads(t.max(1))
            .build()
            .map_err(|e| E::from(e.to_string()))?
            .install(work),
        None => work(),
    }
}

/// The compiled core of the `septa` package.
#[pymodule]
fn _septa(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("InputError", m.py().get_type::<InputError>())?;
    m.add_function(wrap_pyfunction!(checks::check_values, m)?)?;
    m.add_function(wrap_pyfunction!(files::read_input, m)?)?;
    m.add_function(wrap_pyfunction!(files::check_input_file, m)?)?;
    m.add_function(wrap_pyfunction!(files::check_output_file, m)?)?;
    m.add_function(wrap_pyfunction!(checks::check_tets, m)?)?;
    m.add_function(wrap_pyfunction!(viewer::viewer_assets, m)?)?;
    m.add_function(wrap_pyfunction!(viewer::viewer_write, m)?)?;
    m.add_function(wrap_pyfunction!(viewer::viewer_write_result, m)?)?;
    m.add_function(wrap_pyfunction!(viewer::viewer_page, m)?)?;
    m.add_function(wrap_pyfunction!(shapes::box_grid, m)?)?;
    m.add_function(wrap_pyfunction!(shapes::sample_functions, m)?)?;
    m.add_function(wrap_pyfunction!(network::network, m)?)?;
    m.add_function(wrap_pyfunction!(regions::regions, m)?)?;
    m.add_function(wrap_pyfunction!(regions::labels, m)?)?;
    m.add_function(wrap_pyfunction!(result::write_result, m)?)?;
    m.add_function(wrap_pyfunction!(remesh::remesh, m)?)?;
    m.add_function(wrap_pyfunction!(cut::cut, m)?)?;
    m.add_class::<cut::CutResult>()?;
    m.add_function(wrap_pyfunction!(continuation::continuation, m)?)?;
    m.add_function(wrap_pyfunction!(continuation::continuation_seeds_py, m)?)?;
    m.add_function(wrap_pyfunction!(continuation::continuation_blocks, m)?)?;
    m.add_function(wrap_pyfunction!(continuation::continuation_finish, m)?)?;
    m.add_function(wrap_pyfunction!(distributed::sparse_plan, m)?)?;
    m.add_function(wrap_pyfunction!(distributed::sparse_blocks, m)?)?;
    m.add_function(wrap_pyfunction!(distributed::sparse_finish, m)?)?;
    m.add_function(wrap_pyfunction!(distributed::sparse_finish_regions, m)?)?;
    m.add_function(wrap_pyfunction!(distributed::sparse_network, m)?)?;
    m.add_function(wrap_pyfunction!(stream::stream_ply, m)?)?;
    m.add_class::<stream::StreamWriter>()?;
    Ok(())
}
