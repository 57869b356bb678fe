//! Feature curves: the network edges where a kept surface between two
//! regions turns from one function's zero set (IA) or material pair (MI)
//! to another's. For a solid made by CSG these are its sharp edges: the
//! top of a box meeting its side, a drilled hole's rim (Du et al. Fig. 19
//! returns them as the chains of the arrangement; here only those on the
//! solid's boundary). Where three or more regions meet, the edge is a
//! junction (`curves.rs`), never a feature.
//!
//! Exact like the rest: which function holds a polygon and which cells
//! are around an edge are combinatorial facts of the network; only the
//! curves' lengths are floating point.

use rustc_hash::FxHashMap;

use super::curves::{path_length, polylines, Curve, CurveKind};
use crate::complex::NONE;
use crate::network::Network;
use crate::scene::RegionId;

/// The feature curves of the kept polygons (`faces[i]` the network polygon
/// of kept polygon `i`, its loop `loops[loop_start[i]..loop_start[i + 1]]`),
/// grouped by (region pair, functions) and joined into polylines between
/// vertices where other curves meet; sorted by that key.
pub(crate) fn extract(
    net: &Network,
    region: &[RegionId],
    faces: &[u32],
    loop_start: &[u32],
    loops: &[u32],
) -> Vec<Curve> {
    // (edge, the function pair of the kept polygon), one per kept polygon
    // edge: an edge's generating functions are a sorted run.
    let mut uses: Vec<((u32, u32), [u32; 2])> = Vec::with_capacity(loops.len());
    for (i, &f) in faces.iter().enumerate() {
        let l = net.face_label[f as usize];
        let gen = [l[0].min(l[1]) as u32, l[0].max(l[1]) as u32];
        let p = &loops[loop_start[i] as usize..loop_start[i + 1] as usize];
        for k in 0..p.len() {
            let (a, b) = (p[k], p[(k + 1) % p.len()]);
            uses.push(((a.min(b), a.max(b)), gen));
        }
    }
    uses.sort_unstable();
    // Candidate edges: two or more kept polygons, not all on one function.
    let mut candidates: Vec<((u32, u32), Vec<u32>)> = Vec::new();
    let mut i = 0;
    while i < uses.len() {
        let e = uses[i].0;
        let mut j = i;
        while j < uses.len() && uses[j].0 == e {
            j += 1;
        }
        if uses[i].1 != uses[j - 1].1 {
            let mut fs: Vec<u32> = uses[i..j].iter().flat_map(|u| u.1).collect();
            fs.sort_unstable();
            fs.dedup();
            candidates.push((e, fs));
        }
        i = j;
    }
    if candidates.is_empty() {
        return Vec::new();
    }
    // The regions around each candidate edge, from every network polygon
    // at it (dropped ones too: a third region there makes it a junction).
    let index: FxHashMap<(u32, u32), usize> = candidates.iter().enumerate().map(|(k, c)| (c.0, k)).collect();
    let mut marked = vec![false; net.points.len()];
    for ((a, b), _) in &candidates {
        marked[*a as usize] = true;
        marked[*b as usize] = true;
    }
    // Up to three distinct regions per edge (three is enough to refuse it).
    let mut around: Vec<([RegionId; 3], u8)> = vec![([0; 3], 0); candidates.len()];
    for f in 0..net.num_faces() {
        let p = net.face(f);
        for k in 0..p.len() {
            let (a, b) = (p[k], p[(k + 1) % p.len()]);
            if !(marked[a as usize] && marked[b as usize]) {
                continue;
            }
            let Some(&c) = index.get(&(a.min(b), a.max(b))) else { continue };
            let (set, n) = &mut around[c];
            for cell in net.face_cells[f] {
                if cell == NONE {
                    continue;
                }
                let r = region[cell as usize];
                if (*n as usize) < 3 && !set[..*n as usize].contains(&r) {
                    set[*n as usize] = r;
                    *n += 1;
                }
            }
        }
    }
    let mut groups: FxHashMap<([RegionId; 2], Vec<u32>), Vec<(u32, u32)>> = FxHashMap::default();
    for (k, (e, fs)) in candidates.into_iter().enumerate() {
        let (set, n) = around[k];
        if n != 2 {
            continue;
        }
        let pair = [set[0].min(set[1]), set[0].max(set[1])];
        groups.entry((pair, fs)).or_default().push(e);
    }
    let mut keys: Vec<([RegionId; 2], Vec<u32>)> = groups.keys().cloned().collect();
    keys.sort();
    let mut out = Vec::new();
    for key in keys {
        for (vertices, closed) in polylines(&groups[&key]) {
            let length = path_length(&net.points, &vertices);
            out.push(Curve {
                kind: CurveKind::Feature,
                regions: key.0.to_vec(),
                functions: key.1.clone(),
                vertices,
                closed,
                length,
            });
        }
    }
    out
}
