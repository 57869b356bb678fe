//! The grid a scene asks for ([`GridSpec`]): a box grid split into
//! tetrahedra, read from a scene's `"grid"` (inline, a grid file, or the
//! adaptive-grid paper's form).

use std::path::Path;

use serde_json::Value;

use super::error::{err, JsonPath, Located};
use super::spec::{array, num, vec3, Obj};
use super::vec3::V3;
use crate::grid::{BoxGrid, Split};

/// A box grid split into tetrahedra.
#[derive(Clone, Debug, PartialEq)]
pub struct GridSpec {
    /// Number of cubes along x, y, z (each >= 1).
    pub resolution: [usize; 3],
    /// Min and max corners.
    pub bounds: [V3; 2],
    /// Tets per cube: 5 (alternating, as the reference) or 6.
    pub split: u8,
}

impl GridSpec {
    /// `n^3` cubes over `[lo, hi]`, 5 tets per cube.
    pub fn cube(n: usize, lo: f64, hi: f64) -> GridSpec {
        GridSpec { resolution: [n; 3], bounds: [[lo; 3], [hi; 3]], split: 5 }
    }

    /// Position of grid vertex `(i, j, k)`, as [`BoxGrid::vertex`] places it
    /// ([`crate::grid::grid_coordinate`] per axis).
    pub fn vertex(&self, ijk: [usize; 3]) -> V3 {
        let [lo, hi] = self.bounds;
        [0, 1, 2].map(|a| crate::grid::grid_coordinate(lo[a], hi[a], ijk[a], self.resolution[a]))
    }

    /// The box grid this spec describes (the one builder every front end uses).
    pub fn box_grid(&self) -> Result<BoxGrid, crate::grid::GridError> {
        BoxGrid::new(self.resolution, self.bounds, Split::try_from(self.split)?)
    }

    /// All vertices, vertex `(i, j, k)` at index
    /// `(i * (ny + 1) + j) * (nz + 1) + k` (the reference's order).
    pub fn vertices(&self) -> Vec<V3> {
        let [nx, ny, nz] = self.resolution;
        let mut v = Vec::with_capacity((nx + 1) * (ny + 1) * (nz + 1));
        for i in 0..=nx {
            for j in 0..=ny {
                for k in 0..=nz {
                    v.push(self.vertex([i, j, k]));
                }
            }
        }
        v
    }
}

pub(super) fn grid(v: &Value, path: &JsonPath, base_dir: Option<&Path>) -> Result<GridSpec, Located> {
    if let Value::String(file) = v {
        // A grid file of the adaptive-grid paper (`grid_1.json`).
        let full = base_dir.map_or_else(|| Path::new(file).to_path_buf(), |d| d.join(file));
        let text =
            crate::io::read_input_text(&full).or_else(|e| err(path, format!("cannot read {}: {e}", full.display())))?;
        let g: Value = super::strict_json::parse(&text).or_else(|e| err(path, format!("{}: {e}", full.display())))?;
        if !g.is_object() || g.get("bbox_min").is_none() {
            return err(path, format!("{}: not a grid file (resolution, bbox_min, bbox_max)", full.display()));
        }
        return grid(&g, path, None).or_else(|e| err(path, format!("{}: {}: {}", full.display(), e.path, e.message)));
    }
    if v.get("bbox_min").is_some() {
        return anchor_grid(v, path);
    }
    let o = Obj::new(v, path)?;
    let rp = path.key("resolution");
    let r = o.get("resolution")?;
    o.mark_all(&["resolution", "bounds", "split"]);
    o.finish()?;
    let res: Vec<&Value> = match r {
        Value::Array(a) => a.iter().collect(),
        _ => vec![r; 3],
    };
    if res.len() != 3 {
        return err(&rp, "expected n or [nx, ny, nz]");
    }
    let mut resolution = [0usize; 3];
    for (i, x) in res.iter().enumerate() {
        match x.as_i64() {
            Some(n) if (1..=1 << 20).contains(&n) => resolution[i] = n as usize,
            Some(n) => return err(&rp, format!("empty grid: resolution {n} (needs at least 1 cube per axis)")),
            None => return err(&rp, "resolution must be a whole number"),
        }
    }
    let bp = path.key("bounds");
    let b = array(o.get("bounds")?, &bp)?;
    if b.len() != 2 {
        return err(&bp, "expected [[x0,y0,z0],[x1,y1,z1]]");
    }
    let bounds = [vec3(&b[0], &bp.index(0))?, vec3(&b[1], &bp.index(1))?];
    if (0..3).any(|i| bounds[1][i] <= bounds[0][i] || bounds[1][i].is_nan()) {
        return err(&bp, "empty grid: each max must exceed its min");
    }
    let vertices: u128 = resolution.iter().map(|&n| n as u128 + 1).product();
    if vertices > u32::MAX as u128 {
        return err(&rp, format!("grid too large: {vertices} vertices (at most {})", u32::MAX));
    }
    let split = if o.has("split") { num(o.get("split")?, &path.key("split"))? } else { 5.0 };
    if split != 5.0 && split != 6.0 {
        return err(&path.key("split"), "split must be 5 or 6");
    }
    Ok(GridSpec { resolution, bounds, split: split as u8 })
}

/// The adaptive-grid paper's grid (`{"resolution": [n], "bbox_min": [..],
/// "bbox_max": [..]}`): `n` cubes per axis (or `[nx, ny, nz]`), 6 tets per
/// cube as that program splits them.
fn anchor_grid(v: &Value, path: &JsonPath) -> Result<GridSpec, Located> {
    let o = Obj::new(v, path)?;
    o.mark_all(&["resolution", "bbox_min", "bbox_max"]);
    o.finish()?;
    let rp = path.key("resolution");
    let r = o.get("resolution")?;
    let res: Vec<&Value> = match r {
        Value::Array(a) if a.len() == 1 => vec![&a[0]; 3],
        Value::Array(a) => a.iter().collect(),
        _ => vec![r; 3],
    };
    if res.len() != 3 {
        return err(&rp, "expected [n] or [nx, ny, nz]");
    }
    let mut resolution = [0usize; 3];
    for (i, x) in res.iter().enumerate() {
        match x.as_i64() {
            Some(n) if (1..=1 << 20).contains(&n) => resolution[i] = n as usize,
            _ => return err(&rp, "resolution must be a whole number of at least 1"),
        }
    }
    let bounds = [o.vec3("bbox_min")?, o.vec3("bbox_max")?];
    if (0..3).any(|i| bounds[1][i] <= bounds[0][i]) {
        return err(&path.key("bbox_max"), "empty grid: each max must exceed its min");
    }
    Ok(GridSpec { resolution, bounds, split: 6 })
}
