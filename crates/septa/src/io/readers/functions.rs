//! The reference implementation's tet-mesh JSON files. Its function JSON
//! is read by the scene reader (`scene::load_function_list`), the one
//! reader and evaluator of every primitive.

use std::path::Path;

/// Why a reference-format file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum RefError {
    /// File system error.
    #[error("{path}: {source}")]
    Io {
        /// File.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
    /// Bad content.
    #[error("{path}: {message}")]
    Format {
        /// File.
        path: String,
        /// What is wrong, naming the element.
        message: String,
    },
}

fn read_json(path: &Path) -> Result<serde_json::Value, RefError> {
    let p = path.display().to_string();
    let text =
        crate::io::files::input::read_input_text(path).map_err(|source| RefError::Io { path: p.clone(), source })?;
    serde_json::from_str(&text).map_err(|e| RefError::Format { path: p, message: format!("not JSON: {e}") })
}

fn vec3(v: &serde_json::Value) -> Option<[f64; 3]> {
    let a = v.as_array()?;
    if a.len() != 3 {
        return None;
    }
    Some([a[0].as_f64()?, a[1].as_f64()?, a[2].as_f64()?])
}

/// Vertex positions and tets (0-based vertex indices, as read).
pub type MeshData = (Vec<[f64; 3]>, Vec<[i64; 4]>);

/// Reads a tet-mesh JSON `[[[x,y,z], ...], [[v0,v1,v2,v3], ...]]` (0-based).
pub fn read_tet_mesh_json(path: &Path) -> Result<MeshData, RefError> {
    let v = read_json(path)?;
    let bad = |message: String| RefError::Format { path: path.display().to_string(), message };
    let top = v.as_array().filter(|a| a.len() == 2).ok_or_else(|| bad("expected [vertices, tets]".into()))?;
    let verts = top[0].as_array().ok_or_else(|| bad("vertices is not a list".into()))?;
    let mut vertices = Vec::with_capacity(verts.len());
    for (i, p) in verts.iter().enumerate() {
        vertices.push(vec3(p).ok_or_else(|| bad(format!("vertex {i} is not [x, y, z]")))?);
    }
    let tl = top[1].as_array().ok_or_else(|| bad("tets is not a list".into()))?;
    let mut tets = Vec::with_capacity(tl.len());
    for (i, t) in tl.iter().enumerate() {
        let a = t.as_array().filter(|a| a.len() == 4).ok_or_else(|| bad(format!("tet {i} is not 4 indices")))?;
        let mut out = [0i64; 4];
        for (j, x) in a.iter().enumerate() {
            out[j] = x.as_i64().ok_or_else(|| bad(format!("tet {i} index {j} is not an integer")))?;
        }
        tets.push(out);
    }
    Ok((vertices, tets))
}
