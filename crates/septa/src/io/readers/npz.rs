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
pub enum NpyArray {
    /// Float data (from `<f8` / `<f4`).
    F64(Vec<usize>, Vec<f64>),
    /// Integer data (from signed or unsigned integers up to 64 bits).
    I64(Vec<usize>, Vec<i64>),
    /// A unicode or byte string scalar.
    Str(String),
}

impl NpyArray {
    /// Shape (empty for strings).
    pub fn shape(&self) -> &[usize] {
        match self {
            NpyArray::F64(s, _) | NpyArray::I64(s, _) => s,
            NpyArray::Str(_) => &[],
        }
    }
}

/// Reads every array of an `.npz` file.
pub fn read_npz(path: &Path) -> Result<BTreeMap<String, NpyArray>, NpzError> {
    read_npz_arrays(path, None)
}

/// Reads the arrays `wanted` (every array for `None`) of an `.npz` file.
/// Each member is inflated only as far as its `.npy` header declares
/// ([`read_member`]); members not wanted are not inflated at all (a 2 MB
/// archive could otherwise inflate to gigabytes for a 5-vertex input).
pub fn read_npz_arrays(path: &Path, wanted: Option<&[&str]>) -> Result<BTreeMap<String, NpyArray>, NpzError> {
    let p = path.display().to_string();
    let file =
        crate::io::files::input::open_regular(path).map_err(|source| NpzError::Io { path: p.clone(), source })?;
    let zerr = |e: zip::result::ZipError| NpzError::Zip { path: p.clone(), message: e.to_string() };
    let mut zip = zip::ZipArchive::new(std::io::BufReader::new(file)).map_err(zerr)?;
    let mut out = BTreeMap::new();
    for i in 0..zip.len() {
        let member = zip.by_index(i).map_err(zerr)?;
        let name = member.name().trim_end_matches(".npy").to_string();
        if wanted.is_some_and(|w| !w.contains(&name.as_str())) {
            continue;
        }
        let bytes =
            read_member(member).map_err(|message| NpzError::Array { path: p.clone(), array: name.clone(), message })?;
        let arr =
            parse_npy(&bytes).map_err(|message| NpzError::Array { path: p.clone(), array: name.clone(), message })?;
        out.insert(name, arr);
    }
    Ok(out)
}

/// The bytes of one `.npy` member, inflated no further than its header
/// declares: the header is read from the first 64 KiB, then exactly the
/// data its shape and dtype need (less when the member is shorter, which
/// [`parse_npy`] then reports). The zip's own size field is not trusted.
fn read_member(mut r: impl Read) -> Result<Vec<u8>, String> {
    let io = |e: std::io::Error| format!("cannot inflate: {e}");
    let mut buf = Vec::new();
    (&mut r).take(1 << 16).read_to_end(&mut buf).map_err(io)?;
    let mut rest: &[u8] = &buf;
    let header = npyz::NpyHeader::from_reader(&mut rest).map_err(|e| format!("not a readable .npy array: {e}"))?;
    let header_len = buf.len() - rest.len();
    let npyz::DType::Plain(ts) = header.dtype() else {
        return Err(format!("structured dtype {} is not supported (expected numbers)", header.dtype().descr()));
    };
    // bytes per item: `<U5` holds 5 characters of 4 bytes; an object
    // (pickled) array has no fixed size and is refused by `parse_npy`
    let item = ts.num_bytes().ok_or_else(|| format!("dtype {} has no fixed item size", header.dtype().descr()))?;
    let count = header.shape().iter().try_fold(1u64, |a, &d| a.checked_mul(d));
    let data = count.and_then(|c| c.checked_mul(item as u64));
    let limit = crate::io::files::input::input_limit();
    let need = match data.and_then(|d| d.checked_add(header_len as u64)) {
        Some(n) if n <= limit => n,
        _ => {
            return Err(format!(
            "shape {:?} of {} declares more data than the input limit of {} (the memory budget, or SEPTA_MAX_INPUT)",
            header.shape(),
            header.dtype().descr(),
            crate::grid::memory::human(limit)
        ))
        }
    };
    if (buf.len() as u64) < need {
        let more = need - buf.len() as u64;
        r.take(more).read_to_end(&mut buf).map_err(io)?;
    }
    buf.truncate(need as usize);
    Ok(buf)
}

/// Parses one `.npy` with the maintained `npyz` reader: format versions
/// 1-3, either byte order, C or Fortran order (numpy writes Fortran order
/// for transposed arrays; nibabel returns them), bool, signed and unsigned
/// integers, f32/f64 and string scalars. The data is returned in C order
/// (Fortran arrays are transposed here). Before: the hand-written parser
/// refused Fortran order, bool and big-endian arrays.
pub fn parse_npy(b: &[u8]) -> Result<NpyArray, String> {
    use npyz::{DType, TypeChar};
    let mut data: &[u8] = b;
    let header = npyz::NpyHeader::from_reader(&mut data).map_err(|e| format!("not a readable .npy array: {e}"))?;
    let file = npyz::NpyFile::with_header(header, data);
    let shape: Vec<usize> = file
        .shape()
        .iter()
        .map(|&d| usize::try_from(d).map_err(|_| format!("axis length {d} is too large")))
        .collect::<Result<_, _>>()?;
    let count = shape.iter().try_fold(1usize, |a, &d| a.checked_mul(d)).ok_or("the shape's element count overflows")?;
    let fortran = file.order() == npyz::Order::Fortran;
    let DType::Plain(ts) = file.dtype() else {
        return Err(format!("structured dtype {} is not supported (expected numbers)", file.dtype().descr()));
    };
    let size = ts.size_field() as usize;
    // Refuse before allocating: a header may claim more items than the file holds.
    if !matches!(ts.type_char(), TypeChar::UnicodeStr | TypeChar::ByteStr)
        && count.checked_mul(size).is_none_or(|need| data.len() < need)
    {
        return Err(format!("data truncated: {} bytes for {count} items of {size} bytes", data.len()));
    }
    let io = |e: std::io::Error| format!("cannot read the data: {e}");
    let descr = file.dtype().descr();
    let arr = match (ts.type_char(), size) {
        (TypeChar::Float, 8) => NpyArray::F64(shape, file.into_vec::<f64>().map_err(io)?),
        (TypeChar::Float, 4) => {
            NpyArray::F64(shape, file.into_vec::<f32>().map_err(io)?.into_iter().map(f64::from).collect())
        }
        (TypeChar::Bool, 1) => {
            NpyArray::I64(shape, file.into_vec::<bool>().map_err(io)?.into_iter().map(i64::from).collect())
        }
        (TypeChar::Int, 1) => {
            NpyArray::I64(shape, file.into_vec::<i8>().map_err(io)?.into_iter().map(i64::from).collect())
        }
        (TypeChar::Int, 2) => {
            NpyArray::I64(shape, file.into_vec::<i16>().map_err(io)?.into_iter().map(i64::from).collect())
        }
        (TypeChar::Int, 4) => {
            NpyArray::I64(shape, file.into_vec::<i32>().map_err(io)?.into_iter().map(i64::from).collect())
        }
        (TypeChar::Int, 8) => NpyArray::I64(shape, file.into_vec::<i64>().map_err(io)?),
        (TypeChar::Uint, 1) => {
            NpyArray::I64(shape, file.into_vec::<u8>().map_err(io)?.into_iter().map(i64::from).collect())
        }
        (TypeChar::Uint, 2) => {
            NpyArray::I64(shape, file.into_vec::<u16>().map_err(io)?.into_iter().map(i64::from).collect())
        }
        (TypeChar::Uint, 4) => {
            NpyArray::I64(shape, file.into_vec::<u32>().map_err(io)?.into_iter().map(i64::from).collect())
        }
        (TypeChar::Uint, 8) => {
            let v = file.into_vec::<u64>().map_err(io)?;
            let mut out = Vec::with_capacity(v.len());
            for (i, x) in v.into_iter().enumerate() {
                out.push(i64::try_from(x).map_err(|_| format!("item {i}: unsigned value {x} does not fit in i64"))?);
            }
            NpyArray::I64(shape, out)
        }
        (TypeChar::UnicodeStr | TypeChar::ByteStr, _) if count == 1 => NpyArray::Str(
            file.into_vec::<String>().map_err(io)?.pop().unwrap_or_default().trim_end_matches('\0').to_string(),
        ),
        _ => return Err(format!("unsupported dtype {descr}")),
    };
    Ok(if fortran { to_c_order(arr) } else { arr })
}

/// The same array with its data in C order (last axis fastest), from
/// Fortran order (first axis fastest).
fn to_c_order(a: NpyArray) -> NpyArray {
    fn permute<T: Copy>(shape: &[usize], f: &[T]) -> Vec<T> {
        if shape.len() < 2 {
            return f.to_vec();
        }
        // Fortran strides: axis 0 has stride 1.
        let mut stride = vec![1usize; shape.len()];
        for a in 1..shape.len() {
            stride[a] = stride[a - 1] * shape[a - 1];
        }
        let mut out = Vec::with_capacity(f.len());
        let mut idx = vec![0usize; shape.len()];
        for _ in 0..f.len() {
            out.push(f[idx.iter().zip(&stride).map(|(i, s)| i * s).sum::<usize>()]);
            // Next C-order multi-index: the last axis runs fastest.
            for a in (0..shape.len()).rev() {
                idx[a] += 1;
                if idx[a] < shape[a] {
                    break;
                }
                idx[a] = 0;
            }
        }
        out
    }
    match a {
        NpyArray::F64(s, d) => {
            let d = permute(&s, &d);
            NpyArray::F64(s, d)
        }
        NpyArray::I64(s, d) => {
            let d = permute(&s, &d);
            NpyArray::I64(s, d)
        }
        other => other,
    }
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
    let mut arrays = read_npz_arrays(path, Some(&["vertices", "tets", "values", "grid_res", "bbox"]))?;
    let p = path.display().to_string();
    let mut take = |name: &str| arrays.remove(name).ok_or(NpzError::Missing { path: p.clone(), array: name.into() });
    let bad = |array: &str, message: String| NpzError::Array { path: p.clone(), array: array.into(), message };
    let (vs, vd) = match take("vertices")? {
        NpyArray::F64(s, d) => (s, d),
        NpyArray::I64(s, d) => (s, d.into_iter().map(|x| x as f64).collect()),
        NpyArray::Str(_) => return Err(bad("vertices", "is a string".into())),
    };
    if vs.len() != 2 || vs[1] != 3 {
        return Err(bad("vertices", format!("shape {vs:?}, expected (N, 3)")));
    }
    let vertices: Vec<[f64; 3]> = vd.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    let tets = match take("tets")? {
        NpyArray::I64(s, d) if s.len() == 2 && s[1] == 4 => {
            d.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect()
        }
        a => return Err(bad("tets", format!("shape {:?} / dtype, expected (M, 4) integers", a.shape()))),
    };
    let (values, k) = match take("values")? {
        NpyArray::F64(s, d) if s.len() == 2 && s[0] == vertices.len() => (d, s[1]),
        NpyArray::F64(s, d) if s.len() == 1 && s[0] == vertices.len() => (d, 1),
        a => return Err(bad("values", format!("shape {:?}, expected ({}, k) floats", a.shape(), vertices.len()))),
    };
    let grid_res = match arrays.remove("grid_res") {
        Some(NpyArray::I64(_, d)) if d.len() == 1 && d[0] > 0 => Some(d[0] as usize),
        _ => None,
    };
    let bbox = match arrays.remove("bbox") {
        Some(NpyArray::F64(_, d)) if d.len() == 6 => Some([[d[0], d[1], d[2]], [d[3], d[4], d[5]]]),
        _ => None,
    };
    Ok(GridInput { vertices, tets, values, k, grid_res, bbox })
}
