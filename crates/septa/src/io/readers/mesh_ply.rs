//! PLY triangle meshes (ascii, binary little and big endian): `vertex`
//! element with `x y z`, `face` element with a vertex index list.

use crate::io::readers::mesh::{push_fan, IndexedMesh, ReadError};
use std::path::Path;

#[derive(Clone, Copy)]
enum Ty {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

fn ty(name: &str) -> Option<Ty> {
    Some(match name {
        "char" | "int8" => Ty::I8,
        "uchar" | "uint8" => Ty::U8,
        "short" | "int16" => Ty::I16,
        "ushort" | "uint16" => Ty::U16,
        "int" | "int32" => Ty::I32,
        "uint" | "uint32" => Ty::U32,
        "float" | "float32" => Ty::F32,
        "double" | "float64" => Ty::F64,
        _ => return None,
    })
}

fn size(t: Ty) -> usize {
    match t {
        Ty::I8 | Ty::U8 => 1,
        Ty::I16 | Ty::U16 => 2,
        Ty::I32 | Ty::U32 | Ty::F32 => 4,
        Ty::F64 => 8,
    }
}

struct Prop {
    name: String,
    list: Option<Ty>,
    ty: Ty,
}

struct Elem {
    name: String,
    count: u64,
    props: Vec<Prop>,
}

enum Src<'a> {
    Ascii(std::iter::Peekable<std::vec::IntoIter<(usize, &'a str)>>),
    Bin { data: &'a [u8], pos: usize, big: bool },
}

impl Src<'_> {
    fn read(&mut self, path: &Path, t: Ty) -> Result<f64, ReadError> {
        match self {
            Src::Ascii(it) => {
                let (l, tok) = it.next().ok_or_else(|| ReadError::new(path, 0, "file ends inside the data"))?;
                let v: f64 = tok.parse().map_err(|_| ReadError::new(path, l, format!("'{tok}' is not a number")))?;
                if !v.is_finite() {
                    return Err(ReadError::new(path, l, format!("'{tok}' is not finite")));
                }
                Ok(v)
            }
            Src::Bin { data, pos, big } => {
                let n = size(t);
                if *pos + n > data.len() {
                    return Err(ReadError::new(path, 0, "binary data ends early"));
                }
                let mut b = [0u8; 8];
                b[..n].copy_from_slice(&data[*pos..*pos + n]);
                if *big {
                    b[..n].reverse();
                }
                *pos += n;
                let v = match t {
                    Ty::I8 => b[0] as i8 as f64,
                    Ty::U8 => b[0] as f64,
                    Ty::I16 => i16::from_le_bytes([b[0], b[1]]) as f64,
                    Ty::U16 => u16::from_le_bytes([b[0], b[1]]) as f64,
                    Ty::I32 => i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
                    Ty::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
                    Ty::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
                    Ty::F64 => f64::from_le_bytes(b),
                };
                if !v.is_finite() {
                    return Err(ReadError::new(path, 0, format!("non-finite value at byte {}", *pos - n)));
                }
                Ok(v)
            }
        }
    }
}

/// Parses PLY.
pub fn parse_ply(path: &Path, bytes: &[u8]) -> Result<IndexedMesh, ReadError> {
    let end =
        bytes.windows(10).position(|w| w == b"end_header").ok_or_else(|| ReadError::new(path, 1, "no end_header"))?;
    let head = std::str::from_utf8(&bytes[..end]).map_err(|_| ReadError::new(path, 1, "header is not text"))?;
    let mut body = end + 10;
    while body < bytes.len() && (bytes[body] == b'\r' || bytes[body] == b' ') {
        body += 1;
    }
    if body < bytes.len() && bytes[body] == b'\n' {
        body += 1;
    }
    let mut format = "";
    let mut elems: Vec<Elem> = Vec::new();
    let header_lines = head.lines().count() + 1;
    for (i, raw) in head.lines().enumerate() {
        let line = i + 1;
        let w: Vec<&str> = raw.split_whitespace().collect();
        match w.first().copied() {
            Some("ply") | Some("comment") | Some("obj_info") | None => {}
            Some("format") => format = w.get(1).copied().unwrap_or(""),
            Some("element") => {
                let count = w
                    .get(2)
                    .and_then(|c| c.parse().ok())
                    .ok_or_else(|| ReadError::new(path, line, "bad element line"))?;
                elems.push(Elem { name: w.get(1).unwrap_or(&"").to_string(), count, props: Vec::new() });
            }
            Some("property") => {
                let e = elems.last_mut().ok_or_else(|| ReadError::new(path, line, "property before element"))?;
                let bad = || ReadError::new(path, line, format!("unsupported property '{raw}'"));
                if w.get(1) == Some(&"list") {
                    let lt = w.get(2).and_then(|t| ty(t)).ok_or_else(bad)?;
                    let it = w.get(3).and_then(|t| ty(t)).ok_or_else(bad)?;
                    e.props.push(Prop { name: w.get(4).unwrap_or(&"").to_string(), list: Some(lt), ty: it });
                } else {
                    let t = w.get(1).and_then(|t| ty(t)).ok_or_else(bad)?;
                    e.props.push(Prop { name: w.get(2).unwrap_or(&"").to_string(), list: None, ty: t });
                }
            }
            Some(other) => return Err(ReadError::new(path, line, format!("unknown header keyword '{other}'"))),
        }
    }
    let mut src = match format {
        "ascii" => {
            let text =
                std::str::from_utf8(&bytes[body..]).map_err(|_| ReadError::new(path, 0, "ascii body is not text"))?;
            let toks: Vec<(usize, &str)> = text
                .lines()
                .enumerate()
                .flat_map(|(i, l)| l.split_whitespace().map(move |t| (header_lines + 1 + i, t)))
                .collect();
            Src::Ascii(toks.into_iter().peekable())
        }
        "binary_little_endian" => Src::Bin { data: &bytes[body..], pos: 0, big: false },
        "binary_big_endian" => Src::Bin { data: &bytes[body..], pos: 0, big: true },
        f => return Err(ReadError::new(path, 2, format!("unknown PLY format '{f}'"))),
    };
    // Counts come from the header: each is checked against the bytes left
    // before any work (an element of no properties reads nothing, so a
    // count of 1.8e19 would loop forever; 1e11 vertices would fill the
    // memory with a file of a hundred bytes).
    let mut left = bytes.len() - body;
    for e in &elems {
        if e.name == "vertex" {
            for axis in ["x", "y", "z"] {
                if !e.props.iter().any(|p| p.name == axis && p.list.is_none()) {
                    return Err(ReadError::new(path, 0, format!("element vertex has no `{axis}` property")));
                }
            }
        }
        if e.props.is_empty() {
            continue;
        }
        // at least one byte per value as text, the fixed sizes (a list's
        // count) in binary
        let per: usize = match &src {
            Src::Ascii(_) => e.props.len(),
            Src::Bin { .. } => e.props.iter().map(|p| size(p.list.unwrap_or(p.ty))).sum(),
        };
        let n = crate::io::files::input::check_count(e.count, per as u64, left, &format!("element {}", e.name))
            .map_err(|m| ReadError::new(path, 0, m))?;
        left -= n * per;
    }
    let mut mesh = IndexedMesh::default();
    let mut poly = Vec::new();
    for e in elems.iter().filter(|e| !e.props.is_empty()) {
        for r in 0..e.count {
            let mut p = [0.0; 3];
            for pr in &e.props {
                if let Some(lt) = pr.list {
                    let n = src.read(path, lt)? as usize;
                    poly.clear();
                    for _ in 0..n {
                        poly.push(src.read(path, pr.ty)?);
                    }
                    if e.name == "face" && (pr.name == "vertex_indices" || pr.name == "vertex_index") {
                        let nv = mesh.vertices.len();
                        let mut idx = Vec::with_capacity(n);
                        for &k in &poly {
                            if k < 0.0 || k as usize >= nv || k.fract() != 0.0 {
                                return Err(ReadError::new(
                                    path,
                                    0,
                                    format!("face {r}: vertex index {k} out of range"),
                                ));
                            }
                            idx.push(k as u32);
                        }
                        if n < 3 {
                            return Err(ReadError::new(path, 0, format!("face {r} has fewer than 3 corners")));
                        }
                        push_fan(&mut mesh.triangles, &idx);
                    }
                } else {
                    let v = src.read(path, pr.ty)?;
                    if e.name == "vertex" {
                        match pr.name.as_str() {
                            "x" => p[0] = v,
                            "y" => p[1] = v,
                            "z" => p[2] = v,
                            _ => {}
                        }
                    }
                }
            }
            if e.name == "vertex" {
                mesh.vertices.push(p);
            }
        }
    }
    Ok(mesh)
}
