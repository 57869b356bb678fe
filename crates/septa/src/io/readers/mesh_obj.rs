//! Wavefront OBJ triangle meshes (`v x y z`, `f i j k` with 1-based or
//! negative indices, `i/t/n` corners; polygons are fanned).

use crate::io::readers::mesh::{parse_f64, push_fan, IndexedMesh, ReadError};
use std::path::Path;

/// Parses OBJ text.
pub fn parse_obj(path: &Path, bytes: &[u8]) -> Result<IndexedMesh, ReadError> {
    let text = std::str::from_utf8(bytes).map_err(|e| ReadError::new(path, 0, format!("not UTF-8 text: {e}")))?;
    let mut mesh = IndexedMesh::default();
    let mut poly: Vec<u32> = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let mut it = raw.split_ascii_whitespace();
        match it.next() {
            Some("v") => {
                let x = parse_f64(path, line, it.next(), "x")?;
                let y = parse_f64(path, line, it.next(), "y")?;
                let z = parse_f64(path, line, it.next(), "z")?;
                mesh.vertices.push([x, y, z]);
            }
            Some("f") => {
                poly.clear();
                for tok in it {
                    let idx = tok.split('/').next().unwrap_or("");
                    let k: i64 = idx
                        .parse()
                        .map_err(|_| ReadError::new(path, line, format!("face index '{tok}' is not an integer")))?;
                    let n = mesh.vertices.len() as i64;
                    let k0 = if k > 0 {
                        k - 1
                    } else if k < 0 {
                        n + k
                    } else {
                        -1
                    };
                    if k0 < 0 || k0 >= n {
                        return Err(ReadError::new(
                            path,
                            line,
                            format!("face index {k} out of range (have {n} vertices)"),
                        ));
                    }
                    poly.push(k0 as u32);
                }
                if poly.len() < 3 {
                    return Err(ReadError::new(path, line, "face with fewer than 3 corners"));
                }
                push_fan(&mut mesh.triangles, &poly);
            }
            _ => {}
        }
    }
    Ok(mesh)
}
