//! Surfaces of interest: kept polygons, oriented from the lesser region,
//! grouped into connected pieces per region pair, with their topology.

use rustc_hash::FxHashMap;

use crate::network::Network;
use crate::scene::{must_flip, Interest, RegionId};
use crate::uf::UnionFind;

/// A connected surface separating one region pair of interest.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Surface {
    /// The region pair, ascending.
    pub regions: [RegionId; 2],
    /// Number of polygons.
    pub faces: usize,
    /// Euler characteristic `V - E + F` of the surface's polygons.
    pub euler: i64,
    /// Number of boundary loops (cycles of edges used by one polygon).
    pub boundary_loops: usize,
}

pub(crate) struct Extracted {
    pub faces: Vec<u32>,
    pub loop_start: Vec<u32>,
    pub loops: Vec<u32>,
    pub face_surface: Vec<u32>,
    pub surfaces: Vec<Surface>,
}

fn edge(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

pub(crate) fn extract(net: &Network, region: &[RegionId], interest: &Interest) -> Extracted {
    let mut faces = Vec::new();
    let mut pairs = Vec::new();
    let mut loop_start = vec![0u32];
    let mut loops = Vec::new();
    for f in 0..net.num_faces() {
        let [cp, cn] = net.face_cells[f];
        if cp == u32::MAX || cn == u32::MAX {
            continue; // on the grid boundary: the outside is no region
        }
        let (rp, rn) = (region[cp as usize], region[cn as usize]);
        if !interest.surface(rp, rn) {
            continue;
        }
        faces.push(f as u32);
        pairs.push([rp.min(rn), rp.max(rn)]);
        // Network polygons are counter-clockwise seen from their positive
        // cell, i.e. their normal points into region rp.
        let verts = net.face(f);
        if must_flip(rp, rn) {
            loops.extend(verts.iter().rev());
        } else {
            loops.extend_from_slice(verts);
        }
        loop_start.push(loops.len() as u32);
    }
    let n = faces.len();
    let poly = |i: usize| &loops[loop_start[i] as usize..loop_start[i + 1] as usize];
    // Join kept polygons of one pair across shared edges: (edge, pair,
    // polygon) entries sorted, so the polygons at one edge of one pair are
    // a run (component numbering does not depend on the union order). Each
    // entry is packed into one `u128` in the same order (the pair by its
    // rank among the distinct pairs), which sorts several times faster than
    // a tuple of 32 bytes.
    let mut ranks: Vec<[RegionId; 2]> = pairs.clone();
    ranks.sort_unstable();
    ranks.dedup();
    let rank = |p: &[RegionId; 2]| ranks.binary_search(p).expect("a listed pair") as u128;
    let mut by_edge: Vec<u128> = Vec::with_capacity(loops.len());
    for i in 0..n {
        let p = poly(i);
        let r = rank(&pairs[i]) << 32 | i as u128;
        for k in 0..p.len() {
            let (a, b) = edge(p[k], p[(k + 1) % p.len()]);
            by_edge.push((a as u128) << 96 | (b as u128) << 64 | r);
        }
    }
    by_edge.sort_unstable();
    let mut uf = UnionFind::new(n);
    for w in by_edge.windows(2) {
        if w[0] >> 32 == w[1] >> 32 {
            uf.union(w[0] as u32, w[1] as u32);
        }
    }
    let (comp, count) = uf.components();
    let mut surfaces: Vec<Surface> =
        (0..count).map(|_| Surface { regions: [0, 0], faces: 0, euler: 0, boundary_loops: 0 }).collect();
    for i in 0..n {
        surfaces[comp[i] as usize].regions = pairs[i];
    }
    count_surfaces(&mut surfaces, &loop_start, &loops, &comp);
    Extracted { faces, loop_start, loops, face_surface: comp, surfaces }
}

/// Recounts the surfaces of `r` (faces, Euler characteristic, boundary
/// loops) from its polygons, keeping their region pairs.
pub(crate) fn recount(r: &mut super::RegionSurfaces) {
    count_surfaces(&mut r.surfaces, &r.loop_start, &r.loops, &r.face_surface);
}

/// Fills each surface's polygon count, Euler characteristic `V - E + F` and
/// number of boundary loops (cycles of edges used by one polygon).
fn count_surfaces(surfaces: &mut [Surface], loop_start: &[u32], loops: &[u32], face_surface: &[u32]) {
    let count = surfaces.len();
    let mut verts: Vec<Vec<u32>> = vec![Vec::new(); count];
    let mut edges: Vec<Vec<(u32, u32)>> = vec![Vec::new(); count];
    for s in surfaces.iter_mut() {
        s.faces = 0;
    }
    for i in 0..face_surface.len() {
        let s = face_surface[i] as usize;
        surfaces[s].faces += 1;
        let p = &loops[loop_start[i] as usize..loop_start[i + 1] as usize];
        verts[s].extend_from_slice(p);
        for k in 0..p.len() {
            edges[s].push(edge(p[k], p[(k + 1) % p.len()]));
        }
    }
    for s in 0..count {
        verts[s].sort_unstable();
        verts[s].dedup();
        edges[s].sort_unstable();
        // Boundary edges appear once; others (usually) twice.
        let mut boundary = Vec::new();
        let mut distinct = 0;
        let mut i = 0;
        while i < edges[s].len() {
            let mut j = i;
            while j < edges[s].len() && edges[s][j] == edges[s][i] {
                j += 1;
            }
            if j - i == 1 {
                boundary.push(edges[s][i]);
            }
            distinct += 1;
            i = j;
        }
        surfaces[s].euler = verts[s].len() as i64 - distinct as i64 + surfaces[s].faces as i64;
        surfaces[s].boundary_loops = count_loops(&boundary);
    }
}

/// Connected components of a set of edges.
fn count_loops(edges: &[(u32, u32)]) -> usize {
    let mut id: FxHashMap<u32, u32> = FxHashMap::default();
    for &(a, b) in edges {
        for v in [a, b] {
            let n = id.len() as u32;
            id.entry(v).or_insert(n);
        }
    }
    let mut uf = UnionFind::new(id.len());
    for &(a, b) in edges {
        uf.union(id[&a], id[&b]);
    }
    uf.components().1
}
