//! The fast path for blocks of a box grid: a cube whose 8 corners carry the
//! same region label (IA: the same strict sign of every function; MI: the
//! same unique strict maximum) holds no part of the network in any of its
//! tets, so it becomes one region node without per-tet work, joined to
//! empty neighbour cubes by index and to the rest through face contacts.
//!
//! Why it is exact: IA, a linear function with one strict sign at the 4
//! corners of a tet is nonzero in it; MI, a function strictly maximal at the
//! 4 corners of a tet strictly dominates every other one there.

use smallvec::SmallVec;

use super::mask::NO_ROW;
use super::simple::CubeCorners;
use super::state::{contact, face_key, State};
use super::types::{copy_label, Label};
use super::values::Ctx;
use super::worker::Worker;
use crate::complex::{Mode, NONE};
use crate::grid::{grid_coordinate, BoxGrid};
use crate::network::NetworkError;

/// Corner label of a vertex: IA sign bits (k <= 63), MI the strict argmax;
/// `BAD` when a value is zero (IA) or the maximum is tied (MI).
const BAD: u64 = u64::MAX;

/// Whether the fast path applies.
pub(crate) fn applies(ctx: &Ctx) -> bool {
    super::mask::applies(ctx.mode, ctx.k)
}

fn vertex_label(ctx: &Ctx, v: u32, buf: &mut Vec<f64>) -> u64 {
    if let Some(l) = ctx.label(v) {
        // Indicators: the 1 is the unique strict maximum.
        return l as u64;
    }
    row_label(ctx, ctx.row(v, buf))
}

/// [`vertex_label`] of the vertex whose `k` values are `row`.
fn row_label(ctx: &Ctx, row: &[f64]) -> u64 {
    let k = ctx.k;
    match ctx.mode {
        Mode::Ia => {
            // Without branches (a zero is rare): every vertex of a block
            // goes through here, k values each.
            let (mut bits, mut zero) = (0u64, false);
            for (f, &x) in row.iter().enumerate() {
                bits |= ((x > 0.0) as u64) << f;
                zero |= x == 0.0;
            }
            if zero {
                BAD
            } else {
                bits
            }
        }
        Mode::Mi => {
            let mut best = 0;
            let mut tied = false;
            for f in 1..k {
                if row[f] > row[best] {
                    best = f;
                    tied = false;
                } else if row[f] == row[best] {
                    tied = true;
                }
            }
            if tied {
                BAD
            } else {
                best as u64
            }
        }
    }
}

/// Tet faces of a cube lying on each of its 6 faces (axis * 2 + side), as
/// (local tet, tet face) pairs, for a cube with the parity of `cube`.
fn cube_face_table(g: &BoxGrid, cube: [usize; 3]) -> [SmallVec<[(usize, usize); 2]>; 6] {
    let per = g.split.tets_per_cube();
    let c = g.cube_index(cube);
    let mut out: [SmallVec<[(usize, usize); 2]>; 6] = Default::default();
    for lt in 0..per {
        let tet = g.tet(c * per + lt);
        let ijk = tet.map(|v| g.vertex_ijk(v));
        for skip in 0..4 {
            for axis in 0..3 {
                for side in 0..2 {
                    let want = cube[axis] + side;
                    if (0..4).filter(|&j| j != skip).all(|j| ijk[j][axis] == want) {
                        out[axis * 2 + side].push((lt, skip));
                    }
                }
            }
        }
    }
    out
}

/// Processes the cubes `lo..hi` of a box grid.
pub(super) fn run_box(
    w: &mut Worker,
    ctx: &Ctx,
    st: &mut State,
    g: &BoxGrid,
    lo: [usize; 3],
    hi: [usize; 3],
) -> Result<(), NetworkError> {
    let n = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    let vn = [n[0] + 1, n[1] + 1, n[2] + 1];
    // Sub-boxes proven empty (`mask.rs`): their cubes would be skipped as
    // one-label cubes, and their vertices carry no samples. Only without
    // grouping, where such cubes are nobody's region.
    let mask = if st.grouping { None } else { ctx.sparse.and_then(|s| s.mask()) };
    let block_labels = ctx.sparse.and_then(|s| s.block_labels(lo, vn));
    let mut vl = match block_labels {
        // A label volume: every vertex's label is its corner label.
        Some(labels) => labels.iter().map(|&l| l as u64).collect(),
        None => vec![BAD; vn[0] * vn[1] * vn[2]],
    };
    // This block's samples as rows, read by local index (the walk below
    // knows every corner's), not located from grid vertex ids.
    let rows = ctx.block_rows.filter(|r| r.lo == lo && r.vn == vn);
    let mut buf = Vec::with_capacity(ctx.k);
    for i in 0..if block_labels.is_some() { 0 } else { vn[0] } {
        for j in 0..vn[1] {
            for k in 0..vn[2] {
                let local = (i * vn[1] + j) * vn[2] + k;
                if mask.is_some_and(|m| m.row(local) == NO_ROW) {
                    continue;
                }
                vl[local] = match &rows {
                    Some(r) => row_label(ctx, &r.data[r.row_of(local) as usize * ctx.k..][..ctx.k]),
                    None => vertex_label(ctx, g.vertex_index([lo[0] + i, lo[1] + j, lo[2] + k]), &mut buf),
                };
            }
        }
    }
    let per = g.split.tets_per_cube();
    // Label volumes: tets decided by their corner labels (voxels.rs).
    let indicators = super::voxels::applies(ctx, g.vertex_index(lo));
    // The block's grid lines per axis (`BoxGrid::vertex`'s coordinates).
    let axes: [Vec<f64>; 3] = std::array::from_fn(|a| {
        (lo[a]..=hi[a]).map(|i| grid_coordinate(g.bounds[0][a], g.bounds[1][a], i, g.res[a])).collect()
    });
    let cube_vol =
        if ctx.volumes { (0..3).map(|a| (g.bounds[1][a] - g.bounds[0][a]) / g.res[a] as f64).product() } else { 0.0 };
    let mut node = vec![NONE; n[0] * n[1] * n[2]];
    let local = |i: usize, j: usize, k: usize| (i * n[1] + j) * n[2] + k;
    // Per row of cubes, `column[k]`: the 4 vertices (i|i+1, j|j+1, k) share
    // one label (not BAD). A cube has one label when its two columns do and
    // agree: the 8-corner test becomes 3 comparisons, and the column pass
    // runs over 4 contiguous rows (which the compiler can vectorize).
    let mut column = vec![false; vn[2]];
    for i in 0..n[0] {
        for j in 0..n[1] {
            let row = |a: usize, b: usize| &vl[((i + a) * vn[1] + j + b) * vn[2]..][..vn[2]];
            let (r00, r01, r10, r11) = (row(0, 0), row(0, 1), row(1, 0), row(1, 1));
            for k in 0..vn[2] {
                let l = r00[k];
                column[k] = l != BAD && r01[k] == l && r10[k] == l && r11[k] == l;
            }
            for k in 0..n[2] {
                if mask.is_some_and(|m| !m.cube([i, j, k])) {
                    continue;
                }
                let l0 = r00[k];
                let same = column[k] && column[k + 1] && r00[k + 1] == l0;
                if same && !st.grouping {
                    // Without grouping an empty cube is nobody's region: skip it.
                    continue;
                }
                let cube = g.cube_index([lo[0] + i, lo[1] + j, lo[2] + k]);
                if same {
                    let id = st.uf.push();
                    let l: Label = match ctx.mode {
                        Mode::Ia => {
                            let mut v: Label = SmallVec::from_elem(0, 1);
                            v[0] = l0;
                            v
                        }
                        Mode::Mi => SmallVec::from_elem(l0, 1),
                    };
                    st.node_label.push(l);
                    st.node_volume.push(cube_vol);
                    node[local(i, j, k)] = id;
                } else {
                    // The cube's 8 corners (bit code `a << 2 | b << 1 | c`, as
                    // `tet_corners` names them): grid vertex, corner label and
                    // sample row, once per cube instead of once per tet.
                    let gc = [lo[0] + i, lo[1] + j, lo[2] + k];
                    let at = |p: usize| [(p >> 2) & 1, (p >> 1) & 1, p & 1];
                    let locals: [usize; 8] = std::array::from_fn(|p| {
                        let [a, b, c] = at(p);
                        ((i + a) * vn[1] + j + b) * vn[2] + k + c
                    });
                    let cube_ids: [u32; 8] = std::array::from_fn(|p| {
                        let [a, b, c] = at(p);
                        g.vertex_index([gc[0] + a, gc[1] + b, gc[2] + c])
                    });
                    let cube_labels = locals.map(|l| vl[l]);
                    let cube_rows = rows.map(|r| locals.map(|l| r.row_of(l)));
                    for (lt, t) in (cube * per..(cube + 1) * per).enumerate() {
                        // IA: the active functions are the sign bits that differ
                        // between the tet's corners, the label at corner 0 the
                        // base of its cells' labels (when no value is zero).
                        w.active_hint = None;
                        w.base_hint = None;
                        w.pair_hint = None;
                        w.winner_hint = None;
                        let ps = g.tet_corners(gc, lt).map(|p| p as usize);
                        let corners = ps.map(|p| cube_labels[p]);
                        if indicators {
                            // `g.tet(t)` without its divisions.
                            let ijk = ps.map(|p| {
                                let [a, b, c] = at(p);
                                [gc[0] + a, gc[1] + b, gc[2] + c]
                            });
                            let tet = ps.map(|p| cube_ids[p]);
                            let geometry = CubeCorners { ijk, lo, hi, axes: &axes };
                            if super::voxels::indicator_tet(w, ctx, st, t, &tet, corners, &geometry)? {
                                continue;
                            }
                        }
                        w.tet_hint = Some(ps.map(|p| cube_ids[p]));
                        w.rows_hint = cube_rows.map(|r| ps.map(|p| r[p]));
                        if ctx.mode == Mode::Mi && !corners.contains(&BAD) {
                            // The unique strict maximum at each corner.
                            w.winner_hint = Some(corners);
                        }
                        if ctx.mode == Mode::Ia {
                            let (mut or, mut and) = (0u64, u64::MAX);
                            for l in corners {
                                or |= l;
                                and &= l;
                            }
                            if !corners.contains(&BAD) {
                                w.active_hint = Some(or ^ and);
                                w.base_hint = Some(corners[0]);
                            }
                        }
                        w.process_tet(ctx, st, t)?;
                    }
                    w.active_hint = None;
                    w.base_hint = None;
                    w.pair_hint = None;
                    w.winner_hint = None;
                }
            }
        }
    }
    if !st.grouping {
        return Ok(());
    }
    // Join empty cubes to empty neighbours by index, the rest by contacts.
    let odd =
        [[0, 0, 1], [0, 1, 0], [1, 0, 0]].into_iter().find(|c| (0..3).all(|a| c[a] < g.res[a])).unwrap_or([0, 0, 0]);
    let tables = [cube_face_table(g, [0, 0, 0]), cube_face_table(g, odd)];
    for i in 0..n[0] {
        for j in 0..n[1] {
            for k in 0..n[2] {
                let id = node[local(i, j, k)];
                if id == NONE {
                    continue;
                }
                let ijk = [i, j, k];
                let gc = [lo[0] + i, lo[1] + j, lo[2] + k];
                let parity = match g.split {
                    crate::grid::Split::Five => (gc[0] + gc[1] + gc[2]) % 2,
                    crate::grid::Split::Six => 0,
                };
                let cube = g.cube_index(gc);
                for axis in 0..3 {
                    for side in 0..2 {
                        let mut nb = ijk;
                        let inside = if side == 1 {
                            nb[axis] += 1;
                            nb[axis] < n[axis]
                        } else if nb[axis] > 0 {
                            nb[axis] -= 1;
                            true
                        } else {
                            false
                        };
                        if inside {
                            let other = node[local(nb[0], nb[1], nb[2])];
                            if other != NONE {
                                // Empty neighbours share 4 corners, hence their label.
                                st.uf.union(id, other);
                                continue;
                            }
                        }
                        let l = copy_label(&st.node_label[id as usize]);
                        for &(lt, f) in &tables[parity][axis * 2 + side] {
                            let tet = g.tet(cube * per + lt);
                            contact(st, face_key(&tet, f), &l, id);
                        }
                    }
                }
            }
        }
    }
    Ok(())
}
