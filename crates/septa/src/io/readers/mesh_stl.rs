//! STL triangle soups (ASCII and binary); corners with bit-identical
//! coordinates are welded into one vertex.

use crate::io::readers::mesh::{parse_f64, IndexedMesh, ReadError};
use std::collections::HashMap;
use std::path::Path;

fn weld(mesh: &mut IndexedMesh, map: &mut HashMap<[u64; 3], u32>, p: [f64; 3]) -> u32 {
    // -0.0 and 0.0 are the same point.
    let key = p.map(|x| if x == 0.0 { 0u64 } else { x.to_bits() });
    *map.entry(key).or_insert_with(|| {
        mesh.vertices.push(p);
        (mesh.vertices.len() - 1) as u32
    })
}

/// Parses STL (binary when the size matches the binary layout, else ASCII).
pub fn parse_stl(path: &Path, bytes: &[u8]) -> Result<IndexedMesh, ReadError> {
    let mut mesh = IndexedMesh::default();
    let mut map = HashMap::new();
    if bytes.len() >= 84 {
        let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
        if bytes.len() == 84 + 50 * n {
            for t in 0..n {
                let base = 84 + 50 * t + 12;
                let mut tri = [0u32; 3];
                for (c, tc) in tri.iter_mut().enumerate() {
                    let mut p = [0.0f64; 3];
                    for (k, pk) in p.iter_mut().enumerate() {
                        let o = base + 12 * c + 4 * k;
                        let v = f32::from_le_bytes([bytes[o], bytes[o + 1], bytes[o + 2], bytes[o + 3]]) as f64;
                        if !v.is_finite() {
                            return Err(ReadError::new(path, 0, format!("triangle {t}: non-finite coordinate")));
                        }
                        *pk = v;
                    }
                    *tc = weld(&mut mesh, &mut map, p);
                }
                mesh.triangles.push(tri);
            }
            return Ok(mesh);
        }
    }
    let text = std::str::from_utf8(bytes).map_err(|_| {
        if bytes.len() >= 84 {
            // binary, but its triangle count does not match its length
            let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
            ReadError::new(
                path,
                0,
                format!(
                    "binary STL whose header says {n} triangles ({} bytes) but the file has {} bytes (truncated or a wrong count)",
                    84 + 50 * n,
                    bytes.len()
                ),
            )
        } else {
            ReadError::new(path, 0, format!("neither binary STL (at least 84 bytes) nor ASCII text ({} bytes)", bytes.len()))
        }
    })?;
    let mut corner = Vec::with_capacity(3);
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let mut it = raw.split_whitespace();
        match it.next() {
            Some("vertex") => {
                let x = parse_f64(path, line, it.next(), "x")?;
                let y = parse_f64(path, line, it.next(), "y")?;
                let z = parse_f64(path, line, it.next(), "z")?;
                corner.push(weld(&mut mesh, &mut map, [x, y, z]));
            }
            Some("endloop") => {
                if corner.len() != 3 {
                    return Err(ReadError::new(path, line, format!("facet with {} vertices (need 3)", corner.len())));
                }
                mesh.triangles.push([corner[0], corner[1], corner[2]]);
                corner.clear();
            }
            _ => {}
        }
    }
    Ok(mesh)
}
