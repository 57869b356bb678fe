//! Input conditions (TopoCut Sec. 2.1 and App. A), checked before any
//! cutting: each failure names the offending element.

use super::nodes::FxMap;
use super::CutError;
use septa_exact::{filtered_sign, Exact, Interval, Ring, Sign};

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
    let mut pos: FxMap<[u64; 3], usize> = FxMap::default();
    for (i, v) in verts.iter().enumerate() {
        let key = v.map(|x| if x == 0.0 { 0 } else { x.to_bits() });
        if let Some(&j) = pos.get(&key) {
            return Err(CutError::DuplicateVertex { first: j, second: i });
        }
        pos.insert(key, i);
    }
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
                let e1: Vec<R> = (0..3).map(|i| b[i].sub(&a[i])).collect();
                let e2: Vec<R> = (0..3).map(|i| c[i].sub(&a[i])).collect();
                let (i, j) = ((k + 1) % 3, (k + 2) % 3);
                e1[i].mul(&e2[j]).sub(&e1[j].mul(&e2[i]))
            }
            filtered_sign(|| f::<Interval>(verts, tri, k), || f::<Exact>(verts, tri, k)) == Sign::Zero
        });
        if zero {
            return Err(CutError::DegenerateTriangle { triangle: t });
        }
    }
    let mut half: FxMap<(u32, u32), u32> = FxMap::default();
    for (t, tri) in tris.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            if let Some(&other) = half.get(&(a, b)) {
                return Err(CutError::NonManifoldOrFlipped { triangle: t, other: other as usize, a, b });
            }
            half.insert((a, b), t as u32);
        }
    }
    let mut edges = Vec::new();
    let mut index: FxMap<(u32, u32), u32> = FxMap::default();
    let mut edge_tris = Vec::new();
    for (&(a, b), &t) in half.iter() {
        let Some(&t2) = half.get(&(b, a)) else {
            return Err(CutError::NotWatertight { triangle: t as usize, a, b });
        };
        if a < b {
            index.insert((a, b), edges.len() as u32);
            edges.push([a, b]);
            edge_tris.push([t, t2]);
        }
    }
    // deterministic edge order
    let mut order: Vec<usize> = (0..edges.len()).collect();
    order.sort_by_key(|&i| edges[i]);
    let edges: Vec<[u32; 2]> = order.iter().map(|&i| edges[i]).collect();
    let edge_tris: Vec<[u32; 2]> = order.iter().map(|&i| edge_tris[i]).collect();
    let index: FxMap<(u32, u32), u32> = edges.iter().enumerate().map(|(i, e)| ((e[0], e[1]), i as u32)).collect();
    let tri_edges = tris
        .iter()
        .map(|tri| [0, 1, 2].map(|k| {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            index[&(a.min(b), a.max(b))]
        }))
        .collect();
    // manifold vertices: the triangles around each vertex form one fan
    let mut around: Vec<Vec<u32>> = vec![Vec::new(); verts.len()];
    for (t, tri) in tris.iter().enumerate() {
        for &v in tri {
            around[v as usize].push(t as u32);
        }
    }
    for (v, ts) in around.iter().enumerate() {
        if ts.is_empty() {
            continue;
        }
        // walk the fan from ts[0]: next triangle across the edge (v, b)
        let v = v as u32;
        let mut count = 0;
        let mut t = ts[0];
        loop {
            count += 1;
            let tri = tris[t as usize];
            let k = tri.iter().position(|&x| x == v).unwrap();
            let prev = tri[(k + 2) % 3];
            // edge (prev -> v) in t; the neighbour holds (v -> prev)
            t = half[&(v, prev)];
            if t == ts[0] || count > ts.len() {
                break;
            }
        }
        if count != ts.len() {
            return Err(CutError::NonManifoldVertex { vertex: v as usize });
        }
    }
    // positive volume (outward orientation)
    let mut vol = 0.0;
    let mut scale = 0.0f64;
    for tri in tris {
        let [a, b, c] = tri.map(|i| verts[i as usize]);
        let cr = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
        vol += (cr[0] * c[0] + cr[1] * c[1] + cr[2] * c[2]) / 6.0;
        scale = scale.max(a.iter().chain(b.iter()).fold(0.0f64, |m, x| m.max(x.abs())));
    }
    if vol <= 0.0 {
        return Err(CutError::InwardOrientation { volume: vol });
    }
    Ok((edges, tri_edges, edge_tris))
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
                        || Interval::point(p[a]).mul(&Interval::point(q[b])).sub(&Interval::point(p[b]).mul(&Interval::point(q[a]))),
                        || Exact::from_f64(p[a]).mul(&Exact::from_f64(q[b])).sub(&Exact::from_f64(p[b]).mul(&Exact::from_f64(q[a]))),
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
