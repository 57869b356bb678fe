//! Global vertex keys (Du et al. Sec. 5.1): a network vertex is named by
//! the grid element it lies in and the functions defining it, so the same
//! vertex met in different tets and blocks gets the same key exactly.

use super::state::State;
use super::values::Ctx;
use crate::complex::{Complex, Mode};
use crate::grid::Grid;
use crate::network::VKey;

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
    // the key's grid vertices (up to the first unused slot) in a fixed
    // array: a collected SmallVec was half of this test's cost, which runs
    // for every new vertex
    let mut ijk = [[0usize; 3]; 4];
    let mut n = 0;
    for &v in key.grid.iter().take_while(|&&v| v != u32::MAX) {
        ijk[n] = match &ctx.lookup {
            Some(l) => l.ijk(v),
            None => g.vertex_ijk(v),
        };
        n += 1;
    }
    let ijk = &ijk[..n];
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
            let corner = ctx.vertex(tet[i]);
            for k in 0..3 {
                p[k] += b[i] * corner[k];
            }
        }
    }
    p
}

/// The commonest vertices packed into one word for the block's vertex map:
/// a function's zero on a grid edge (IA: 2 grid vertices, 1 function; MI: 2
/// grid vertices, 2 functions). The edge is its smaller grid vertex and the
/// difference to the larger one, which is small on box grids (at most
/// `(R+1)^2 + R + 2`). Keys that do not fit go to the full-key map; a key
/// either always fits or never does, so each vertex lives in one map and
/// gets one id. Hashing and comparing one word instead of 24 bytes is what
/// the per-tet extraction spends its vertex look-ups on.
fn packed(key: &VKey) -> Option<u64> {
    let [g0, g1, g2, _] = key.grid;
    if g1 == u32::MAX || g2 != u32::MAX {
        return None;
    }
    let [f0, f1, f2, _] = key.funcs;
    if f0 == u16::MAX || f2 != u16::MAX {
        return None;
    }
    packed_edge(g0, g1, f0, f1)
}

/// [`packed`] of the vertex on grid edge `g0 < g1` defined by function `f0`
/// (`f1 == u16::MAX`) or by the pair `f0 < f1`.
#[inline]
fn packed_edge(g0: u32, g1: u32, f0: u16, f1: u16) -> Option<u64> {
    let d = (g1 - g0) as u64;
    let (g0, f0, f1) = (g0 as u64, f0 as u64, f1 as u64);
    if f1 == u16::MAX as u64 {
        // Tag bit 63 clear: 22 bits of difference, 9 of function.
        (d < 1 << 22 && f0 < 1 << 9).then(|| g0 | d << 32 | f0 << 54)
    } else {
        // Tag bit 63 set: 17 bits of difference, 7 bits per function.
        (d < 1 << 17 && f1 < 1 << 7).then(|| g0 | d << 32 | f0 << 49 | f1 << 56 | 1 << 63)
    }
}

/// Block id of the vertex with global key `key`; `position` is asked for
/// only when the key is new to the block.
pub(crate) fn vertex_id_by_key(ctx: &Ctx, st: &mut State, key: VKey, position: impl FnOnce() -> [f64; 3]) -> u32 {
    let block = st.block_box;
    vertex_id_with(st, key, || on_block_boundary(ctx, block, &key), position)
}

/// The grid edge (`g0 < g1`) of tet element `simplex` (two corners) and the
/// sorted global ids of the local functions `funcs` (one, then
/// `u16::MAX`, or two): what [`edge_vertex_id`] takes, as [`key_of`] names
/// the vertex.
#[inline]
pub(crate) fn edge_and_functions(simplex: u8, funcs: &[u16], tet: &[u32; 4], active: &[u16]) -> ([u32; 2], [u16; 2]) {
    debug_assert!(simplex.count_ones() == 2 && (1..=2).contains(&funcs.len()), "an edge vertex");
    let (a, b) = (simplex.trailing_zeros() as usize, 31 - (simplex as u32).leading_zeros() as usize);
    let mut f = [u16::MAX; 2];
    for (j, &l) in funcs.iter().enumerate() {
        f[j] = active[l as usize];
    }
    if f[1] < f[0] {
        f.swap(0, 1);
    }
    ([tet[a].min(tet[b]), tet[a].max(tet[b])], f)
}

/// [`vertex_id_by_key`] for the vertex on grid edge `g0 < g1` defined by
/// function `f0` (`f1 == u16::MAX`) or by the pair `f0 < f1` (global ids):
/// the packed key is made from these directly, and the full key only for
/// a vertex new to the block (most look-ups find one a neighbour made).
pub(crate) fn edge_vertex_id(
    ctx: &Ctx,
    st: &mut State,
    [g0, g1]: [u32; 2],
    [f0, f1]: [u16; 2],
    position: impl FnOnce() -> [f64; 3],
) -> u32 {
    let key = || VKey { grid: [g0, g1, u32::MAX, u32::MAX], funcs: [f0, f1, u16::MAX, u16::MAX] };
    let Some(p) = packed_edge(g0, g1, f0, f1) else {
        return vertex_id_by_key(ctx, st, key(), position);
    };
    let next = st.out.keys.len() as u32;
    let id = *st.emap.entry(p).or_insert(next);
    if id == next {
        let key = key();
        debug_assert_eq!(packed(&key), Some(p));
        let block = st.block_box;
        push_vertex(st, key, on_block_boundary(ctx, block, &key), position());
    }
    id
}

/// Appends a vertex new to the block: its key, whether another block may
/// share it, and its position.
#[inline]
fn push_vertex(st: &mut State, key: VKey, shared: bool, position: [f64; 3]) {
    st.out.keys.push(key);
    st.out.shared.push(shared);
    st.out.points.push(position);
}

/// [`vertex_id_by_key`] with the block-boundary test supplied by a caller
/// that knows the grid element's indices (the same answer as
/// `on_block_boundary`, without its divisions).
#[inline]
pub(crate) fn vertex_id_with(
    st: &mut State,
    key: VKey,
    shared: impl FnOnce() -> bool,
    position: impl FnOnce() -> [f64; 3],
) -> u32 {
    let next = st.out.keys.len() as u32;
    let id = match packed(&key) {
        Some(p) => *st.emap.entry(p).or_insert(next),
        None => *st.vmap.entry(key).or_insert(next),
    };
    if id == next {
        push_vertex(st, key, shared(), position());
    }
    id
}

#[cfg(test)]
mod tests {
    use super::packed;
    use crate::network::VKey;

    fn key(grid: &[u32], funcs: &[u16]) -> VKey {
        let mut k = VKey { grid: [u32::MAX; 4], funcs: [u16::MAX; 4] };
        k.grid[..grid.len()].copy_from_slice(grid);
        k.funcs[..funcs.len()].copy_from_slice(funcs);
        k
    }

    #[test]
    fn packed_keys_are_distinct_and_only_for_edge_vertices() {
        // Distinct edge keys never share a word (ids must not merge).
        let mut seen = std::collections::HashMap::new();
        for g0 in [0u32, 1, 7, 1 << 20, u32::MAX - (1 << 22)] {
            for d in [1u32, 2, 101, 10_303, (1 << 17) - 1, (1 << 22) - 1] {
                for f in [[0u16, u16::MAX], [5, u16::MAX], [511, u16::MAX], [0, 1], [3, 127], [126, 127]] {
                    let k = key(&[g0, g0 + d], if f[1] == u16::MAX { &f[..1] } else { &f });
                    if let Some(p) = packed(&k) {
                        assert_eq!(*seen.entry(p).or_insert(k), k, "{k:?}");
                    }
                }
            }
        }
        assert!(seen.len() > 100);
        // Too large to pack: the full-key map takes them.
        assert_eq!(packed(&key(&[0, 1 << 22], &[0])), None);
        assert_eq!(packed(&key(&[0, 1], &[512])), None);
        assert_eq!(packed(&key(&[0, 1 << 17], &[0, 1])), None);
        assert_eq!(packed(&key(&[0, 1], &[0, 128])), None);
        // Grid vertices, face and tet vertices are not packed.
        assert_eq!(packed(&key(&[4], &[])), None);
        assert_eq!(packed(&key(&[4], &[1, 2, 3])), None);
        assert_eq!(packed(&key(&[1, 2, 3], &[0, 1])), None);
        assert_eq!(packed(&key(&[1, 2, 3, 4], &[0, 1, 2])), None);
        assert_eq!(packed(&key(&[1, 2], &[0, 1, 2])), None);
    }
}
