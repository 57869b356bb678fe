//! Polyhedral `.vtu` files (VTK XML UnstructuredGrid of `VTK_POLYHEDRON`
//! cells): the binary writer behind `cells.vtu` (inline base64, a `UInt64`
//! byte-count header encoded together with the data, as VTK and meshio read
//! it) and a reader of the points and cell faces of any such file, ASCII or
//! binary, so that `septa cut --verify FILE.vtu` can check what was written.

use std::io::Write as _;
use std::path::Path;

const B64: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/// Standard base64 with padding (the tests' view of [`push_base64`]).
#[cfg(test)]
fn base64_encode(bytes: &[u8]) -> String {
    let mut out = Vec::new();
    push_base64(&mut out, bytes);
    String::from_utf8(out).expect("base64 is ASCII")
}

/// Appends the base64 text of `bytes` to `out`: the text is sized first
/// (padding included) and written in place, two 3-byte groups (8 symbols)
/// per step, then the last group and the padded tail (cells.vtu of a large
/// cut is tens of MB of base64).
fn push_base64(out: &mut Vec<u8>, bytes: &[u8]) {
    let start = out.len();
    out.resize(start + bytes.len().div_ceil(3) * 4, b'=');
    let pairs = bytes.len() / 6;
    let (head, rest) = bytes.split_at(pairs * 6);
    let (text_head, text) = out[start..].split_at_mut(pairs * 8);
    for (o, c) in text_head.chunks_exact_mut(8).zip(head.chunks_exact(6)) {
        // the 48 bits in the top of a word, 6 bits a symbol from the top
        let n = u64::from_be_bytes([c[0], c[1], c[2], c[3], c[4], c[5], 0, 0]);
        let sym = |k: u32| B64[(n >> (58 - 6 * k) & 63) as usize];
        o.copy_from_slice(&[sym(0), sym(1), sym(2), sym(3), sym(4), sym(5), sym(6), sym(7)]);
    }
    let sym = |n: u32, k: u32| B64[(n >> (18 - 6 * k) & 63) as usize];
    let whole = rest.chunks_exact(3);
    let tail = whole.remainder();
    for (o, c) in text.chunks_exact_mut(4).zip(whole) {
        let n = (c[0] as u32) << 16 | (c[1] as u32) << 8 | c[2] as u32;
        o.copy_from_slice(&[sym(n, 0), sym(n, 1), sym(n, 2), sym(n, 3)]);
    }
    if !tail.is_empty() {
        let n = (tail[0] as u32) << 16 | (*tail.get(1).unwrap_or(&0) as u32) << 8;
        let last = text.len() - 4;
        // the symbols the tail's bytes reach; the rest stays '='
        for k in 0..=tail.len() {
            text[last + k] = sym(n, k as u32);
        }
    }
}

/// Decodes base64, ignoring whitespace; `None` on a character outside the alphabet.
pub fn base64_decode(s: &str) -> Option<Vec<u8>> {
    let mut out = Vec::with_capacity(s.len() / 4 * 3);
    let (mut acc, mut bits) = (0u32, 0u32);
    for ch in s.bytes() {
        let v = match ch {
            b'A'..=b'Z' => ch - b'A',
            b'a'..=b'z' => ch - b'a' + 26,
            b'0'..=b'9' => ch - b'0' + 52,
            b'+' => 62,
            b'/' => 63,
            b'=' | b' ' | b'\n' | b'\r' | b'\t' => continue,
            _ => return None,
        };
        acc = acc << 6 | v as u32;
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    Some(out)
}

/// One binary `DataArray` element: `block` (from [`block`]) base64-encoded.
fn binary_array(s: &mut Vec<u8>, ty: &str, name: Option<&str>, comps: usize, block: &[u8]) {
    let name = name.map(|n| format!(" Name=\"{n}\"")).unwrap_or_default();
    let comps = if comps > 1 { format!(" NumberOfComponents=\"{comps}\"") } else { String::new() };
    let _ = writeln!(s, "<DataArray type=\"{ty}\"{name}{comps} format=\"binary\">");
    push_base64(s, block);
    s.extend_from_slice(b"\n</DataArray>\n");
}

/// The binary block of one array: its `UInt64` byte count, then the values
/// little-endian (one buffer, encoded as one base64 text).
fn block<T: Copy, const N: usize>(v: &[T], f: impl Fn(T) -> [u8; N]) -> Vec<u8> {
    let mut out = Vec::with_capacity(8 + N * v.len());
    out.extend_from_slice(&((N * v.len()) as u64).to_le_bytes());
    for &x in v {
        out.extend_from_slice(&f(x));
    }
    out
}

/// A binary `.vtu` of polyhedral cells: `points`, each cell a list of
/// outward polygons and its distinct points ascending (`cell_points`),
/// and `Float64` / `Int64` cell data arrays.
pub fn polyhedra_vtu(
    points: &[[f64; 3]],
    cells: &[Vec<&[u32]>],
    cell_points: &[Vec<u32>],
    float_data: &[(&str, &[f64])],
    int_data: &[(&str, &[i64])],
) -> String {
    // bytes, not a String: the base64 goes in place, and the text is
    // checked as UTF-8 once at the end
    let mut s: Vec<u8> = Vec::new();
    s.extend_from_slice(b"<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<UnstructuredGrid>\n");
    let _ = writeln!(s, "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">", points.len(), cells.len());
    s.extend_from_slice(b"<Points>\n");
    let flat: Vec<f64> = points.iter().flatten().copied().collect();
    binary_array(&mut s, "Float64", None, 3, &block(&flat, f64::to_le_bytes));
    s.extend_from_slice(b"</Points>\n<Cells>\n");
    let (mut conn, mut offsets, mut faces, mut face_offsets) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (c, used) in cells.iter().zip(cell_points) {
        conn.extend(used.iter().map(|&v| v as i64));
        offsets.push(conn.len() as i64);
        faces.push(c.len() as i64);
        for p in c.iter() {
            faces.push(p.len() as i64);
            faces.extend(p.iter().map(|&v| v as i64));
        }
        face_offsets.push(faces.len() as i64);
    }
    binary_array(&mut s, "Int64", Some("connectivity"), 1, &block(&conn, i64::to_le_bytes));
    binary_array(&mut s, "Int64", Some("offsets"), 1, &block(&offsets, i64::to_le_bytes));
    binary_array(&mut s, "UInt8", Some("types"), 1, &block(&vec![42u8; cells.len()], |t| [t]));
    binary_array(&mut s, "Int64", Some("faces"), 1, &block(&faces, i64::to_le_bytes));
    binary_array(&mut s, "Int64", Some("faceoffsets"), 1, &block(&face_offsets, i64::to_le_bytes));
    s.extend_from_slice(b"</Cells>\n<CellData>\n");
    for (name, v) in int_data {
        binary_array(&mut s, "Int64", Some(name), 1, &block(v, i64::to_le_bytes));
    }
    for (name, v) in float_data {
        binary_array(&mut s, "Float64", Some(name), 1, &block(v, f64::to_le_bytes));
    }
    s.extend_from_slice(b"</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
    String::from_utf8(s).expect("a .vtu text is ASCII")
}

/// `v` as an index below `n`: a whole, non-negative number less than `n`.
fn whole(v: f64, n: usize) -> Option<usize> {
    (v >= 0.0 && v.fract() == 0.0 && v < n as f64).then_some(v as usize)
}

/// Points and cells (outward polygons) of a polyhedral `.vtu`.
pub type Polyhedra = (Vec<[f64; 3]>, Vec<Vec<Vec<u32>>>);

/// Reads the points and the `VTK_POLYHEDRON` cells of a `.vtu` (ASCII or
/// inline binary with `UInt32`/`UInt64` headers, uncompressed). Errors name
/// the file and what is missing or wrong.
pub fn read_polyhedra(path: &Path) -> Result<Polyhedra, String> {
    let err = |m: String| format!("{}: {m}", path.display());
    let text = crate::io::files::input::read_input_text(path).map_err(|e| err(format!("cannot read: {e}")))?;
    let compressed = text.contains("compressor=");
    let header64 = !text.contains("header_type=\"UInt32\"");
    // (opening tag, content) of every DataArray, in file order
    let mut arrays: Vec<(&str, &str)> = Vec::new();
    let mut rest = text.as_str();
    while let Some(i) = rest.find("<DataArray") {
        let tag_end = rest[i..].find('>').ok_or_else(|| err("unterminated DataArray tag".into()))? + i;
        let close = rest[tag_end..].find("</DataArray>").ok_or_else(|| err("DataArray without end".into()))? + tag_end;
        let mut body = &rest[tag_end + 1..close];
        // VTK writes <InformationKey> elements (range metadata) next to the
        // values, after them (or before): keep the text outside the elements
        if let (Some(a), Some(b)) = (body.find('<'), body.rfind('>')) {
            body = if body[..a].trim().is_empty() { &body[b + 1..] } else { &body[..a] };
        }
        arrays.push((&rest[i..tag_end], body));
        rest = &rest[close..];
    }
    let attr = |tag: &str, key: &str| -> Option<String> {
        let k = format!(" {key}=\"");
        let i = tag.find(&k)? + k.len();
        Some(tag[i..i + tag[i..].find('"')?].to_string())
    };
    let values = |(tag, body): (&str, &str)| -> Result<Vec<f64>, String> {
        let ty = attr(tag, "type").unwrap_or_default();
        if attr(tag, "format").as_deref() != Some("binary") {
            return body
                .split_ascii_whitespace()
                .map(|t| t.parse::<f64>().map_err(|_| err(format!("'{t}' is not a number in {tag}>"))))
                .collect();
        }
        if compressed {
            return Err(err("compressed binary .vtu is not supported (write it uncompressed or ASCII)".into()));
        }
        let bytes = base64_decode(body).ok_or_else(|| err(format!("bad base64 in {tag}>")))?;
        let h = if header64 { 8 } else { 4 };
        let data = bytes.get(h..).ok_or_else(|| err(format!("short binary block in {tag}>")))?;
        let w = match ty.as_str() {
            "Float64" | "Int64" | "UInt64" => 8,
            "Float32" | "Int32" | "UInt32" => 4,
            "Int16" | "UInt16" => 2,
            "Int8" | "UInt8" => 1,
            _ => return Err(err(format!("unsupported type '{ty}'"))),
        };
        Ok(data
            .chunks_exact(w)
            .map(|c| match ty.as_str() {
                "Float64" => f64::from_le_bytes(c.try_into().unwrap()),
                "Int64" => i64::from_le_bytes(c.try_into().unwrap()) as f64,
                "UInt64" => u64::from_le_bytes(c.try_into().unwrap()) as f64,
                "Float32" => f32::from_le_bytes(c.try_into().unwrap()) as f64,
                "Int32" => i32::from_le_bytes(c.try_into().unwrap()) as f64,
                "UInt32" => u32::from_le_bytes(c.try_into().unwrap()) as f64,
                "Int16" => i16::from_le_bytes(c.try_into().unwrap()) as f64,
                "UInt16" => u16::from_le_bytes(c.try_into().unwrap()) as f64,
                "Int8" => c[0] as i8 as f64,
                _ => c[0] as f64,
            })
            .collect())
    };
    let pts_at = text.find("<Points>").ok_or_else(|| err("no <Points>".into()))?;
    let pts_tag = arrays
        .iter()
        .find(|(t, _)| t.as_ptr() as usize > text.as_ptr() as usize + pts_at)
        .ok_or_else(|| err("no points array".into()))?;
    let flat = values(*pts_tag)?;
    if flat.len() % 3 != 0 {
        return Err(err("points array length is not a multiple of 3".into()));
    }
    let points: Vec<[f64; 3]> = flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    // the exact check reasons about finite doubles only: a point at
    // infinity or NaN would be read as geometry it is not
    if let Some((i, p)) = points.iter().enumerate().find(|(_, p)| !p.iter().all(|c| c.is_finite())) {
        return Err(err(format!("point {i} has a non-finite coordinate ({}, {}, {})", p[0], p[1], p[2])));
    }
    let named = |n: &str| -> Result<Vec<f64>, String> {
        let a = arrays
            .iter()
            .find(|(t, _)| attr(t, "Name").as_deref() == Some(n))
            .ok_or_else(|| err(format!("no '{n}' array (not a polyhedral .vtu)")))?;
        values(*a)
    };
    let types = named("types")?;
    let np = points.len();
    // an index is a whole number in range: `nan` or `0.7` is not point 0
    let check_point = |c: usize, v: f64| -> Result<u32, String> {
        match whole(v, np) {
            Some(i) => Ok(i as u32),
            None => Err(err(format!("cell {c} refers to point {v}, not one of the {np} points (0..{np})"))),
        }
    };
    for (c, &t) in types.iter().enumerate() {
        if t != 42.0 {
            return Err(err(format!("cell {c} has VTK type {t}, not a polyhedron (42)")));
        }
    }
    let mut cells = Vec::with_capacity(types.len());
    if arrays.iter().all(|(t, _)| attr(t, "Name").as_deref() != Some("faces")) {
        // VTK >= 9.4 layout: face_connectivity / face_offsets (end of each
        // face), polyhedron_to_faces / polyhedron_offsets (end of each cell)
        let (fc, fo) = (named("face_connectivity")?, named("face_offsets")?);
        let (pf, po) = (named("polyhedron_to_faces")?, named("polyhedron_offsets")?);
        let mut start = 0usize;
        for (c, &end) in po.iter().enumerate() {
            let mut polys = Vec::new();
            let end = whole(end, pf.len() + 1).ok_or_else(|| err(format!("cell {c}: polyhedron_offsets {end}")))?;
            for &f in pf.get(start..end).ok_or_else(|| err(format!("cell {c}: bad polyhedron_offsets")))? {
                let f = whole(f, fo.len()).ok_or_else(|| err(format!("cell {c}: face {f} missing")))?;
                let offset = |v: f64| whole(v, fc.len() + 1).ok_or_else(|| err(format!("cell {c}: face_offsets {v}")));
                let a = if f == 0 { 0 } else { offset(fo[f - 1])? };
                let b = offset(fo[f])?;
                let ids = fc.get(a..b).ok_or_else(|| err(format!("cell {c}: face {f} out of range")))?;
                polys.push(ids.iter().map(|&v| check_point(c, v)).collect::<Result<Vec<u32>, String>>()?);
            }
            cells.push(polys);
            start = end;
        }
        if cells.len() != types.len() {
            return Err(err(format!("{} polyhedra for {} cells", cells.len(), types.len())));
        }
        return Ok((points, cells));
    }
    let faces = named("faces")?;
    let mut i = 0usize;
    let mut next = |what: &str| -> Result<f64, String> {
        let v = *faces.get(i).ok_or_else(|| err(format!("faces stream ends inside {what}")))?;
        i += 1;
        Ok(v)
    };
    // counts are checked against what the stream has left before anything
    // is reserved (a face count of 1e19 was a capacity overflow)
    let left = faces.len();
    for c in 0..types.len() {
        let nf = next("a cell")?;
        let nf = whole(nf, left + 1).ok_or_else(|| err(format!("cell {c}: face count {nf} is not possible here")))?;
        let mut polys = Vec::with_capacity(nf);
        for _ in 0..nf {
            let nv = next("a face")?;
            let nv =
                whole(nv, left + 1).ok_or_else(|| err(format!("cell {c}: face size {nv} is not possible here")))?;
            let mut p = Vec::with_capacity(nv);
            for _ in 0..nv {
                p.push(check_point(c, next("a face")?)?);
            }
            polys.push(p);
        }
        cells.push(polys);
    }
    Ok((points, cells))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_round_trip() {
        for n in 0..40usize {
            let b: Vec<u8> = (0..n as u8).map(|i| i.wrapping_mul(97).wrapping_add(13)).collect();
            let text = base64_encode(&b);
            assert_eq!(text.len(), n.div_ceil(3) * 4);
            assert_eq!(base64_decode(&text).unwrap(), b);
        }
        // every 6-bit value in every symbol position of a two-group step
        let b: Vec<u8> = (0..=255u8).chain((0..=255u8).rev()).collect();
        assert_eq!(base64_decode(&base64_encode(&b)).unwrap(), b);
        assert_eq!(base64_encode(b"Many hands"), "TWFueSBoYW5kcw==");
        assert_eq!(base64_encode(b"Man"), "TWFu");
        assert_eq!(base64_encode(b"Ma"), "TWE=");
        assert_eq!(base64_encode(b"M"), "TQ==");
        assert_eq!(base64_encode(b""), "");
    }
}
