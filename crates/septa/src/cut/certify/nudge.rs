//! Certified vertex moves, the last step of the repair ([`crate::cut::certify::repair`]):
//! where no triangulation of the faces helps (pieces of nearly coplanar
//! input triangles whose rounded cut-vertices cross each other's pieces,
//! TopoCut Sec. 8, Limitations), the vertices of the offending faces are
//! moved by a few ulps. Each candidate position is scored by an exact local
//! check (the triangles at the vertex against every triangle near them,
//! `tri_pair::pair_intersects`, plus collinear corners), the best is kept only
//! if it lowers that count, and the whole result is checked again by
//! [`crate::cut::check::verify`]: the guarantee is that global check, never the local
//! score. Input vertices stay exact; faces at a moved vertex are written as
//! triangles (relax planarity).

use crate::cut::base::geom::Def;
use crate::cut::check::polygon::collinear;
use crate::cut::triangles::tri_pair::pair_intersects;
use crate::cut::triangles::triangulate::{triangulate, triangulate_shaped};
use crate::cut::CutCellMesh;
use rustc_hash::FxHashMap;

/// Moves tried per vertex: steps of `s` ulps per coordinate towards each of
/// the 26 neighbouring directions, smallest steps first.
const STEPS: [f64; 6] = [1.0, 2.0, 4.0, 16.0, 64.0, 256.0];
/// Most vertices moved in one round (the local checks cost `O(near)` each).
const MAX_VERTICES: usize = 4000;

type Bx = ([f64; 3], [f64; 3]);

/// The bounding box of triangle `t`.
pub(crate) fn tri_box(x: &[[f64; 3]], t: &[u32; 3]) -> Bx {
    let mut b = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for &v in t {
        for k in 0..3 {
            b.0[k] = b.0[k].min(x[v as usize][k]);
            b.1[k] = b.1[k].max(x[v as usize][k]);
        }
    }
    b
}

/// Do two closed boxes overlap (touching counts)?
pub(crate) fn meet(a: &Bx, b: &Bx) -> bool {
    (0..3).all(|k| a.0[k] <= b.1[k] && b.0[k] <= a.1[k])
}

/// Exact local violations at `v`: its triangles with collinear corners, and
/// pairs (its triangle, a triangle near it) that meet away from shared
/// vertices and edges.
fn local(x: &[[f64; 3]], tris: &[[u32; 3]], mine: &[u32], near: &[u32]) -> usize {
    let mut bad = 0;
    for &a in mine {
        let t = &tris[a as usize];
        if collinear(x, t[0], t[1], t[2]) {
            bad += 1;
            continue;
        }
        let ba = tri_box(x, t);
        for &b in near {
            let u = &tris[b as usize];
            // a pair of the vertex's own triangles is seen from both sides: once
            if b == a || (mine.contains(&b) && b < a) || !meet(&ba, &tri_box(x, u)) {
                continue;
            }
            if !collinear(x, u[0], u[1], u[2]) && pair_intersects(x, t, u) {
                bad += 1;
            }
        }
    }
    bad
}

/// Moves the movable vertices of `faces` (cut-vertices not at an input
/// vertex, and face centres) where the exact local check improves; returns
/// the vertices moved. Faces at those vertices are written as triangles.
pub fn nudge(out: &mut CutCellMesh, faces: &[u32]) -> usize {
    let nd = out.vertex_defs.len();
    let movable = |v: u32| (v as usize) >= nd || !matches!(out.vertex_defs[v as usize], Def::V(_));
    let mut verts: Vec<u32> = Vec::new();
    for &f in faces {
        let i = f as usize;
        if out.face_split[i] {
            verts.extend(out.face_triangles[i].iter().flatten().copied().filter(|&v| movable(v)));
        } else {
            verts.extend(out.faces[i].loops.iter().flatten().copied().filter(|&v| movable(v)));
        }
    }
    verts.sort_unstable();
    verts.dedup();
    verts.truncate(MAX_VERTICES);
    if verts.is_empty() {
        return 0;
    }
    let is_cand: FxHashMap<u32, ()> = verts.iter().map(|&v| (v, ())).collect();
    // faces at a candidate vertex are written as triangles from now on
    for i in 0..out.faces.len() {
        if out.face_split[i] || !out.faces[i].loops.iter().flatten().any(|v| is_cand.contains_key(v)) {
            continue;
        }
        let f = &out.faces[i];
        let n = out.support_normal(f);
        out.face_triangles[i] =
            triangulate_shaped(&out.vertices, &f.loops, n).unwrap_or_else(|| triangulate(&out.vertices, &f.loops, n));
        out.face_split[i] = true;
    }
    // every written triangle (unsplit faces as the check would cut them)
    let mut tris: Vec<[u32; 3]> = Vec::new();
    for (i, f) in out.faces.iter().enumerate() {
        if out.face_split[i] {
            tris.extend_from_slice(&out.face_triangles[i]);
        } else {
            tris.extend(triangulate(&out.vertices, &f.loops, out.support_normal(f)));
        }
    }
    let mut at: FxHashMap<u32, Vec<u32>> = FxHashMap::default();
    for (ti, t) in tris.iter().enumerate() {
        for v in t {
            if is_cand.contains_key(v) {
                at.entry(*v).or_default().push(ti as u32);
            }
        }
    }
    let boxes: Vec<Bx> = tris.iter().map(|t| tri_box(&out.vertices, t)).collect();
    let mut moved = 0;
    for &v in &verts {
        let Some(mine) = at.get(&v) else { continue };
        // near: boxes meeting the vertex's triangles widened by the largest move
        let ulp = ulps(&out.vertices[v as usize]);
        let mut reach = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for &t in mine {
            for k in 0..3 {
                let pad = STEPS[STEPS.len() - 1] * 2.0 * ulp[k];
                reach.0[k] = reach.0[k].min(boxes[t as usize].0[k] - pad);
                reach.1[k] = reach.1[k].max(boxes[t as usize].1[k] + pad);
            }
        }
        let near: Vec<u32> = (0..tris.len() as u32).filter(|&t| meet(&reach, &boxes[t as usize])).collect();
        let (now, after) = best_position(&mut out.vertices, &tris, v, mine, &near);
        if after < now {
            moved += 1;
        }
    }
    moved
}

/// About one ulp of each coordinate (a move by it changes the double).
fn ulps(x: &[f64; 3]) -> [f64; 3] {
    std::array::from_fn(|k| x[k].abs().max(f64::MIN_POSITIVE) * f64::EPSILON)
}

/// Moves `v` to the candidate position (the [`STEPS`] around it) with the
/// fewest exact local violations, if that is fewer than now; returns the
/// counts before and after. `mine`: the triangles at `v`; `near`: every
/// triangle that may meet them after a move.
fn best_position(x: &mut [[f64; 3]], tris: &[[u32; 3]], v: u32, mine: &[u32], near: &[u32]) -> (usize, usize) {
    let now = local(x, tris, mine, near);
    if now == 0 {
        return (0, 0);
    }
    let x0 = x[v as usize];
    let ulp = ulps(&x0);
    let mut best = (now, x0);
    'search: for s in STEPS {
        for d in 0..27 {
            if d == 13 {
                continue;
            }
            let dir = [(d / 9) as f64 - 1.0, ((d / 3) % 3) as f64 - 1.0, (d % 3) as f64 - 1.0];
            let p: [f64; 3] = std::array::from_fn(|k| x0[k] + dir[k] * s * ulp[k]);
            x[v as usize] = p;
            let c = local(x, tris, mine, near);
            if c < best.0 {
                best = (c, p);
                if c == 0 {
                    break 'search;
                }
            }
        }
    }
    x[v as usize] = best.1;
    (now, best.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A corner one ulp below the plane z = 1 of another triangle it
    /// pierces: the smallest move that clears it is found, and only it.
    #[test]
    fn moves_a_corner_off_a_crossed_triangle() {
        let below = 1.0 - f64::EPSILON / 2.0;
        let mut x = vec![
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [0.0, 1.0, 1.0],
            [0.2, 0.2, below],
            [0.3, 0.2, 2.0],
            [0.2, 0.3, 2.0],
        ];
        let tris = [[0, 1, 2], [3, 4, 5]];
        assert!(pair_intersects(&x, &tris[0], &tris[1]));
        let (before, after) = best_position(&mut x, &tris, 3, &[1], &[0, 1]);
        assert_eq!((before, after), (1, 0));
        assert!(!pair_intersects(&x, &tris[0], &tris[1]));
        assert!(x[3][2] > 1.0 && x[3][2] - 1.0 < 1e-13, "{:?}", x[3]);
        // nothing to improve: nothing moves
        let y = x.clone();
        assert_eq!(best_position(&mut x, &tris, 3, &[1], &[0, 1]), (0, 0));
        assert_eq!(x, y);
    }
}
