//! Cut-plane lists: TopoCut's format (first line `N 4`, then `a b c d`
//! lines) or plain `a b c d` lines, for the plane `a x + b y + c z + d = 0`;
//! and the generated sets `--grid N` or `--grid NX NY NZ` (TopoCut's An
//! and `bound_box_xyz`) and `--random N`
//! (TopoCut's Rn).

use crate::io::readers::mesh::{parse_f64, ReadError};
use rand::{Rng, SeedableRng};
use std::path::Path;

/// Reads a plane file (with or without the `N 4` header line).
pub fn read_planes(path: &Path) -> Result<Vec<[f64; 4]>, ReadError> {
    let text = crate::io::files::input::read_input_text(path)
        .map_err(|e| ReadError::new(path, 0, format!("cannot read: {e}")))?;
    parse_planes(path, &text)
}

/// Parses plane-file text.
pub fn parse_planes(path: &Path, text: &str) -> Result<Vec<[f64; 4]>, ReadError> {
    let mut out = Vec::new();
    let mut expected: Option<usize> = None;
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let body = raw.split('#').next().unwrap_or("");
        let toks: Vec<&str> = body.split_whitespace().collect();
        if toks.is_empty() {
            continue;
        }
        if out.is_empty() && expected.is_none() && toks.len() == 2 {
            let n = toks[0].parse::<usize>().map_err(|_| ReadError::new(path, line, "header must be 'N 4'"))?;
            if toks[1] != "4" {
                return Err(ReadError::new(path, line, "header must be 'N 4'"));
            }
            expected = Some(n);
            continue;
        }
        if toks.len() != 4 {
            return Err(ReadError::new(path, line, format!("expected 4 numbers 'a b c d', found {}", toks.len())));
        }
        let mut p = [0.0; 4];
        for k in 0..4 {
            p[k] = parse_f64(path, line, Some(toks[k]), ["a", "b", "c", "d"][k])?;
        }
        out.push(p);
    }
    if let Some(n) = expected {
        if n != out.len() {
            return Err(ReadError::new(path, 1, format!("header announces {n} planes, file has {}", out.len())));
        }
    }
    Ok(out)
}

/// Bounding box `(min, max)` of points.
pub fn bounding_box(vertices: &[[f64; 3]]) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for v in vertices {
        for k in 0..3 {
            lo[k] = lo[k].min(v[k]);
            hi[k] = hi[k].max(v[k]);
        }
    }
    (lo, hi)
}

/// TopoCut's `An`: `n` planes per axis, [`grid_planes_xyz`] with `[n; 3]`.
pub fn grid_planes(vertices: &[[f64; 3]], n: usize) -> Vec<[f64; 4]> {
    grid_planes_xyz(vertices, [n; 3])
}

/// TopoCut's `plane -s bound_box_xyz --nx NX --ny NY --nz NZ`: on axis
/// `a`, `n[a]` planes `x_a = min_a + (max_a - min_a) * j / (n[a] - 1)` for
/// `j = 0 .. n[a]-1` over the bounding box of all vertices, so the first and
/// the last lie on the box's faces (TopoCut computes the same positions; the
/// last is taken as `max_a` itself, not the rounded formula). `n[a]` planes
/// make `n[a] - 1` slabs: `--grid 21 6 6` on a 4 x 1 x 1 box gives cubes of
/// side 0.2. `n[a] = 1` puts one plane through the box's middle (TopoCut
/// divides by zero there). The planes come axis by axis, x first.
pub fn grid_planes_xyz(vertices: &[[f64; 3]], n: [usize; 3]) -> Vec<[f64; 4]> {
    let (lo, hi) = bounding_box(vertices);
    let mut out = Vec::new();
    for axis in 0..3 {
        let n = n[axis];
        for j in 0..n {
            let x = if n == 1 {
                0.5 * (lo[axis] + hi[axis])
            } else if j + 1 == n {
                hi[axis]
            } else {
                lo[axis] + (hi[axis] - lo[axis]) * j as f64 / (n - 1) as f64
            };
            let mut p = [0.0; 4];
            p[axis] = 1.0;
            p[3] = -x;
            out.push(p);
        }
    }
    out
}

/// TopoCut's `Rn`: `n` planes through random points of the bounding-box
/// diagonal with random (not normalised) normals, reproducible from `seed`.
pub fn random_planes(vertices: &[[f64; 3]], n: usize, seed: u64) -> Vec<[f64; 4]> {
    let (lo, hi) = bounding_box(vertices);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            let t: f64 = rng.gen_range(0.05..0.95);
            let x: [f64; 3] = std::array::from_fn(|k| lo[k] + t * (hi[k] - lo[k]));
            let nrm: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
            let d = -(nrm[0] * x[0] + nrm[1] * x[1] + nrm[2] * x[2]);
            [nrm[0], nrm[1], nrm[2], d]
        })
        .collect()
}
