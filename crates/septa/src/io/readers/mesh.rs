//! Triangle meshes as read from files, the error every reader returns, and
//! the parsing helpers the readers of each format share.

use std::path::{Path, PathBuf};

/// A triangle mesh as read: vertex coordinates and 0-based triangles.
#[derive(Clone, Debug, Default)]
pub struct IndexedMesh {
    /// Vertex coordinates.
    pub vertices: Vec<[f64; 3]>,
    /// Triangles as 0-based vertex indices.
    pub triangles: Vec<[u32; 3]>,
}

/// A file that could not be read as a mesh or plane list.
#[derive(Debug, thiserror::Error)]
#[error("{path}:{line}: {message}")]
pub struct ReadError {
    /// The file.
    pub path: PathBuf,
    /// 1-based line number (0 when not line-based, e.g. binary files).
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

impl ReadError {
    pub(crate) fn new(path: &Path, line: usize, message: impl Into<String>) -> ReadError {
        ReadError { path: path.to_path_buf(), line, message: message.into() }
    }
}

/// Parses one finite double, naming the file and line on failure.
pub(crate) fn parse_f64(path: &Path, line: usize, tok: Option<&str>, what: &str) -> Result<f64, ReadError> {
    let tok = tok.ok_or_else(|| ReadError::new(path, line, format!("missing {what}")))?;
    let v: f64 = tok.parse().map_err(|_| ReadError::new(path, line, format!("{what} '{tok}' is not a number")))?;
    if !v.is_finite() {
        return Err(ReadError::new(path, line, format!("{what} '{tok}' is not finite")));
    }
    Ok(v)
}

/// Splits a polygon into a triangle fan (faces with more than three corners).
pub(crate) fn push_fan(out: &mut Vec<[u32; 3]>, poly: &[u32]) {
    for k in 1..poly.len().saturating_sub(1) {
        out.push([poly[0], poly[k], poly[k + 1]]);
    }
}
