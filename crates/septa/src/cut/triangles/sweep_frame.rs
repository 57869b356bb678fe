//! The frame in which `selfx` boxes its triangles to find candidate pairs.
//!
//! Candidate pairs are the triangles whose bounding boxes overlap (TopoCut
//! App. A). Axis-aligned boxes serve a mesh whose surfaces follow the axes
//! or curve in every direction, but not a thin part tilted against them:
//! on plate_genus9 (a plate whose two large faces have the normal
//! ±(0.56, -0.51, -0.66)) every triangle of the top face overlaps in its
//! box the triangles of the bottom face below it, and so do the cut-faces'
//! slivers across the plate; most of the check's candidates were such
//! pairs, each turned away only by an orientation test. Boxed along the
//! plate's normal, top and bottom are apart by the plate's thickness.
//!
//! Why any frame is sound. The rows `r_k` of the frame are three vectors of
//! doubles, any three (not even orthogonal). Two triangles that meet share
//! a point `p`, and `r_k . p` lies in the range of `r_k . q` over the
//! corners `q` of each (a linear function's range over a triangle is that
//! over its corners). The ranges are computed in floating point, each end
//! widened by a bound on the rounding error (below), so they contain the
//! exact ranges: boxes that do not overlap prove the pair apart. The pairs
//! found are then decided exactly on the input doubles, as before; the
//! frame changes which pairs are tested, never an answer.
//!
//! The frame tried is that of the triangles' normals: the eigenvectors of
//! their area-weighted tensor `sum |n_i| u_i u_i^T` (`u_i` the unit
//! normals), so that a direction most of the area faces becomes an axis.
//! It is used when its boxes are clearly smaller, their summed volume below
//! three quarters of the axis-aligned boxes' (plate_genus9's input: 0.002
//! of it; its cut with 20 random planes: 0.53). A mesh along the axes
//! (cube, staircase) keeps them: its axis-aligned boxes are flat. On curved
//! meshes the share is 0.6 to 1.2, and where it is below the threshold
//! (the R20 cuts of fertility, rocker_arm, nefertiti) the frame gains or
//! costs nothing measurable.
//!
//! On plate_genus9 the frame takes the input check from 3.7 to 1.8 ms and
//! the certification of its R20 cut from 40 to 34 ms (a fifth fewer
//! candidate pairs reach the exact test).

use crate::cut::triangles::pair_grid::Aabb;

/// The frame is used when its boxes' summed volume is below this share of
/// the axis-aligned boxes' (a tilted flat part: far below it).
const VOLUME_SHARE: f64 = 0.75;

/// The frame's rows for the normals `n` (any lengths; zero ones ignored):
/// the eigenvectors of their area-weighted tensor (see the module doc), or
/// `None` when it has no direction (no triangle with a finite normal).
pub(crate) fn normal_frame(normals: impl Iterator<Item = [f64; 3]>) -> Option<[[f64; 3]; 3]> {
    let mut t = [[0.0f64; 3]; 3];
    for n in normals {
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        if !(len > 0.0 && len.is_finite()) {
            continue;
        }
        // |n| u u^T = n n^T / |n|
        let m = n.map(|c| c / len);
        for i in 0..3 {
            for j in 0..3 {
                t[i][j] += n[i] * m[j];
            }
        }
    }
    let trace = t[0][0] + t[1][1] + t[2][2];
    if !(trace > 0.0 && trace.is_finite()) {
        return None;
    }
    Some(symmetric_eigen(t).1)
}

/// The frame and the choice are made on about this many triangles (every
/// `n / SAMPLE`-th): a share far below or above the threshold shows on any
/// such sample, and on the large curved meshes, which keep the axes, the
/// choice made on all triangles cost 5-8 ms of a 60 ms check.
const SAMPLE: usize = 4096;

/// The boxes of `tris` in the frame of their normals when those are much
/// smaller than the axis-aligned `boxes` (summed volume below
/// [`VOLUME_SHARE`] of theirs, on a sample of [`SAMPLE`] triangles), else
/// `None`: the axes are kept.
pub(crate) fn sweep_boxes(
    x: &[[f64; 3]],
    tris: &[[u32; 3]],
    normals: impl Iterator<Item = [f64; 3]>,
    boxes: &[Aabb],
) -> Option<Vec<Aabb>> {
    let step = tris.len().div_ceil(SAMPLE).max(1);
    let r = normal_frame(normals.step_by(step))?;
    let sample: Vec<[u32; 3]> = tris.iter().step_by(step).copied().collect();
    let axis_aligned: Vec<Aabb> = boxes.iter().step_by(step).copied().collect();
    let volume = |b: &[Aabb]| b.iter().map(|(lo, hi)| (0..3).map(|k| hi[k] - lo[k]).product::<f64>()).sum::<f64>();
    if !(volume(&framed_boxes(x, &sample, &r)?) < VOLUME_SHARE * volume(&axis_aligned)) {
        return None;
    }
    framed_boxes(x, tris, &r)
}

/// Eigenvalues and unit eigenvectors (rows) of a symmetric 3x3 matrix by
/// cyclic Jacobi rotations (Golub and Van Loan, "Matrix Computations",
/// 4th ed., Sec. 8.5). Only a frame for boxes depends on it: accuracy
/// matters for tight boxes, never for correctness.
fn symmetric_eigen(mut a: [[f64; 3]; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _sweep in 0..32 {
        let off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        let diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
        if off <= 1e-30 * diag {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            // the rotation zeroing a[p][q] (Golub and Van Loan, Alg. 8.5.1)
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            for row in a.iter_mut() {
                let (akp, akq) = (row[p], row[q]);
                row[p] = c * akp - s * akq;
                row[q] = s * akp + c * akq;
            }
            let (rp, rq) = (a[p], a[q]);
            a[p] = std::array::from_fn(|k| c * rp[k] - s * rq[k]);
            a[q] = std::array::from_fn(|k| s * rp[k] + c * rq[k]);
            for row in v.iter_mut() {
                let (rp, rq) = (row[p], row[q]);
                row[p] = c * rp - s * rq;
                row[q] = s * rp + c * rq;
            }
        }
    }
    // the columns of `v` are the eigenvectors; return them as rows
    let vectors = std::array::from_fn(|i| [v[0][i], v[1][i], v[2][i]]);
    ([a[0][0], a[1][1], a[2][2]], vectors)
}

/// The boxes of the triangles `tris` (corners in `x`) in the frame with
/// rows `r`, each end widened by the bound on its rounding error so that
/// the box holds the exact image of the triangle.
///
/// Error bound: `fl(r0 p0 + r1 p1 + r2 p2)`, summed left to right, differs
/// from the exact value by at most `gamma_3 * (|r0 p0| + |r1 p1| + |r2 p2|)`
/// with `gamma_3 = 3u / (1 - 3u)`, `u = 2^-53` (Higham, "Accuracy and
/// Stability of Numerical Algorithms", 2nd ed., Sec. 3.1). With `M_j` the
/// largest `|p_j|` over the vertices used, one widening `e_k = 4u fl(S_k)`,
/// `S_k = |r_k0| M_0 + |r_k1| M_1 + |r_k2| M_2`, covers every vertex with
/// room for the rounding of `fl(S_k)` and of `e_k` and for the widening's
/// own rounding (`fl(lo - e) <= lo - e` is not guaranteed, so the ends are
/// moved one more ulp outwards). Products below the normal range lose an
/// absolute `2^-1075` at most, which `2^-1000` added to `e_k` covers.
/// Non-finite coordinates, and coordinates so large that an image could
/// overflow, give `None` (no frame is used).
pub(crate) fn framed_boxes(x: &[[f64; 3]], tris: &[[u32; 3]], r: &[[f64; 3]; 3]) -> Option<Vec<Aabb>> {
    const U: f64 = f64::EPSILON / 2.0;
    let mut m = [0.0f64; 3];
    for t in tris {
        for &v in t {
            for j in 0..3 {
                m[j] = m[j].max(x[v as usize][j].abs());
            }
        }
    }
    if !m.iter().all(|c| c.is_finite()) {
        return None;
    }
    let s: [f64; 3] = std::array::from_fn(|k| r[k][0].abs() * m[0] + r[k][1].abs() * m[1] + r[k][2].abs() * m[2]);
    // every partial sum of an image is at most `S_k` in magnitude (up to its
    // rounding): with `2 S_k` finite no image overflows, where an infinite
    // one could leave a box without its exact point
    if !s.iter().all(|c| (2.0 * c).is_finite()) {
        return None;
    }
    let e: [f64; 3] = std::array::from_fn(|k| 4.0 * U * s[k] + f64::from_bits(0x0170_0000_0000_0000)); // + 2^-1000
    let image =
        |p: &[f64; 3]| -> [f64; 3] { std::array::from_fn(|k| r[k][0] * p[0] + r[k][1] * p[1] + r[k][2] * p[2]) };
    Some(
        tris.iter()
            .map(|t| {
                let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
                for &v in t {
                    let q = image(&x[v as usize]);
                    for k in 0..3 {
                        lo[k] = lo[k].min(q[k]);
                        hi[k] = hi[k].max(q[k]);
                    }
                }
                (std::array::from_fn(|k| (lo[k] - e[k]).next_down()), std::array::from_fn(|k| (hi[k] + e[k]).next_up()))
            })
            .collect(),
    )
}

#[cfg(test)]
#[path = "sweep_frame_tests.rs"]
mod tests;
