//! Cut-cells (TopoCut Sec. 5): half-faces joined across cut-edges by the
//! face-cycle order around each edge; a cut-cell is an equivalence class of
//! the `adj` relation (eq. 11). Edges with two incident faces need no
//! ordering (the topological case); others are ordered exactly.

use crate::cut::arrangement::nodes::FxMap;
use crate::cut::arrangement::plane_graph::dir_vec;
use crate::cut::base::geom::{cross3, dot3, neg3, Ctx, LineDir, V3};
use crate::cut::Support;
use crate::uf::UnionFind;
use septa_exact::{filtered_sign_bounded, Bounded, Exact, Interval, Ring, Sign};

/// A cut-face loop with the line of each edge.
#[derive(Clone, Debug)]
pub struct FaceLoop {
    /// Supporting triangle or plane.
    pub support: Support,
    /// Corners (compact cut-vertex ids), counter-clockwise about the
    /// support normal for an outer boundary. Inline up to 6, as the clipped
    /// pieces' corners (the pieces of the input's triangles, a million on the
    /// large meshes, have a few).
    pub verts: smallvec::SmallVec<[u32; 6]>,
    /// Line of edge `i -> i+1`, and whether it runs along `+dir`.
    pub dirs: smallvec::SmallVec<[(LineDir, bool); 6]>,
    /// The cut-face this loop bounds (several loops for a face with holes).
    pub face: u32,
}

fn normal<R: Ring>(c: &Ctx, s: Support) -> V3<R> {
    match s {
        Support::Tri(t) => c.tn(t),
        Support::Plane(p) => c.pn(p),
    }
}

/// In-face direction `n_f x h` at an edge traversed along `h`.
fn wvec<R: Ring>(c: &Ctx, s: Support, h: (LineDir, bool)) -> V3<R> {
    cross3(&normal::<R>(c, s), &dir_vec::<R>(c, h.0, h.1))
}

/// Result of cell assembly.
pub struct Cells {
    /// Cell of each half-face `2 f` (+ side) and `2 f + 1` (- side) of
    /// cut-face `f`; `u32::MAX` if none.
    pub cell_of: Vec<u32>,
    /// Number of cells.
    pub count: usize,
    /// Number of cut-edges.
    pub edges: usize,
    /// Edges that needed an exact face-cycle order (more than two faces).
    pub ordered_edges: usize,
}

/// Joins half-faces into cells.
pub fn assemble(c: &Ctx, faces: &[FaceLoop]) -> Cells {
    // incident (edge key, face loop, `2 i + 1` for the loop's edge `i` when
    // it traverses min -> max, else `2 i`), grouped by sorting (no per-edge
    // allocation); the edge's direction label is read from the loop only
    // where more than two faces meet (16 bytes an entry instead of 32: the
    // entries of the large meshes are some 500,000, sorted by a copy)
    let mut inc: Vec<(u64, u32, u32)> = Vec::with_capacity(faces.iter().map(|f| f.verts.len()).sum());
    for (f, fl) in faces.iter().enumerate() {
        let n = fl.verts.len();
        for i in 0..n {
            let (a, b) = (fl.verts[i], fl.verts[(i + 1) % n]);
            let key = ((a.min(b) as u64) << 32) | a.max(b) as u64;
            inc.push((key, f as u32, (i as u32) << 1 | (a < b) as u32));
        }
    }
    // in order of (edge key, face loop): a counting sort by the smaller
    // vertex (the key's high half), then each short bucket by the larger
    // vertex, stably (the entries were made in face-loop order); the
    // comparison sort of all entries was a twentieth of the run on the
    // large meshes
    let inc = {
        let nb = inc.iter().map(|x| (x.0 >> 32) as usize + 1).max().unwrap_or(0);
        let mut start = vec![0u32; nb + 1];
        for x in &inc {
            start[(x.0 >> 32) as usize + 1] += 1;
        }
        for b in 0..nb {
            start[b + 1] += start[b];
        }
        let mut fill = start.clone();
        let mut order = vec![0u32; inc.len()];
        for (i, x) in inc.iter().enumerate() {
            let b = (x.0 >> 32) as usize;
            order[fill[b] as usize] = i as u32;
            fill[b] += 1;
        }
        for b in 0..nb {
            let run = &mut order[start[b] as usize..start[b + 1] as usize];
            if run.len() > 1 {
                run.sort_by_key(|&i| inc[i as usize].0);
            }
        }
        order.iter().map(|&i| inc[i as usize]).collect::<Vec<_>>()
    };
    let nf = faces.iter().map(|f| f.face + 1).max().unwrap_or(0) as usize;
    let mut sides = UnionFind::new(2 * nf);
    let fid = |f: u32| faces[f as usize].face;
    let is_plane = |f: u32| matches!(faces[f as usize].support, Support::Plane(_));
    let mut ordered = 0usize;
    let mut nedges = 0usize;
    let mut list: Vec<(u32, bool, (LineDir, bool))> = Vec::new();
    let mut g0 = 0;
    while g0 < inc.len() {
        let mut g1 = g0 + 1;
        while g1 < inc.len() && inc[g1].0 == inc[g0].0 {
            g1 += 1;
        }
        list.clear();
        let labelled = g1 - g0 > 2;
        list.extend(inc[g0..g1].iter().map(|&(_, f, e)| {
            let dir = if labelled { faces[f as usize].dirs[(e >> 1) as usize] } else { (LineDir::Mesh(0), false) };
            (f, e & 1 == 1, dir)
        }));
        g0 = g1;
        nedges += 1;
        let k = list.len();
        if k > 2 {
            ordered += 1;
            // D: the direction min -> max, from the first face's label
            let (_, fwd0, h0) = list[0];
            let d: (LineDir, bool) = if fwd0 { h0 } else { (h0.0, !h0.1) };
            let items: Vec<(u32, bool)> = list.iter().map(|x| (x.0, x.1)).collect();
            let hof = |up: bool| if up { d } else { (d.0, !d.1) };
            let dv_b = dir_vec::<Bounded>(c, d.0, d.1);
            let w0 = (faces[items[0].0 as usize].support, hof(items[0].1));
            // the filters' in-face directions n_f x (+-D): one bounded
            // n_f x D from the D already formed, negated for faces running
            // along -D (negation is exact, so the bound still holds for the
            // real vector); the exact fallbacks use `wvec` itself. Only
            // the first face and those off its support are ever filtered
            // (the others are class 2 below): no product for the rest.
            let wbs: Vec<V3<Bounded>> = items
                .iter()
                .enumerate()
                .map(|(i, &(f, up))| {
                    let sup = faces[f as usize].support;
                    if i > 0 && sup == faces[items[0].0 as usize].support {
                        return [Bounded::of(0.0); 3];
                    }
                    let w = cross3(&normal::<Bounded>(c, sup), &dv_b);
                    if up {
                        w
                    } else {
                        neg3(&w)
                    }
                })
                .collect();
            let class = |x: (Support, (LineDir, bool)), wbx: &V3<Bounded>| -> u8 {
                fn b<R: Ring>(
                    c: &Ctx,
                    d: (LineDir, bool),
                    w0: (Support, (LineDir, bool)),
                    x: (Support, (LineDir, bool)),
                ) -> R {
                    let dv = dir_vec::<R>(c, d.0, d.1);
                    dot3(&dv, &cross3(&wvec::<R>(c, w0.0, w0.1), &wvec::<R>(c, x.0, x.1)))
                }
                fn a<R: Ring>(c: &Ctx, w0: (Support, (LineDir, bool)), x: (Support, (LineDir, bool))) -> R {
                    dot3(&wvec::<R>(c, w0.0, w0.1), &wvec::<R>(c, x.0, x.1))
                }
                let sb = match dot3(&dv_b, &cross3(&wbs[0], wbx)).sign() {
                    Some(s) => s,
                    None => filtered_sign_bounded(
                        || b::<Bounded>(c, d, w0, x),
                        || b::<Interval>(c, d, w0, x),
                        || b::<Exact>(c, d, w0, x),
                    ),
                };
                match sb {
                    Sign::Positive => 1,
                    Sign::Negative => 3,
                    Sign::Zero => {
                        if filtered_sign_bounded(
                            || a::<Bounded>(c, w0, x),
                            || a::<Interval>(c, w0, x),
                            || a::<Exact>(c, w0, x),
                        ) == Sign::Positive
                        {
                            0
                        } else {
                            2
                        }
                    }
                }
            };
            let cls: Vec<u8> = items
                .iter()
                .enumerate()
                .map(|(i, &(f, up))| {
                    let sup = faces[f as usize].support;
                    if i == 0 {
                        0
                    } else if sup == w0.0 {
                        // the other side of the edge in the same plane or triangle: opposite to w0
                        2
                    } else {
                        class((sup, hof(up)), &wbs[i])
                    }
                })
                .collect();
            let mut idx: Vec<usize> = (0..k).collect();
            idx.sort_by(|&x, &y| {
                if cls[x] != cls[y] {
                    return cls[x].cmp(&cls[y]);
                }
                if x == y || cls[x] == 0 || cls[x] == 2 {
                    return std::cmp::Ordering::Equal;
                }
                let wx = (faces[items[x].0 as usize].support, hof(items[x].1));
                let wy = (faces[items[y].0 as usize].support, hof(items[y].1));
                fn f<R: Ring>(
                    c: &Ctx,
                    d: (LineDir, bool),
                    wx: (Support, (LineDir, bool)),
                    wy: (Support, (LineDir, bool)),
                ) -> R {
                    let dv = dir_vec::<R>(c, d.0, d.1);
                    dot3(&dv, &cross3(&wvec::<R>(c, wx.0, wx.1), &wvec::<R>(c, wy.0, wy.1)))
                }
                let quick = dot3(&dv_b, &cross3(&wbs[x], &wbs[y])).sign();
                match quick.unwrap_or_else(|| {
                    filtered_sign_bounded(
                        || f::<Bounded>(c, d, wx, wy),
                        || f::<Interval>(c, d, wx, wy),
                        || f::<Exact>(c, d, wx, wy),
                    )
                }) {
                    Sign::Positive => std::cmp::Ordering::Less,
                    Sign::Negative => std::cmp::Ordering::Greater,
                    Sign::Zero => std::cmp::Ordering::Equal,
                }
            });
            let sorted: Vec<_> = idx.iter().map(|&i| list[i]).collect();
            list.copy_from_slice(&sorted);
        }
        // consecutive faces around the edge bound one wedge
        for i in 0..k {
            if k == 1 {
                break;
            }
            let (fa, upa, _) = list[i];
            let (fb, upb, _) = list[(i + 1) % k];
            if k == 2 && i == 1 {
                break;
            }
            let (fa, upa, fb, upb) = if k == 2 {
                // two faces: the wedge on the inner sides (both triangles)
                (fa, upa, fb, upb)
            } else {
                (fa, upa, fb, upb)
            };
            let side_a = if upa { 0 } else { 1 }; // + side of A faces the CCW wedge iff A runs along +D
            let side_b = if upb { 1 } else { 0 }; // + side of B faces the CW wedge iff B runs along -D
            let inside = if k == 2 { true } else { is_plane(fa) || is_plane(fb) || side_a == 1 };
            let (na, nb) =
                if k == 2 { (2 * fid(fa) + 1, 2 * fid(fb) + 1) } else { (2 * fid(fa) + side_a, 2 * fid(fb) + side_b) };
            if inside {
                sides.union(na, nb);
            }
        }
    }
    let mut cell_of = vec![u32::MAX; 2 * nf];
    let mut ids: FxMap<u32, u32> = FxMap::default();
    for fl in faces.iter() {
        for side in 0..2u32 {
            if side == 0 && matches!(fl.support, Support::Tri(_)) {
                continue;
            }
            let n = 2 * fl.face + side;
            let r = sides.find(n);
            let len = ids.len() as u32;
            let id = *ids.entry(r).or_insert(len);
            cell_of[n as usize] = id;
        }
    }
    Cells { cell_of, count: ids.len(), edges: nedges, ordered_edges: ordered }
}
