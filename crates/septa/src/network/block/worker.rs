//! The per-tet worker of a block: active functions, the tet's complex
//! (Du et al. Sec. 4-6), its polygons with global keys, region contacts,
//! shell unions and wedges; fast paths (`simple`, `program`) slot in before
//! the general construction. The block's run (`run.rs`) and the box fast
//! paths (`boxfast`, `voxels`) sit above and call `process_tet`.

use std::sync::Arc;

use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use super::active::{active_functions_with, ia_base_label};
use super::keys::{vertex_id_by_key, vertex_key};
use super::state::{contact, face_key, Lengths, State, FACE_OF};
use super::types::{copy_label, HalfPoly, Label, SRef};
use super::values::Ctx;
use crate::complex::{Complex, Mode, Plane, NONE};
use crate::network::{NetworkError, VKey};

/// Per-thread reusable state.
#[derive(Default)]
pub(crate) struct Worker {
    complex: Complex,
    vals: Vec<[f64; 4]>,
    active: Vec<u16>,
    vid: Vec<u32>,
    fref: Vec<Option<SRef>>,
    pub(super) tets: Vec<usize>,
    pairs: Vec<(u32, u32)>,
    edge_net: Vec<u32>,
    /// IA: the active functions of the next tet as a bit mask, if known.
    pub(super) active_hint: Option<u64>,
    /// IA: the sign bits at corner 0 of the next tet (k <= 63), if known.
    pub(super) base_hint: Option<u64>,
    /// MI: the next tet's two active functions (ascending), if known
    /// (label indicators with two labels at its corners).
    pub(super) pair_hint: Option<[u16; 2]>,
    /// MI: the unique strict maximum at each corner of the next tet, if known.
    pub(super) winner_hint: Option<[u64; 4]>,
    /// The grid vertices of the next tet, if known (`Grid::tet` without its
    /// divisions, from the cube the caller walks).
    pub(super) tet_hint: Option<[u32; 4]>,
    /// The rows of the next tet's corners in the block's samples
    /// (`Values::block_rows`), if known (from the cube the caller walks).
    pub(super) rows_hint: Option<[u32; 4]>,
    cell_labels: Vec<Label>,
    /// IA: sign bits of every function at corner 0 of the current tet.
    base_label: Label,
    /// The block's vertex maps (full and packed keys, `keys::packed`), kept
    /// between blocks so their tables are allocated once per thread.
    pub(super) vmap: FxHashMap<VKey, u32>,
    pub(super) emap: FxHashMap<u64, u32>,
    /// Tet programs by look-up table template (`None`: not programmable).
    programs: FxHashMap<u64, Option<Arc<super::program::Program>>>,
    /// The lengths of the previous block's output arrays (`Lengths`).
    pub(super) last: Lengths,
    /// Label volumes: complexes by their corner values (`voxels::build_complex`).
    indicator_complexes: FxHashMap<Vec<u64>, Complex>,
}

impl Worker {
    /// The per-tet step (active functions, complex, extraction); look-up
    /// tables slot in at the `build` call.
    pub(crate) fn process_tet(&mut self, ctx: &Ctx, st: &mut State, t: usize) -> Result<(), NetworkError> {
        let tet = self.tet_hint.take().unwrap_or_else(|| ctx.grid.tet(t));
        debug_assert_eq!(tet, ctx.grid.tet(t), "grid vertices of tet {t}");
        let rows_hint = self.rows_hint.take();
        let block_data = rows_hint.and(ctx.block_rows).map(|r| r.data);
        let k = ctx.k;
        let row = |f: usize| match (rows_hint, block_data) {
            (Some(r), Some(d)) => {
                let x = r.map(|r| d[r as usize * k + f]);
                debug_assert_eq!(x.map(f64::to_bits), tet.map(|v| ctx.val(v, f).to_bits()), "rows of tet {t}");
                x
            }
            _ => tet.map(|v| ctx.val(v, f)),
        };
        match (self.pair_hint, self.active_hint) {
            (Some(pair), _) => {
                self.active.clear();
                self.active.extend_from_slice(&pair);
            }
            (None, Some(mut mask)) => {
                self.active.clear();
                while mask != 0 {
                    self.active.push(mask.trailing_zeros() as u16);
                    mask &= mask - 1;
                }
            }
            (None, None) => active_functions_with(ctx, t, &tet, self.winner_hint, &mut self.active)?,
        }
        let empty = match ctx.mode {
            Mode::Ia => self.active.is_empty(),
            Mode::Mi => self.active.len() < 2,
        };
        let volume = if ctx.volumes { ctx.grid.tet_volume(t) } else { 0.0 };
        if empty && !st.grouping {
            return Ok(()); // no polygon refers to an empty tet's region
        }
        if empty {
            let label: Label = match ctx.mode {
                Mode::Ia => ia_base_label(&tet, ctx),
                Mode::Mi => SmallVec::from_elem(self.active[0] as u64, 1),
            };
            let node = st.uf.push();
            for i in 0..4 {
                contact(st, face_key(&tet, i), &label, node);
            }
            st.node_label.push(label);
            st.node_volume.push(volume);
            return Ok(());
        }
        st.out.active_tets += 1;
        self.vals.clear();
        for &f in &self.active {
            self.vals.push(row(f as usize));
        }
        if ctx.mode == Mode::Ia {
            self.base_label = match self.base_hint {
                Some(b) => SmallVec::from_elem(b, 1),
                None => ia_base_label(&tet, ctx),
            };
        }
        if super::simple::simple_tet(ctx, st, &tet, &self.active, &self.vals, &self.base_label) {
            return Ok(());
        }
        // Table tets: replay the template's program, or record it.
        let template =
            if st.grouping || ctx.volumes { None } else { Complex::template_key(ctx.mode, &self.vals, &ctx.options) };
        if let Some(key) = template {
            // Borrowed, not cloned: an `Arc` count touched per tet from two
            // threads would bounce its cache line between the cores.
            if let Some(Some(p)) = self.programs.get(&key) {
                super::program::run(p, ctx, st, &tet, &self.active, &self.vals, &self.base_label);
                return Ok(());
            }
            if !self.programs.contains_key(&key) {
                if let Some(p) = super::program::shared(key) {
                    super::program::run(&p, ctx, st, &tet, &self.active, &self.vals, &self.base_label);
                    self.programs.insert(key, Some(p));
                    return Ok(());
                }
            }
        }
        let mark = super::program::Mark::of(st);
        super::voxel_complex::build_complex(&mut self.complex, &mut self.indicator_complexes, ctx, &tet, &self.vals)
            .map_err(|source| NetworkError::Tet { tet: t, source })?;
        let owned = std::mem::take(&mut self.complex);
        let c = &owned;
        // Region labels and nodes.
        let base = st.uf.len() as u32;
        let base_label = std::mem::take(&mut self.base_label);
        self.cell_labels.clear();
        for cell in c.cells() {
            let label: Label = match ctx.mode {
                Mode::Ia => {
                    let mut l = copy_label(&base_label);
                    for (li, &g) in self.active.iter().enumerate() {
                        let (w, b) = (g as usize / 64, g % 64);
                        if cell.is_positive(li as u16) {
                            l[w] |= 1 << b;
                        } else {
                            l[w] &= !(1 << b);
                        }
                    }
                    l
                }
                Mode::Mi => SmallVec::from_elem(self.active[cell.material() as usize] as u64, 1),
            };
            st.uf.push();
            st.node_label.push(copy_label(&label));
            st.node_volume.push(0.0);
            self.cell_labels.push(label);
        }
        self.base_label = base_label;
        if ctx.volumes {
            let corners = tet.map(|v| ctx.vertex(v));
            for (ci, cell) in c.cells().iter().enumerate() {
                st.node_volume[base as usize + ci] = cell_volume(c, cell, &corners, &self.vals);
            }
        }
        // Vertices, lazily keyed.
        self.vid.clear();
        self.vid.resize(c.vertices().len(), NONE);
        self.fref.clear();
        self.fref.resize(c.faces().len(), None);
        self.pairs.clear();
        for (fi, face) in c.faces().iter().enumerate() {
            match face.plane {
                Plane::TetFace(i) => {
                    let i = i as usize;
                    let material = c.cells()[face.cells[0] as usize].material();
                    if let Some(z) = tet_face_zero(ctx.mode, &self.vals, &self.active, FACE_OF[i], material) {
                        let verts = face.vertices.iter().map(|&v| vertex_id(self, c, ctx, st, &tet, v)).collect();
                        let h = st.out.halves.len() as u32;
                        st.out.halves.push(HalfPoly {
                            face: face_key(&tet, i),
                            verts,
                            cell: base + face.cells[0],
                            zero: z,
                        });
                        self.fref[fi] = Some(SRef::Half(h));
                        if ctx.mode == Mode::Mi {
                            self.pairs.push((i as u32, face.cells[0]));
                        }
                    } else {
                        self.pairs.push((i as u32, face.cells[0]));
                    }
                }
                plane => {
                    let label = match plane {
                        Plane::Function(f) => [self.active[f as usize]; 2],
                        Plane::Pair(a, b) => [self.active[a as usize], self.active[b as usize]],
                        Plane::TetFace(_) => unreachable!(),
                    };
                    let p = st.out.poly_label.len() as u32;
                    if st.out.poly_start.is_empty() {
                        st.out.poly_start.push(0);
                    }
                    for &v in &face.vertices {
                        let id = vertex_id(self, c, ctx, st, &tet, v);
                        st.out.poly_verts.push(id);
                    }
                    st.out.poly_start.push(st.out.poly_verts.len() as u32);
                    st.out.poly_label.push(label);
                    st.out.poly_cells.push([base + face.cells[0], base + face.cells[1]]);
                    self.fref[fi] = Some(SRef::Side(p, 0));
                }
            }
        }
        // Region contacts across tet faces (cell grouping), once per (face, cell).
        self.pairs.sort_unstable();
        self.pairs.dedup();
        if st.grouping {
            for j in 0..self.pairs.len() {
                let (i, cell) = self.pairs[j];
                let label = copy_label(&self.cell_labels[cell as usize]);
                contact(st, face_key(&tet, i as usize), &label, base + cell);
            }
        }
        // Shell connectivity (Sec. 7): around an edge of the network, the two
        // faces of a cell there bound the same wedge, so their sides facing the
        // cell belong to one shell. Inside a tet this is a direct union; a wedge
        // leaving through a tet face continues in the neighbour tet, matched by
        // a (tet face, region label, edge) node. Such nodes are only needed
        // where a chain may run: edges on a tet face that carry 2+ network
        // faces of this tet (a surface crossing a tet face transversally has
        // faces on both sides, so both tets see the same count), and network
        // segments of tet edges (degenerate input).
        self.edge_net.clear();
        self.edge_net.resize(c.edges().len(), 0);
        for (fi, face) in c.faces().iter().enumerate() {
            if self.fref[fi].is_some() {
                for &e in &face.edges {
                    self.edge_net[e as usize] += 1;
                }
            }
        }
        // A tet-edge segment can only lie in the network if a function vanishes
        // (IA) or two tie for the maximum (MI) at a tet corner.
        let corner_degenerate = (0..4).any(|i| match ctx.mode {
            Mode::Ia => self.vals.iter().any(|r| r[i] == 0.0),
            Mode::Mi => {
                let m = self.vals.iter().map(|r| r[i]).fold(f64::NEG_INFINITY, f64::max);
                self.vals.iter().filter(|r| r[i] == m).count() >= 2
            }
        });
        for (ci, cell) in c.cells().iter().enumerate() {
            // (edge, face) packed as `e << 32 | f`: the numeric order is
            // the pairs' lexicographic one, and a sort of plain integers
            // (the small sort of every tet) compares once instead of twice
            let mut ef: SmallVec<[u64; 32]> = SmallVec::new();
            for &fi in &cell.faces {
                for &e in &c.faces()[fi as usize].edges {
                    if self.edge_net[e as usize] > 0 || (corner_degenerate && on_tet_edge(c, e)) {
                        ef.push(u64::from(e) << 32 | u64::from(fi));
                    }
                }
            }
            ef.sort_unstable();
            let edge = |k: u64| (k >> 32) as u32;
            let mut j = 0;
            while j + 1 < ef.len() {
                if edge(ef[j]) != edge(ef[j + 1]) {
                    j += 1;
                    continue;
                }
                let (e, f1, f2) = (edge(ef[j]), ef[j] as u32, ef[j + 1] as u32);
                j += 2;
                let [u, w] = c.edges()[e as usize].vertices;
                let (n1, n2) = (self.fref[f1 as usize].is_some(), self.fref[f2 as usize].is_some());
                let tet_edge = on_tet_edge(c, e);
                let needed = if tet_edge {
                    segment_on_network(ctx.mode, c, &self.vals, u, w)
                } else {
                    (n1 && n2) || self.edge_net[e as usize] >= 2
                };
                if !needed {
                    continue;
                }
                let r1 = self.face_ref(c, ctx, st, &tet, ci as u32, f1, u, w);
                let r2 = self.face_ref(c, ctx, st, &tet, ci as u32, f2, u, w);
                st.out.unions.push((r1, r2));
                // Inside the tet, around an edge on 3+ network faces (a chain),
                // the wedges give the cyclic order of faces (Sec. 7).
                if !tet_edge
                    && self.edge_net[e as usize] >= 3
                    && c.edges()[e as usize].planes.iter().all(|p| p.is_network())
                {
                    if let (SRef::Side(..), SRef::Side(..)) = (r1, r2) {
                        let a = vertex_id(self, c, ctx, st, &tet, u);
                        let b = vertex_id(self, c, ctx, st, &tet, w);
                        st.out.wedges.push(([a.min(b), a.max(b)], r1, r2));
                    }
                }
            }
        }
        if let Some(key) = template {
            let program = super::program::record(c, &self.active, &self.vid, st, mark).map(Arc::new);
            if let Some(p) = &program {
                super::program::share(key, p);
            }
            self.programs.insert(key, program);
        }
        self.complex = owned;
        Ok(())
    }

    /// The shell reference of face `f` of cell `cell` at edge `(u, w)`.
    #[allow(clippy::too_many_arguments)]
    fn face_ref(
        &mut self,
        c: &Complex,
        ctx: &Ctx,
        st: &mut State,
        tet: &[u32; 4],
        cell: u32,
        f: u32,
        u: u32,
        w: u32,
    ) -> SRef {
        let face = &c.faces()[f as usize];
        match self.fref[f as usize] {
            Some(SRef::Side(p, _)) => SRef::Side(p, if face.cells[0] == cell { 0 } else { 1 }),
            Some(r) => r,
            None => {
                let Plane::TetFace(i) = face.plane else { unreachable!() };
                let fk = face_key(tet, i as usize);
                let a = vertex_id(self, c, ctx, st, tet, u);
                let b = vertex_id(self, c, ctx, st, tet, w);
                let key = (fk, copy_label(&self.cell_labels[cell as usize]), a.min(b), a.max(b));
                if let Some(t) = st.tmap.remove(&key) {
                    SRef::T(t)
                } else {
                    let t = st.out.tnodes;
                    st.out.tnodes += 1;
                    st.tmap.insert(key, t);
                    SRef::T(t)
                }
            }
        }
    }
}

/// Whether complex edge `e` lies on a tet edge.
fn on_tet_edge(c: &Complex, e: u32) -> bool {
    c.edges()[e as usize].planes.iter().all(|p| !p.is_network())
}

/// The functions vanishing (IA) or tied for the maximum (MI) at a vertex.
fn zero_set(mode: Mode, c: &Complex, vals: &[[f64; 4]], v: u32) -> SmallVec<[u16; 8]> {
    let vert = &c.vertices()[v as usize];
    if vert.dim() > 0 {
        return c.tied_functions(v, vals);
    }
    let corner = vert.simplex().trailing_zeros() as usize;
    match mode {
        Mode::Ia => (0..vals.len() as u16).filter(|&f| vals[f as usize][corner] == 0.0).collect(),
        Mode::Mi => {
            let m = vals.iter().map(|r| r[corner]).fold(f64::NEG_INFINITY, f64::max);
            (0..vals.len() as u16).filter(|&f| vals[f as usize][corner] == m).collect()
        }
    }
}

/// Whether the tet-edge segment `u w` lies on the network: one function
/// vanishes at both ends (IA; it is linear along the edge), or two functions
/// are tied for the maximum at both ends (MI).
fn segment_on_network(mode: Mode, c: &Complex, vals: &[[f64; 4]], u: u32, w: u32) -> bool {
    let (a, b) = (zero_set(mode, c, vals, u), zero_set(mode, c, vals, w));
    let common = a.iter().filter(|f| b.contains(f)).count();
    match mode {
        Mode::Ia => common >= 1,
        Mode::Mi => common >= 2,
    }
}

/// Block id of complex vertex `v`, creating its key and position on first use.
fn vertex_id(w: &mut Worker, c: &Complex, ctx: &Ctx, st: &mut State, tet: &[u32; 4], v: u32) -> u32 {
    if w.vid[v as usize] != NONE {
        return w.vid[v as usize];
    }
    let key = vertex_key(ctx.mode, c, v, tet, &w.active);
    let id = vertex_id_by_key(ctx, st, key, || {
        let corners = tet.map(|g| ctx.vertex(g));
        c.vertex_position(v as usize, &corners, &w.vals)
    });
    w.vid[v as usize] = id;
    id
}

/// The function naming the network face that a piece of tet face
/// `corners` lies on, seen from the piece's cell of material `material`
/// (MI, a local index; IA ignores it), or `None` if the piece is off the
/// network.
/// - IA: a function vanishing at the face's three corners vanishes on the
///   whole face, so every piece lies on its zero set.
/// - MI: another function equal to the material at the three corners ties
///   with it on the whole face (their pair plane is the tet face). Where the
///   material wins on the face, that tie is an interface to the cell across
///   the face; the piece is named by the smaller of the two. Where a third
///   function wins on part of the face, only the rest lies on the network,
///   and the tet across names the same pieces by the same vertex keys.
pub(crate) fn tet_face_zero(
    mode: Mode,
    vals: &[[f64; 4]],
    active: &[u16],
    corners: [usize; 3],
    material: u16,
) -> Option<u16> {
    match mode {
        Mode::Ia => vals.iter().position(|r| corners.iter().all(|&i| r[i] == 0.0)).map(|f| active[f]),
        Mode::Mi => {
            let m = material as usize;
            let tied = |f: usize| f != m && corners.iter().all(|&i| vals[f][i] == vals[m][i]);
            (0..vals.len()).find(|&f| tied(f)).map(|f| active[f.min(m)])
        }
    }
}

/// Volume of a convex cell (floating point; output and invariant checks only):
/// sum of cones from its first vertex over its faces.
fn cell_volume(c: &Complex, cell: &crate::complex::Cell, corners: &[[f64; 3]; 4], vals: &[[f64; 4]]) -> f64 {
    let pos = |v: u32| c.vertex_position(v as usize, corners, vals);
    let apex = pos(c.faces()[cell.faces[0] as usize].vertices[0]);
    let mut vol = 0.0;
    for &fi in &cell.faces {
        let vs = &c.faces()[fi as usize].vertices;
        let p0 = pos(vs[0]);
        for j in 1..vs.len() - 1 {
            let (p1, p2) = (pos(vs[j]), pos(vs[j + 1]));
            vol += crate::grid::tet_volume(&apex, &p0, &p1, &p2).abs();
        }
    }
    vol
}
