//! Tet programs: what a block emits for a tet whose complex comes from a
//! look-up table (Du et al. Sec. 6), recorded once per table template and
//! replayed for every later tet with the same template.
//!
//! A template fixes the whole complex, numbering included, and a tet that
//! reaches a template has no value exactly zero (IA) and no tie (MI) at its
//! corners, so no tet face or tet edge lies in the network. What the block
//! then emits (cells and their labels relative to the tet's functions,
//! network polygons, shell unions and wedges around chain edges, Sec. 7) is
//! a function of the template alone; only vertex keys and positions depend
//! on the tet, and those are recomputed from each vertex's plane-based
//! encoding. The first tet of a template runs the general extraction and
//! its output is turned into the program; a template whose output needs
//! anything tet-specific (pieces of tet faces, transparent face nodes) is
//! never programmed. Programs apply only without cell grouping and volumes.

use std::sync::{Arc, OnceLock, RwLock};

use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use super::keys::{edge_and_functions, edge_vertex_id, key_of, position_on, vertex_id_by_key};
use super::state::State;
use super::types::{copy_label, BlockOut, Label, SRef};
use super::values::Ctx;
use crate::complex::{Complex, Mode};

/// A complex vertex: tet element and local functions.
#[derive(Clone, Copy, Debug)]
struct PVertex {
    simplex: u8,
    funcs: [u16; 4],
    len: u8,
}

/// The recorded emission of one template.
#[derive(Clone, Debug, Default)]
pub(crate) struct Program {
    verts: Vec<PVertex>,
    /// Per complex cell: IA the bit mask of the local functions positive in
    /// it, MI its local material.
    cells: Vec<u64>,
    poly_start: Vec<u32>,
    /// Indices into `verts`.
    poly_verts: Vec<u32>,
    /// Local functions of each polygon's plane.
    poly_plane: Vec<[u16; 2]>,
    /// Local cells `[positive side, negative side]`.
    poly_cells: Vec<[u32; 2]>,
    /// Shell unions as (polygon, side) pairs.
    unions: Vec<([u32; 2], [u32; 2])>,
    /// Wedges: edge end points (indices into `verts`) and two polygon sides.
    wedges: Vec<([u32; 2], [u32; 2], [u32; 2])>,
}

/// Programs recorded by any worker of the process, by template key. A
/// program is a function of its template alone (the module docs), so a
/// worker meeting a template for the first time takes it from here instead
/// of building the complex again: the block runner makes a fresh worker for
/// every piece of work it splits off (more of them with more threads), and
/// each used to record every template again. Only programs are shared;
/// templates that cannot be programmed stay with the worker that found so.
fn shared_programs() -> &'static RwLock<FxHashMap<u64, Arc<Program>>> {
    static SHARED: OnceLock<RwLock<FxHashMap<u64, Arc<Program>>>> = OnceLock::new();
    SHARED.get_or_init(Default::default)
}

/// The program of template `key` recorded by any worker, if one was.
pub(crate) fn shared(key: u64) -> Option<Arc<Program>> {
    shared_programs().read().ok()?.get(&key).cloned()
}

/// Offers a program to the other workers (the first one recorded stays).
pub(crate) fn share(key: u64, program: &Arc<Program>) {
    if let Ok(mut map) = shared_programs().write() {
        map.entry(key).or_insert_with(|| program.clone());
    }
}

/// Lengths of the block output before a tet, to find what the tet added.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Mark {
    nodes: usize,
    polys: usize,
    halves: usize,
    unions: usize,
    wedges: usize,
    tnodes: u32,
}

impl Mark {
    pub(crate) fn of(st: &State) -> Mark {
        let o: &BlockOut = &st.out;
        Mark {
            nodes: st.uf.len(),
            polys: o.poly_label.len(),
            halves: o.halves.len(),
            unions: o.unions.len(),
            wedges: o.wedges.len(),
            tnodes: o.tnodes,
        }
    }
}

/// Turns what the general extraction added since `mark` for complex `c`
/// (built on the functions `active`; `vid` maps complex vertices to block
/// ids) into a program, or `None` if it is tet-specific.
pub(crate) fn record(c: &Complex, active: &[u16], vid: &[u32], st: &State, mark: Mark) -> Option<Program> {
    let o = &st.out;
    if o.halves.len() != mark.halves || o.tnodes != mark.tnodes || st.uf.len() - mark.nodes != c.cells().len() {
        return None;
    }
    let side = |r: SRef| match r {
        SRef::Side(p, s) => Some([p - mark.polys as u32, s as u32]),
        _ => None,
    };
    let mut p = Program::default();
    let mode = c.mode()?;
    for cell in c.cells() {
        p.cells.push(match mode {
            Mode::Ia => (0..active.len() as u16).filter(|&f| cell.is_positive(f)).fold(0, |m, f| m | 1 << f),
            Mode::Mi => cell.material() as u64,
        });
    }
    // Block id -> index into `verts`.
    let mut local: SmallVec<[(u32, u32); 32]> = SmallVec::new();
    let mut vert = |id: u32, p: &mut Program| -> Option<u32> {
        if let Some(&(_, i)) = local.iter().find(|(b, _)| *b == id) {
            return Some(i);
        }
        let cv = vid.iter().position(|&b| b == id)?;
        let v = c.vertices()[cv];
        let mut funcs = [0u16; 4];
        funcs[..v.functions().len()].copy_from_slice(v.functions());
        p.verts.push(PVertex { simplex: v.simplex(), funcs, len: v.functions().len() as u8 });
        let i = p.verts.len() as u32 - 1;
        local.push((id, i));
        Some(i)
    };
    let lf = |g: u16| active.iter().position(|&a| a == g).map(|l| l as u16);
    p.poly_start.push(0);
    for q in mark.polys..o.poly_label.len() {
        for j in o.poly_start[q]..o.poly_start[q + 1] {
            let i = vert(o.poly_verts[j as usize], &mut p)?;
            p.poly_verts.push(i);
        }
        p.poly_start.push(p.poly_verts.len() as u32);
        let [a, b] = o.poly_label[q];
        p.poly_plane.push([lf(a)?, lf(b)?]);
        p.poly_cells.push(o.poly_cells[q].map(|x| x - mark.nodes as u32));
    }
    for &(r1, r2) in &o.unions[mark.unions..] {
        p.unions.push((side(r1)?, side(r2)?));
    }
    for &(e, r1, r2) in &o.wedges[mark.wedges..] {
        let ends = [vert(e[0], &mut p)?, vert(e[1], &mut p)?];
        p.wedges.push((ends, side(r1)?, side(r2)?));
    }
    Some(p)
}

/// Adds a region node for a cell of a tet: IA, `cell` is the mask of the
/// tet's (local) functions positive in it, the other functions keep their
/// signs of `base_label`; MI, `cell` is the local material.
pub(crate) fn push_cell(mode: Mode, st: &mut State, base_label: &Label, active: &[u16], cell: u64) {
    let label: Label = match mode {
        Mode::Ia => {
            let mut l = copy_label(base_label);
            for (li, &g) in active.iter().enumerate() {
                let (w, b) = (g as usize / 64, g % 64);
                if cell >> li & 1 == 1 {
                    l[w] |= 1 << b;
                } else {
                    l[w] &= !(1 << b);
                }
            }
            l
        }
        Mode::Mi => SmallVec::from_elem(active[cell as usize] as u64, 1),
    };
    st.uf.push();
    st.node_label.push(label);
    st.node_volume.push(0.0);
}

/// Emits tet `tet` by `program`: `active` are its functions, `vals` their
/// corner values, `base_label` (IA) the sign bits of every function at corner 0.
pub(crate) fn run(
    program: &Program,
    ctx: &Ctx,
    st: &mut State,
    tet: &[u32; 4],
    active: &[u16],
    vals: &[[f64; 4]],
    base_label: &Label,
) {
    let base = st.uf.len() as u32;
    for &cell in &program.cells {
        push_cell(ctx.mode, st, base_label, active, cell);
    }
    let mut ids: SmallVec<[u32; 32]> = SmallVec::new();
    for v in &program.verts {
        let funcs = &v.funcs[..v.len as usize];
        let position = || position_on(ctx, tet, v.simplex, funcs, vals);
        let id = if v.simplex.count_ones() == 2 && (1..=2).contains(&funcs.len()) {
            // On a tet edge: the packed key straight from the edge and the
            // global functions (the same key as `key_of`, made only when new).
            let (edge, f) = edge_and_functions(v.simplex, funcs, tet, active);
            edge_vertex_id(ctx, st, edge, f, position)
        } else {
            vertex_id_by_key(ctx, st, key_of(ctx.mode, v.simplex, funcs, tet, active), position)
        };
        ids.push(id);
    }
    let poly_base = st.out.poly_label.len() as u32;
    if st.out.poly_start.is_empty() {
        st.out.poly_start.push(0);
    }
    for (q, plane) in program.poly_plane.iter().enumerate() {
        let range = program.poly_start[q] as usize..program.poly_start[q + 1] as usize;
        st.out.poly_verts.extend(program.poly_verts[range].iter().map(|&i| ids[i as usize]));
        st.out.poly_start.push(st.out.poly_verts.len() as u32);
        st.out.poly_label.push(plane.map(|f| active[f as usize]));
        st.out.poly_cells.push(program.poly_cells[q].map(|c| base + c));
    }
    let side = |r: [u32; 2]| SRef::Side(poly_base + r[0], r[1] as u8);
    for &(a, b) in &program.unions {
        st.out.unions.push((side(a), side(b)));
    }
    for &(e, r1, r2) in &program.wedges {
        let (a, b) = (ids[e[0] as usize], ids[e[1] as usize]);
        st.out.wedges.push(([a.min(b), a.max(b)], side(r1), side(r2)));
    }
}
