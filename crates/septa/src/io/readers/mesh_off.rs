//! OFF triangle meshes (`OFF`, counts, vertices, `n i j k ...` faces).

use crate::io::readers::mesh::{parse_f64, push_fan, IndexedMesh, ReadError};
use std::path::Path;

/// Parses OFF text: `OFF` and its variants with per-vertex colours, normals
/// or texture coordinates (`COFF`, `NOFF`, `CNOFF`, `STOFF`, ...: the first
/// three numbers of a vertex line are its position) and per-face colours (a
/// face line is `n i1 .. in` followed by optional colour numbers, ignored).
/// Before: COFF face colours were read as indices ("face index 255").
pub fn parse_off(path: &Path, bytes: &[u8]) -> Result<IndexedMesh, ReadError> {
    let text = std::str::from_utf8(bytes).map_err(|e| ReadError::new(path, 0, format!("not UTF-8 text: {e}")))?;
    // Non-empty lines with their numbers, comments stripped.
    let mut lines = text.lines().enumerate().filter_map(|(i, raw)| {
        let body = raw.split('#').next().unwrap_or("").trim();
        (!body.is_empty()).then_some((i + 1, body))
    });
    let (l, first) = lines.next().ok_or_else(|| ReadError::new(path, 0, "empty file: missing OFF header"))?;
    let mut head = first.split_whitespace();
    let kw = head.next().unwrap_or("");
    if !kw.ends_with("OFF") || kw.starts_with('4') || kw.contains("n") {
        return Err(ReadError::new(path, l, format!("missing OFF header (found '{kw}'; 3D [ST][C][N]OFF expected)")));
    }
    // The counts follow on the header line or on the next line.
    let rest: Vec<&str> = head.collect();
    let (l, counts) = if rest.is_empty() {
        let (l, line) = lines.next().ok_or_else(|| ReadError::new(path, 0, "file ends before the counts"))?;
        (l, line.split_whitespace().collect::<Vec<_>>())
    } else {
        (l, rest)
    };
    let count = |k: usize, what: &str| -> Result<usize, ReadError> {
        let t = counts.get(k).ok_or_else(|| ReadError::new(path, l, format!("missing {what}")))?;
        t.parse().map_err(|_| ReadError::new(path, l, format!("{what} '{t}' is not a count")))
    };
    let nv = count(0, "vertex count")?;
    let nf = count(1, "face count")?;
    let mut mesh = IndexedMesh::default();
    for v in 0..nv {
        let (l, line) =
            lines.next().ok_or_else(|| ReadError::new(path, 0, format!("file ends before vertex {v} of {nv}")))?;
        let mut t = line.split_whitespace();
        let mut c = [0.0; 3];
        for (k, ck) in c.iter_mut().enumerate() {
            *ck = parse_f64(path, l, t.next(), ["x", "y", "z"][k])?;
        }
        mesh.vertices.push(c);
    }
    let mut poly = Vec::new();
    for f in 0..nf {
        let (l, line) =
            lines.next().ok_or_else(|| ReadError::new(path, 0, format!("file ends before face {f} of {nf}")))?;
        let mut t = line.split_whitespace();
        let size = t.next().unwrap_or("");
        let n: usize =
            size.parse().map_err(|_| ReadError::new(path, l, format!("face {f}: size '{size}' is not a count")))?;
        if n < 3 {
            return Err(ReadError::new(path, l, format!("face {f} has {n} corners, at least 3 are needed")));
        }
        poly.clear();
        for _ in 0..n {
            let tok = t.next().ok_or_else(|| ReadError::new(path, l, format!("face {f}: fewer than {n} indices")))?;
            let k: usize = tok
                .parse()
                .map_err(|_| ReadError::new(path, l, format!("face {f}: index '{tok}' is not an integer")))?;
            if k >= nv {
                return Err(ReadError::new(path, l, format!("face {f}: index {k} out of range (have {nv} vertices)")));
            }
            poly.push(k as u32);
        }
        push_fan(&mut mesh.triangles, &poly);
    }
    Ok(mesh)
}
