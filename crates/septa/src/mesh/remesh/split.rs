//! Splitting long edges (Botsch & Kobbelt 2004): an edge longer than
//! `4/3` of its target length (`L`, less near short features: `sizing.rs`) gets a vertex at its middle, put back on the surface, and every
//! triangle on it (every patch around a constraint edge) is split in two
//! with its orientation kept. A constraint edge's new vertex is on its trace.

use super::sizing::Sizing;
use super::soup::{add, ekey, scale, Kind, Soup};
use super::surface::Surface;

/// Splits the edge `ab`; the new vertex.
pub(super) fn split(s: &mut Soup, surf: &Surface, a: u32, b: u32) -> u32 {
    let mid = scale(add(s.x[a as usize], s.x[b as usize]), 0.5);
    let ts = s.edge_tris(a, b);
    let trace = s.feat.get(&ekey(a, b)).copied();
    let kind = match trace {
        Some(t) => Kind::Curve(t),
        None => Kind::Free(s.patch[ts[0] as usize]),
    };
    // the identity of the vertex it is nearer in kind: a curve's inner
    // vertex if one end is one, else either end
    let origin = match (s.kind[a as usize], s.kind[b as usize]) {
        (k, _) if k == kind => s.origin[a as usize],
        (_, k) if k == kind => s.origin[b as usize],
        _ => s.origin[a as usize],
    };
    let p = surf.place(kind, mid);
    let m = s.add_vertex(p, kind, origin);
    for t in ts {
        let tri = s.tris[t as usize];
        let i = (0..3).find(|&k| (tri[k] == a && tri[(k + 1) % 3] == b) || (tri[k] == b && tri[(k + 1) % 3] == a));
        let Some(i) = i else { continue };
        let (p, q, c) = (tri[i], tri[(i + 1) % 3], tri[(i + 2) % 3]);
        s.set_tri(t, [p, m, c]);
        let patch = s.patch[t as usize];
        s.add_tri([m, q, c], patch);
    }
    if let Some(t) = trace {
        s.feat.remove(&ekey(a, b));
        s.feat.insert(ekey(a, m), t);
        s.feat.insert(ekey(m, b), t);
    }
    m
}

/// Splits every edge longer than `4/3` of its target length until none is;
/// how many splits.
pub(super) fn split_long(s: &mut Soup, surf: &Surface, size: &Sizing) -> usize {
    let mut n = 0;
    for _pass in 0..8 {
        let long: Vec<(u32, u32)> =
            s.edges().into_iter().filter(|&(a, b)| s.len(a, b) > 4.0 / 3.0 * size.edge(s, a, b)).collect();
        if long.is_empty() {
            break;
        }
        for (a, b) in long {
            if !s.edge_tris(a, b).is_empty() {
                split(s, surf, a, b);
                n += 1;
            }
        }
    }
    n
}
