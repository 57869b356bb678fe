//! Input conditions (TopoCut Sec. 2.1 and App. A), checked before any
//! cutting: each failure names the offending element. Closed meshes that
//! are not manifolds (App. C) are valid: an edge with as many triangles
//! each way, alternating about it, is paired into wedges (`wedges.rs`); a
//! vertex whose triangles form several fans (pinched) needs nothing more.

use crate::cut::triangles::selfx::intersecting_pairs;
use crate::cut::CutError;
use septa_exact::{filtered_sign, filtered_sign_bounded, Bounded, Exact, Interval, Ring, Sign};

/// Mesh edges `(u < v)`, per-triangle side edges, and per-edge triangles
/// `[t with u->v, t with v->u]` (of a non-manifold edge: its first wedge),
/// after checking watertight and consistently oriented.
pub type Topology = (Vec<[u32; 2]>, Vec<[u32; 3]>, Vec<[u32; 2]>);

/// What a closed mesh that is not a manifold adds to its [`Topology`].
#[derive(Clone, Debug, Default)]
pub struct NonManifold {
    /// Non-manifold edges: the wedges of the domain at each, as
    /// `[t with u->v, t with v->u]` (`wedges.rs`).
    pub wedges: rustc_hash::FxHashMap<u32, Vec<[u32; 2]>>,
    /// Vertices whose triangles form several fans (pinched).
    pub pinched: usize,
    /// Twice the Euler characteristic of the closed domain. Split at its
    /// non-manifold edges and pinched vertices (`V'` vertex copies, one per
    /// fan, `E'` edge copies, one per wedge) the boundary is a manifold
    /// surface of `chi' = V' - E' + T`, bounding a solid of `chi' / 2`;
    /// gluing back lowers both by `g = (V' - V) - (E' - E)`:
    /// `chi(domain) = chi' / 2 - g` (`chi(surface) / 2` for a manifold).
    pub domain_euler2: i64,
}

impl NonManifold {
    /// The triangle across side edge `e` of triangle `t` (its partner in
    /// the wedge for a non-manifold edge).
    pub fn across(&self, edge_tris: &[[u32; 2]], e: u32, t: u32) -> u32 {
        let pair = match self.wedges.get(&e) {
            Some(ws) => *ws.iter().find(|w| w.contains(&t)).expect("each triangle of the edge in one wedge"),
            None => edge_tris[e as usize],
        };
        if pair[0] == t {
            pair[1]
        } else {
            pair[0]
        }
    }
}

/// Checks indices, degenerate triangles, duplicate vertices, edges.
pub fn check_mesh(verts: &[[f64; 3]], tris: &[[u32; 3]]) -> Result<Topology, CutError> {
    check_mesh_nm(verts, tris).map(|x| x.0)
}

/// [`check_mesh`] with what non-manifold edges and vertices add.
pub fn check_mesh_nm(verts: &[[f64; 3]], tris: &[[u32; 3]]) -> Result<(Topology, NonManifold), CutError> {
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
    let mut nm = NonManifold::default();
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
        if fw.len() != bw.len() {
            if j - i == 1 {
                let (a, b) = if sides[i].2 { (u, v) } else { (v, u) };
                return Err(CutError::NotWatertight { triangle: t as usize, a, b });
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
        let e = edges.len() as u32;
        edges.push([u, v]);
        for s in &sides[i..j] {
            tri_edges[s.3 as usize][s.4 as usize] = e;
        }
        if fw.len() > 1 {
            // as many each way (TopoCut App. C): paired by angle into wedges
            let around: Vec<(u32, bool)> = sides[i..j].iter().map(|s| (s.3, s.2)).collect();
            let ws = super::wedges::pair_wedges(verts, tris, u, v, &around)?;
            edge_tris.push(ws[0]);
            nm.wedges.insert(e, ws);
        } else {
            edge_tris.push([fw[0].3, bw[0].3]);
        }
        i = j;
    }
    // the fans around each vertex: the triangles at a corner joined across
    // the sides entering it (a manifold vertex has one; a pinched one more)
    let mut seen = vec![false; 3 * tris.len()];
    let mut fans = vec![0u32; verts.len()];
    for t0 in 0..tris.len() {
        for k0 in 0..3 {
            if seen[3 * t0 + k0] {
                continue;
            }
            let v = tris[t0][k0];
            fans[v as usize] += 1;
            let (mut t, mut k) = (t0, k0);
            while !seen[3 * t + k] {
                seen[3 * t + k] = true;
                // the side entering v; the triangle across it is the next in the fan
                let e = tri_edges[t][(k + 2) % 3];
                t = nm.across(&edge_tris, e, t as u32) as usize;
                k = tris[t].iter().position(|&x| x == v).expect("the fan's triangles hold the vertex");
            }
        }
    }
    let used = fans.iter().filter(|&&f| f > 0).count() as i64;
    let copies: i64 = fans.iter().map(|&f| f as i64).sum();
    nm.pinched = fans.iter().filter(|&&f| f > 1).count();
    let edge_copies: i64 = edges.len() as i64 + nm.wedges.values().map(|w| w.len() as i64 - 1).sum::<i64>();
    let chi_split = copies - edge_copies + tris.len() as i64;
    let glue = (copies - used) - (edge_copies - edges.len() as i64);
    nm.domain_euler2 = chi_split - 2 * glue;
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
    Ok(((edges, tri_edges, edge_tris), nm))
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
