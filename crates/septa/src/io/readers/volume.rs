//! Label volumes as users have them: `.npy`, NIfTI-1 (`.nii`, `.nii.gz`)
//! and NRRD (`.nrrd`, attached data, raw/gzip/ascii), with their
//! voxel-to-world map.
//!
//! The map is the one nibabel and pynrrd give, so that the CLI places
//! surfaces where the Python package does: NIfTI `sform` if its code is set,
//! else `qform` (quaternion, `qfac` flip), else nibabel's fallback (zooms,
//! x mirrored, centred); NRRD `space directions` (one row per axis) and
//! `space origin`. Values go through NIfTI's `scl_slope`/`scl_inter` as
//! nibabel's `dataobj` does; labels must then be whole numbers.

use std::io::Read;
use std::path::Path;

use crate::io::readers::npz::{parse_npy, NpyArray};

/// A 3-axis label volume in C order (`(i * n1 + j) * n2 + k`) and its
/// voxel-to-world map: `world = m[..][..3] * [i, j, k] + m[..][3]`.
#[derive(Clone, Debug, PartialEq)]
pub struct LabelVolume {
    /// Voxels per axis.
    pub shape: [usize; 3],
    /// Labels, C order.
    pub labels: Vec<i64>,
    /// Rows of the 3x4 voxel-to-world affine.
    pub affine: [[f64; 4]; 3],
}

/// The identity placement (`.npy` files carry none).
pub const IDENTITY: [[f64; 4]; 3] = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]];

/// Reads a label volume; errors name the file and the field or voxel.
pub fn read_label_volume(path: &Path) -> Result<LabelVolume, String> {
    let file = path.display().to_string();
    let low = file.to_ascii_lowercase();
    let is_npy = !(low.ends_with(".nii") || low.ends_with(".nii.gz") || low.ends_with(".nrrd"));
    if is_npy {
        if let Some((shape, labels, fortran)) = crate::io::readers::npy_labels::read(path) {
            // Fortran order: to C order as the general reader does.
            let labels = Values::Int(labels).whole(shape, fortran).map_err(|e| format!("{file}: {e}"))?;
            return Ok(LabelVolume { shape, labels, affine: IDENTITY });
        }
    }
    let raw = crate::io::files::input::read_input(path).map_err(|e| format!("{file}: cannot read: {e}"))?;
    let r = if low.ends_with(".nii") || low.ends_with(".nii.gz") {
        nifti_bytes(&raw).and_then(|b| read_nifti(&b))
    } else if low.ends_with(".nrrd") {
        read_nrrd(&raw)
    } else {
        read_npy(&raw)
    };
    r.map_err(|e| format!("{file}: {e}"))
}

/// `raw` inflated when it is gzip, to at most `cap` bytes: what the header
/// declares (a 2 MB gzip inflating to gigabytes for an 8-voxel volume is
/// read no further than the 8 voxels). Data beyond that is not used.
fn maybe_gunzip(raw: &[u8], cap: u64) -> Result<Vec<u8>, String> {
    let limit = crate::io::files::input::input_limit();
    if cap > limit {
        return Err(format!(
            "the header declares {} of voxel data, more than the input limit of {} (the memory budget, or SEPTA_MAX_INPUT)",
            crate::grid::memory::human(cap),
            crate::grid::memory::human(limit)
        ));
    }
    if raw.starts_with(&[0x1f, 0x8b]) {
        let mut out = Vec::new();
        flate2::read::MultiGzDecoder::new(raw)
            .take(cap)
            .read_to_end(&mut out)
            .map_err(|e| format!("bad gzip data: {e}"))?;
        Ok(out)
    } else {
        Ok(raw[..raw.len().min(usize::try_from(cap).unwrap_or(usize::MAX))].to_vec())
    }
}

/// A NIfTI-1 file's bytes, inflated (`.nii.gz`) no further than its header
/// declares: the 348-byte header first, then `vox_offset` plus the voxels.
fn nifti_bytes(raw: &[u8]) -> Result<Vec<u8>, String> {
    let head = maybe_gunzip(raw, 352)?;
    let need = nifti_size(&head).unwrap_or(352);
    maybe_gunzip(raw, need)
}

/// The bytes a NIfTI-1 header declares (`vox_offset` + voxels x size), or
/// `None` when the header is not readable (the reader then says why).
fn nifti_size(b: &[u8]) -> Option<u64> {
    let b: &[u8; 348] = b.get(..348)?.try_into().ok()?;
    let big = i32::from_le_bytes(b[0..4].try_into().ok()?) != 348;
    let i16_at =
        |o: usize| if big { i16::from_be_bytes([b[o], b[o + 1]]) } else { i16::from_le_bytes([b[o], b[o + 1]]) };
    let x = [b[108], b[109], b[110], b[111]];
    let offset = if big { f32::from_be_bytes(x) } else { f32::from_le_bytes(x) };
    let voxels = (1..=3).try_fold(1u64, |a, k| a.checked_mul(u64::try_from(i16_at(40 + 2 * k)).ok()?))?;
    let bytes = voxels.checked_mul(u64::try_from(i16_at(72)).ok()? / 8)?; // bitpix
    (offset >= 0.0 && offset < 1e15).then(|| (offset as u64).saturating_add(bytes))
}

fn read_npy(raw: &[u8]) -> Result<LabelVolume, String> {
    let (shape, values) = match parse_npy(raw)? {
        NpyArray::I64(shape, data) => (shape, Values::Int(data)),
        NpyArray::F64(shape, data) => (shape, Values::Float(data)),
        NpyArray::Str(_) => return Err("labels must be a numeric array, not a string".into()),
    };
    if shape.len() != 3 {
        return Err(format!("labels must have 3 axes, not shape {shape:?}"));
    }
    let shape = [shape[0], shape[1], shape[2]];
    Ok(LabelVolume { shape, labels: values.whole(shape, false)?, affine: IDENTITY })
}

enum Values {
    Int(Vec<i64>),
    Float(Vec<f64>),
}

impl Values {
    /// Labels in C order from values in C order (`fortran`: first axis fastest).
    fn whole(self, shape: [usize; 3], fortran: bool) -> Result<Vec<i64>, String> {
        let at = |i: usize| {
            if fortran {
                [i % shape[0], (i / shape[0]) % shape[1], i / (shape[0] * shape[1])]
            } else {
                [i / (shape[1] * shape[2]), (i / shape[2]) % shape[1], i % shape[2]]
            }
        };
        let ints = match self {
            Values::Int(v) => v,
            // Float label volumes (as some tools save them): whole numbers only.
            Values::Float(v) => {
                let mut out = Vec::with_capacity(v.len());
                for (i, x) in v.into_iter().enumerate() {
                    if !(x.is_finite() && x.fract() == 0.0 && x.abs() < 9.0e15) {
                        return Err(format!("voxel {:?} has label {x}, not a whole number", at(i)));
                    }
                    out.push(x as i64);
                }
                out
            }
        };
        if !fortran {
            return Ok(ints);
        }
        let mut c = vec![0i64; ints.len()];
        for (i, x) in ints.into_iter().enumerate() {
            let [a, b, d] = at(i);
            c[(a * shape[1] + b) * shape[2] + d] = x;
        }
        Ok(c)
    }
}

/// Element kinds of both formats: (bytes, signed integer / unsigned / float).
#[derive(Clone, Copy)]
enum Kind {
    Int(usize),
    Uint(usize),
    Float(usize),
}

fn decode(data: &[u8], kind: Kind, n: usize, big: bool) -> Result<Values, String> {
    let size = match kind {
        Kind::Int(s) | Kind::Uint(s) | Kind::Float(s) => s,
    };
    let need = n.checked_mul(size).ok_or("the volume size overflows")?;
    if data.len() < need {
        return Err(format!("{} bytes of voxel data, {need} expected ({n} voxels of {size} bytes)", data.len()));
    }
    let word = |i: usize| -> [u8; 8] {
        let mut w = [0u8; 8];
        let b = &data[i * size..(i + 1) * size];
        // Little-endian into the low bytes.
        for (k, &x) in b.iter().enumerate() {
            w[if big { size - 1 - k } else { k }] = x;
        }
        w
    };
    Ok(match kind {
        Kind::Int(s) => Values::Int(
            (0..n)
                .map(|i| {
                    let v = u64::from_le_bytes(word(i));
                    let shift = 64 - 8 * s as u32;
                    ((v << shift) as i64) >> shift
                })
                .collect(),
        ),
        Kind::Uint(8) => {
            let mut out = Vec::with_capacity(n);
            for i in 0..n {
                let v = u64::from_le_bytes(word(i));
                out.push(i64::try_from(v).map_err(|_| format!("voxel {i} has label {v}, above 2^63"))?);
            }
            Values::Int(out)
        }
        Kind::Uint(_) => Values::Int((0..n).map(|i| u64::from_le_bytes(word(i)) as i64).collect()),
        Kind::Float(4) => {
            Values::Float((0..n).map(|i| f32::from_bits(u64::from_le_bytes(word(i)) as u32) as f64).collect())
        }
        Kind::Float(_) => Values::Float((0..n).map(|i| f64::from_bits(u64::from_le_bytes(word(i)))).collect()),
    })
}

fn read_nifti(b: &[u8]) -> Result<LabelVolume, String> {
    if b.len() < 348 {
        return Err(format!("{} bytes: too short for a NIfTI-1 header (348)", b.len()));
    }
    let big = match (i32::from_le_bytes(b[0..4].try_into().unwrap()), i32::from_be_bytes(b[0..4].try_into().unwrap())) {
        (348, _) => false,
        (_, 348) => true,
        (540, _) | (_, 540) => return Err("NIfTI-2 files are not supported (convert to NIfTI-1)".into()),
        (n, _) => return Err(format!("sizeof_hdr is {n}, not 348: not a NIfTI-1 file")),
    };
    if &b[344..347] != b"n+1" {
        return Err("magic is not \"n+1\": only single-file NIfTI-1 (.nii) is supported".into());
    }
    let i16_at = |o: usize| {
        let x = [b[o], b[o + 1]];
        if big {
            i16::from_be_bytes(x)
        } else {
            i16::from_le_bytes(x)
        }
    };
    let f32_at = |o: usize| {
        let x = [b[o], b[o + 1], b[o + 2], b[o + 3]];
        (if big { f32::from_be_bytes(x) } else { f32::from_le_bytes(x) }) as f64
    };
    let dim: Vec<i64> = (0..8).map(|k| i16_at(40 + 2 * k) as i64).collect();
    let nd = dim[0];
    if !(3..=7).contains(&nd) || dim[4..=nd as usize].iter().any(|&d| d != 1) {
        return Err(format!("dim is {:?}: labels must have 3 axes", &dim[1..=(nd.clamp(0, 7) as usize)]));
    }
    if dim[1..4].iter().any(|&d| d < 1) {
        return Err(format!("dim {:?} has an axis of length < 1", &dim[1..4]));
    }
    let shape = [dim[1] as usize, dim[2] as usize, dim[3] as usize];
    let kind = match i16_at(70) {
        2 => Kind::Uint(1),
        4 => Kind::Int(2),
        8 => Kind::Int(4),
        16 => Kind::Float(4),
        64 => Kind::Float(8),
        256 => Kind::Int(1),
        512 => Kind::Uint(2),
        768 => Kind::Uint(4),
        1024 => Kind::Int(8),
        1280 => Kind::Uint(8),
        t => return Err(format!("datatype {t} is not a label type (integers, float32 or float64)")),
    };
    let offset = f32_at(108);
    if !(offset >= 348.0 && offset.fract() == 0.0 && offset <= b.len() as f64) {
        return Err(format!("vox_offset {offset} is not a byte offset inside the file"));
    }
    let n = shape[0] * shape[1] * shape[2]; // below 2^45: each axis is an i16
    let mut values = decode(&b[offset as usize..], kind, n, big)?;
    // nibabel's dataobj scales unless the slope is 0 or NaN (or exactly 1, 0).
    let (slope, inter) = (f32_at(112), f32_at(116));
    if slope != 0.0 && slope.is_finite() && !(slope == 1.0 && (inter == 0.0 || !inter.is_finite())) {
        let inter = if inter.is_finite() { inter } else { 0.0 };
        let v: Vec<f64> = match values {
            Values::Int(v) => v.into_iter().map(|x| x as f64).collect(),
            Values::Float(v) => v,
        };
        values = Values::Float(v.into_iter().map(|x| x * slope + inter).collect());
    }
    let labels = values.whole(shape, true)?;
    let pixdim: Vec<f64> = (0..8).map(|k| f32_at(76 + 4 * k)).collect();
    let affine = if i16_at(254) > 0 {
        [0, 1, 2].map(|r| std::array::from_fn(|c| f32_at(280 + 16 * r + 4 * c)))
    } else if i16_at(252) > 0 {
        let (qb, qc, qd) = (f32_at(256), f32_at(260), f32_at(264));
        let qfac = if pixdim[0] < 0.0 { -1.0 } else { 1.0 };
        // nibabel's quat2mat: a from the unit norm (0 when rounding makes
        // the rest exceed 1), then normalised.
        let qa = (1.0 - (qb * qb + qc * qc + qd * qd)).max(0.0).sqrt();
        let (w, x, y, z) = (qa, qb, qc, qd);
        let nq = w * w + x * x + y * y + z * z;
        let s = if nq < 1e-300 { 0.0 } else { 2.0 / nq };
        let r = [
            [1.0 - s * (y * y + z * z), s * (x * y - w * z), s * (x * z + w * y)],
            [s * (x * y + w * z), 1.0 - s * (x * x + z * z), s * (y * z - w * x)],
            [s * (x * z - w * y), s * (y * z + w * x), 1.0 - s * (x * x + y * y)],
        ];
        let zooms = [pixdim[1], pixdim[2], pixdim[3] * qfac];
        let t = [f32_at(268), f32_at(272), f32_at(276)];
        [0, 1, 2].map(|i| [r[i][0] * zooms[0], r[i][1] * zooms[1], r[i][2] * zooms[2], t[i]])
    } else {
        // nibabel's base affine: x mirrored, the volume centred on 0.
        let z = [pixdim[1], pixdim[2], pixdim[3]].map(|p| if p == 0.0 { 1.0 } else { p.abs() });
        let c = shape.map(|s| (s as f64 - 1.0) / 2.0);
        [[-z[0], 0.0, 0.0, c[0] * z[0]], [0.0, z[1], 0.0, -c[1] * z[1]], [0.0, 0.0, z[2], -c[2] * z[2]]]
    };
    Ok(LabelVolume { shape, labels, affine })
}

fn read_nrrd(raw: &[u8]) -> Result<LabelVolume, String> {
    if !raw.starts_with(b"NRRD000") {
        return Err("does not start with NRRD000x: not a NRRD file".into());
    }
    // The header ends at the first empty line; attached data follows.
    let mut pos = 0;
    let mut fields = std::collections::HashMap::new();
    let mut line_no = 0;
    loop {
        let end = raw[pos..].iter().position(|&c| c == b'\n').ok_or("the header has no empty line before the data")?;
        let line = std::str::from_utf8(&raw[pos..pos + end])
            .map_err(|_| format!("header line {} is not text", line_no + 1))?;
        let line = line.trim_end_matches('\r');
        pos += end + 1;
        line_no += 1;
        if line.is_empty() {
            break;
        }
        if line_no == 1 || line.starts_with('#') || line.contains(":=") {
            continue;
        }
        let (k, v) = line.split_once(": ").ok_or(format!("header line {line_no} {line:?} has no \"field: value\""))?;
        fields.insert(k.trim().to_ascii_lowercase(), v.trim().to_string());
    }
    let get = |k: &str| fields.get(k).map(String::as_str);
    if get("data file").or(get("datafile")).is_some() {
        return Err("detached data files are not supported: save with the data attached".into());
    }
    let dim: usize =
        get("dimension").ok_or("no \"dimension\" field")?.parse().map_err(|_| "\"dimension\" is not a number")?;
    let sizes: Vec<usize> = get("sizes")
        .ok_or("no \"sizes\" field")?
        .split_whitespace()
        .map(|s| s.parse().map_err(|_| format!("\"sizes\" entry {s:?} is not a number")))
        .collect::<Result<_, _>>()?;
    if dim != 3 || sizes.len() != 3 || sizes.iter().any(|&s| s == 0) {
        return Err(format!("labels must have 3 axes, not sizes {sizes:?}"));
    }
    let shape = [sizes[0], sizes[1], sizes[2]];
    let t = get("type").ok_or("no \"type\" field")?;
    let kind = match t.trim_end_matches("_t") {
        "signed char" | "int8" => Kind::Int(1),
        "uchar" | "unsigned char" | "uint8" => Kind::Uint(1),
        "short" | "short int" | "signed short" | "signed short int" | "int16" => Kind::Int(2),
        "ushort" | "unsigned short" | "unsigned short int" | "uint16" => Kind::Uint(2),
        "int" | "signed int" | "int32" => Kind::Int(4),
        "uint" | "unsigned int" | "uint32" => Kind::Uint(4),
        "longlong" | "long long" | "long long int" | "signed long long" | "signed long long int" | "int64" => {
            Kind::Int(8)
        }
        "ulonglong" | "unsigned long long" | "unsigned long long int" | "uint64" => Kind::Uint(8),
        "float" => Kind::Float(4),
        "double" => Kind::Float(8),
        _ => return Err(format!("type {t:?} is not a label type")),
    };
    let big = get("endian") == Some("big");
    // the product of the sizes must not wrap around (2^61+1 x 4 x 2 did)
    let n = shape[0]
        .checked_mul(shape[1])
        .and_then(|n| n.checked_mul(shape[2]))
        .filter(|&n| n.checked_mul(8).is_some())
        .ok_or_else(|| format!("sizes {sizes:?}: the voxel count overflows"))?;
    let item = match kind {
        Kind::Int(s) | Kind::Uint(s) | Kind::Float(s) => s,
    };
    let body = &raw[pos..];
    let values = match get("encoding").ok_or("no \"encoding\" field")? {
        "raw" => decode(body, kind, n, big)?,
        "gzip" | "gz" => decode(&maybe_gunzip(body, (n * item) as u64)?, kind, n, big)?,
        "ascii" | "text" | "txt" => {
            let text = std::str::from_utf8(body).map_err(|_| "ascii data is not text")?;
            let nums: Vec<f64> = text
                .split_whitespace()
                .take(n)
                .map(|s| s.parse().map_err(|_| format!("ascii value {s:?} is not a number")))
                .collect::<Result<_, _>>()?;
            if nums.len() < n {
                return Err(format!("{} ascii values, {n} expected", nums.len()));
            }
            Values::Float(nums)
        }
        e => return Err(format!("encoding {e:?} is not supported (raw, gzip or ascii)")),
    };
    let labels = values.whole(shape, true)?;
    let vector = |s: &str| -> Result<[f64; 3], String> {
        let inner =
            s.trim().strip_prefix('(').and_then(|s| s.strip_suffix(')')).ok_or(format!("{s:?} is not (x,y,z)"))?;
        let v: Vec<f64> = inner
            .split(',')
            .map(|x| x.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| format!("{s:?} is not (x,y,z)"))?;
        <[f64; 3]>::try_from(v).map_err(|_| format!("{s:?} does not have 3 numbers"))
    };
    let mut affine = IDENTITY;
    if let Some(d) = get("space directions") {
        // One vector per axis: the world step of one voxel along it.
        let rows: Vec<[f64; 3]> =
            d.split_whitespace().map(vector).collect::<Result<_, _>>().map_err(|e| format!("space directions: {e}"))?;
        if rows.len() != 3 {
            return Err(format!("space directions has {} vectors, expected 3", rows.len()));
        }
        for (axis, row) in rows.iter().enumerate() {
            for (k, &x) in row.iter().enumerate() {
                affine[k][axis] = x;
            }
        }
    }
    if let Some(o) = get("space origin") {
        let o = vector(o).map_err(|e| format!("space origin: {e}"))?;
        for k in 0..3 {
            affine[k][3] = o[k];
        }
    }
    Ok(LabelVolume { shape, labels, affine })
}

/// The map `origin + index * spacing` (what `--spacing`/`--origin` give).
pub fn diagonal_affine(spacing: [f64; 3], origin: [f64; 3]) -> [[f64; 4]; 3] {
    [0, 1, 2].map(|r| {
        std::array::from_fn(|c| {
            if c == 3 {
                origin[r]
            } else if c == r {
                spacing[r]
            } else {
                0.0
            }
        })
    })
}

/// Checks that `affine` takes every point of a volume of `shape` voxels
/// (voxel corners from -1 to `shape`, where label surfaces lie) to finite
/// world points: a map is linear, so its extremes are at the box's corners.
/// Before: `--spacing 1e308` wrote infinite points as `null`, exit 0.
pub fn check_placement(affine: &[[f64; 4]; 3], shape: [usize; 3]) -> Result<(), String> {
    for c in 0..8 {
        let p: [f64; 3] = std::array::from_fn(|a| if c >> a & 1 == 1 { shape[a] as f64 } else { -1.0 });
        let q: [f64; 3] =
            std::array::from_fn(|k| affine[k][0] * p[0] + affine[k][1] * p[1] + affine[k][2] * p[2] + affine[k][3]);
        if q.iter().any(|x| !x.is_finite()) {
            return Err(format!(
                "the voxel-to-world map (spacing and origin) takes voxel {p:?} to {q:?}, outside the finite doubles; give a smaller spacing or origin"
            ));
        }
    }
    Ok(())
}

/// Moves label surfaces from voxel indices to world points by `affine`
/// (points only: the combinatorics do not move). A mirroring map (negative
/// determinant, decided exactly) reverses every polygon, so each stays
/// counter-clockwise seen from the lesser region; normals map by the
/// inverse transpose. Fails for a singular or non-finite map.
pub fn place_surfaces(r: &mut crate::regions::RegionSurfaces, affine: &[[f64; 4]; 3]) -> Result<(), String> {
    let m: [[f64; 3]; 3] = affine.map(|row| [row[0], row[1], row[2]]);
    let det = septa_exact::det_sign(&m);
    if affine.iter().flatten().any(|x| !x.is_finite()) || det == septa_exact::Sign::Zero {
        return Err(format!("the voxel-to-world matrix {m:?} is not invertible and finite"));
    }
    if *affine == IDENTITY {
        return Ok(());
    }
    let placed: Vec<[f64; 3]> = r
        .network
        .points
        .iter()
        .map(|p| std::array::from_fn(|k| m[k][0] * p[0] + m[k][1] * p[1] + m[k][2] * p[2] + affine[k][3]))
        .collect();
    if let Some(i) = placed.iter().position(|q| q.iter().any(|x| !x.is_finite())) {
        return Err(format!(
            "the voxel-to-world map takes point {:?} to {:?}, outside the finite doubles",
            r.network.points[i], placed[i]
        ));
    }
    r.network.points = placed;
    // Cofactor matrix = det * inverse transpose: same directions up to the sign of det.
    let cof = |i: usize, j: usize| {
        let (a, b) = ((i + 1) % 3, (i + 2) % 3);
        let (c, d) = ((j + 1) % 3, (j + 2) % 3);
        m[a][c] * m[b][d] - m[a][d] * m[b][c]
    };
    let flip = if det == septa_exact::Sign::Negative { -1.0 } else { 1.0 };
    for (_, _, n) in &mut r.normals {
        let v: [f64; 3] = std::array::from_fn(|i| flip * (cof(i, 0) * n[0] + cof(i, 1) * n[1] + cof(i, 2) * n[2]));
        let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        *n = v.map(|x| x / len);
    }
    if det == septa_exact::Sign::Negative {
        for f in 0..r.faces.len() {
            r.loops[r.loop_start[f] as usize..r.loop_start[f + 1] as usize].reverse();
        }
    }
    // Volumes, areas and lengths measured again on the moved points and box.
    r.domain = r.domain.as_ref().map(|d| d.mapped(affine));
    r.measure();
    Ok(())
}
