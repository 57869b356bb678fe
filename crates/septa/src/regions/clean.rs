//! Clean-up of small and thin triangles (Bloomenthal 4.5.3.1) that never
//! changes the combinatorics of the shape: the surfaces keep their Euler
//! characteristic and boundary loops, the curves their corners and order,
//! polygons their orientation.
//!
//! Bloomenthal replaces each pair of close vertices joined by a triangle
//! edge by their average, and a vertex close to the opposite edge by the
//! edge's midpoint, then drops degenerate triangles; done blindly this can
//! pinch a surface, close a small hole or cut a curve. Here the kept
//! polygons are fanned into triangles and the short edges are collapsed,
//! shortest first, each only where it is safe:
//!
//! - **features stay**: an edge is a feature when it lies on a curve of
//!   interest, on the boundary of a surface, or between two surfaces; a
//!   vertex on a feature may only slide along one of its feature edges, and
//!   a *corner* (a curve's end, or a vertex on more or fewer than two
//!   feature edges) never moves;
//! - **the link condition** (Dey et al., Edelsbrunner): collapsing `uv`
//!   keeps the topology of the triangle complex (all surfaces together)
//!   iff the vertices adjacent to both `u` and `v` are exactly the apexes of
//!   the triangles on `uv`, and no two triangles `uxy` and `vxy` exist;
//! - **no fold**: no triangle of `u`'s star turns over or becomes degenerate.
//!
//! A thin triangle whose obtuse vertex lies closer than the threshold to
//! the opposite edge (Bloomenthal's second case) has that edge flipped
//! instead of the vertex moved onto it: a flip of a non-feature edge
//! between two triangles of one surface keeps every count (vertices, edges,
//! triangles) and every feature, provided the new edge does not exist yet
//! and neither new triangle turns over.
//!
//! `u` goes to `v`'s position (a network vertex): no new coordinates are
//! made. Floating point only chooses which short edges to collapse; which
//! collapses are allowed is decided combinatorially. The result is checked
//! (`tests/regions/clean.rs`): surface Euler characteristics and boundary
//! loops, curve corners, and consistent orientation are unchanged.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use rustc_hash::{FxHashMap, FxHashSet};

use super::RegionSurfaces;

/// What the clean-up did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CleanStats {
    /// Triangles before (the kept polygons fanned).
    pub triangles_before: usize,
    /// Triangles after.
    pub triangles_after: usize,
    /// Edges collapsed.
    pub collapsed: usize,
    /// Short edges left because a collapse would have changed the shape's
    /// combinatorics (link condition, a corner or feature) or folded a triangle.
    pub refused: usize,
    /// Edges flipped under a thin triangle's obtuse vertex.
    pub flipped: usize,
    /// Smallest triangle angle before and after, in degrees (a measure of
    /// thin triangles; floating point, for reporting).
    pub min_angle: [f64; 2],
}

/// Smallest angle (degrees) of the live triangles.
fn min_angle(m: &Mesh) -> f64 {
    let mut best = 180.0f64;
    for (t, tri) in m.tris.iter().enumerate() {
        if m.alive[t] {
            best = best.min(tri_min_angle(tri.map(|x| m.points[x as usize])));
        }
    }
    best
}

/// Smallest angle (degrees) of a triangle (0 when degenerate).
fn tri_min_angle(p: [P3; 3]) -> f64 {
    let mut best = 180.0f64;
    for k in 0..3 {
        let (u, v) = (sub(p[(k + 1) % 3], p[k]), sub(p[(k + 2) % 3], p[k]));
        let c = dot(u, v) / (len(u) * len(v));
        best = best.min(if c.is_finite() { c.clamp(-1.0, 1.0).acos().to_degrees() } else { 0.0 });
    }
    best
}

type P3 = [f64; 3];

fn sub(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: P3, b: P3) -> P3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn dot(a: P3, b: P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn len(a: P3) -> f64 {
    dot(a, a).sqrt()
}

fn key(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

/// The triangle complex being collapsed.
struct Mesh<'a> {
    points: &'a [P3],
    tris: Vec<[u32; 3]>,
    surface: Vec<u32>,
    alive: Vec<bool>,
    /// Triangles at each vertex (may hold dead ones; filtered on use).
    at: FxHashMap<u32, Vec<u32>>,
    /// Feature edges and the number of feature edges at each vertex.
    feature: FxHashSet<(u32, u32)>,
    feature_deg: FxHashMap<u32, u32>,
    corner: FxHashSet<u32>,
}

impl Mesh<'_> {
    fn star(&self, v: u32) -> Vec<u32> {
        self.at.get(&v).map_or_else(Vec::new, |ts| {
            ts.iter().copied().filter(|&t| self.alive[t as usize] && self.tris[t as usize].contains(&v)).collect()
        })
    }

    fn neighbours(&self, v: u32) -> FxHashSet<u32> {
        let mut n = FxHashSet::default();
        for t in self.star(v) {
            for &x in &self.tris[t as usize] {
                if x != v {
                    n.insert(x);
                }
            }
        }
        n
    }

    /// Whether collapsing `u` into `v` keeps the combinatorics (module doc).
    fn can_collapse(&self, u: u32, v: u32) -> bool {
        if self.corner.contains(&u) {
            return false;
        }
        let on_feature = self.feature_deg.get(&u).copied().unwrap_or(0) > 0;
        if on_feature && !self.feature.contains(&key(u, v)) {
            return false;
        }
        let su = self.star(u);
        let sv = self.star(v);
        let on_uv: Vec<u32> = su.iter().copied().filter(|&t| self.tris[t as usize].contains(&v)).collect();
        if on_uv.is_empty() {
            return false;
        }
        // Link condition, vertices: common neighbours are the apexes on uv.
        let apex: FxHashSet<u32> =
            on_uv.iter().flat_map(|&t| self.tris[t as usize]).filter(|&x| x != u && x != v).collect();
        let (nu, nv) = (self.neighbours(u), self.neighbours(v));
        if nu.iter().filter(|x| nv.contains(x)).any(|x| !apex.contains(x)) {
            return false;
        }
        // Link condition, edges: no triangles uxy and vxy.
        let opposite = |s: &[u32], w: u32| -> FxHashSet<(u32, u32)> {
            s.iter()
                .map(|&t| {
                    let r: Vec<u32> = self.tris[t as usize].iter().copied().filter(|&x| x != w).collect();
                    key(r[0], r[1])
                })
                .collect()
        };
        let (ou, ov) = (opposite(&su, u), opposite(&sv, v));
        if ou.iter().any(|e| ov.contains(e)) {
            return false;
        }
        // A feature loop of three edges would vanish.
        if on_feature {
            let others: Vec<u32> =
                nu.iter().copied().filter(|&x| x != v && self.feature.contains(&key(u, x))).collect();
            if others.iter().any(|&w| self.feature.contains(&key(v, w))) {
                return false;
            }
        }
        // No fold: u's other triangles keep their orientation, and the
        // smallest angle around u does not get worse.
        let pv = self.points[v as usize];
        let (mut old, mut new) = (180.0f64, 180.0f64);
        for &t in &su {
            let tri = self.tris[t as usize];
            let p = tri.map(|x| self.points[x as usize]);
            old = old.min(tri_min_angle(p));
            if tri.contains(&v) {
                continue;
            }
            let q = tri.map(|x| if x == u { pv } else { self.points[x as usize] });
            let (n0, n1) = (cross(sub(p[1], p[0]), sub(p[2], p[0])), cross(sub(q[1], q[0]), sub(q[2], q[0])));
            if !(dot(n0, n1) > 0.0) {
                return false;
            }
            new = new.min(tri_min_angle(q));
        }
        new >= old
    }

    fn collapse(&mut self, u: u32, v: u32) {
        for t in self.star(u) {
            let tri = &mut self.tris[t as usize];
            if tri.contains(&v) {
                self.alive[t as usize] = false;
            } else {
                for x in tri.iter_mut() {
                    if *x == u {
                        *x = v;
                    }
                }
                self.at.entry(v).or_default().push(t);
            }
        }
        self.at.remove(&u);
        // u's feature edge to v disappears; its other one now ends at v.
        if self.feature.remove(&key(u, v)) {
            let others: Vec<(u32, u32)> = self.feature.iter().copied().filter(|&(a, b)| a == u || b == u).collect();
            for (a, b) in others {
                let w = if a == u { b } else { a };
                self.feature.remove(&(a, b));
                self.feature.insert(key(v, w));
            }
            self.feature_deg.remove(&u);
        }
    }
}

/// Flips the edge under the obtuse vertex of each thin triangle where that
/// is safe (module doc); a few rounds, until none is left. Returns the flips.
fn flip_thin(m: &mut Mesh, close: f64) -> usize {
    let mut flips = 0;
    for _round in 0..4 {
        let mut edges: FxHashMap<(u32, u32), Vec<u32>> = FxHashMap::default();
        for t in 0..m.tris.len() {
            if m.alive[t] {
                let tri = m.tris[t];
                for k in 0..3 {
                    edges.entry(key(tri[k], tri[(k + 1) % 3])).or_default().push(t as u32);
                }
            }
        }
        let mut changed = 0;
        for ti in 0..m.tris.len() {
            if !m.alive[ti] {
                continue;
            }
            let t = ti as u32;
            let tri = m.tris[ti];
            let p = tri.map(|x| m.points[x as usize]);
            let n = cross(sub(p[1], p[0]), sub(p[2], p[0]));
            for k in 0..3 {
                // Vertex k opposite edge (a, b): thin when obtuse at k and near the edge.
                let (a, b, c) = (tri[(k + 1) % 3], tri[(k + 2) % 3], tri[k]);
                let (pa, pb, pc) = (p[(k + 1) % 3], p[(k + 2) % 3], p[k]);
                let base = len(sub(pb, pa));
                if !(dot(sub(pa, pc), sub(pb, pc)) < 0.0 && len(n) / base < close) {
                    continue;
                }
                let e = key(a, b);
                if m.feature.contains(&e) {
                    continue;
                }
                let Some(ts) = edges.get(&e) else { continue };
                if ts.len() != 2 || m.surface[ts[0] as usize] != m.surface[ts[1] as usize] {
                    continue;
                }
                let other = if ts[0] == t { ts[1] } else { ts[0] };
                if !m.alive[other as usize] {
                    continue;
                }
                let d = m.tris[other as usize].iter().copied().find(|&x| x != a && x != b).expect("a triangle");
                if edges.contains_key(&key(c, d)) || c == d {
                    continue;
                }
                // t is (a, b, c) in its orientation (a -> b), other has b -> a:
                // the new pair (c, a, d) and (d, b, c) keeps both orientations.
                let (pd, nt) = (m.points[d as usize], n);
                let n1 = cross(sub(pa, pc), sub(pd, pc));
                let n2 = cross(sub(pb, pd), sub(pc, pd));
                if !(dot(n1, nt) > 0.0 && dot(n2, nt) > 0.0) {
                    continue;
                }
                // Only a flip that raises the pair's smallest angle.
                let old = tri_min_angle([pa, pb, pc]).min(tri_min_angle([pb, pa, pd]));
                if tri_min_angle([pc, pa, pd]).min(tri_min_angle([pd, pb, pc])) <= old {
                    continue;
                }
                m.tris[ti] = [c, a, d];
                m.tris[other as usize] = [d, b, c];
                for (x, tt) in [(c, other), (d, t)] {
                    m.at.entry(x).or_default().push(tt);
                }
                // The triangles no longer at a (other) and b (t) are filtered by `star`.
                edges.remove(&e);
                edges.insert(key(c, d), vec![t, other]);
                for (x, y, from, to) in [(a, d, other, t), (b, c, t, other)] {
                    if let Some(l) = edges.get_mut(&key(x, y)) {
                        for z in l.iter_mut() {
                            if *z == from {
                                *z = to;
                            }
                        }
                    }
                }
                changed += 1;
                break;
            }
        }
        flips += changed;
        if changed == 0 {
            break;
        }
    }
    flips
}

/// Cleans `r` (module doc): edges shorter than `close` (a length) are
/// collapsed where safe. Returns the cleaned surfaces, whose kept polygons
/// are triangles (each still naming its network polygon in `faces`), with
/// curves and surface counts updated; normals, if any, are recomputed by
/// the caller.
pub fn clean(r: &RegionSurfaces, close: f64) -> (RegionSurfaces, CleanStats) {
    let points = &r.network.points;
    let mut tris = Vec::new();
    let mut surface = Vec::new();
    let mut origin = Vec::new();
    for i in 0..r.faces.len() {
        let p = &r.loops[r.loop_start[i] as usize..r.loop_start[i + 1] as usize];
        for k in 1..p.len() - 1 {
            tris.push([p[0], p[k], p[k + 1]]);
            surface.push(r.face_surface[i]);
            origin.push(r.faces[i]);
        }
    }
    let n = tris.len();
    // Features: curve edges, and edges not shared by exactly two triangles of one surface.
    let mut uses: FxHashMap<(u32, u32), Vec<u32>> = FxHashMap::default();
    for (t, tri) in tris.iter().enumerate() {
        for k in 0..3 {
            uses.entry(key(tri[k], tri[(k + 1) % 3])).or_default().push(t as u32);
        }
    }
    let mut feature: FxHashSet<(u32, u32)> = FxHashSet::default();
    for (e, ts) in &uses {
        if ts.len() != 2 || surface[ts[0] as usize] != surface[ts[1] as usize] {
            feature.insert(*e);
        }
    }
    let mut corner: FxHashSet<u32> = FxHashSet::default();
    for c in &r.curves {
        for w in c.vertices.windows(2) {
            feature.insert(key(w[0], w[1]));
        }
        if !c.closed {
            corner.extend([c.vertices[0], *c.vertices.last().unwrap_or(&c.vertices[0])]);
        }
    }
    let mut feature_deg: FxHashMap<u32, u32> = FxHashMap::default();
    for &(a, b) in &feature {
        *feature_deg.entry(a).or_default() += 1;
        *feature_deg.entry(b).or_default() += 1;
    }
    corner.extend(feature_deg.iter().filter(|(_, &d)| d != 2).map(|(&v, _)| v));
    let mut at: FxHashMap<u32, Vec<u32>> = FxHashMap::default();
    for (t, tri) in tris.iter().enumerate() {
        for &x in tri {
            at.entry(x).or_default().push(t as u32);
        }
    }
    let mut m = Mesh { points, tris, surface, alive: vec![true; n], at, feature, feature_deg, corner };
    // Shortest first; lengths are fixed (no vertex moves but onto another).
    let mut heap: BinaryHeap<Reverse<(u64, u32, u32)>> = BinaryHeap::new();
    let edge_len = |a: u32, b: u32| len(sub(points[a as usize], points[b as usize]));
    for &(a, b) in uses.keys() {
        let l = edge_len(a, b);
        if l < close {
            heap.push(Reverse((l.to_bits(), a, b)));
        }
    }
    let mut stats = CleanStats { triangles_before: n, ..CleanStats::default() };
    stats.min_angle[0] = min_angle(&m);
    let mut removed: FxHashMap<u32, u32> = FxHashMap::default();
    while let Some(Reverse((_, a, b))) = heap.pop() {
        if removed.contains_key(&a) || removed.contains_key(&b) || !m.neighbours(a).contains(&b) {
            continue;
        }
        // Move the vertex that may move; prefer keeping feature vertices.
        let (u, v) = if m.can_collapse(a, b) {
            (a, b)
        } else if m.can_collapse(b, a) {
            (b, a)
        } else {
            stats.refused += 1;
            continue;
        };
        m.collapse(u, v);
        removed.insert(u, v);
        stats.collapsed += 1;
        for x in m.neighbours(v) {
            let l = edge_len(v, x);
            if l < close {
                heap.push(Reverse((l.to_bits(), v.min(x), v.max(x))));
            }
        }
    }
    stats.flipped = flip_thin(&mut m, close);
    stats.min_angle[1] = min_angle(&m);
    // Rebuild the region surfaces from the live triangles.
    let resolve = |mut v: u32| {
        while let Some(&w) = removed.get(&v) {
            v = w;
        }
        v
    };
    let mut out = r.clone();
    out.faces.clear();
    out.loops.clear();
    out.loop_start = vec![0];
    out.face_surface.clear();
    for t in 0..n {
        if m.alive[t] {
            out.faces.push(origin[t]);
            out.loops.extend_from_slice(&m.tris[t]);
            out.loop_start.push(out.loops.len() as u32);
            out.face_surface.push(m.surface[t]);
        }
    }
    for c in &mut out.curves {
        let mut vs: Vec<u32> = Vec::with_capacity(c.vertices.len());
        for &v in &c.vertices {
            let v = resolve(v);
            if vs.last() != Some(&v) {
                vs.push(v);
            }
        }
        c.length = vs.windows(2).map(|w| edge_len(w[0], w[1])).sum();
        c.vertices = vs;
    }
    super::surfaces::recount(&mut out);
    stats.triangles_after = out.faces.len();
    out.normals.clear();
    (out, stats)
}
