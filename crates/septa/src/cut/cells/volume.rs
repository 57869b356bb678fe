//! Exact sign of each cut-cell's volume (TopoCut Sec. 6.2's check that
//! every cell has positive volume). A cell can be legitimately tiny: planes
//! `x = 1/3`, `y = 1/3`, `z = 2/3` in floating point meet a hair's breadth
//! off the face `x + y + z = 1` of a tet and cut off a corner of volume
//! ~1e-48, whose floating-point volume (from rounded cut-vertices) is 0 or
//! even negative. Whether a volume is zero is a combinatorial question, so
//! it is decided exactly, as `voids.rs` does for triangle-only shells.
//!
//! The volume is `1/6 sum det[p0, pk, pk+1]` over the fan of every loop of
//! the cell's faces (oriented as in `cut_impl`). Each cut-vertex is `p =
//! H / W` in homogeneous coordinates from its defining faces
//! ([`Ctx::hom`]), so with `L` the product of the `W` of the cell's
//! vertices, `6 L vol = sum det[H_a, H_b, H_c] prod_{v not in {a, b, c}} W_v`:
//! a polynomial in the input numbers, evaluated with [`Exact`]. A float
//! evaluation with a proven error bound (`volume_filter.rs`), then an
//! interval evaluation of the same sum on the divided points, decide almost
//! every cell first (both proven filters: they enclose the exact volume).

use rayon::prelude::*;
use septa_exact::{Exact, Interval, Ring, Sign};

use crate::cut::base::geom::{cross3, dot3, Ctx, V3};
use crate::cut::cells::volume_filter::{fan_sign, FilterPoint};
use crate::cut::CutCellMesh;

/// `det[a, b, c] = a . (b x c)`.
fn det<R: Ring>(a: &V3<R>, b: &V3<R>, c: &V3<R>) -> R {
    dot3(a, &cross3(b, c))
}

/// The fan triangles `(a, b, c)` (vertex ids) of every loop of a cell's
/// faces, with `+1` or `-1` for the face's orientation with respect to it.
fn fan(out: &CutCellMesh, faces: &[usize], cell: u32) -> Vec<([u32; 3], bool)> {
    let mut tris = Vec::new();
    for &i in faces {
        let f = &out.faces[i];
        // Loops contribute + to cells[0] and - to cells[1] (see `cut_impl`).
        let positive = match (f.cells[0] == cell, f.cells[1] == cell) {
            (true, false) => true,
            (false, true) => false,
            _ => continue,
        };
        for lp in &f.loops {
            for k in 1..lp.len().saturating_sub(1) {
                tris.push(([lp[0], lp[k], lp[k + 1]], positive));
            }
        }
    }
    tris
}

/// Interval box enclosing cut-vertex `v`'s exact point `H / W`, or `None`
/// when its `W` interval contains 0 (as `embed::round` computes it).
type PointBox<'a> = &'a (dyn Fn(u32) -> Option<[Interval; 3]> + Sync);

/// Interval enclosure of `6 vol`, or `None` when a vertex's `W` interval
/// contains 0 (cannot happen for a valid cut-vertex, but then the exact
/// path decides). `point` encloses each vertex's exact point.
fn volume_interval(out: &CutCellMesh, tris: &[([u32; 3], bool)], point: PointBox) -> Option<Interval> {
    // Relative to a float point `o` near the cell (exactly representable,
    // so the sum is unchanged: a closed surface's fan sum does not depend
    // on the origin), keeping the terms as small as the cell.
    let o = match tris.first() {
        Some((t, _)) => out.vertices[t[0] as usize].map(Interval::point),
        None => return Some(Interval::point(0.0)),
    };
    // The cell's own vertices (a few dozen): a sorted list, not a map
    // over every cut-vertex.
    let mut ids: Vec<u32> = tris.iter().flat_map(|(t, _)| *t).collect();
    ids.sort_unstable();
    ids.dedup();
    let mut pts: Vec<V3<Interval>> = Vec::with_capacity(ids.len());
    for &v in &ids {
        let b = point(v)?;
        pts.push([b[0].sub(&o[0]), b[1].sub(&o[1]), b[2].sub(&o[2])]);
    }
    let mut acc = Interval::point(0.0);
    for (t, positive) in tris {
        let p = t.map(|v| &pts[ids.binary_search(&v).unwrap()]);
        let d = det(p[0], p[1], p[2]);
        acc = if *positive { acc.add(&d) } else { acc.sub(&d) };
    }
    Some(acc)
}

/// Exact sign of `vol` by the polynomial of the module doc.
fn volume_exact(c: &Ctx, out: &CutCellMesh, tris: &[([u32; 3], bool)]) -> Sign {
    let mut ids: Vec<u32> = tris.iter().flat_map(|(t, _)| *t).collect();
    ids.sort_unstable();
    ids.dedup();
    let hom: Vec<(V3<Exact>, Exact)> = ids.iter().map(|&v| c.hom::<Exact>(out.vertex_defs[v as usize])).collect();
    let at = |v: u32| ids.binary_search(&v).unwrap();
    let mut l_sign = Sign::Positive;
    for (_, w) in &hom {
        l_sign = l_sign.mul(w.sign());
    }
    if l_sign == Sign::Zero {
        // A cut-vertex at infinity: not a valid cell.
        return Sign::Zero;
    }
    let mut acc = Exact::zero();
    for (t, positive) in tris {
        let [a, b, cc] = t.map(at);
        let mut term = det(&hom[a].0, &hom[b].0, &hom[cc].0);
        for (i, (_, w)) in hom.iter().enumerate() {
            if i != a && i != b && i != cc {
                term = term.mul(w);
            }
        }
        acc = if *positive { acc.add(&term) } else { acc.sub(&term) };
    }
    acc.sign().mul(l_sign)
}

/// Exact sign of the volume of `cell`, bounded by the faces `faces`.
pub(crate) fn cell_volume_sign(c: &Ctx, out: &CutCellMesh, faces: &[usize], cell: u32) -> Sign {
    let point = |v: u32| {
        let (h, w) = c.hom::<Interval>(out.vertex_defs[v as usize]);
        crate::cut::embed::side_filter::exact_box(&h, &w)
    };
    volume_sign_with(c, out, faces, cell, &point)
}

/// The float filter of `volume_filter.rs` on the fan, relative to the same
/// origin as [`volume_interval`]: the exact sign, or `None` (undecided, or
/// a vertex without a box).
fn volume_filtered(out: &CutCellMesh, tris: &[([u32; 3], bool)], point: PointBox) -> Option<Sign> {
    let o = out.vertices[tris.first()?.0[0] as usize];
    let mut ids: Vec<u32> = tris.iter().flat_map(|(t, _)| *t).collect();
    ids.sort_unstable();
    ids.dedup();
    let mut pts = Vec::with_capacity(ids.len());
    for &v in &ids {
        pts.push(FilterPoint::new(&point(v)?, &o));
    }
    let at: Vec<([usize; 3], bool)> =
        tris.iter().map(|(t, p)| (t.map(|v| ids.binary_search(&v).unwrap()), *p)).collect();
    fan_sign(&pts, &at)
}

fn volume_sign_with(c: &Ctx, out: &CutCellMesh, faces: &[usize], cell: u32, point: PointBox) -> Sign {
    let tris = fan(out, faces, cell);
    if let Some(s) = volume_filtered(out, &tris, point) {
        return s;
    }
    match volume_interval(out, &tris, point).and_then(|v| v.sign()) {
        Some(s) => s,
        None => volume_exact(c, out, &tris),
    }
}

/// Exact sign of every cell's volume (after voids are attached). `boxes`
/// enclose the cut-vertices' exact points (`embed::round`: the same
/// quotients `H / W` in intervals, formed once per vertex instead of once
/// per cell of the vertex).
pub(crate) fn cell_volume_signs(c: &Ctx, out: &CutCellMesh, boxes: &[Option<[Interval; 3]>]) -> Vec<Sign> {
    let point = |v: u32| boxes[v as usize];
    let mut faces_of: Vec<Vec<usize>> = vec![Vec::new(); out.num_cells];
    for (i, f) in out.faces.iter().enumerate() {
        for &cell in f.cells.iter().filter(|&&x| x != u32::MAX) {
            if faces_of[cell as usize].last() != Some(&i) {
                faces_of[cell as usize].push(i);
            }
        }
    }
    (0..out.num_cells).into_par_iter().map(|k| volume_sign_with(c, out, &faces_of[k], k as u32, &point)).collect()
}
