//! The reference implementation's tet-mesh JSON and function JSON files.
//!
//! Function evaluation proper lives in `scene/`; this reader evaluates the
//! primitives whose values are needed to switch from the reference
//! (`sphere`, `plane`, `zero`) and names any other type in its error.

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
    let text = std::fs::read_to_string(path).map_err(|source| RefError::Io { path: p.clone(), source })?;
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

/// The box grid of a reference config: `gridResolution` (a whole number
/// >= 1) and `gridBbox` (`[[x0, y0, z0], [x1, y1, z1]]`, finite), each
/// `None` when absent. A key that is present but malformed is an error
/// naming it (issue 14: a 2-number corner was ignored and the default box
/// used).
pub fn config_grid(
    cfg: &serde_json::Map<String, serde_json::Value>,
    path: &Path,
) -> Result<(Option<usize>, Option<[[f64; 3]; 2]>), RefError> {
    let bad = |message: String| RefError::Format { path: path.display().to_string(), message };
    let res = match cfg.get("gridResolution") {
        None => None,
        Some(r) => match r.as_u64() {
            Some(n) if n >= 1 => Some(n as usize),
            _ => return Err(bad(format!("\"gridResolution\": expected a whole number >= 1, not {r}"))),
        },
    };
    let bbox = match cfg.get("gridBbox") {
        None => None,
        Some(b) => {
            let corners = b.as_array().filter(|a| a.len() == 2).ok_or_else(|| {
                bad(format!("\"gridBbox\": expected [[x0, y0, z0], [x1, y1, z1]], not {b}"))
            })?;
            let mut out = [[0.0; 3]; 2];
            for (i, c) in corners.iter().enumerate() {
                out[i] = vec3(c).filter(|p| p.iter().all(|x| x.is_finite())).ok_or_else(|| {
                    bad(format!("\"gridBbox\" corner {i}: expected 3 finite numbers [x, y, z], not {c}"))
                })?;
            }
            Some(out)
        }
    };
    Ok((res, bbox))
}

/// A primitive of the reference's function JSON that this reader evaluates.
#[derive(Clone, Debug, PartialEq)]
pub enum Primitive {
    /// `r - |p - c|`.
    Sphere {
        /// Centre.
        center: [f64; 3],
        /// Radius.
        radius: f64,
    },
    /// `(p - point) . normal`.
    Plane {
        /// A point on the plane.
        point: [f64; 3],
        /// Normal.
        normal: [f64; 3],
    },
    /// Constant 0.
    Zero,
}

impl Primitive {
    /// Value at `p`.
    pub fn eval(&self, p: &[f64; 3]) -> f64 {
        match self {
            Primitive::Sphere { center, radius } => {
                let d = [p[0] - center[0], p[1] - center[1], p[2] - center[2]];
                radius - (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
            }
            Primitive::Plane { point, normal } => {
                (p[0] - point[0]) * normal[0] + (p[1] - point[1]) * normal[1] + (p[2] - point[2]) * normal[2]
            }
            Primitive::Zero => 0.0,
        }
    }
}

/// Parses a function list (the reference's function JSON, or `spec_json` of the test inputs).
pub fn parse_functions(text: &str, path: &str) -> Result<Vec<Primitive>, RefError> {
    let bad = |message: String| RefError::Format { path: path.to_string(), message };
    let v: serde_json::Value = serde_json::from_str(text).map_err(|e| bad(format!("not JSON: {e}")))?;
    let list = v.as_array().ok_or_else(|| bad("expected a list of functions".into()))?;
    let mut out = Vec::with_capacity(list.len());
    for (i, f) in list.iter().enumerate() {
        let ty = f["type"].as_str().ok_or_else(|| bad(format!("function {i} has no \"type\"")))?;
        let num = |k: &str| f[k].as_f64().ok_or_else(|| bad(format!("function {i} ({ty}): missing number \"{k}\"")));
        let v3 = |k: &str| vec3(&f[k]).ok_or_else(|| bad(format!("function {i} ({ty}): missing [x, y, z] \"{k}\"")));
        out.push(match ty {
            "sphere" => Primitive::Sphere { center: v3("center")?, radius: num("radius")? },
            "plane" => Primitive::Plane { point: v3("point")?, normal: v3("normal")? },
            "zero" => Primitive::Zero,
            other => return Err(bad(format!("function {i}: type \"{other}\" is not supported by this reader"))),
        });
    }
    Ok(out)
}

/// Reads a function JSON file.
pub fn read_functions(path: &Path) -> Result<Vec<Primitive>, RefError> {
    let text =
        std::fs::read_to_string(path).map_err(|source| RefError::Io { path: path.display().to_string(), source })?;
    parse_functions(&text, &path.display().to_string())
}

/// Values `out[v * k + f]` of the functions at the vertices of `grid`,
/// without materialising the vertex positions (memory: the values only).
pub fn sample_grid(functions: &[Primitive], grid: &crate::grid::Grid) -> Vec<f64> {
    let n = grid.num_vertices();
    let mut out = Vec::with_capacity(n * functions.len());
    for v in 0..n as u32 {
        let p = grid.vertex(v);
        for f in functions {
            out.push(f.eval(&p));
        }
    }
    out
}

/// Values `out[v * k + f]` of the functions at the given points.
pub fn sample(functions: &[Primitive], points: &[[f64; 3]]) -> Vec<f64> {
    let mut out = Vec::with_capacity(points.len() * functions.len());
    for p in points {
        for f in functions {
            out.push(f.eval(p));
        }
    }
    out
}
