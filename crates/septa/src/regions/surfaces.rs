//! Surfaces of interest: kept polygons, oriented from the lesser region,
//! grouped into connected pieces per region pair, with their topology.

use rustc_hash::FxHashMap;

use crate::buckets::for_each_bucket;
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
    // Join kept polygons of one pair across shared edges: (edge, pair,
    // polygon) entries sorted, so the polygons at one edge of one pair are
    // a run (component numbering does not depend on the union order). Each
    // entry is packed into one `u128` in the same order (the pair by its
    // rank among the distinct pairs).
    // The distinct pairs are few: gathered in a set, not by sorting a copy
    // of every polygon's pair.
    let distinct: rustc_hash::FxHashSet<[RegionId; 2]> = pairs.iter().copied().collect();
    let mut ranks: Vec<[RegionId; 2]> = distinct.into_iter().collect();
    ranks.sort_unstable();
    let rank = |p: &[RegionId; 2]| ranks.binary_search(p).expect("a listed pair") as u128;
    let by_edge = sorted_edge_entries(&loop_start, &loops, |i| rank(&pairs[i]), net.points.len());
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
    count_sorted(&mut surfaces, &by_edge, &loop_start, &loops, &comp, net.points.len());
    Extracted { faces, loop_start, loops, face_surface: comp, surfaces }
}

/// The entries `a << 96 | b << 64 | rank << 32 | polygon` of every side
/// `(a, b)`, `a < b`, of the `n` polygons, sorted ascending. A counting sort
/// on the lesser vertex `a` (an index below `points`) written in place by a
/// second pass over the polygons, then a sort of each vertex's few entries:
/// the same order as sorting the whole array, without its `log n` passes
/// over half a million 16-byte entries.
fn sorted_edge_entries(loop_start: &[u32], loops: &[u32], rank: impl Fn(usize) -> u128, points: usize) -> Vec<u128> {
    let n = loop_start.len() - 1;
    let sides = |i: usize| {
        let p = &loops[loop_start[i] as usize..loop_start[i + 1] as usize];
        // The successor without `%`: a division per polygon side was a visible
        // share of this pass.
        (0..p.len()).map(move |k| edge(p[k], p[if k + 1 == p.len() { 0 } else { k + 1 }]))
    };
    let mut start = vec![0u32; points + 1];
    for i in 0..n {
        for (a, _) in sides(i) {
            start[a as usize + 1] += 1;
        }
    }
    for v in 0..points {
        start[v + 1] += start[v];
    }
    let mut by_edge = vec![0u128; start[points] as usize];
    let mut next = start.clone();
    for i in 0..n {
        let r = rank(i) << 32 | i as u128;
        for (a, b) in sides(i) {
            let slot = &mut next[a as usize];
            by_edge[*slot as usize] = (a as u128) << 96 | (b as u128) << 64 | r;
            *slot += 1;
        }
    }
    for_each_bucket(&mut by_edge, &start, |_, entries| {
        entries.sort_unstable();
        0
    });
    by_edge
}

/// [`count_surfaces`] from the sorted (edge, pair, polygon) entries of
/// [`extract`], without sorting again: the entries of one edge and one pair
/// are a run whose polygons were joined, so each run is one edge of one
/// surface (a boundary edge when the run has one entry); vertices are
/// counted per surface with a mark per vertex, the polygons visited
/// surface by surface (a counting sort by surface).
fn count_sorted(
    surfaces: &mut [Surface],
    by_edge: &[u128],
    loop_start: &[u32],
    loops: &[u32],
    face_surface: &[u32],
    points: usize,
) {
    let count = surfaces.len();
    let mut distinct = vec![0i64; count];
    let mut boundary: Vec<Vec<(u32, u32)>> = vec![Vec::new(); count];
    let mut i = 0;
    while i < by_edge.len() {
        let mut j = i + 1;
        while j < by_edge.len() && by_edge[j] >> 32 == by_edge[i] >> 32 {
            j += 1;
        }
        let s = face_surface[by_edge[i] as u32 as usize] as usize;
        distinct[s] += 1;
        if j - i == 1 {
            boundary[s].push(((by_edge[i] >> 96) as u32, (by_edge[i] >> 64) as u32));
        }
        i = j;
    }
    // Polygons by surface (stable), then distinct vertices per surface.
    let mut start = vec![0u32; count + 1];
    for &s in face_surface {
        start[s as usize + 1] += 1;
    }
    for s in 0..count {
        start[s + 1] += start[s];
    }
    let mut order = vec![0u32; face_surface.len()];
    let mut next = start.clone();
    for (f, &s) in face_surface.iter().enumerate() {
        order[next[s as usize] as usize] = f as u32;
        next[s as usize] += 1;
    }
    let mut mark = vec![u32::MAX; points];
    for s in 0..count {
        let mut verts = 0i64;
        for &f in &order[start[s] as usize..start[s + 1] as usize] {
            for &v in &loops[loop_start[f as usize] as usize..loop_start[f as usize + 1] as usize] {
                if mark[v as usize] != s as u32 {
                    mark[v as usize] = s as u32;
                    verts += 1;
                }
            }
        }
        let faces = (start[s + 1] - start[s]) as i64;
        surfaces[s].faces = faces as usize;
        surfaces[s].euler = verts - distinct[s] + faces;
        surfaces[s].boundary_loops = count_loops(&boundary[s]);
    }
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
            edges[s].push(edge(p[k], p[if k + 1 == p.len() { 0 } else { k + 1 }]));
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
