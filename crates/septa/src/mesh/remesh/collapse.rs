//! Collapsing short edges (Botsch & Kobbelt 2004): an edge shorter than
//! `4/5 L` loses one end, which goes into the other, only where that keeps
//! every patch, trace and fixed vertex:
//!
//! - who may go: a free vertex into any neighbour; a curve vertex only
//!   into a neighbour along its own trace (the trace stays a path between
//!   its fixed ends); a fixed vertex never;
//! - the link condition (Dey et al.; Edelsbrunner): the vertices adjacent
//!   to both ends are exactly the apexes of the triangles on the edge, so
//!   the complex of all patches together keeps its topology;
//! - no triangle turns over (its normal within 60 degrees of its patch's
//!   area-weighted normal there), gets an edge longer than `4/3 L`, or,
//!   with three constraint vertices (which nothing later improves), a new
//!   angle under 25 degrees (or under the smallest there before).
//!
//! Two free ends meet at their middle, put back on the patch.

use super::sizing::Sizing;
use super::soup::{add, ekey, min_angle, scale, Kind, Soup, V};
use super::surface::Surface;

/// Whether `u` may go into `v` (module doc).
fn may_go(s: &Soup, u: u32, v: u32) -> bool {
    match s.kind[u as usize] {
        Kind::Fixed => false,
        Kind::Free(_) => true,
        Kind::Curve(t) => s.feat.get(&ekey(u, v)) == Some(&t),
    }
}

/// The link condition for the edge `uv`.
fn link_ok(s: &Soup, u: u32, v: u32) -> bool {
    let nu = s.neighbours(u);
    let nv = s.neighbours(v);
    let mut apexes: Vec<u32> = s.edge_tris(u, v).iter().map(|&t| s.apex(t, u, v)).collect();
    apexes.sort_unstable();
    apexes.dedup();
    let common: Vec<u32> = nu.iter().copied().filter(|w| nv.contains(w)).collect();
    common == apexes
}

/// Whether no triangle of `u`'s, with `u` at `v`, would have the corners of
/// one of `v`'s (two triangles on the same three vertices: the link
/// condition's exception, a tetrahedron's boundary collapsing to a pillow).
fn no_twins(s: &Soup, u: u32, v: u32) -> bool {
    let sorted = |t: [u32; 3]| {
        let mut t = t;
        t.sort_unstable();
        t
    };
    let theirs: Vec<[u32; 3]> =
        s.vt[v as usize].iter().map(|&t| s.tris[t as usize]).filter(|t| !t.contains(&u)).map(sorted).collect();
    s.vt[u as usize].iter().map(|&t| s.tris[t as usize]).filter(|t| !t.contains(&v)).all(|t| {
        let t = sorted(t.map(|w| if w == u { v } else { w }));
        !theirs.contains(&t)
    })
}

/// Whether the triangles of `u` and `v` stay good with `u` at `v` and `v`
/// at `p`.
fn shape_ok(s: &Soup, u: u32, v: u32, p: V, hi: f64) -> bool {
    let at = |w: u32| if w == u || w == v { p } else { s.x[w as usize] };
    let on_edge = |t: &[u32; 3]| t.contains(&u) && t.contains(&v);
    if !s.faces_ok(&[u, v], on_edge, at) {
        return false;
    }
    let (mut old_min, mut new_min) = (180.0f64, 180.0f64);
    for &w in [u, v].iter() {
        for &t in &s.vt[w as usize] {
            let tri = s.tris[t as usize];
            old_min = old_min.min(min_angle(tri.map(|x| s.x[x as usize])));
            if !on_edge(&tri) {
                let q = tri.map(at);
                if (0..3).any(|k| super::soup::dist(q[k], q[(k + 1) % 3]) > hi) {
                    return false;
                }
                // only triangles of constraint vertices, which no later
                // operation can improve
                let w = tri.map(|x| if x == u { v } else { x });
                if w.iter().all(|&x| !matches!(s.kind[x as usize], Kind::Free(_))) {
                    new_min = new_min.min(min_angle(q));
                }
            }
        }
    }
    // no new small angle (an ear of three curve vertices, where a free
    // vertex inside a small disk went into its rim)
    new_min >= old_min.min(MIN_ANGLE)
}

/// Angles a collapse or flip may not newly go under (degrees).
pub(super) const MIN_ANGLE: f64 = 25.0;

/// Collapses `u` into `v` with `v` put at `p`.
fn collapse(s: &mut Soup, u: u32, v: u32, p: V) {
    for t in s.edge_tris(u, v) {
        s.kill_tri(t);
    }
    for t in s.vt[u as usize].clone() {
        let tri = s.tris[t as usize].map(|w| if w == u { v } else { w });
        s.set_tri(t, tri);
    }
    if let Kind::Curve(tr) = s.kind[u as usize] {
        s.feat.remove(&ekey(u, v));
        let others: Vec<u32> = s.neighbours(v).into_iter().filter(|&w| s.feat.get(&ekey(u, w)) == Some(&tr)).collect();
        for w in others {
            s.feat.remove(&ekey(u, w));
            s.feat.insert(ekey(v, w), tr);
        }
    }
    s.x[v as usize] = p;
    s.kind[u as usize] = Kind::Fixed;
    s.vt[u as usize].clear();
}

/// Collapses the edges shorter than `lo` where allowed; how many.
pub(super) fn collapse_short(s: &mut Soup, surf: &Surface, size: &Sizing) -> usize {
    let mut n = 0;
    let mut short: Vec<(f64, u32, u32)> = s
        .edges()
        .into_iter()
        .map(|(a, b)| (s.len(a, b), a, b))
        .filter(|e| e.0 < 0.8 * size.edge(s, e.1, e.2))
        .collect();
    short.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (_, a, b) in short {
        if s.vt[a as usize].is_empty() || s.vt[b as usize].is_empty() || s.edge_tris(a, b).is_empty() {
            continue;
        }
        let h = size.edge(s, a, b);
        let (lo, hi) = (0.8 * h, 4.0 / 3.0 * h);
        if s.len(a, b) >= lo || !link_ok(s, a, b) || !no_twins(s, a, b) || !no_twins(s, b, a) {
            continue;
        }
        let both_free = matches!((s.kind[a as usize], s.kind[b as usize]), (Kind::Free(_), Kind::Free(_)));
        let mut tries: Vec<(u32, u32, V)> = Vec::new();
        if both_free {
            let mid = surf.place(s.kind[b as usize], scale(add(s.x[a as usize], s.x[b as usize]), 0.5));
            tries.push((a, b, mid));
        }
        if may_go(s, a, b) {
            tries.push((a, b, s.x[b as usize]));
        }
        if may_go(s, b, a) {
            tries.push((b, a, s.x[a as usize]));
        }
        if let Some(&(u, v, p)) = tries.iter().find(|&&(u, v, p)| shape_ok(s, u, v, p, hi)) {
            collapse(s, u, v, p);
            n += 1;
        }
    }
    n
}
