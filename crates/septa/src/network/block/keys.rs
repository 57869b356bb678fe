//! Global vertex keys (Du et al. Sec. 5.1): a network vertex is named by
//! the grid element it lies in and the functions defining it, so the same
//! vertex met in different tets and blocks gets the same key exactly.

use super::values::Ctx;
use super::worker::State;
use crate::complex::{Complex, Mode};
use crate::grid::Grid;
use crate::network::VKey;
use smallvec::SmallVec;

/// Global key of complex vertex `v` of tet `tet` built on the functions `active`.
pub(crate) fn vertex_key(mode: Mode, c: &Complex, v: u32, tet: &[u32; 4], active: &[u16]) -> VKey {
    let vert = c.vertices()[v as usize];
    key_of(mode, vert.simplex(), vert.functions(), tet, active)
}

/// Global key of the vertex on tet element `simplex` defined by the local
/// functions `funcs` (Sec. 5.1: sorted grid vertices of the element, sorted
/// global function ids; an MI tet corner is keyed by its grid vertex alone).
pub(crate) fn key_of(mode: Mode, simplex: u8, funcs: &[u16], tet: &[u32; 4], active: &[u16]) -> VKey {
    let mut key = VKey { grid: [u32::MAX; 4], funcs: [u16::MAX; 4] };
    let mut n = 0;
    for i in 0..4 {
        if simplex >> i & 1 == 1 {
            key.grid[n] = tet[i];
            n += 1;
        }
    }
    key.grid[..n].sort_unstable();
    if !(mode == Mode::Mi && n == 1) {
        for (j, &f) in funcs.iter().enumerate() {
            key.funcs[j] = active[f as usize];
        }
        key.funcs.sort_unstable();
    }
    key
}

/// Whether the grid element of `key` lies on the boundary of the box block
/// `lo..hi` (all its grid vertices on one side plane), so that another block
/// may produce the same vertex. Mesh blocks: always (conservative).
fn on_block_boundary(ctx: &Ctx, block: Option<([usize; 3], [usize; 3])>, key: &VKey) -> bool {
    let (Grid::Box(g), Some((lo, hi))) = (ctx.grid, block) else {
        return true;
    };
    let verts = key.grid.iter().take_while(|&&v| v != u32::MAX);
    let ijk: SmallVec<[[usize; 3]; 4]> = verts.map(|&v| g.vertex_ijk(v)).collect();
    (0..3).any(|a| ijk.iter().all(|p| p[a] == lo[a]) || ijk.iter().all(|p| p[a] == hi[a]))
}

/// Position of the vertex on tet element `simplex` defined by the local
/// functions `funcs` (rows of `vals`). Only the element's corners are
/// looked up: the other barycentric weights are exactly 0, and adding
/// `0 * corner` never changes a sum that starts at `+0.0`, so this rounds
/// exactly like `Complex::vertex_position` over all four corners.
pub(crate) fn position_on(ctx: &Ctx, tet: &[u32; 4], simplex: u8, funcs: &[u16], vals: &[[f64; 4]]) -> [f64; 3] {
    let b = crate::complex::barycentric(Some(ctx.mode), simplex, funcs, vals);
    let mut p = [0.0; 3];
    for i in 0..4 {
        if simplex >> i & 1 == 1 {
            let corner = ctx.grid.vertex(tet[i]);
            for k in 0..3 {
                p[k] += b[i] * corner[k];
            }
        }
    }
    p
}

/// Block id of the vertex with global key `key`; `position` is asked for
/// only when the key is new to the block.
pub(crate) fn vertex_id_by_key(ctx: &Ctx, st: &mut State, key: VKey, position: impl FnOnce() -> [f64; 3]) -> u32 {
    let next = st.out.keys.len() as u32;
    let id = *st.vmap.entry(key).or_insert(next);
    if id == next {
        st.out.keys.push(key);
        st.out.shared.push(on_block_boundary(ctx, st.block_box, &key));
        st.out.points.push(position());
    }
    id
}
