//! Cells by topological ray shooting (Du et al. Sec. 7.1, Appendix A).
//!
//! From each connected component of the network one ray leaves its
//! edge-point with the smallest ordering vector `{v, u, i}` and travels along
//! grid edges in steepest descent of the vertex order (lexicographic in x,
//! y, z, which is the vertex id order of a box grid) until it meets another
//! edge-point or the sink (vertex 0). The shells at both ends of a ray bound
//! the same region; regions are the connected components of the graph of
//! shells and rays. Every step is combinatorial: points along a grid edge
//! come in order from the per-tet complex.
//!
//! Degenerate inputs (values exactly 0 or tied at grid vertices) put
//! network vertices at grid vertices and network faces in tet faces. The
//! ordering vector is extended to them: a network vertex at grid vertex `w`
//! orders as `{w, 0}`, before every edge-point `{w, u, i}` (`u > w`). A ray
//! leaves from its component's smallest point in this order, along a grid
//! edge towards a smaller vertex; every point it meets is smaller still,
//! so it never meets its own component, and no ray segment lies in the
//! network: a segment of the network below the start would hold smaller
//! points of the same component, and a ray walking from a vertex off the
//! network meets the network first at a point. At a network vertex on a
//! grid vertex the shell facing the ray is read from whichever tet around
//! the grid edge has a network face there (a tet may touch the network
//! only at that corner). A component through the sink itself (a plane
//! through a corner of the box) sends no ray: nothing lies below it, and
//! every other ray reaching vertex 0 meets it there.
//!
//! Preconditions, checked: a box grid (convex boundary, no cavities or
//! handles). Components whose sheets touch only at points need the shells
//! that meet there linked first (`contact.rs`). Where the local picture is
//! still ambiguous the answer is `None` and the caller falls back to cell
//! grouping.

use smallvec::SmallVec;

use crate::complex::{Complex, Mode, Plane};
use crate::grid::{BoxGrid, Grid};
use crate::network::block::{active_functions, tet_face_zero, vertex_key, Ctx, FACE_OF};
use crate::network::VKey;
use crate::uf::UnionFind;

use super::ray_index::{FaceSide, RayIndex};

/// A per-tet complex built on demand along a ray.
pub(super) struct TetView {
    pub(super) tet: [u32; 4],
    pub(super) active: Vec<u16>,
    /// Values of the active functions at the tet's corners.
    pub(super) vals: Vec<[f64; 4]>,
    pub(super) complex: Complex,
}

/// Cell of each of the `num_shells` shells and the number of cells, or
/// `None` when the preconditions do not hold. `starts` holds, per network
/// component, the smallest grid edge `(v, u)` carrying one of its
/// edge-points (components numbered as `index` numbers them). `links`
/// pairs shells known to bound one cell already (sheets touching at
/// points: `contact.rs`).
pub(crate) fn ray_cells(
    ctx: &Ctx,
    index: &mut dyn RayIndex,
    starts: &[(u32, u32)],
    num_shells: usize,
    links: &[[u32; 2]],
) -> Option<(Vec<u32>, usize)> {
    let Grid::Box(g) = ctx.grid else { return None };
    let mut uf = UnionFind::new(num_shells + 1);
    for &[a, b] in links {
        uf.union(a, b);
    }
    let mut sink_on_network = false;
    for (c, &(v, u)) in starts.iter().enumerate() {
        let c = c as u32;
        if (v, u) == (0, 0) {
            sink_on_network = true;
            // The component holds the sink, grid vertex 0 (a plane through a
            // corner of the box): nothing lies below it, so no ray leaves it.
            // Every other ray that reaches vertex 0 meets this component's
            // point there first, so the outer node stays unused (below).
            continue;
        }
        // A start at grid vertex `w = v` runs along the edge to w's lowest
        // neighbour; an edge-point start along its own edge towards `v`.
        let (v, u, at_corner) = if u == 0 { (lowest_neighbour(g, v), v, true) } else { (v, u, false) };
        let view = tet_view(ctx, g, v, u)?;
        let pts = edge_points(ctx, &view, v, u, index);
        // The component's point closest to v on this edge (the corner `u`
        // itself for a start at a grid vertex).
        let j = if at_corner {
            (pts.last() == Some(&Some(c))).then(|| pts.len() - 1)?
        } else {
            (1..pts.len().saturating_sub(1)).find(|&j| pts[j] == Some(c))?
        };
        let start_shell = facing_shell_around(ctx, g, index, &view, v, u, j, true)?;
        let end_shell = match (0..j).rev().find(|&k| pts[k].is_some()) {
            Some(k) => {
                if pts[k] == Some(c) {
                    return None;
                }
                facing_shell_around(ctx, g, index, &view, v, u, k, false)?
            }
            None => walk(ctx, g, index, num_shells, v, c)?,
        };
        uf.union(start_shell, end_shell);
    }
    let (comp, mut n) = uf.components();
    // With the sink on the network the outer node is joined to no shell;
    // labels come in order of first appearance, so it holds the last label
    // alone: it is no cell. (Without a network it is the one cell.)
    if sink_on_network && !comp[..num_shells].contains(&comp[num_shells]) {
        n -= 1;
    }
    Some((comp[..num_shells].to_vec(), n))
}

/// Steepest descent from grid vertex `from` to the first edge-point (its
/// shell facing the ray) or the sink (the outer node).
#[allow(clippy::too_many_arguments)]
fn walk(ctx: &Ctx, g: &BoxGrid, index: &mut dyn RayIndex, num_shells: usize, from: u32, comp: u32) -> Option<u32> {
    let mut cur = from;
    loop {
        if cur == 0 {
            return Some(num_shells as u32);
        }
        let w = lowest_neighbour(g, cur);
        if edge_may_cross(ctx, w, cur) {
            let view = tet_view(ctx, g, w, cur)?;
            let pts = edge_points(ctx, &view, w, cur, index);
            // The network point closest to `cur` (possibly `w` itself); the ray
            // arrives from `cur`'s side.
            if let Some(k) = (0..pts.len().saturating_sub(1)).rev().find(|&k| pts[k].is_some()) {
                if pts[k] == Some(comp) {
                    return None;
                }
                return facing_shell_around(ctx, g, index, &view, w, cur, k, false);
            }
        }
        cur = w;
    }
}

/// Whether any network point can lie on the grid edge `a b` (IA: a sign
/// change or zero; MI: the unique strict maximum differs or is tied).
fn edge_may_cross(ctx: &Ctx, a: u32, b: u32) -> bool {
    let k = ctx.k;
    let (mut ba, mut bb) = (Vec::new(), Vec::new());
    let (ra, rb) = (ctx.row(a, &mut ba), ctx.row(b, &mut bb));
    match ctx.mode {
        Mode::Ia => ra.iter().zip(rb).any(|(&x, &y)| !(x > 0.0 && y > 0.0 || x < 0.0 && y < 0.0)),
        Mode::Mi => {
            let arg = |r: &[f64]| {
                let m = r.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                let mut it = (0..k).filter(|&f| r[f] == m);
                let first = it.next();
                if it.next().is_some() {
                    None
                } else {
                    first
                }
            };
            match (arg(ra), arg(rb)) {
                (Some(x), Some(y)) => x != y,
                _ => true,
            }
        }
    }
}

/// The grid vertex adjacent to `v` (along a tet edge) with the smallest id.
fn lowest_neighbour(g: &BoxGrid, v: u32) -> u32 {
    let mut best = u32::MAX;
    for_tets_at(g, v, |tet| {
        for &x in &tet {
            if x != v {
                best = best.min(x);
            }
        }
        false
    });
    best
}

/// Calls `f` on every tet containing grid vertex `v` until it returns true.
pub(super) fn for_tets_at(g: &BoxGrid, v: u32, mut f: impl FnMut([u32; 4]) -> bool) {
    let ijk = g.vertex_ijk(v);
    let per = g.split.tets_per_cube();
    for di in 0..2 {
        for dj in 0..2 {
            for dk in 0..2 {
                let d = [di, dj, dk];
                if (0..3).any(|a| ijk[a] < d[a] || ijk[a] - d[a] >= g.res[a]) {
                    continue;
                }
                let cube = g.cube_index([ijk[0] - di, ijk[1] - dj, ijk[2] - dk]);
                for t in cube * per..(cube + 1) * per {
                    let tet = g.tet(t);
                    if tet.contains(&v) && f(tet) {
                        return;
                    }
                }
            }
        }
    }
}

/// The complex of a tet containing grid edge `a b`.
fn tet_view(ctx: &Ctx, g: &BoxGrid, a: u32, b: u32) -> Option<TetView> {
    let mut found = None;
    for_tets_at(g, a, |tet| {
        if tet.contains(&b) {
            found = Some(tet);
            true
        } else {
            false
        }
    });
    view_of(ctx, found?)
}

/// The complex of grid tet `tet`.
pub(super) fn view_of(ctx: &Ctx, tet: [u32; 4]) -> Option<TetView> {
    let mut active = Vec::new();
    active_functions(ctx, 0, &tet, &mut active).ok()?;
    let vals: Vec<[f64; 4]> = active.iter().map(|&f| tet.map(|v| ctx.val(v, f as usize))).collect();
    let mut complex = Complex::new();
    let empty = match ctx.mode {
        Mode::Ia => active.is_empty(),
        Mode::Mi => active.len() < 2,
    };
    if !empty {
        complex.build(ctx.mode, &vals, &ctx.options).ok()?;
    }
    Some(TetView { tet, active, vals, complex })
}

/// The vertices of grid edge `a b` in the tet's complex, ordered from `a`
/// to `b` (corners included), each with its component if it is a network vertex.
fn edge_points(ctx: &Ctx, view: &TetView, a: u32, b: u32, index: &mut dyn RayIndex) -> SmallVec<[Option<u32>; 8]> {
    if view.complex.vertices().is_empty() {
        return SmallVec::from_elem(None, 2);
    }
    let la = view.tet.iter().position(|&x| x == a).unwrap() as u8;
    let lb = view.tet.iter().position(|&x| x == b).unwrap() as u8;
    view.complex
        .tet_edge_points(la, lb)
        .iter()
        .map(|&cv| index.component(&view.tet, vertex_key(ctx.mode, &view.complex, cv, &view.tet, &view.active)))
        .collect()
}

/// [`facing_shell`] in `view`, or, at a corner of the edge (a network vertex
/// at a grid vertex), in any other tet around grid edge `a b`: a tet may
/// touch the network only at that corner, with the faces there in its
/// neighbours. Every tet around the edge has the same points on it.
#[allow(clippy::too_many_arguments)]
fn facing_shell_around(
    ctx: &Ctx,
    g: &BoxGrid,
    index: &mut dyn RayIndex,
    view: &TetView,
    a: u32,
    b: u32,
    j: usize,
    towards_a: bool,
) -> Option<u32> {
    if let Some(s) = facing_shell(ctx, index, view, a, b, j, towards_a) {
        return Some(s);
    }
    let mut tets: SmallVec<[[u32; 4]; 8]> = SmallVec::new();
    for_tets_at(g, a, |tet| {
        if tet.contains(&b) && tet != view.tet {
            tets.push(tet);
        }
        false
    });
    if let Some(s) = tets.into_iter().find_map(|tet| {
        let other = view_of(ctx, tet)?;
        facing_shell(ctx, index, &other, a, b, j, towards_a)
    }) {
        return Some(s);
    }
    // No tet around the edge has a network face at the corner: look for
    // one in the region's other tet cells around that grid vertex.
    let w = if j == 0 { a } else { b };
    let c = &view.complex;
    let list = c.tet_edge_points(local(view, a)?, local(view, b)?);
    if j != 0 && j + 1 != list.len() {
        return None;
    }
    let q = if towards_a { list[j - 1] } else { *list.get(j + 1)? };
    let cell = cell_at_edge(c, list[j], q)?;
    shell_around_vertex(ctx, g, index, view.tet, cell, w)
}

/// Local index of grid vertex `v` in the tet of `view`.
fn local(view: &TetView, v: u32) -> Option<u8> {
    view.tet.iter().position(|&x| x == v).map(|i| i as u8)
}

/// The cell of complex `c` along complex edge `p q`, if that edge is in no
/// network face (a segment of a ray off the network lies in one cell).
fn cell_at_edge(c: &Complex, p: u32, q: u32) -> Option<u32> {
    let edge = c.edges().iter().position(|e| e.vertices == [p, q] || e.vertices == [q, p])? as u32;
    if c.faces().iter().any(|f| f.plane.is_network() && f.edges.contains(&edge)) {
        return None;
    }
    c.cells()
        .iter()
        .position(|cl| cl.faces.iter().any(|&f| c.faces()[f as usize].edges.contains(&edge)))
        .map(|i| i as u32)
}

/// The shell of a network face at grid vertex `w` that bounds the region of
/// cell `cell` of tet `tet`'s complex near `w`: a search over the cells of
/// the tets around `w` that have `w` as a corner, crossing tet-face pieces
/// at `w` that are no part of the network (paired across tets by their
/// vertex keys, as the merge pairs them), until a cell has a network face
/// at `w`. A tet may touch the network only at `w`, with the faces there in
/// its neighbours (a plane through grid vertices).
fn shell_around_vertex(
    ctx: &Ctx,
    g: &BoxGrid,
    index: &mut dyn RayIndex,
    tet: [u32; 4],
    cell: u32,
    w: u32,
) -> Option<u32> {
    let mut tets: SmallVec<[[u32; 4]; 32]> = SmallVec::new();
    for_tets_at(g, w, |t| {
        tets.push(t);
        false
    });
    let views: Vec<TetView> = tets.iter().map(|&t| view_of(ctx, t)).collect::<Option<_>>()?;
    // The complex vertex at corner w of each tet (none in an empty complex).
    let corner: Vec<Option<u32>> = views
        .iter()
        .map(|v| {
            let lw = local(v, w)?;
            v.complex.vertices().iter().position(|x| x.simplex() == 1 << lw).map(|i| i as u32)
        })
        .collect();
    let key_set = |v: &TetView, face: &crate::complex::Face| -> SmallVec<[VKey; 8]> {
        let mut k: SmallVec<[VKey; 8]> =
            face.vertices.iter().map(|&x| vertex_key(ctx.mode, &v.complex, x, &v.tet, &v.active)).collect();
        k.sort_unstable();
        k
    };
    let t0 = tets.iter().position(|&t| t == tet)?;
    let mut seen: rustc_hash::FxHashSet<(usize, u32)> = Default::default();
    seen.insert((t0, cell));
    let mut queue = vec![(t0, cell)];
    while let Some((t, cell)) = queue.pop() {
        let v = &views[t];
        let Some(p) = corner[t] else { continue };
        for &fi in &v.complex.cells()[cell as usize].faces {
            let face = &v.complex.faces()[fi as usize];
            if !face.vertices.contains(&p) {
                continue;
            }
            if face_side(ctx, v, face, cell).is_some() {
                if let Some(s) = shell_of_face(ctx, index, v, face, cell) {
                    return Some(s);
                }
                // MI: a tie over a tet face with one material on both sides
                // is no face (the merge pairs it away): crossed like any
                // other piece off the network.
                if !matches!(face.plane, Plane::TetFace(_)) {
                    continue;
                }
            }
            // A piece of a tet face off the network: the same piece in the
            // tet on its other side (none on the grid's boundary).
            let keys = key_set(v, face);
            for (t2, v2) in views.iter().enumerate() {
                if t2 == t {
                    continue;
                }
                for f2 in v2.complex.faces() {
                    if matches!(f2.plane, Plane::TetFace(_))
                        && f2.vertices.len() == keys.len()
                        && key_set(v2, f2) == keys
                        && seen.insert((t2, f2.cells[0]))
                    {
                        queue.push((t2, f2.cells[0]));
                    }
                }
            }
        }
    }
    None
}

/// The shell on the side of the network, at the `j`-th point of the list
/// `[a, points.., b]` along grid edge `a b`, that faces the segment towards
/// `a` (`towards_a`) or towards `b`.
fn facing_shell(
    ctx: &Ctx,
    index: &mut dyn RayIndex,
    view: &TetView,
    a: u32,
    b: u32,
    j: usize,
    towards_a: bool,
) -> Option<u32> {
    let c = &view.complex;
    let list = c.tet_edge_points(local(view, a)?, local(view, b)?);
    if list.len() < 2 {
        return None;
    }
    let p = list[j];
    let q = if towards_a { list[j - 1] } else { *list.get(j + 1)? };
    // A ray segment lying in the network has no side: ambiguous (`None`).
    let cell = cell_at_edge(c, p, q)?;
    c.cells()[cell as usize]
        .faces
        .iter()
        .map(|&fi| &c.faces()[fi as usize])
        .filter(|face| face.vertices.contains(&p))
        .find_map(|face| shell_of_face(ctx, index, view, face, cell))
}

/// The shell of network face `face` of the tet's complex on the side of
/// cell `cell`, or `None` if the face is no part of the network.
pub(super) fn shell_of_face(
    ctx: &Ctx,
    index: &mut dyn RayIndex,
    view: &TetView,
    face: &crate::complex::Face,
    cell: u32,
) -> Option<u32> {
    let side = face_side(ctx, view, face, cell)?;
    let keys: SmallVec<[VKey; 8]> =
        face.vertices.iter().map(|&v| vertex_key(ctx.mode, &view.complex, v, &view.tet, &view.active)).collect();
    index.shell(&view.tet, &keys, side)
}

/// The side of network face `face` of the tet's complex that cell `cell`
/// is on, or `None` if the face is no part of the network (a tet face the
/// network does not contain).
pub(super) fn face_side(ctx: &Ctx, view: &TetView, face: &crate::complex::Face, cell: u32) -> Option<FaceSide> {
    let Plane::TetFace(i) = face.plane else {
        return Some(FaceSide::Of(if face.cells[0] == cell { 0 } else { 1 }));
    };
    let c = &view.complex.cells()[cell as usize];
    let z = tet_face_zero(ctx.mode, &view.vals, &view.active, FACE_OF[i as usize], c.material())?;
    Some(match ctx.mode {
        Mode::Ia => {
            let local = view.active.iter().position(|&f| f == z)? as u16;
            FaceSide::Positive(c.is_positive(local))
        }
        Mode::Mi => FaceSide::Material(view.active[c.material() as usize]),
    })
}
