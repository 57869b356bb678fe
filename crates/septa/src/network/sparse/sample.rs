//! Sampling one block of a sparse job (`run.rs`): the functions' bounds
//! decide first whether the block may hold a part of the network at all,
//! then which of its sub-boxes may (`block/mask.rs`); only the vertices of
//! those are sampled, per axis coordinate, into the block's rows of values
//! (or, for a label volume, its one indicator per vertex).

use crate::complex::Mode;
use crate::grid::BoxGrid;
use crate::network::block::{mask_applies, BlockLabels, BlockValues, CubeMask, NO_ROW};
use crate::network::field::BoundedField;
use crate::network::NetworkError;

/// Whether a block may hold a part of the network, by the functions' bounds
/// over its box (no sampling).
pub(super) fn may_be_active(
    grid: &BoxGrid,
    functions: &dyn BoundedField,
    mode: Mode,
    lo: [usize; 3],
    hi: [usize; 3],
) -> bool {
    let a = grid.vertex(grid.vertex_index(lo));
    let b = grid.vertex(grid.vertex_index(hi));
    functions.may_be_active(mode, a, b)
}

/// A block's samples: `k` values per vertex, or (label volumes, MI) the
/// one indicator that is 1 per vertex.
pub(super) enum Sampled {
    Rows(BlockValues),
    Labels(BlockLabels),
}

/// The coordinates of the vertices of cubes `lo..hi` along each axis: a
/// vertex's coordinate on an axis depends on its index on that axis alone,
/// so these are the same bits as `grid.vertex` per point, without its
/// divisions (a third of the sampling cost before, on 18 spheres).
fn axis_coordinates(grid: &BoxGrid, lo: [usize; 3], hi: [usize; 3]) -> [Vec<f64>; 3] {
    [0, 1, 2].map(|a| {
        (lo[a]..=hi[a])
            .map(|l| {
                let mut ijk = lo;
                ijk[a] = l;
                grid.vertex(grid.vertex_index(ijk))[a]
            })
            .collect()
    })
}

/// The vertices of cubes `lo..hi` as label indices, when the field is a
/// label volume's indicators and the mode MI (one strict maximum at every
/// vertex, so ray shooting's precondition holds).
fn sample_block_labels(
    grid: &BoxGrid,
    functions: &dyn BoundedField,
    mode: Mode,
    lo: [usize; 3],
    hi: [usize; 3],
) -> Option<BlockLabels> {
    let vn = [hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1];
    if mode != Mode::Mi {
        return None;
    }
    let mut labels = Vec::with_capacity(vn[0] * vn[1] * vn[2]);
    let [xs, ys, zs] = axis_coordinates(grid, lo, hi);
    // One row of vertices along the last axis per call: a label volume
    // reads a row as a slice of consecutive voxels.
    let mut points = Vec::with_capacity(vn[2]);
    for &x in &xs {
        for &y in &ys {
            points.clear();
            points.extend(zs.iter().map(|&z| [x, y, z]));
            if !functions.sample_labels(&points, &mut labels) {
                return None;
            }
        }
    }
    Some(BlockLabels::new(grid, lo, vn, labels))
}

/// Samples the vertices of cubes `lo..hi`; also says whether ray shooting's
/// precondition holds there (IA no value 0, MI a unique strict maximum).
pub(super) fn sample_block(
    grid: &BoxGrid,
    functions: &dyn BoundedField,
    mode: Mode,
    lo: [usize; 3],
    hi: [usize; 3],
) -> Result<(Sampled, bool), NetworkError> {
    if let Some(labels) = sample_block_labels(grid, functions, mode, lo, hi) {
        return Ok((Sampled::Labels(labels), true));
    }
    let k = functions.functions();
    let vn = [hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1];
    // IA: the functions of one proven sign on the block's box (its first
    // and last grid vertex; every vertex lies in it) are neither bounded on
    // its sub-boxes nor sampled: no tet of the block has them active, and
    // IA reads them only through that sign (field.rs).
    let signs = (mode == Mode::Ia).then(|| {
        let at = |l: [usize; 3]| grid.vertex(grid.vertex_index(l));
        functions.ia_signs_on_box(at(lo), at(hi))
    });
    let mask = sub_box_mask(grid, functions, mode, lo, hi, signs.as_deref());
    // One `sample` call for the whole block (rows along the last axis, in
    // the block's vertex order): one allocation and one split into parallel
    // chunks per block, not per row; the values are the same bits.
    let [xs, ys, zs] = axis_coordinates(grid, lo, hi);
    let mut points = Vec::with_capacity(mask.as_ref().map_or(vn[0] * vn[1] * vn[2], |m| m.sampled()));
    let mut local = 0;
    for &x in &xs {
        for &y in &ys {
            match &mask {
                None => points.extend(zs.iter().map(|&z| [x, y, z])),
                Some(m) => {
                    for (l, &z) in (local..).zip(&zs) {
                        if m.row(l) != NO_ROW {
                            points.push([x, y, z]);
                        }
                    }
                }
            }
            local += zs.len();
        }
    }
    let data = match &signs {
        Some(signs) => functions.sample_ia_with_signs(&points, signs),
        None => functions.sample(&points),
    };
    drop(points);
    // Vertices of sub-boxes proven empty are proven clean and finite by the
    // same bounds (`scene/sample.rs`), so only the samples are checked.
    // Whole-array passes without early exits (they vectorize); the rows are
    // walked only to name the first non-finite value.
    if !data.iter().fold(true, |all, x| all & x.is_finite()) {
        for (n, row) in data.chunks_exact(k).enumerate() {
            if let Some(f) = row.iter().position(|x| !x.is_finite()) {
                let n = match &mask {
                    None => n,
                    Some(m) => (0..vn[0] * vn[1] * vn[2]).find(|&l| m.row(l) as usize == n).unwrap_or(n),
                };
                let ijk = [lo[0] + n / (vn[1] * vn[2]), lo[1] + n / vn[2] % vn[1], lo[2] + n % vn[2]];
                let v = grid.vertex_index(ijk);
                return Err(NetworkError::NonFinite { vertex: v as usize, function: f, value: row[f] });
            }
        }
    }
    let clean = match mode {
        Mode::Ia => data.iter().fold(true, |all, &x| all & (x != 0.0)),
        Mode::Mi => data.chunks_exact(k).all(|row| {
            let m = row.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            row.iter().filter(|&&x| x == m).count() == 1
        }),
    };
    let values = match mask {
        None => BlockValues::new(grid, lo, vn, k, data),
        Some(m) => BlockValues::masked(grid, lo, vn, k, data, m),
    };
    Ok((Sampled::Rows(values), clean))
}

/// The sub-boxes of the block of cubes `lo..hi` that the functions' bounds
/// cannot prove empty (`block/mask.rs`), when some can be. Each sub-box's box
/// runs from its first to its last grid vertex, so it holds every vertex of
/// its cubes (grid coordinates are monotone in the index), as for blocks.
fn sub_box_mask(
    grid: &BoxGrid,
    functions: &dyn BoundedField,
    mode: Mode,
    lo: [usize; 3],
    hi: [usize; 3],
    ia_signs: Option<&[Option<bool>]>,
) -> Option<CubeMask> {
    if !mask_applies(mode, functions.functions()) {
        return None;
    }
    let n = [0, 1, 2].map(|a| hi[a] - lo[a]);
    let at = |l: [usize; 3]| grid.vertex(grid.vertex_index([lo[0] + l[0], lo[1] + l[1], lo[2] + l[2]]));
    CubeMask::build(n, |a, b| match ia_signs {
        Some(signs) => functions.may_be_active_quick_ia_with_signs(at(a), at(b), signs),
        None => functions.may_be_active_quick(mode, at(a), at(b)),
    })
}
