//! Exact self-intersection test of the input mesh (TopoCut App. A): no
//! edge may meet a triangle except at their shared vertices. Candidate
//! pairs come from a uniform grid over the bounding box (each pair is
//! tested once, in the grid cell holding the low corner of the overlap of
//! their boxes); every decision is an exact orientation sign.

use super::tri_pair::{pair_intersects_planes, TriPlane};
use super::CutError;
use rayon::prelude::*;

/// Fails with the first intersecting pair (by triangle index).
pub fn check_self_intersections(x: &[[f64; 3]], tris: &[[u32; 3]]) -> Result<(), CutError> {
    match intersecting_pairs(x, tris, true).first() {
        Some(&(a, b)) => Err(CutError::SelfIntersection { first: a as usize, second: b as usize }),
        None => Ok(()),
    }
}

/// Pairs of triangles (`first < second`, sorted) that meet anywhere besides
/// their shared vertices and edges, decided exactly on the doubles `x`;
/// with `first_only` just the smallest pair (or none). Triangles must not be
/// degenerate (collinear corners).
pub fn intersecting_pairs(x: &[[f64; 3]], tris: &[[u32; 3]], first_only: bool) -> Vec<(u32, u32)> {
    intersecting_pairs_touching(x, tris, None, first_only)
}

/// [`intersecting_pairs`] restricted to the pairs with at least one `fresh`
/// triangle (all pairs with `None`): a re-check after some faces were
/// re-written, the other pairs being known from the previous check (their
/// coordinates unchanged). Only grid cells holding a fresh triangle are
/// filled and swept.
pub fn intersecting_pairs_touching(
    x: &[[f64; 3]],
    tris: &[[u32; 3]],
    fresh: Option<&[bool]>,
    first_only: bool,
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
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for b in &boxes {
        for k in 0..3 {
            lo[k] = lo[k].min(b.0[k]);
            hi[k] = hi[k].max(b.1[k]);
        }
    }
    // cells about the size of a typical (median) triangle: a surface mesh
    // then puts a few triangles in each occupied cell. The mean would let
    // the long triangles of a large cut-face's triangulation coarsen the
    // grid for all; they enter many cells instead, as long as the entries
    // stay within a budget (else the grid is coarsened).
    let mut extents: Vec<f64> = boxes.iter().map(|b| (0..3).map(|k| b.1[k] - b.0[k]).fold(0.0, f64::max)).collect();
    let mid = extents.len() / 2;
    let median = *extents.select_nth_unstable_by(mid, f64::total_cmp).1;
    let ext = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    let mut res = ((ext / (1.5 * median).max(f64::MIN_POSITIVE)).ceil() as usize).clamp(1, 1 << 20);
    let entries_at = |res: usize| -> usize {
        let size: [f64; 3] = std::array::from_fn(|k| ((hi[k] - lo[k]) / res as f64).max(f64::MIN_POSITIVE));
        let cell = |p: f64, k: usize| (((p - lo[k]) / size[k]) as usize).min(res - 1);
        boxes.iter().map(|b| (0..3).map(|k| cell(b.1[k], k) - cell(b.0[k], k) + 1).product::<usize>()).sum()
    };
    while res > 1 && entries_at(res) > 8 * n {
        res = res * 3 / 4;
    }
    let size: [f64; 3] = std::array::from_fn(|k| ((hi[k] - lo[k]) / res as f64).max(f64::MIN_POSITIVE));
    let cell = |p: f64, k: usize| (((p - lo[k]) / size[k]) as usize).min(res - 1);
    let key = |c: [usize; 3]| ((c[0] as u64 * res as u64 + c[1] as u64) * res as u64) + c[2] as u64;
    // each triangle's low grid corner, once: `cell` is monotonic, so the
    // cell of the low corner of two boxes' overlap is the larger of their
    // low cells, per axis (no division per pair)
    let low_cell: Vec<[u32; 3]> = boxes.iter().map(|b| [0, 1, 2].map(|k| cell(b.0[k], k) as u32)).collect();
    let planes: Vec<TriPlane> = tris.iter().map(|t| TriPlane::new(x, t)).collect();
    let mut entries: Vec<(u64, u32)> = Vec::new();
    let cells_of = |t: usize, f: &mut dyn FnMut(u64)| {
        let (c0, c1) = (low_cell[t].map(|c| c as usize), [0, 1, 2].map(|k| cell(boxes[t].1[k], k)));
        for i in c0[0]..=c1[0] {
            for j in c0[1]..=c1[1] {
                for l in c0[2]..=c1[2] {
                    f(key([i, j, l]));
                }
            }
        }
    };
    match fresh {
        None => (0..n).for_each(|t| cells_of(t, &mut |k| entries.push((k, t as u32)))),
        Some(fresh) => {
            // the cells of the fresh triangles, then every triangle in them
            let mut hot: rustc_hash::FxHashSet<u64> = Default::default();
            (0..n).filter(|&t| fresh[t]).for_each(|t| {
                cells_of(t, &mut |k| {
                    hot.insert(k);
                })
            });
            for t in 0..n {
                cells_of(t, &mut |k| {
                    if fresh[t] || hot.contains(&k) {
                        entries.push((k, t as u32))
                    }
                });
            }
        }
    }
    // the order inside a cell is irrelevant (it is sorted by x below)
    entries.sort_unstable_by_key(|e| e.0);
    let mut groups: Vec<(usize, usize)> = Vec::new();
    let mut s = 0;
    while s < entries.len() {
        let mut e = s + 1;
        while e < entries.len() && entries[e].0 == entries[s].0 {
            e += 1;
        }
        groups.push((s, e));
        s = e;
    }
    // One grid cell's triangles, copied next to each other (box, low cell,
    // id) and swept along x: sorted by the low x of their boxes, each
    // triangle meets only the following ones that start before it ends,
    // instead of every other triangle of the cell. The found pairs are
    // sorted at the end, so the order of the tests changes nothing.
    type Local = ([f64; 3], [f64; 3], [u32; 3], u32);
    let per_group = |buf: &mut Vec<Local>, &(s, e): &(usize, usize)| -> Vec<(u32, u32)> {
        let here = entries[s].0;
        buf.clear();
        buf.extend(entries[s..e].iter().map(|&(_, t)| {
            let b = &boxes[t as usize];
            (b.0, b.1, low_cell[t as usize], t)
        }));
        buf.sort_unstable_by(|p, q| p.0[0].total_cmp(&q.0[0]));
        let mut found: Vec<(u32, u32)> = Vec::new();
        for a in 0..buf.len() {
            let (lo1, hi1, l1, t1) = buf[a];
            let old1 = fresh.is_some_and(|f| !f[t1 as usize]);
            for &(lo2, hi2, l2, t2) in &buf[a + 1..] {
                if lo2[0] > hi1[0] {
                    break;
                }
                if old1 && fresh.is_some_and(|f| !f[t2 as usize]) {
                    continue;
                }
                if lo1[1] > hi2[1] || lo2[1] > hi1[1] || lo1[2] > hi2[2] || lo2[2] > hi1[2] {
                    continue;
                }
                // test each pair once: in the cell of the overlap's low corner
                let low = key([0, 1, 2].map(|k| l1[k].max(l2[k]) as usize));
                if low != here {
                    continue;
                }
                let (u1, u2) = (t1 as usize, t2 as usize);
                if pair_intersects_planes(x, &tris[u1], &planes[u1], &tris[u2], &planes[u2]) {
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
        return groups
            .par_iter()
            .map_init(Vec::new, per_group)
            .filter_map(|v| v.first().copied())
            .min()
            .into_iter()
            .collect();
    }
    let mut all: Vec<(u32, u32)> = groups.par_iter().map_init(Vec::new, per_group).flatten().collect();
    all.sort_unstable();
    all
}

#[cfg(test)]
#[path = "selfx_tests.rs"]
mod tests;
