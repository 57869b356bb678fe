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
//! Preconditions, checked: a box grid (convex boundary, no cavities or
//! handles). Network vertices at grid vertices are points a ray can hit
//! too; where the local picture is ambiguous (a ray segment lying in the
//! network, a ray returning to its own component) the answer is `None` and
//! the caller falls back to cell grouping.

use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use crate::complex::{Complex, Mode, NONE};
use crate::grid::{BoxGrid, Grid};
use crate::network::block::{active_functions, vertex_key, Ctx};
use crate::network::VKey;
use crate::uf::UnionFind;

/// What ray shooting asks of the network: which component a vertex is in,
/// and which shell a face side belongs to. Both questions name the tet
/// being looked at, so an index may answer from that tet's block alone
/// (the in-memory network, or a block re-run on demand: `rerun.rs`).
pub(crate) trait RayIndex {
    /// The connected component of the network vertex with key `key` (a
    /// vertex of the complex of `tet`), or `None` if it is no network vertex.
    fn component(&mut self, tet: &[u32; 4], key: VKey) -> Option<u32>;

    /// The shell of side `side` (0 positive, 1 negative) of the network
    /// face of `tet` whose vertices have the keys `keys`.
    fn shell(&mut self, tet: &[u32; 4], keys: &[VKey], side: usize) -> Option<u32>;
}

/// The in-memory network as ray shooting sees it.
pub(crate) struct RayInput<'a> {
    pub keys: &'a [VKey],
    pub face_start: &'a [u32],
    pub face_verts: &'a [u32],
    pub face_patch: &'a [u32],
    pub shell_of_hp: &'a [u32],
    /// Connected component of each vertex.
    pub vertex_comp: &'a [u32],
    pub num_comps: usize,
}

impl RayInput<'_> {
    /// Per component, the smallest grid edge `(v, u)` carrying one of its
    /// edge-points (where its ray starts), or `None` if a component touches
    /// no grid edge (cannot happen on a proper network).
    pub(crate) fn starts(&self) -> Option<Vec<(u32, u32)>> {
        let mut best: Vec<(u32, u32)> = vec![(u32::MAX, u32::MAX); self.num_comps];
        for (v, k) in self.keys.iter().enumerate() {
            if k.grid[2] == u32::MAX {
                let c = self.vertex_comp[v] as usize;
                best[c] = best[c].min((k.grid[0], k.grid[1]));
            }
        }
        best.iter().all(|b| b.0 != u32::MAX).then_some(best)
    }
}

/// [`RayIndex`] over the merged network: a vertex-to-face index built once.
pub(crate) struct MergedIndex<'a> {
    inp: &'a RayInput<'a>,
    vmap: KeyIndex<'a>,
    /// Faces at vertex `v`: `vf[start[v]..start[v + 1]]`.
    start: Vec<u32>,
    vf: Vec<u32>,
}

impl<'a> MergedIndex<'a> {
    pub(crate) fn new(inp: &'a RayInput<'a>) -> MergedIndex<'a> {
        let (start, vf) = faces_at_vertices(inp.keys.len(), inp.face_start, inp.face_verts);
        MergedIndex { inp, vmap: KeyIndex::new(inp.keys), start, vf }
    }
}

/// The faces at each of `nv` vertices, as `(start, faces)`: face ids at `v`
/// are `faces[start[v]..start[v + 1]]` (polygon `f` is
/// `face_verts[face_start[f]..face_start[f + 1]]`).
pub(crate) fn faces_at_vertices(nv: usize, face_start: &[u32], face_verts: &[u32]) -> (Vec<u32>, Vec<u32>) {
    let mut start = vec![0u32; nv + 1];
    for &v in face_verts {
        start[v as usize + 1] += 1;
    }
    for v in 0..nv {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut faces = vec![0u32; face_verts.len()];
    for f in 0..face_start.len().saturating_sub(1) {
        for j in face_start[f]..face_start[f + 1] {
            let v = face_verts[j as usize] as usize;
            faces[fill[v] as usize] = f as u32;
            fill[v] += 1;
        }
    }
    (start, faces)
}

impl RayIndex for MergedIndex<'_> {
    fn component(&mut self, _tet: &[u32; 4], key: VKey) -> Option<u32> {
        self.vmap.get(key).map(|id| self.inp.vertex_comp[id as usize])
    }

    fn shell(&mut self, _tet: &[u32; 4], keys: &[VKey], side: usize) -> Option<u32> {
        let mut ids: SmallVec<[u32; 8]> = SmallVec::new();
        for &k in keys {
            ids.push(self.vmap.get(k)?);
        }
        ids.sort_unstable();
        let inp = self.inp;
        let at = ids[0] as usize;
        for &gf in &self.vf[self.start[at] as usize..self.start[at + 1] as usize] {
            let mut vs: SmallVec<[u32; 8]> =
                inp.face_verts[inp.face_start[gf as usize] as usize..inp.face_start[gf as usize + 1] as usize].into();
            vs.sort_unstable();
            if vs == ids {
                let s = inp.shell_of_hp[2 * inp.face_patch[gf as usize] as usize + side];
                return (s != NONE).then_some(s);
            }
        }
        None
    }
}

/// Global vertex id by key. Rays look up only a few keys, so when the keys
/// are in canonical order (sorted by grid element, as after
/// `canon::canonicalize_merged`) a binary search beats hashing every vertex;
/// otherwise a hash map is built.
enum KeyIndex<'a> {
    Sorted(&'a [VKey]),
    Hashed(FxHashMap<VKey, u32>),
}

impl<'a> KeyIndex<'a> {
    fn new(keys: &'a [VKey]) -> KeyIndex<'a> {
        if keys.windows(2).all(|w| w[0].grid <= w[1].grid) {
            KeyIndex::Sorted(keys)
        } else {
            KeyIndex::Hashed(keys.iter().enumerate().map(|(i, k)| (*k, i as u32)).collect())
        }
    }

    fn get(&self, key: VKey) -> Option<u32> {
        match self {
            KeyIndex::Sorted(keys) => {
                let lo = keys.partition_point(|k| k.grid < key.grid);
                keys[lo..].iter().take_while(|k| k.grid == key.grid).position(|k| *k == key).map(|i| (lo + i) as u32)
            }
            KeyIndex::Hashed(map) => map.get(&key).copied(),
        }
    }
}

/// A per-tet complex built on demand along a ray.
struct TetView {
    tet: [u32; 4],
    active: Vec<u16>,
    complex: Complex,
}

/// Cell of each of the `num_shells` shells and the number of cells, or
/// `None` when the preconditions do not hold. `starts` holds, per network
/// component, the smallest grid edge `(v, u)` carrying one of its
/// edge-points (components numbered as `index` numbers them).
pub(crate) fn ray_cells(
    ctx: &Ctx,
    index: &mut dyn RayIndex,
    starts: &[(u32, u32)],
    num_shells: usize,
) -> Option<(Vec<u32>, usize)> {
    let Grid::Box(g) = ctx.grid else { return None };
    let mut uf = UnionFind::new(num_shells + 1);
    for (c, &(v, u)) in starts.iter().enumerate() {
        let c = c as u32;
        let view = tet_view(ctx, g, v, u)?;
        let pts = edge_points(ctx, &view, v, u, index);
        // The component's point closest to v on this edge (never a corner).
        let j = (1..pts.len().saturating_sub(1)).find(|&j| pts[j] == Some(c))?;
        let start_shell = facing_shell(ctx, index, &view, v, u, j, true)?;
        let end_shell = match (0..j).rev().find(|&k| pts[k].is_some()) {
            Some(k) => {
                if pts[k] == Some(c) {
                    return None;
                }
                facing_shell(ctx, index, &view, v, u, k, false)?
            }
            None => walk(ctx, g, index, num_shells, v, c)?,
        };
        uf.union(start_shell, end_shell);
    }
    let (comp, n) = uf.components();
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
                return facing_shell(ctx, index, &view, w, cur, k, false);
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
fn for_tets_at(g: &BoxGrid, v: u32, mut f: impl FnMut([u32; 4]) -> bool) {
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
    let tet = found?;
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
    Some(TetView { tet, active, complex })
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
    let la = view.tet.iter().position(|&x| x == a)? as u8;
    let lb = view.tet.iter().position(|&x| x == b)? as u8;
    let list = c.tet_edge_points(la, lb);
    if list.len() < 2 {
        return None;
    }
    let p = list[j];
    let q = if towards_a { list[j - 1] } else { *list.get(j + 1)? };
    let edge = c.edges().iter().position(|e| e.vertices == [p, q] || e.vertices == [q, p])? as u32;
    // A ray segment lying in the network has no side: ambiguous.
    if c.faces().iter().any(|f| f.plane.is_network() && f.edges.contains(&edge)) {
        return None;
    }
    let cell =
        c.cells().iter().position(|cl| cl.faces.iter().any(|&f| c.faces()[f as usize].edges.contains(&edge)))? as u32;
    for &fi in &c.cells()[cell as usize].faces {
        let face = &c.faces()[fi as usize];
        if !face.plane.is_network() || !face.vertices.contains(&p) {
            continue;
        }
        let keys: SmallVec<[VKey; 8]> =
            face.vertices.iter().map(|&v| vertex_key(ctx.mode, c, v, &view.tet, &view.active)).collect();
        let side = if face.cells[0] == cell { 0 } else { 1 };
        if let Some(s) = index.shell(&view.tet, &keys, side) {
            return Some(s);
        }
    }
    None
}
