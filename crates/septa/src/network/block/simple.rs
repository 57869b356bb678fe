//! The single-polygon fast path: most active tets hold one network polygon
//! and nothing else (IA: one active function, nonzero at the 4 corners; MI:
//! two active functions, never tied at a corner). Their complex is decided by
//! the corner sign pattern alone (Du et al. Sec. 6, the look-up table of one
//! function), so the polygon, its two cells and their labels are read from a
//! template per sign pattern instead of decoding a whole complex and walking
//! its tet faces, edges and wedges.
//!
//! Why it gives the same output as the general path: the templates are made
//! by building the complex itself, once, on values with the same corner
//! signs; vertex keys and positions are computed by the same functions
//! ([`super::block::vertex_key`]'s rule, [`crate::complex::barycentric`]);
//! and such a tet adds nothing else to the block: no tet face lies in the
//! network, no network edge carries two faces of the tet, no tet edge lies
//! in the network, so the general path emits no shell unions or wedges for
//! it. It is used only where the general path would not group cells or
//! compute volumes (those need the tet-face contacts and cell geometry).

use std::sync::OnceLock;

use smallvec::SmallVec;

use super::keys::{edge_and_functions, edge_vertex_id, position_on, vertex_id_with};
use super::state::State;
use super::types::Label;
use super::values::Ctx;
use crate::complex::{barycentric, Complex, Mode, Options, Plane};
use crate::network::VKey;

/// One vertex of the template polygon: on the tet edge `simplex` (bit mask
/// of its two corners), defined by local functions `funcs[..len]`.
#[derive(Clone, Copy, Debug)]
struct TVertex {
    simplex: u8,
    funcs: [u16; 2],
    len: u8,
}

/// The complex of one sign pattern, reduced to what the block emits.
#[derive(Clone, Debug)]
struct Template {
    /// The polygon loop, counter-clockwise from its positive side.
    verts: SmallVec<[TVertex; 4]>,
    /// The polygon's plane as local functions (IA `[0, 0]`, MI the pair).
    plane: [u16; 2],
    /// Per complex cell (in the complex's order): IA whether function 0 is
    /// positive, MI the local material.
    cells: [u16; 2],
    /// The polygon's `[positive side, negative side]` cells (0 or 1).
    sides: [u32; 2],
    /// MI: per polygon vertex, its barycentric weights when the two
    /// functions are label indicators (function 0 is 1 at the corners of
    /// the pattern's bits, function 1 at the others): the values then
    /// follow from the pattern, so the weights are computed once here, by
    /// the same [`crate::complex::barycentric`] the general path calls.
    indicator: SmallVec<[[f64; 4]; 4]>,
}

/// Templates per mode (IA 0, MI 1) and corner sign pattern (bit `i`: IA
/// `f > 0` at corner `i`; MI the first active function exceeds the second).
fn templates() -> &'static [[Option<Template>; 16]; 2] {
    static T: OnceLock<[[Option<Template>; 16]; 2]> = OnceLock::new();
    T.get_or_init(|| {
        let make = |mode: Mode, pattern: usize| -> Option<Template> {
            if pattern == 0 || pattern == 15 {
                return None;
            }
            let f0: [f64; 4] = std::array::from_fn(|i| if pattern >> i & 1 == 1 { 1.0 } else { -1.0 });
            let vals: Vec<[f64; 4]> = match mode {
                Mode::Ia => vec![f0],
                Mode::Mi => vec![f0, [0.0; 4]],
            };
            let mut c = Complex::new();
            c.build(mode, &vals, &Options::default()).ok()?;
            let mut net = c.faces().iter().filter(|f| f.plane.is_network());
            let face = net.next()?;
            if net.next().is_some() || c.cells().len() != 2 {
                return None;
            }
            let verts: SmallVec<[TVertex; 4]> = face
                .vertices
                .iter()
                .map(|&v| {
                    let vert = c.vertices()[v as usize];
                    let fs = vert.functions();
                    let mut funcs = [0u16; 2];
                    funcs[..fs.len()].copy_from_slice(fs);
                    TVertex { simplex: vert.simplex(), funcs, len: fs.len() as u8 }
                })
                .collect();
            let plane = match face.plane {
                Plane::Function(f) => [f, f],
                Plane::Pair(a, b) => [a, b],
                Plane::TetFace(_) => return None,
            };
            let cell = |i: usize| match mode {
                Mode::Ia => c.cells()[i].is_positive(0) as u16,
                Mode::Mi => c.cells()[i].material(),
            };
            let indicator = match mode {
                Mode::Ia => SmallVec::new(),
                Mode::Mi => {
                    let vals = indicator_values(pattern);
                    let weights = |v: &TVertex| barycentric(Some(mode), v.simplex, &v.funcs[..v.len as usize], &vals);
                    verts.iter().map(weights).collect()
                }
            };
            Some(Template { verts, plane, cells: [cell(0), cell(1)], sides: face.cells, indicator })
        };
        [Mode::Ia, Mode::Mi].map(|mode| std::array::from_fn(|p| make(mode, p)))
    })
}

/// Emits tet `tet` by its template if it is a single-polygon tet (see the
/// module docs) and returns whether it did. `active` are its active
/// functions, `vals` their corner values, `base_label` (IA) the sign bits of
/// every function at corner 0.
pub(crate) fn simple_tet(
    ctx: &Ctx,
    st: &mut State,
    tet: &[u32; 4],
    active: &[u16],
    vals: &[[f64; 4]],
    base_label: &Label,
) -> bool {
    if st.grouping || ctx.volumes || !ctx.options.lookup {
        return false;
    }
    let (mi, pattern) = match (ctx.mode, vals) {
        (Mode::Ia, [r]) => {
            if r.contains(&0.0) {
                return false;
            }
            (0, (0..4).fold(0, |p, i| p | ((r[i] > 0.0) as usize) << i))
        }
        (Mode::Mi, [a, b]) => {
            if (0..4).any(|i| a[i] == b[i]) {
                return false;
            }
            (1, (0..4).fold(0, |p, i| p | ((a[i] > b[i]) as usize) << i))
        }
        _ => return false,
    };
    let Some(t) = &templates()[mi][pattern] else {
        return false;
    };
    // The two cells, in the complex's order.
    let base = st.uf.len() as u32;
    for &cell in &t.cells {
        super::program::push_cell(ctx.mode, st, base_label, active, cell as u64);
    }
    // The polygon.
    if st.out.poly_start.is_empty() {
        st.out.poly_start.push(0);
    }
    for tv in &t.verts {
        // Every vertex of a one-polygon template is on a tet edge (Sec. 5.1
        // key: the edge's grid vertices, the sorted global functions).
        let funcs = &tv.funcs[..tv.len as usize];
        let (edge, f) = edge_and_functions(tv.simplex, funcs, tet, active);
        let id = edge_vertex_id(ctx, st, edge, f, || position_on(ctx, tet, tv.simplex, funcs, vals));
        st.out.poly_verts.push(id);
    }
    st.out.poly_start.push(st.out.poly_verts.len() as u32);
    st.out.poly_label.push(t.plane.map(|f| active[f as usize]));
    st.out.poly_cells.push(t.sides.map(|s| base + s));
    true
}

/// The rows of two label indicators at a tet's corners: the first is 1
/// where `pattern` has its bit (the corner's label is the lesser one).
pub(crate) fn indicator_values(pattern: usize) -> [[f64; 4]; 2] {
    let first: [f64; 4] = std::array::from_fn(|i| (pattern >> i & 1) as f64);
    [first, first.map(|x| 1.0 - x)]
}

/// Where a box-grid tet's corners are, known from its cube: each corner's
/// grid index triple, and per axis the coordinates of the block's grid lines
/// from `lo` (the same bits as `BoxGrid::vertex`, without its divisions).
pub(crate) struct CubeCorners<'a> {
    pub ijk: [[usize; 3]; 4],
    pub lo: [usize; 3],
    pub hi: [usize; 3],
    pub axes: &'a [Vec<f64>; 3],
}

impl CubeCorners<'_> {
    fn position(&self, i: usize) -> [f64; 3] {
        std::array::from_fn(|a| self.axes[a][self.ijk[i][a] - self.lo[a]])
    }

    /// Whether the tet edge `simplex` lies on a side plane of the block
    /// `lo..hi` (the rule of `keys::on_block_boundary`, from the indices).
    fn edge_on_block_boundary(&self, simplex: u8) -> bool {
        let (p, q) = (self.ijk[simplex.trailing_zeros() as usize], self.ijk[7 - simplex.leading_zeros() as usize]);
        (0..3).any(|a| (p[a] == self.lo[a] && q[a] == self.lo[a]) || (p[a] == self.hi[a] && q[a] == self.hi[a]))
    }
}

/// [`simple_tet`] for an MI tet whose corners carry the two labels `pair`
/// (`pair[0] < pair[1]`; bit `i` of `pattern`: corner `i` has `pair[0]`),
/// the functions being the labels' indicators (`voxels.rs`). The same
/// template, keys and cells; the vertex positions from the template's
/// indicator weights and the corners' coordinates, which is what
/// `position_on` computes from those values. Returns false where
/// [`simple_tet`] would.
pub(crate) fn indicator_pair_tet(
    ctx: &Ctx,
    st: &mut State,
    tet: &[u32; 4],
    pair: &[u16; 2],
    pattern: usize,
    corners: &CubeCorners,
) -> bool {
    if st.grouping || ctx.volumes || !ctx.options.lookup {
        return false;
    }
    let Some(t) = &templates()[1][pattern] else {
        return false;
    };
    let base = st.uf.len() as u32;
    for &cell in &t.cells {
        super::program::push_cell(ctx.mode, st, &Label::new(), pair, cell as u64);
    }
    if st.out.poly_start.is_empty() {
        st.out.poly_start.push(0);
    }
    for (tv, w) in t.verts.iter().zip(&t.indicator) {
        let mut key = VKey { grid: [u32::MAX; 4], funcs: [u16::MAX; 4] };
        let (a, b) = (tv.simplex.trailing_zeros() as usize, 7 - tv.simplex.leading_zeros() as usize);
        key.grid[0] = tet[a].min(tet[b]);
        key.grid[1] = tet[a].max(tet[b]);
        for j in 0..tv.len as usize {
            key.funcs[j] = pair[tv.funcs[j] as usize];
        }
        key.funcs[..tv.len as usize].sort_unstable();
        let position = || {
            let mut p = [0.0; 3];
            for i in [a, b] {
                let corner = corners.position(i);
                for k in 0..3 {
                    p[k] += w[i] * corner[k];
                }
            }
            #[cfg(debug_assertions)]
            {
                let vals = indicator_values(pattern);
                let want = position_on(ctx, tet, tv.simplex, &tv.funcs[..tv.len as usize], &vals);
                debug_assert_eq!(p.map(f64::to_bits), want.map(f64::to_bits), "vertex of tet {tet:?}");
            }
            p
        };
        let id = vertex_id_with(st, key, || corners.edge_on_block_boundary(tv.simplex), position);
        st.out.poly_verts.push(id);
    }
    st.out.poly_start.push(st.out.poly_verts.len() as u32);
    st.out.poly_label.push(t.plane.map(|f| pair[f as usize]));
    st.out.poly_cells.push(t.sides.map(|s| base + s));
    true
}

#[cfg(test)]
mod tests {
    use super::templates;

    #[test]
    fn every_mixed_pattern_has_a_template() {
        for mode in templates() {
            for (p, t) in mode.iter().enumerate() {
                assert_eq!(t.is_some(), p != 0 && p != 15, "pattern {p}");
                if let Some(t) = t {
                    // A triangle for one corner apart, a quad for two.
                    let apart = (p as u32).count_ones().min(4 - (p as u32).count_ones());
                    assert_eq!(t.verts.len(), if apart == 1 { 3 } else { 4 });
                    assert!(t.verts.iter().all(|v| v.simplex.count_ones() == 2));
                }
            }
        }
    }
}
