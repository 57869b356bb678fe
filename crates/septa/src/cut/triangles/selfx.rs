//! Exact self-intersection test of the input mesh (TopoCut App. A): no
//! edge may meet a triangle except at their shared vertices. Candidate
//! pairs come from a uniform grid over the bounding box (`pair_grid`; each
//! pair is tested once, in the grid cell holding the low corner of the
//! overlap of their boxes); every decision is an exact orientation sign.

use crate::cut::triangles::box_contact::{box_contact, extreme_corners};
use crate::cut::triangles::pair_grid::PairGrid;
use crate::cut::triangles::plane_separation::PlaneSeparation;
use crate::cut::triangles::sweep_frame::sweep_boxes;
use crate::cut::triangles::tri_pair::{pair_intersects_planes, TriPlane};
use rayon::prelude::*;

/// Pairs of triangles (`first < second`, sorted) that meet anywhere besides
/// their shared vertices and edges, decided exactly on the doubles `x`;
/// with `first_only` just the smallest pair (or none). Triangles must not be
/// degenerate (collinear corners).
pub fn intersecting_pairs(x: &[[f64; 3]], tris: &[[u32; 3]], first_only: bool) -> Vec<(u32, u32)> {
    intersecting_pairs_touching(x, tris, None, None, first_only)
}

/// [`intersecting_pairs`] restricted to the pairs with at least one `fresh`
/// triangle (all pairs with `None`): a re-check after some faces were
/// re-written, the other pairs being known from the previous check (their
/// coordinates unchanged). Only grid cells holding a fresh triangle are
/// filled and swept. With `separation`, the pairs it proves apart skip the
/// exact test (the same answer, sooner).
pub(crate) fn intersecting_pairs_touching(
    x: &[[f64; 3]],
    tris: &[[u32; 3]],
    fresh: Option<&[bool]>,
    separation: Option<&PlaneSeparation>,
    first_only: bool,
) -> Vec<(u32, u32)> {
    intersecting_pairs_wanted(x, tris, fresh, separation, first_only, &|_, _| true)
}

/// [`intersecting_pairs_touching`] restricted further to the pairs `(a, b)`
/// (indices into `tris`) for which `wanted(a, b)` holds: the pairs a
/// certificate still needs ([`crate::cut::check::tiling`]).
pub(crate) fn intersecting_pairs_wanted(
    x: &[[f64; 3]],
    tris: &[[u32; 3]],
    fresh: Option<&[bool]>,
    separation: Option<&PlaneSeparation>,
    first_only: bool,
    wanted: &(impl Fn(usize, usize) -> bool + Sync),
) -> Vec<(u32, u32)> {
    let n = tris.len();
    if n < 2 {
        return Vec::new();
    }
    let boxes: Vec<([f64; 3], [f64; 3])> = tris
        .iter()
        .map(|t| {
            let mut lo = [f64::INFINITY; 3];
            let mut hi = [f64::NEG_INFINITY; 3];
            for &v in t {
                for k in 0..3 {
                    lo[k] = lo[k].min(x[v as usize][k]);
                    hi[k] = hi[k].max(x[v as usize][k]);
                }
            }
            (lo, hi)
        })
        .collect();
    let extremes: Vec<u32> = tris.iter().zip(&boxes).map(|(t, b)| extreme_corners(x, t, b)).collect();
    let planes: Vec<TriPlane> = tris.iter().map(|t| TriPlane::new(x, t)).collect();
    // the boxes the grid and the sweep compare: along the axes, or along
    // the frame of a thin part tilted against them (`sweep_frame`). Either
    // kind holds its triangle, so a pair that meets passes both; with a
    // frame the axis-aligned boxes are compared too, and `box_contact`
    // always reads those. "x", "y", "z" below are the sweep boxes' axes.
    let framed = sweep_boxes(x, tris, planes.iter().map(TriPlane::normal), &boxes);
    let sweep_boxes = framed.as_deref().unwrap_or(&boxes);
    let grid = PairGrid::new(sweep_boxes, fresh);
    let (low_cell, ids) = (&grid.low_cell, &grid.ids);
    // One grid cell's triangles, copied next to each other (box, start
    // bits, id) and swept along x: in order of the low x of their boxes (as
    // the grid leaves them), each triangle meets only the following ones
    // that start before it ends, instead of every other triangle of the
    // cell. The found pairs are sorted at the end, so the order of the
    // tests changes nothing.
    //
    // Each pair is tested once, in the cell of the low corner of the overlap
    // of the boxes, `max(low_a, low_b)` per axis: as both boxes enter this
    // cell (their low cells are at most its coordinates), that is this cell
    // iff on every axis one of the two starts in it. The triangles starting
    // before it in x come first in the sweep order (the cell of a coordinate
    // is monotonic in it), so they are only paired with the later ones that
    // start in it; the start bits in y and z are compared per pair. Long
    // triangles (slivers of the large cut-faces) enter many cells and met
    // each other in every one of them before being turned away by this rule.
    type Local = ([f64; 3], [f64; 3], u8, u32);
    let per_group = |buf: &mut Vec<Local>, &(key, s, e): &(u64, u32, u32)| -> Vec<(u32, u32)> {
        let here = grid.coords(key);
        buf.clear();
        buf.extend(ids[s as usize..e as usize].iter().map(|&t| {
            let (b, l) = (&sweep_boxes[t as usize], &low_cell[t as usize]);
            let starts = (l[0] == here[0]) as u8 | ((l[1] == here[1]) as u8) << 1 | ((l[2] == here[2]) as u8) << 2;
            (b.0, b.1, starts, t)
        }));
        let first_here = buf.partition_point(|q| q.2 & 1 == 0);
        let mut found: Vec<(u32, u32)> = Vec::new();
        for a in 0..buf.len() {
            let (lo1, hi1, m1, t1) = buf[a];
            let old1 = fresh.is_some_and(|f| !f[t1 as usize]);
            for &(lo2, hi2, m2, t2) in &buf[(a + 1).max(first_here)..] {
                if lo2[0] > hi1[0] {
                    break;
                }
                if (m1 | m2) & 6 != 6 {
                    continue;
                }
                if old1 && fresh.is_some_and(|f| !f[t2 as usize]) {
                    continue;
                }
                if lo1[1] > hi2[1] || lo2[1] > hi1[1] || lo1[2] > hi2[2] || lo2[2] > hi1[2] {
                    continue;
                }
                let (u1, u2) = (t1 as usize, t2 as usize);
                if !wanted(u1, u2) {
                    continue;
                }
                if separation.is_some_and(|s| s.separated(u1, u2)) {
                    continue;
                }
                let (b1, b2) = match framed {
                    None => ((lo1, hi1), (lo2, hi2)),
                    Some(_) => {
                        let (b1, b2) = (boxes[u1], boxes[u2]);
                        if (0..3).any(|k| b1.0[k] > b2.1[k] || b2.0[k] > b1.1[k]) {
                            continue;
                        }
                        (b1, b2)
                    }
                };
                let meets = match box_contact(x, &tris[u1], &b1, extremes[u1], &tris[u2], &b2, extremes[u2]) {
                    Some(m) => m,
                    None => pair_intersects_planes(x, &tris[u1], &planes[u1], &tris[u2], &planes[u2]),
                };
                if meets {
                    let p = (t1.min(t2), t1.max(t2));
                    if !first_only {
                        found.push(p);
                    } else if found.first().is_none_or(|f| p < *f) {
                        found = vec![p];
                    }
                }
            }
        }
        found
    };
    if first_only {
        return grid
            .groups
            .par_iter()
            .map_init(Vec::new, per_group)
            .filter_map(|v| v.first().copied())
            .min()
            .into_iter()
            .collect();
    }
    let mut all: Vec<(u32, u32)> = grid.groups.par_iter().map_init(Vec::new, per_group).flatten().collect();
    all.sort_unstable();
    all
}

#[cfg(test)]
#[path = "selfx_tests.rs"]
mod tests;
