//! What remeshing is judged by: the triangles' angles and radius ratios,
//! each patch's Euler characteristic and boundary loops (which must not
//! change), and the Hausdorff distance between the remeshed and the
//! unremeshed surfaces, each way, sampled. Floating point: reports, not
//! decisions.

use rustc_hash::FxHashMap;

use super::original::{On, Original};
use super::soup::{add, cross, dist, min_angle, norm, scale, sub, V};

/// Shape of a set of triangles.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct Quality {
    /// Triangles measured.
    pub triangles: usize,
    /// The smallest angle of any triangle, in degrees.
    pub min_angle: f64,
    /// The mean over the triangles of their smallest angle, in degrees.
    pub mean_min_angle: f64,
    /// Triangles whose smallest angle is under 20 degrees.
    pub below_20_degrees: usize,
    /// Radius ratio `2 r / R` (1: equilateral, 0: degenerate) in tenths:
    /// `radius_ratio[i]` triangles in `[i/10, (i+1)/10)` (1.0 in the last).
    pub radius_ratio: [usize; 10],
}

/// The angle of triangle `p` at its corner `k`, in degrees.
fn angle_at(p: [V; 3], k: usize) -> f64 {
    let (u, v) = (sub(p[(k + 1) % 3], p[k]), sub(p[(k + 2) % 3], p[k]));
    let c = super::soup::dot(u, v) / (norm(u) * norm(v));
    if c.is_finite() {
        c.clamp(-1.0, 1.0).acos().to_degrees()
    } else {
        0.0
    }
}

/// The input's sharp wedges: `(vertex, patch)` for a vertex that never
/// moves (`fixed`) where the patch's triangles around it make an angle
/// under 20 degrees in all. A triangle of that patch at that vertex has
/// its angle there below the wedge's, whatever the remeshing does: the
/// bound the input sets (two chains meeting at a small angle at a corner).
pub(super) fn sharp_wedges(x: &[V], tris: &[[u32; 3]], patch: &[u32], fixed: &[bool]) -> Vec<(u32, u32)> {
    let mut sum: FxHashMap<(u32, u32), f64> = FxHashMap::default();
    for (t, tri) in tris.iter().enumerate() {
        let p = tri.map(|v| x[v as usize]);
        for k in 0..3 {
            if fixed[tri[k] as usize] {
                *sum.entry((tri[k], patch[t])).or_default() += angle_at(p, k);
            }
        }
    }
    let mut out: Vec<(u32, u32)> = sum.into_iter().filter(|&(_, a)| a < 20.0).map(|(k, _)| k).collect();
    out.sort_unstable();
    out
}

/// The smallest angle of the triangles at no sharp wedge (`sharp`, sorted)
/// and the number of triangles at one.
pub(super) fn away_from_sharp(x: &[V], tris: &[[u32; 3]], patch: &[u32], sharp: &[(u32, u32)]) -> (f64, usize) {
    let mut best = if tris.is_empty() { 0.0 } else { 180.0f64 };
    let mut at = 0;
    for (t, tri) in tris.iter().enumerate() {
        if tri.iter().any(|&v| sharp.binary_search(&(v, patch[t])).is_ok()) {
            at += 1;
        } else {
            best = best.min(min_angle(tri.map(|v| x[v as usize])));
        }
    }
    (best, at)
}

/// `2 r / R` of a triangle (inradius over circumradius, doubled).
pub(super) fn radius_ratio(p: [V; 3]) -> f64 {
    let (a, b, c) = (dist(p[1], p[2]), dist(p[0], p[2]), dist(p[0], p[1]));
    let area = 0.5 * norm(cross(sub(p[1], p[0]), sub(p[2], p[0])));
    let s = 0.5 * (a + b + c);
    let q = 8.0 * area * area / (s * a * b * c);
    if q.is_finite() {
        q.clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// The quality of `tris` on `x`.
pub(super) fn quality(x: &[V], tris: &[[u32; 3]]) -> Quality {
    let mut q =
        Quality { triangles: tris.len(), min_angle: if tris.is_empty() { 0.0 } else { 180.0 }, ..Default::default() };
    let mut sum = 0.0;
    for t in tris {
        let p = t.map(|v| x[v as usize]);
        let m = min_angle(p);
        q.min_angle = q.min_angle.min(m);
        sum += m;
        q.below_20_degrees += (m < 20.0) as usize;
        q.radius_ratio[((radius_ratio(p) * 10.0) as usize).min(9)] += 1;
    }
    q.mean_min_angle = if tris.is_empty() { 0.0 } else { sum / tris.len() as f64 };
    q
}

/// Per patch (of `count`): triangles, Euler characteristic `V - E + F` and
/// boundary loops (cycles of edges held by one of its triangles).
pub(super) fn patch_counts(tris: &[[u32; 3]], patch: &[u32], count: usize) -> Vec<[i64; 3]> {
    let mut verts: Vec<Vec<u32>> = vec![Vec::new(); count];
    let mut edges: Vec<Vec<(u32, u32)>> = vec![Vec::new(); count];
    let mut faces = vec![0i64; count];
    for (t, tri) in tris.iter().enumerate() {
        let p = patch[t] as usize;
        faces[p] += 1;
        verts[p].extend_from_slice(tri);
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            edges[p].push((a.min(b), a.max(b)));
        }
    }
    (0..count)
        .map(|p| {
            let v = &mut verts[p];
            v.sort_unstable();
            v.dedup();
            let e = &mut edges[p];
            e.sort_unstable();
            // border edges: held once
            let mut border: Vec<(u32, u32)> = Vec::new();
            let mut i = 0;
            while i < e.len() {
                let mut j = i;
                while j < e.len() && e[j] == e[i] {
                    j += 1;
                }
                if j - i == 1 {
                    border.push(e[i]);
                }
                i = j;
            }
            e.dedup();
            [faces[p], v.len() as i64 - e.len() as i64 + faces[p], loops(&border) as i64]
        })
        .collect()
}

/// Cycles of the border edges (components of the graph they make).
fn loops(border: &[(u32, u32)]) -> usize {
    let mut id: FxHashMap<u32, u32> = FxHashMap::default();
    let mut parent: Vec<u32> = Vec::new();
    fn find(p: &mut [u32], mut i: u32) -> u32 {
        while p[i as usize] != i {
            p[i as usize] = p[p[i as usize] as usize];
            i = p[i as usize];
        }
        i
    }
    for &(a, b) in border {
        let mut at = |v: u32, parent: &mut Vec<u32>| {
            *id.entry(v).or_insert_with(|| {
                parent.push(parent.len() as u32);
                parent.len() as u32 - 1
            })
        };
        let (ia, ib) = (at(a, &mut parent), at(b, &mut parent));
        let (ra, rb) = (find(&mut parent, ia), find(&mut parent, ib));
        parent[ra as usize] = rb;
    }
    (0..parent.len() as u32).filter(|&i| find(&mut parent, i) == i).count()
}

/// Points on each triangle: its corners, edge middles and centroid.
fn samples(x: &[V], tris: &[[u32; 3]]) -> Vec<V> {
    let mut out = Vec::with_capacity(tris.len() * 4);
    for t in tris {
        let [a, b, c] = t.map(|v| x[v as usize]);
        out.push(a);
        out.push(scale(add(a, b), 0.5));
        out.push(scale(add(a, c), 0.5));
        out.push(scale(add(add(a, b), c), 1.0 / 3.0));
    }
    out
}

/// The largest distance from samples of `a` to the surface `b`.
fn one_way(ax: &[V], at: &[[u32; 3]], b: &Original) -> f64 {
    use rayon::prelude::*;
    samples(ax, at).par_iter().map(|&p| dist(p, b.closest(p, On::Any))).reduce(|| 0.0, f64::max)
}

/// The sampled Hausdorff distance each way: `[remeshed -> original,
/// original -> remeshed]`.
pub(super) fn hausdorff(x0: &[V], t0: &[[u32; 3]], x1: &[V], t1: &[[u32; 3]], size: f64) -> [f64; 2] {
    let zero0 = vec![0u32; t0.len()];
    let zero1 = vec![0u32; t1.len()];
    let o0 = Original::new(x0, t0, &zero0, &[], &[], size);
    let o1 = Original::new(x1, t1, &zero1, &[], &[], size);
    [one_way(x1, t1, &o0), one_way(x0, t0, &o1)]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fan at vertex 0 (fixed): patch 0 has triangles of 10 and 5
    /// degrees there (a wedge of 15), patch 1 one of 30 degrees.
    #[test]
    fn sharp_wedges_are_a_patch_s_angle_sum_under_20_at_a_fixed_vertex() {
        let dir = |deg: f64| {
            let a = deg.to_radians();
            [a.cos(), a.sin(), 0.0]
        };
        let x = vec![[0.0; 3], dir(0.0), dir(10.0), dir(15.0), dir(45.0)];
        let tris = [[0, 1, 2], [0, 2, 3], [0, 3, 4]];
        let patch = [0, 0, 1];
        let mut fixed = vec![false; 5];
        assert!(sharp_wedges(&x, &tris, &patch, &fixed).is_empty(), "only fixed vertices count");
        fixed[0] = true;
        let sharp = sharp_wedges(&x, &tris, &patch, &fixed);
        assert_eq!(sharp, vec![(0, 0)]);
        let (away, at) = away_from_sharp(&x, &tris, &patch, &sharp);
        assert_eq!(at, 2);
        assert!((away - 30.0).abs() < 1e-9, "{away}");
    }
}
