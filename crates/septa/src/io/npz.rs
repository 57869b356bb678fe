//! Reading numpy `.npz` archives (a zip of `.npy` arrays) of tet grids and
//! function values: arrays `vertices` (N,3), `tets` (M,4), `values` (N,k).

use std::collections::BTreeMap;
use std::io::Read;
use std::path::Path;

/// Why an `.npz` file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum NpzError {
    /// File system error.
    #[error("{path}: {source}")]
    Io {
        /// File.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
    /// Not a zip archive, or a broken member.
    #[error("{path}: not a readable .npz archive: {message}")]
    Zip {
        /// File.
        path: String,
        /// What failed.
        message: String,
    },
    /// A member is not a `.npy` array this reader understands.
    #[error("{path}: array '{array}': {message}")]
    Array {
        /// File.
        path: String,
        /// Array name.
        array: String,
        /// What is wrong.
        message: String,
    },
    /// A required array is missing.
    #[error("{path}: no array '{array}'")]
    Missing {
        /// File.
        path: String,
        /// Array name.
        array: String,
    },
}

/// One array: its shape and data (numbers as `f64` or `i64`, or a string).
#[derive(Clone, Debug, PartialEq)]
pub enum Array {
    /// Float data (from `<f8` / `<f4`).
    F64(Vec<usize>, Vec<f64>),
    /// Integer data (from signed or unsigned integers up to 64 bits).
    I64(Vec<usize>, Vec<i64>),
    /// A unicode or byte string scalar.
    Str(String),
}

impl Array {
    /// Shape (empty for strings).
    pub fn shape(&self) -> &[usize] {
        match self {
            Array::F64(s, _) | Array::I64(s, _) => s,
            Array::Str(_) => &[],
        }
    }
}

/// Reads every array of an `.npz` file.
pub fn read_npz(path: &Path) -> Result<BTreeMap<String, Array>, NpzError> {
    let p = path.display().to_string();
    let file = std::fs::File::open(path).map_err(|source| NpzError::Io { path: p.clone(), source })?;
    let zerr = |e: zip::result::ZipError| NpzError::Zip { path: p.clone(), message: e.to_string() };
    let mut zip = zip::ZipArchive::new(std::io::BufReader::new(file)).map_err(zerr)?;
    let mut out = BTreeMap::new();
    for i in 0..zip.len() {
        let mut member = zip.by_index(i).map_err(zerr)?;
        let name = member.name().trim_end_matches(".npy").to_string();
        let mut bytes = Vec::with_capacity(member.size() as usize);
        member
            .read_to_end(&mut bytes)
            .map_err(|e| NpzError::Zip { path: p.clone(), message: format!("member {name}: {e}") })?;
        let arr =
            parse_npy(&bytes).map_err(|message| NpzError::Array { path: p.clone(), array: name.clone(), message })?;
        out.insert(name, arr);
    }
    Ok(out)
}

/// Parses one `.npy` (format versions 1-3, little-endian, C order).
pub fn parse_npy(b: &[u8]) -> Result<Array, String> {
    if b.len() < 10 || &b[..6] != b"\x93NUMPY" {
        return Err("not a .npy array (bad magic)".into());
    }
    let (hlen, hstart) = match b[6] {
        1 => (u16::from_le_bytes([b[8], b[9]]) as usize, 10),
        2 | 3 if b.len() >= 12 => (u32::from_le_bytes([b[8], b[9], b[10], b[11]]) as usize, 12),
        v => return Err(format!("unsupported .npy version {v}")),
    };
    let header = b.get(hstart..hstart + hlen).ok_or("truncated header")?;
    let header = std::str::from_utf8(header).map_err(|_| "header is not text")?;
    let descr = dict_str(header, "descr").ok_or("no 'descr' in header")?;
    if header.contains("'fortran_order': True") {
        return Err("Fortran-ordered arrays are not supported".into());
    }
    let shape = dict_shape(header).ok_or("no readable 'shape' in header")?;
    let count: usize = shape.iter().product();
    let data = &b[hstart + hlen..];
    let need = |size: usize| -> Result<(), String> {
        if data.len() < count * size {
            Err(format!("data truncated: {} bytes for {count} items of {size}", data.len()))
        } else {
            Ok(())
        }
    };
    let (order, kind, size) = split_descr(&descr)?;
    if order == '>' && size > 1 {
        return Err(format!("big-endian dtype {descr} is not supported"));
    }
    match (kind, size) {
        ('f', 8) => {
            need(8)?;
            Ok(Array::F64(
                shape,
                data.chunks_exact(8).take(count).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect(),
            ))
        }
        ('f', 4) => {
            need(4)?;
            Ok(Array::F64(
                shape,
                data.chunks_exact(4).take(count).map(|c| f32::from_le_bytes(c.try_into().unwrap()) as f64).collect(),
            ))
        }
        ('i' | 'u', 1 | 2 | 4 | 8) => {
            need(size)?;
            let signed = kind == 'i';
            let mut v = Vec::with_capacity(count);
            for c in data.chunks_exact(size).take(count) {
                let mut buf = [0u8; 8];
                buf[..size].copy_from_slice(c);
                let neg = signed && c[size - 1] & 0x80 != 0;
                if neg {
                    buf[size..].fill(0xff);
                }
                let x = i64::from_le_bytes(buf);
                if kind == 'u' && size == 8 && x < 0 {
                    return Err("unsigned value does not fit in i64".into());
                }
                v.push(x);
            }
            Ok(Array::I64(shape, v))
        }
        ('U', n) => {
            // UTF-32 little-endian, `n` characters.
            let mut s = String::new();
            for c in data.chunks_exact(4).take(n) {
                let u = u32::from_le_bytes(c.try_into().unwrap());
                if u == 0 {
                    break;
                }
                s.push(char::from_u32(u).ok_or("bad character in string")?);
            }
            Ok(Array::Str(s))
        }
        ('S', n) => {
            Ok(Array::Str(String::from_utf8_lossy(&data[..n.min(data.len())]).trim_end_matches('\0').to_string()))
        }
        _ => Err(format!("unsupported dtype {descr}")),
    }
}

fn split_descr(d: &str) -> Result<(char, char, usize), String> {
    let mut it = d.chars();
    let order = it.next().ok_or("empty dtype")?;
    let kind = it.next().ok_or("short dtype")?;
    let size = it.as_str().parse().map_err(|_| format!("bad dtype {d}"))?;
    Ok((order, kind, size))
}

fn dict_str(h: &str, key: &str) -> Option<String> {
    let i = h.find(&format!("'{key}'"))?;
    let rest = &h[i + key.len() + 2..];
    let a = rest.find('\'')?;
    let b = rest[a + 1..].find('\'')?;
    Some(rest[a + 1..a + 1 + b].to_string())
}

fn dict_shape(h: &str) -> Option<Vec<usize>> {
    let i = h.find("'shape'")?;
    let rest = &h[i..];
    let a = rest.find('(')?;
    let b = rest.find(')')?;
    rest[a + 1..b]
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.trim_end_matches('L').parse().ok())
        .collect()
}

/// A tet grid with function values, as stored in the test inputs.
#[derive(Clone, Debug)]
pub struct GridInput {
    /// Vertex positions.
    pub vertices: Vec<[f64; 3]>,
    /// Tets (0-based, as given).
    pub tets: Vec<[i64; 4]>,
    /// Values, `values[v * k + f]`.
    pub values: Vec<f64>,
    /// Number of functions.
    pub k: usize,
    /// `grid_res` if present (a 5-split box of R^3 cubes).
    pub grid_res: Option<usize>,
    /// `bbox` if present.
    pub bbox: Option<[[f64; 3]; 2]>,
}

/// Reads `vertices`, `tets`, `values` (and `grid_res`, `bbox` if present).
pub fn read_grid_input(path: &Path) -> Result<GridInput, NpzError> {
    let mut arrays = read_npz(path)?;
    let p = path.display().to_string();
    let mut take = |name: &str| arrays.remove(name).ok_or(NpzError::Missing { path: p.clone(), array: name.into() });
    let bad = |array: &str, message: String| NpzError::Array { path: p.clone(), array: array.into(), message };
    let (vs, vd) = match take("vertices")? {
        Array::F64(s, d) => (s, d),
        Array::I64(s, d) => (s, d.into_iter().map(|x| x as f64).collect()),
        Array::Str(_) => return Err(bad("vertices", "is a string".into())),
    };
    if vs.len() != 2 || vs[1] != 3 {
        return Err(bad("vertices", format!("shape {vs:?}, expected (N, 3)")));
    }
    let vertices: Vec<[f64; 3]> = vd.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    let tets = match take("tets")? {
        Array::I64(s, d) if s.len() == 2 && s[1] == 4 => d.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect(),
        a => return Err(bad("tets", format!("shape {:?} / dtype, expected (M, 4) integers", a.shape()))),
    };
    let (values, k) = match take("values")? {
        Array::F64(s, d) if s.len() == 2 && s[0] == vertices.len() => (d, s[1]),
        Array::F64(s, d) if s.len() == 1 && s[0] == vertices.len() => (d, 1),
        a => return Err(bad("values", format!("shape {:?}, expected ({}, k) floats", a.shape(), vertices.len()))),
    };
    let grid_res = match arrays.remove("grid_res") {
        Some(Array::I64(_, d)) if d.len() == 1 && d[0] > 0 => Some(d[0] as usize),
        _ => None,
    };
    let bbox = match arrays.remove("bbox") {
        Some(Array::F64(_, d)) if d.len() == 6 => Some([[d[0], d[1], d[2]], [d[3], d[4], d[5]]]),
        _ => None,
    };
    Ok(GridInput { vertices, tets, values, k, grid_res, bbox })
}
