//! Shells that meet where sheets touch only at a point.
//!
//! Ray shooting (Du et al. Sec. 7.1) joins the shells of different network
//! components; within one component, shells come from half-patches joined
//! around chains (Sec. 7, shells). That covers a component whose faces
//! connect across edges (one *sheet*). Degenerate inputs can join sheets
//! at isolated points: two spheres tangent at a grid vertex, two planes of
//! one function pinched at a vertex. There the outer shells of the two
//! sheets bound the same cell without sharing a chain, and nothing links
//! them.
//!
//! This module links them from the local picture at each contact point
//! `p`: the cells of the per-tet complexes around `p` that contain `p` are
//! joined across the pieces of tet faces at `p` that are no part of the
//! network (paired across tets by their vertex keys, as the merge pairs
//! halves); each class is a *wedge*, one local region at `p`; and every
//! shell facing a wedge from a network face at `p` bounds that region, so
//! they are linked. Every link is sound (a wedge lies in one cell). With one
//! ray per component they suffice: a cell's boundary within one component
//! is connected, so its shells of different sheets meet at contact points,
//! and a sheet's side faces one wedge there, the region on that side (each
//! sheet separates space: its part of each function's zero set has no
//! boundary but points, so is a closed 2-cycle).

use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use super::ray_index::RayIndex;
use super::raytrace::{face_side, for_tets_at, shell_of_face, view_of, TetView};
use crate::complex::{Mode, Plane};
use crate::grid::{BoxGrid, Grid};
use crate::network::block::{vertex_key, Ctx};
use crate::network::VKey;
use crate::uf::UnionFind;

/// Pairs of shells that face one wedge at the network vertex with key
/// `key` (see the module doc), or `None` if the local picture cannot be
/// read (not a box grid, or a face whose shell `index` does not know).
pub(crate) fn contact_links(ctx: &Ctx, index: &mut dyn RayIndex, key: &VKey) -> Option<Vec<[u32; 2]>> {
    let Grid::Box(g) = ctx.grid else { return None };
    let element: SmallVec<[u32; 4]> = key.grid.iter().copied().filter(|&v| v != u32::MAX).collect();
    let mut tets: SmallVec<[[u32; 4]; 32]> = SmallVec::new();
    for_tets_at(g, *element.first()?, |t| {
        if element.iter().all(|v| t.contains(v)) {
            tets.push(t);
        }
        false
    });
    let views: Vec<TetView> = tets.iter().map(|&t| view_of(ctx, t)).collect::<Option<_>>()?;
    let keys_of = |v: &TetView| -> Vec<VKey> {
        (0..v.complex.vertices().len() as u32).map(|x| vertex_key(ctx.mode, &v.complex, x, &v.tet, &v.active)).collect()
    };
    let keys: Vec<Vec<VKey>> = views.iter().map(keys_of).collect();
    // The point in each tet's complex (a tet whose complex lacks it has no
    // function vanishing or tied there: none around a network vertex).
    let at: Vec<Option<u32>> = keys.iter().map(|k| k.iter().position(|x| x == key).map(|i| i as u32)).collect();
    // Nodes: the cells at the point, numbered tet by tet.
    let mut first = vec![0u32; views.len() + 1];
    for (t, v) in views.iter().enumerate() {
        first[t + 1] = first[t] + v.complex.cells().len() as u32;
    }
    let mut wedges = UnionFind::new(first[views.len()] as usize);
    // Tet-face pieces at the point that are off the network, by their sorted
    // vertex keys: the same piece seen from the tet on its other side.
    let mut pieces: FxHashMap<SmallVec<[VKey; 8]>, u32> = FxHashMap::default();
    let mut facing: Vec<(u32, u32)> = Vec::new();
    for (t, v) in views.iter().enumerate() {
        let Some(p) = at[t] else { continue };
        for (ci, cell) in v.complex.cells().iter().enumerate() {
            let node = first[t] + ci as u32;
            for &fi in &cell.faces {
                let face = &v.complex.faces()[fi as usize];
                if !face.vertices.contains(&p) {
                    continue;
                }
                let in_tet_face = matches!(face.plane, Plane::TetFace(_));
                if face_side(ctx, v, face, ci as u32).is_some() {
                    match shell_of_face(ctx, index, v, face, ci as u32) {
                        Some(s) => {
                            facing.push((node, s));
                            continue;
                        }
                        // MI: a tie over a tet face with one material on
                        // both sides is no face (the merge pairs it away).
                        None if in_tet_face && ctx.mode == Mode::Mi => {}
                        None => return None,
                    }
                }
                if in_tet_face {
                    let mut k: SmallVec<[VKey; 8]> = face.vertices.iter().map(|&x| keys[t][x as usize]).collect();
                    k.sort_unstable();
                    if let Some(&other) = pieces.get(&k) {
                        wedges.union(node, other);
                    } else {
                        pieces.insert(k, node);
                    }
                }
            }
        }
    }
    let mut shell_of_wedge: FxHashMap<u32, u32> = FxHashMap::default();
    let mut links = Vec::new();
    for (node, shell) in facing {
        let w = wedges.find(node);
        let s = *shell_of_wedge.entry(w).or_insert(shell);
        if s != shell {
            links.push([s, shell]);
        }
    }
    Some(links)
}

/// Whether the network edge between the vertices with keys `a` and `b` lies
/// on the grid's boundary, where an edge of one face is expected. An edge
/// of one face anywhere else is a crack: one point reached by two tets
/// under different keys. Tied points are named by the point alone
/// (complex/ties.rs), so a crack means a defect; links at contact points
/// are not trusted there (cells are then grouped), a guard that costs one
/// check per edge.
pub(crate) fn edge_on_grid_boundary(g: &BoxGrid, a: &VKey, b: &VKey) -> bool {
    // Most edges are inside: their first grid vertex is off every boundary plane.
    let p = g.vertex_ijk(a.grid[0]);
    if (0..3).all(|x| p[x] != 0 && p[x] != g.res[x]) {
        return false;
    }
    let ijk: SmallVec<[[usize; 3]; 8]> =
        a.grid.iter().chain(&b.grid).filter(|&&v| v != u32::MAX).map(|&v| g.vertex_ijk(v)).collect();
    (0..3).any(|x| [0, g.res[x]].iter().any(|&side| ijk.iter().all(|p| p[x] == side)))
}
