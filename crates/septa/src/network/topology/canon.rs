//! Canonical numbering of the merged network, so the output does not depend
//! on the thread count, the block size or the order of the functions (the
//! same network.json for any permutation of the functions, after mapping the
//! labels back; invariant 2 of docs/architecture.md).
//!
//! Vertices are numbered by their grid element (sorted grid vertex ids, no
//! function ids), then by the bit patterns of their coordinates, with the
//! function ids only as a last resort (two distinct vertices in one grid
//! element at the same floating-point position). Faces are numbered by their
//! sorted vertex ids and rotated to start at their smallest vertex (the
//! orientation is kept). Patches, shells and chains then follow from the
//! topology stage (which numbers by smallest member); cells are renumbered
//! here by their smallest shell and cyclic patch orders by their smallest
//! rotation.

use rayon::prelude::*;
use smallvec::SmallVec;

use crate::buckets::for_each_bucket;

use super::build::Topology;
use super::merge::Merged;
use crate::complex::NONE;

/// Renumbers the vertices and faces of `m` canonically (see the module docs).
pub(crate) fn canonicalize_merged(m: &mut Merged) {
    let nv = m.keys.len();
    let nf = m.face_label.len();
    // Vertices: a counting sort by the element's smallest grid vertex, then
    // the short buckets by the whole element, coordinates, functions.
    let bits = |p: &[f64; 3]| p.map(f64::to_bits);
    let nb = m.keys.iter().map(|k| k.grid[0] as usize + 1).max().unwrap_or(0);
    let order = bucket_sort(
        nv,
        nb,
        |v| m.keys[v].grid[0],
        |&a, &b| {
            let (ka, kb) = (&m.keys[a as usize], &m.keys[b as usize]);
            ka.grid
                .cmp(&kb.grid)
                .then_with(|| bits(&m.points[a as usize]).cmp(&bits(&m.points[b as usize])))
                .then_with(|| ka.funcs.cmp(&kb.funcs))
        },
    );
    // Only vertices of faces are network vertices: a point found in a tet
    // (say, a tie of two materials at a grid vertex) that bounds no face
    // after the merge is no vertex and no component of the network.
    let mut used = vec![false; nv];
    for &v in &m.face_verts {
        used[v as usize] = true;
    }
    let mut order = order;
    order.retain(|&o| used[o as usize]);
    let mut vnew = vec![NONE; nv];
    for (i, &o) in order.iter().enumerate() {
        vnew[o as usize] = i as u32;
    }
    m.keys = order.par_iter().map(|&o| m.keys[o as usize]).collect();
    m.points = order.par_iter().map(|&o| m.points[o as usize]).collect();
    m.face_verts.par_iter_mut().for_each(|v| *v = vnew[*v as usize]);
    // Faces: by sorted vertex ids, then (degenerate duplicates only) label.
    // Bucket by the smallest vertex, sort each bucket by the second and
    // third smallest packed in one word (faces sharing two are common:
    // neighbours across an edge), then the rare runs of faces sharing all
    // three by all their vertices. The smallest is found again for the
    // bucket keys rather than kept: that array is the canonical order's
    // largest at the time, and the extra pass is one `min` per face.
    let face = |f: usize| &m.face_verts[m.face_start[f] as usize..m.face_start[f + 1] as usize];
    let mut second_third: Vec<u64> = (0..nf)
        .into_par_iter()
        .map(|f| {
            let (mut a, mut b, mut c) = (u32::MAX, u32::MAX, u32::MAX);
            for &v in face(f) {
                if v < a {
                    (a, b, c) = (v, a, b);
                } else if v < b {
                    (b, c) = (v, b);
                } else if v < c {
                    c = v;
                }
            }
            u64::from(b) << 32 | u64::from(c)
        })
        .collect();
    let sorted = |f: u32| {
        let mut s: SmallVec<[u32; 8]> = face(f as usize).into();
        s.sort_unstable();
        s
    };
    let forder = bucket_sort(
        nf,
        nv,
        |f| face(f).iter().copied().min().unwrap_or(u32::MAX),
        |&a, &b| {
            second_third[a as usize]
                .cmp(&second_third[b as usize])
                .then_with(|| sorted(a).cmp(&sorted(b)))
                .then_with(|| m.face_label[a as usize].cmp(&m.face_label[b as usize]))
        },
    );
    second_third = Vec::new();
    drop(second_third);
    let mut fnew = vec![0u32; nf];
    let mut start = Vec::with_capacity(nf + 1);
    start.push(0u32);
    for (i, &o) in forder.iter().enumerate() {
        fnew[o as usize] = i as u32;
        start.push(start[i] + (m.face_start[o as usize + 1] - m.face_start[o as usize]));
    }
    // Each face's loop, rotated to start at its smallest vertex, written
    // into its new place: face `i` is bucket `i` of the new vertex list.
    let mut verts = vec![0u32; m.face_verts.len()];
    for_each_bucket(&mut verts, &start, |i, out| {
        let vs = face(forder[i] as usize);
        let r = (0..vs.len()).min_by_key(|&j| vs[j]).unwrap_or(0);
        out[..vs.len() - r].copy_from_slice(&vs[r..]);
        out[vs.len() - r..].copy_from_slice(&vs[..r]);
        0
    });
    m.face_start = start;
    m.face_verts = verts;
    m.face_label = forder.par_iter().map(|&o| m.face_label[o as usize]).collect();
    m.face_nodes = forder.par_iter().map(|&o| m.face_nodes[o as usize]).collect();
    // Shell nodes `2f + s` follow their faces; other nodes keep their ids.
    let sides = 2 * nf as u32;
    let side = |x: u32| if x < sides { 2 * fnew[x as usize / 2] + (x & 1) } else { x };
    m.shell_pairs.par_iter_mut().for_each(|p| *p = (side(p.0), side(p.1)));
    m.wedges.par_iter_mut().for_each(|w| {
        let (a, b) = (vnew[w.0[0] as usize], vnew[w.0[1] as usize]);
        *w = ([a.min(b), a.max(b)], side(w.1), side(w.2));
    });
    // Same order as before for equal edges: keep the wedges sorted by edge
    // and side so the cyclic walk starts the same way every time. A counting
    // sort by the edge's smaller vertex, then each vertex's few wedges
    // sorted whole: the same order as one comparison sort (entries are
    // distinct or equal as a whole), in linear time.
    m.wedges = sort_wedges(std::mem::take(&mut m.wedges));
}

/// `wedges` in ascending order.
fn sort_wedges(wedges: Vec<([u32; 2], u32, u32)>) -> Vec<([u32; 2], u32, u32)> {
    let nv = wedges.iter().map(|w| w.0[0] as usize + 1).max().unwrap_or(0);
    let mut start = vec![0u32; nv + 1];
    for w in &wedges {
        start[w.0[0] as usize + 1] += 1;
    }
    for v in 0..nv {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut out = vec![([0u32; 2], 0u32, 0u32); wedges.len()];
    for w in wedges {
        let f = &mut fill[w.0[0] as usize];
        out[*f as usize] = w;
        *f += 1;
    }
    drop(fill);
    for_each_bucket(&mut out, &start, |_, r| {
        if r.len() > 1 {
            r.sort_unstable();
        }
        0
    });
    out
}

/// Renumbers cells by their smallest shell (a cell without shells, the
/// whole grid when there is no network, keeps its place at the end), and
/// rotates each chain's cyclic patch order to its smallest form (over both
/// directions, since the walk's direction is not tied to the chain's).
pub(crate) fn canonicalize_topology(t: &mut Topology) {
    let nc = t.cells.len();
    let mut corder: Vec<u32> = (0..nc as u32).collect();
    corder.sort_by_key(|&c| t.cells[c as usize].shells.iter().min().copied().unwrap_or(u32::MAX));
    let mut cnew = vec![0u32; nc];
    for (i, &o) in corder.iter().enumerate() {
        cnew[o as usize] = i as u32;
    }
    let mut old = std::mem::take(&mut t.cells);
    t.cells = corder.iter().map(|&o| std::mem::replace(&mut old[o as usize], empty_cell())).collect();
    for fc in t.face_cells.iter_mut() {
        *fc = fc.map(|c| if c == NONE { NONE } else { cnew[c as usize] });
    }
    for cyc in t.chain_patches.iter_mut() {
        *cyc = min_rotation(cyc);
    }
}

/// `0..n` ordered by `bucket` (a counting sort over `0..nb`), then within
/// each bucket by `cmp`: linear time when buckets are short. The keys and
/// the buckets' sorts run in parallel ([`for_each_bucket`]); the order is
/// the same on any number of threads.
fn bucket_sort(
    n: usize,
    nb: usize,
    bucket: impl Fn(usize) -> u32 + Sync + Send,
    cmp: impl Fn(&u32, &u32) -> std::cmp::Ordering + Sync,
) -> Vec<u32> {
    let mut start = vec![0u32; nb + 1];
    let keys: Vec<u32> = (0..n).into_par_iter().map(&bucket).collect();
    for &k in &keys {
        start[k as usize + 1] += 1;
    }
    for b in 0..nb {
        start[b + 1] += start[b];
    }
    let mut fill = start.clone();
    let mut order = vec![0u32; n];
    for (i, &k) in keys.iter().enumerate() {
        order[fill[k as usize] as usize] = i as u32;
        fill[k as usize] += 1;
    }
    drop((keys, fill));
    for_each_bucket(&mut order, &start, |_, r| {
        if r.len() > 1 {
            r.sort_unstable_by(&cmp);
        }
        0
    });
    order
}

fn empty_cell() -> crate::network::CellInfo {
    crate::network::CellInfo { shells: Vec::new(), label: Default::default(), volume: 0.0 }
}

/// The lexicographically smallest rotation of `c` or of its reverse.
pub(crate) fn min_rotation(c: &[u32]) -> Vec<u32> {
    let n = c.len();
    let rev: Vec<u32> = c.iter().rev().copied().collect();
    let mut best = c.to_vec();
    for s in [c, &rev[..]] {
        for r in 0..n {
            let cand: Vec<u32> = s[r..].iter().chain(&s[..r]).copied().collect();
            if cand < best {
                best = cand;
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::min_rotation;

    #[test]
    fn rotation() {
        assert_eq!(min_rotation(&[3, 1, 2]), vec![1, 2, 3]);
        assert_eq!(min_rotation(&[3, 2, 1]), vec![1, 2, 3]);
        assert_eq!(min_rotation(&[2, 1, 2, 0]), vec![0, 2, 1, 2]);
        assert!(min_rotation(&[]).is_empty());
    }
}
