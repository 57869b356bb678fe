//! OFF triangle meshes (`OFF`, counts, vertices, `n i j k ...` faces).

use super::mesh::{parse_f64, push_fan, ReadError, TriMesh};
use std::path::Path;

/// Parses OFF text.
pub fn parse_off(path: &Path, bytes: &[u8]) -> Result<TriMesh, ReadError> {
    let text = std::str::from_utf8(bytes).map_err(|e| ReadError::new(path, 0, format!("not UTF-8 text: {e}")))?;
    // Tokens with their line numbers, comments stripped.
    let mut toks: Vec<(usize, &str)> = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let body = raw.split('#').next().unwrap_or("");
        toks.extend(body.split_whitespace().map(|t| (i + 1, t)));
    }
    let mut pos = 0usize;
    let mut next = |what: &str| -> Result<(usize, &str), ReadError> {
        let t = toks.get(pos).copied().ok_or_else(|| ReadError::new(path, 0, format!("file ends before {what}")))?;
        pos += 1;
        Ok(t)
    };
    let (l, head) = next("header")?;
    if !head.ends_with("OFF") {
        return Err(ReadError::new(path, l, "missing OFF header"));
    }
    let mut count = |what: &str| -> Result<usize, ReadError> {
        let (l, t) = next(what)?;
        t.parse().map_err(|_| ReadError::new(path, l, format!("{what} '{t}' is not a count")))
    };
    let nv = count("vertex count")?;
    let nf = count("face count")?;
    let _ne = count("edge count")?;
    let mut mesh = TriMesh::default();
    for _ in 0..nv {
        let mut c = [0.0; 3];
        for (k, ck) in c.iter_mut().enumerate() {
            let (l, t) = next("vertex coordinate")?;
            *ck = parse_f64(path, l, Some(t), ["x", "y", "z"][k])?;
        }
        mesh.vertices.push(c);
    }
    let mut poly = Vec::new();
    for _ in 0..nf {
        let (l, t) = next("face")?;
        let n: usize = t.parse().map_err(|_| ReadError::new(path, l, format!("face size '{t}' is not a count")))?;
        poly.clear();
        for _ in 0..n {
            let (l, t) = next("face index")?;
            let k: usize =
                t.parse().map_err(|_| ReadError::new(path, l, format!("face index '{t}' is not an integer")))?;
            if k >= nv {
                return Err(ReadError::new(path, l, format!("face index {k} out of range (have {nv} vertices)")));
            }
            poly.push(k as u32);
        }
        if n < 3 {
            return Err(ReadError::new(path, l, "face with fewer than 3 corners"));
        }
        push_fan(&mut mesh.triangles, &poly);
    }
    Ok(mesh)
}
