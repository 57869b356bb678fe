//! Input conditions (TopoCut Sec. 2.1 and App. A), checked before any
//! cutting: each failure names the offending element.

use crate::cut::triangles::selfx::intersecting_pairs;
use crate::cut::CutError;
use septa_exact::{filtered_sign, filtered_sign_bounded, Bounded, Exact, Interval, Ring, Sign};

/// Mesh edges `(u < v)`, per-triangle side edges, and per-edge triangles
/// `[t with u->v, t with v->u]`, after checking watertight, manifold and
/// consistently oriented.
pub type Topology = (Vec<[u32; 2]>, Vec<[u32; 3]>, Vec<[u32; 2]>);

/// Checks indices, degenerate triangles, duplicate vertices, edges.
pub fn check_mesh(verts: &[[f64; 3]], tris: &[[u32; 3]]) -> Result<Topology, CutError> {
    if tris.is_empty() {
        return Err(CutError::EmptyMesh);
    }
    for (i, v) in verts.iter().enumerate() {
        if v.iter().any(|x| !x.is_finite()) {
            return Err(CutError::NonFiniteVertex { vertex: i });
        }
    }
    let key = |i: u32| verts[i as usize].map(|x| if x == 0.0 { 0u64 } else { x.to_bits() });
    // nearly always no two at one point: a set of positions proves it; the
    // sort names the first pair in a fixed order when there is one
    let mut seen: rustc_hash::FxHashSet<[u64; 3]> = Default::default();
    seen.reserve(verts.len());
    if !(0..verts.len() as u32).all(|i| seen.insert(key(i))) {
        let mut order: Vec<u32> = (0..verts.len() as u32).collect();
        order.sort_unstable_by_key(|&i| (key(i), i));
        for w in order.windows(2) {
            if key(w[0]) == key(w[1]) {
                return Err(CutError::DuplicateVertex { first: w[0] as usize, second: w[1] as usize });
            }
        }
    }
    drop(seen);
    let nv = verts.len() as u32;
    for (t, tri) in tris.iter().enumerate() {
        if tri.iter().any(|&v| v >= nv) {
            return Err(CutError::BadIndex { triangle: t });
        }
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
            return Err(CutError::DegenerateTriangle { triangle: t });
        }
        // exact collinearity: all components of (b-a) x (c-a) vanish
        let zero = (0..3).all(|k| {
            fn f<R: Ring>(v: &[[f64; 3]], tri: &[u32; 3], k: usize) -> R {
                let p = |i: usize| verts3::<R>(&v[tri[i] as usize]);
                let (a, b, c) = (p(0), p(1), p(2));
                let (i, j) = ((k + 1) % 3, (k + 2) % 3);
                let (e1i, e1j) = (b[i].sub(&a[i]), b[j].sub(&a[j]));
                let (e2i, e2j) = (c[i].sub(&a[i]), c[j].sub(&a[j]));
                e1i.mul(&e2j).sub(&e1j.mul(&e2i))
            }
            filtered_sign_bounded(
                || f::<Bounded>(verts, tri, k),
                || f::<Interval>(verts, tri, k),
                || f::<Exact>(verts, tri, k),
            ) == Sign::Zero
        });
        if zero {
            return Err(CutError::DegenerateTriangle { triangle: t });
        }
    }
    // undirected sides (min, max, forward?, triangle, side k), grouped by
    // sorting: placed straight into buckets by the smaller vertex (a
    // counting sort), then each short bucket sorted (the entries are
    // distinct: the same order as sorting all)
    let side = |t: usize, k: usize| {
        let (a, b) = (tris[t][k], tris[t][(k + 1) % 3]);
        (a.min(b), a.max(b), a < b, t as u32, k as u8)
    };
    let sides = {
        let mut start = vec![0u32; verts.len() + 1];
        for tri in tris {
            for k in 0..3 {
                start[tri[k].min(tri[(k + 1) % 3]) as usize + 1] += 1;
            }
        }
        for b in 0..verts.len() {
            start[b + 1] += start[b];
        }
        let mut fill = start.clone();
        let mut out = vec![(0, 0, false, 0, 0); 3 * tris.len()];
        for t in 0..tris.len() {
            for k in 0..3 {
                let e = side(t, k);
                out[fill[e.0 as usize] as usize] = e;
                fill[e.0 as usize] += 1;
            }
        }
        for b in 0..verts.len() {
            out[start[b] as usize..start[b + 1] as usize].sort_unstable();
        }
        out
    };
    let mut edges = Vec::with_capacity(sides.len() / 2);
    let mut edge_tris = Vec::with_capacity(sides.len() / 2);
    let mut tri_edges = vec![[0u32; 3]; tris.len()];
    let mut i = 0;
    while i < sides.len() {
        let mut j = i + 1;
        while j < sides.len() && sides[j].0 == sides[i].0 && sides[j].1 == sides[i].1 {
            j += 1;
        }
        let (u, v, _, t, _) = sides[i];
        // the sides run v -> u (`false`) sort before those u -> v
        let (bw, fw) = sides[i..j].split_at(sides[i..j].iter().take_while(|s| !s.2).count());
        if fw.len() > 1 || bw.len() > 1 {
            if fw.len() == bw.len() {
                // consistently oriented around the edge (TopoCut App. C)
                let triangles = sides[i..j].iter().take(8).map(|s| s.3 as usize).collect();
                return Err(CutError::NonManifoldEdge { a: u, b: v, count: j - i, triangles });
            }
            let (two, other) = if fw.len() > bw.len() { (fw, bw) } else { (bw, fw) };
            let (a, b) = if two[0].2 { (u, v) } else { (v, u) };
            return Err(CutError::NonManifoldOrFlipped {
                triangle: two[1].3 as usize,
                other: two[0].3 as usize,
                a,
                b,
                forward: two.len(),
                backward: other.len(),
            });
        }
        if fw.is_empty() || bw.is_empty() {
            let (a, b) = if sides[i].2 { (u, v) } else { (v, u) };
            return Err(CutError::NotWatertight { triangle: t as usize, a, b });
        }
        let e = edges.len() as u32;
        edges.push([u, v]);
        edge_tris.push([fw[0].3, bw[0].3]);
        tri_edges[fw[0].3 as usize][fw[0].4 as usize] = e;
        tri_edges[bw[0].3 as usize][bw[0].4 as usize] = e;
        i = j;
    }
    // manifold vertices: the triangles around each vertex form one fan
    let mut valence = vec![0u32; verts.len()];
    let mut first = vec![u32::MAX; verts.len()];
    for (t, tri) in tris.iter().enumerate() {
        for &v in tri {
            valence[v as usize] += 1;
            if first[v as usize] == u32::MAX {
                first[v as usize] = t as u32;
            }
        }
    }
    for v in 0..verts.len() {
        if valence[v] == 0 {
            continue;
        }
        let t0 = first[v];
        let mut t = t0;
        let mut count = 0;
        loop {
            count += 1;
            let tri = tris[t as usize];
            let k = tri.iter().position(|&x| x == v as u32).unwrap();
            // the side entering v; its other triangle is the next in the fan
            let e = tri_edges[t as usize][(k + 2) % 3] as usize;
            t = if edge_tris[e][0] == t { edge_tris[e][1] } else { edge_tris[e][0] };
            if t == t0 || count > valence[v] {
                break;
            }
        }
        if count != valence[v] {
            return Err(CutError::NonManifoldVertex {
                vertex: v,
                valence: valence[v] as usize,
                fans: fans_at(tris, &tri_edges, &edge_tris, v as u32),
                first_fan: count as usize,
            });
        }
    }
    // positive volume (outward orientation), computed on coordinates scaled
    // by a power of two (exact) so that the largest is about 1: a closed
    // cube scaled by 1e-200 has a volume of 1e-600, which underflows to 0
    // and was rejected as inward.
    let big = tris.iter().flatten().fold(0.0f64, |m, &i| verts[i as usize].iter().fold(m, |m, x| m.max(x.abs())));
    let pow2 =
        if big > 0.0 && big.is_finite() { 2f64.powi(-(big.log2().ceil() as i32).clamp(-1000, 1000)) } else { 1.0 };
    let mut vol = 0.0;
    let mut scale = 0.0f64;
    for tri in tris {
        let [a, b, c] = tri.map(|i| verts[i as usize].map(|x| x * pow2));
        let cr = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
        vol += (cr[0] * c[0] + cr[1] * c[1] + cr[2] * c[2]) / 6.0;
        scale = scale.max(a.iter().chain(b.iter()).fold(0.0f64, |m, x| m.max(x.abs())));
    }
    if vol <= 0.0 {
        return Err(CutError::InwardOrientation { volume: vol });
    }
    Ok((edges, tri_edges, edge_tris))
}

/// The number of fans of triangles around vertex `v` (error reporting
/// only: a scan of all triangles).
fn fans_at(tris: &[[u32; 3]], tri_edges: &[[u32; 3]], edge_tris: &[[u32; 2]], v: u32) -> usize {
    let around: Vec<u32> = (0..tris.len() as u32).filter(|&t| tris[t as usize].contains(&v)).collect();
    let mut seen = vec![false; around.len()];
    let mut fans = 0;
    for start in 0..around.len() {
        if seen[start] {
            continue;
        }
        fans += 1;
        let mut stack = vec![around[start]];
        seen[start] = true;
        while let Some(t) = stack.pop() {
            // the two sides of t at v lead to its neighbours in the fan
            for (k, &e) in tri_edges[t as usize].iter().enumerate() {
                let tri = tris[t as usize];
                if tri[k] != v && tri[(k + 1) % 3] != v {
                    continue;
                }
                for o in edge_tris[e as usize] {
                    if let Some(p) = around.iter().position(|&x| x == o) {
                        if !seen[p] {
                            seen[p] = true;
                            stack.push(o);
                        }
                    }
                }
            }
        }
    }
    fans
}

fn verts3<R: Ring>(v: &[f64; 3]) -> [R; 3] {
    [R::of(v[0]), R::of(v[1]), R::of(v[2])]
}

/// Checks planes; returns the indices kept (duplicates of an earlier plane
/// dropped, reported in `dropped`).
pub fn check_planes(planes: &[[f64; 4]], dropped: &mut Vec<(usize, usize)>) -> Result<Vec<usize>, CutError> {
    let mut keep: Vec<usize> = Vec::new();
    for (i, p) in planes.iter().enumerate() {
        if p.iter().any(|x| !x.is_finite()) {
            return Err(CutError::NonFinitePlane { plane: i });
        }
        if p[0] == 0.0 && p[1] == 0.0 && p[2] == 0.0 {
            return Err(CutError::ZeroNormal { plane: i });
        }
        // same plane: (n_i, d_i) and (n_j, d_j) proportional (App. B, T_pp coplanar)
        let dup = keep.iter().copied().find(|&j| {
            let q = &planes[j];
            (0..4).all(|a| {
                (a + 1..4).all(|b| {
                    filtered_sign(
                        || {
                            Interval::point(p[a])
                                .mul(&Interval::point(q[b]))
                                .sub(&Interval::point(p[b]).mul(&Interval::point(q[a])))
                        },
                        || {
                            Exact::from_f64(p[a])
                                .mul(&Exact::from_f64(q[b]))
                                .sub(&Exact::from_f64(p[b]).mul(&Exact::from_f64(q[a])))
                        },
                    ) == Sign::Zero
                })
            })
        });
        match dup {
            Some(j) => dropped.push((i, j)),
            None => keep.push(i),
        }
    }
    Ok(keep)
}

/// The input has no self-intersection (TopoCut App. A, decided exactly by
/// [`intersecting_pairs`]); fails with the first intersecting pair (by
/// triangle index).
pub fn check_self_intersections(x: &[[f64; 3]], tris: &[[u32; 3]]) -> Result<(), CutError> {
    match intersecting_pairs(x, tris, true).first() {
        Some(&(a, b)) => Err(CutError::SelfIntersection { first: a as usize, second: b as usize }),
        None => Ok(()),
    }
}
