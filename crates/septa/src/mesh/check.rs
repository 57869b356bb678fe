//! The exact check of a result's written doubles (the guarantee cut-cells
//! have from `cut/check/verify.rs`, for grid networks, region surfaces and label
//! volumes): each polygon is fanned from its first vertex, as the writers
//! and readers do, and on those triangles
//!
//! 1. no two distinct vertices in use are at the same point (bitwise, with
//!    `-0.0 == 0.0`);
//! 2. no triangle has collinear corners (exact 2D orientations in the three
//!    axis projections, `cut::collinear`);
//! 3. no two triangles meet except in shared vertices and edges (the cut's
//!    exact triangle-pair test and candidate grid, `cut::intersecting_pairs`);
//! 4. every cell closed by the polygons up to the grid's box has a positive
//!    volume where a flux proves it (`volume.rs`).
//!
//! Nothing is decided by a tolerance: a zero report is a proof about the
//! written doubles.

use rayon::prelude::*;
use rustc_hash::FxHashSet;

use super::volume::{cell_fluxes_positive, CellFaces};
use crate::cut::{collinear, intersecting_pairs};
use crate::network::embedding::EmbeddingCheck;

/// Polygons as the writers see them: polygon `f` is
/// `verts[start[f]..start[f + 1]]`, counter-clockwise seen from its positive
/// side, with `cells[f] = [positive side, negative side]` (`u32::MAX`: none).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Polygons<'a> {
    pub start: &'a [u32],
    pub verts: &'a [u32],
    /// Per polygon its two cells, when cells are to be checked.
    pub cells: Option<&'a [[u32; 2]]>,
}

impl<'a> Polygons<'a> {
    pub fn len(&self) -> usize {
        self.start.len().saturating_sub(1)
    }

    pub fn poly(&self, f: usize) -> &'a [u32] {
        &self.verts[self.start[f] as usize..self.start[f + 1] as usize]
    }
}

/// The written triangles: each polygon fanned from its first vertex.
#[derive(Clone, Debug, Default)]
pub(crate) struct Fans {
    pub tris: Vec<[u32; 3]>,
    /// The polygon of each triangle.
    pub poly: Vec<u32>,
}

pub(crate) fn fans(p: &Polygons) -> Fans {
    let mut out = Fans::default();
    for f in 0..p.len() {
        let l = p.poly(f);
        for k in 1..l.len().saturating_sub(1) {
            out.tris.push([l[0], l[k], l[k + 1]]);
            out.poly.push(f as u32);
        }
    }
    out
}

/// What [`check`] found: the report and the offending elements.
#[derive(Clone, Debug, Default)]
pub(crate) struct Findings {
    pub check: EmbeddingCheck,
    /// Triangles (indices into the fans) that are degenerate or meet another.
    pub bad: Vec<u32>,
    /// Pairs of distinct vertices at one point.
    pub coincident: Vec<[u32; 2]>,
    /// The fans checked.
    pub fans: Fans,
}

impl Findings {
    fn note(&mut self, s: impl FnOnce() -> String) {
        if self.check.examples.len() < 10 {
            self.check.examples.push(s());
        }
    }
}

/// The position's bits, `-0.0` as `0.0` (the same point).
pub(crate) fn point_bits(p: &[f64; 3]) -> [u64; 3] {
    p.map(|c| (c + 0.0).to_bits())
}

/// Pairs of distinct vertices among `used` (ascending) at the same point,
/// consecutive in the order of their positions.
pub(crate) fn coincident_pairs(x: &[[f64; 3]], used: &[u32]) -> Vec<[u32; 2]> {
    let mut seen: FxHashSet<[u64; 3]> = FxHashSet::default();
    seen.reserve(used.len());
    if used.iter().all(|&v| seen.insert(point_bits(&x[v as usize]))) {
        return Vec::new();
    }
    let mut by_pos: Vec<([u64; 3], u32)> = used.iter().map(|&v| (point_bits(&x[v as usize]), v)).collect();
    by_pos.par_sort_unstable();
    by_pos.windows(2).filter(|w| w[0].0 == w[1].0).map(|w| [w[0].1, w[1].1]).collect()
}

/// The vertices in use by `tris`, ascending.
pub(crate) fn used_vertices(n: usize, tris: &[[u32; 3]]) -> Vec<u32> {
    let mut in_use = vec![false; n];
    for &v in tris.iter().flatten() {
        in_use[v as usize] = true;
    }
    (0..n as u32).filter(|&v| in_use[v as usize]).collect()
}

/// Checks the fans of `p` exactly on the doubles `x` (module doc); `bounds`:
/// the grid's box, which closes the cells that reach it.
pub(crate) fn check(x: &[[f64; 3]], p: &Polygons, bounds: Option<[[f64; 3]; 2]>) -> Findings {
    let fans = fans(p);
    let mut out = Findings::default();
    out.check.triangles = fans.tris.len();
    let used = used_vertices(x.len(), &fans.tris);
    let nonfinite: Vec<u32> = used.iter().copied().filter(|&v| !x[v as usize].iter().all(|c| c.is_finite())).collect();
    if !nonfinite.is_empty() {
        out.check.nonfinite_points = nonfinite.len();
        for &v in nonfinite.iter().take(3) {
            out.note(|| format!("vertex {v} has a coordinate that is not finite: {:?}", x[v as usize]));
        }
        out.fans = fans;
        return out;
    }
    out.coincident = coincident_pairs(x, &used);
    out.check.coincident_points = out.coincident.len();
    for &[a, b] in out.coincident.clone().iter().take(3) {
        out.note(|| format!("vertices {a} and {b} are at the same point {:?}", x[a as usize]));
    }
    let degenerate: Vec<bool> = fans.tris.par_iter().map(|t| collinear(x, t[0], t[1], t[2])).collect();
    let good: Vec<u32> = (0..fans.tris.len() as u32).filter(|&t| !degenerate[t as usize]).collect();
    out.check.degenerate_triangles = fans.tris.len() - good.len();
    for (t, _) in degenerate.iter().enumerate().filter(|(_, &d)| d).take(3) {
        let (tri, f) = (fans.tris[t], fans.poly[t]);
        out.note(|| format!("triangle {tri:?} of polygon {f} has collinear corners"));
    }
    out.bad.extend((0..fans.tris.len() as u32).filter(|&t| degenerate[t as usize]));
    let tris: Vec<[u32; 3]> = good.iter().map(|&t| fans.tris[t as usize]).collect();
    let pairs = intersecting_pairs(x, &tris, false);
    out.check.intersecting_pairs = pairs.len();
    for &(a, b) in pairs.iter().take(3) {
        let (ta, tb) = (good[a as usize], good[b as usize]);
        let (fa, fb) = (fans.poly[ta as usize], fans.poly[tb as usize]);
        let (a3, b3) = (fans.tris[ta as usize], fans.tris[tb as usize]);
        out.note(|| format!("triangle {a3:?} of polygon {fa} meets triangle {b3:?} of polygon {fb}"));
    }
    out.bad.extend(pairs.iter().flat_map(|&(a, b)| [good[a as usize], good[b as usize]]));
    out.bad.sort_unstable();
    out.bad.dedup();
    if let Some(cells) = p.cells {
        let faces = CellFaces::new(p, cells, x, bounds);
        let (checked, positive) = cell_fluxes_positive(x, &faces, &fans, bounds);
        out.check.cells_checked = checked;
        out.check.cells_positive = positive;
    }
    out.fans = fans;
    out
}
