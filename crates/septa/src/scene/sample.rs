//! Sampling functions at grid vertices, and the block tests of sparse
//! evaluation (docs/sparse.md).

use rayon::prelude::*;

use super::gradbound::difference_lower;
use super::primitive::Primitive;
use super::vec3::V3;

/// Values of every function at every point, row-major `(N, k)`:
/// `out[i * k + j] = functions[j].eval(points[i])`.
///
/// Each value is computed exactly once, in parallel over points; the
/// result does not depend on the thread count (every value is computed
/// independently by the same formula).
///
/// ```
/// use septa::scene::{sample_grid, Primitive};
/// let f = [Primitive::sphere([0.0; 3], 1.0), Primitive::Constant(0.0)];
/// let v = sample_grid(&f, &[[0.0; 3], [2.0, 0.0, 0.0]]);
/// assert_eq!(v, vec![1.0, 0.0, -1.0, 0.0]);
/// ```
pub fn sample_grid(functions: &[Primitive], points: &[V3]) -> Vec<f64> {
    let k = functions.len();
    // Chunks of rows keep the per-task overhead small.
    const ROWS: usize = 256;
    // A block of sparse evaluation (17^3 points by default) runs on one
    // thread (the blocks themselves run in parallel): values appended in
    // order, without zeroing the array first or splitting it into tasks.
    if points.len() <= 32 * ROWS {
        let mut out = Vec::with_capacity(points.len() * k);
        for p in points {
            out.extend(functions.iter().map(|f| f.eval(*p)));
        }
        return out;
    }
    let mut out = vec![0.0; points.len() * k];
    if k == 0 {
        return out;
    }
    out.par_chunks_mut(ROWS * k).zip(points.par_chunks(ROWS)).for_each(|(rows, pts)| {
        for (row, p) in rows.chunks_mut(k).zip(pts) {
            for (v, f) in row.iter_mut().zip(functions) {
                *v = f.eval(*p);
            }
        }
    });
    out
}

/// How many times an undecided box is split in 8 before giving up: the
/// per-box bounds are first order, so splitting proves many more blocks
/// empty near (but not on) the surfaces, at a cost still tiny next to
/// sampling a block.
const REFINE: u32 = 2;

/// The eight halves-by-axis of a box (they cover it; shared faces).
fn children(lo: V3, hi: V3) -> impl Iterator<Item = (V3, V3)> {
    let mid = [0, 1, 2].map(|a| 0.5 * (lo[a] + hi[a]));
    (0..8).map(move |c: usize| {
        let pick = |a: usize| c >> a & 1 == 1;
        let l = [0, 1, 2].map(|a| if pick(a) { mid[a] } else { lo[a] });
        let h = [0, 1, 2].map(|a| if pick(a) { hi[a] } else { mid[a] });
        (l, h)
    })
}

/// The strict sign `f` provably keeps on the box, if any.
///
/// Exactness (sparse equals dense): the bound encloses every *rounded*
/// value `eval` returns in the box (`rounding.rs`), and every grid vertex of
/// a block lies in the block's box (vertex coordinates `lo + (hi - lo) i / n`
/// are monotone in `i`). A finite bound also proves every sample finite, so
/// the dense path would not have stopped on a non-finite value there either.
fn ia_sign(f: &Primitive, lo: V3, hi: V3, depth: u32) -> Option<bool> {
    let (l, h) = f.bounds(lo, hi);
    if l > 0.0 && h < f64::INFINITY {
        return Some(true);
    }
    if h < 0.0 && l > f64::NEG_INFINITY {
        return Some(false);
    }
    if depth == 0 {
        return None;
    }
    let mut sign = None;
    for (cl, ch) in children(lo, hi) {
        let s = ia_sign(f, cl, ch, depth - 1)?;
        if sign.is_some_and(|t| t != s) {
            return None;
        }
        sign = Some(s);
    }
    sign
}

/// The function that provably exceeds every other on the box, if any.
fn mi_owner(functions: &[Primitive], lo: V3, hi: V3, depth: u32) -> Option<usize> {
    // The owner, if any, has the largest computed value at the centre too.
    let c = [0, 1, 2].map(|a| 0.5 * (lo[a] + hi[a]));
    let owner =
        (0..functions.len()).max_by(|&i, &j| functions[i].eval(c).total_cmp(&functions[j].eval(c))).unwrap_or(0);
    let f = &functions[owner];
    // `difference_lower` bounds the difference of the *rounded* values
    // (rounding.rs), so the owner's sample is strictly the largest at every
    // grid vertex of the box; finite bounds prove every sample finite.
    if functions.iter().enumerate().all(|(j, g)| j == owner || difference_lower(f, g, lo, hi) > 0.0)
        && functions.iter().all(|g| {
            let (l, h) = g.bounds(lo, hi);
            l.is_finite() && h.is_finite()
        })
    {
        return Some(owner);
    }
    if depth == 0 {
        return None;
    }
    let mut all = None;
    for (cl, ch) in children(lo, hi) {
        let o = mi_owner(functions, cl, ch, depth - 1)?;
        if all.is_some_and(|t| t != o) {
            return None;
        }
        all = Some(o);
    }
    all
}

/// IA block test: true unless every function provably keeps one strict
/// sign on the box `[min, max]` (then the box holds no part of the
/// arrangement and can be skipped before sampling). Undecided boxes are
/// split in 8 up to twice.
///
/// ```
/// use septa::scene::{block_may_be_active_ia, Primitive};
/// let f = [Primitive::sphere([0.0; 3], 1.0)];
/// assert!(block_may_be_active_ia(&f, [0.9, -0.1, -0.1], [1.1, 0.1, 0.1]));
/// assert!(!block_may_be_active_ia(&f, [2.0, 2.0, 2.0], [3.0, 3.0, 3.0]));
/// ```
pub fn block_may_be_active_ia(functions: &[Primitive], min: V3, max: V3) -> bool {
    functions.iter().any(|f| ia_sign(f, min, max, REFINE).is_none())
}

/// MI block test: false iff one function provably exceeds every other
/// on the box (one material owns it). Per pair the better of two bounds is
/// used: one function's lower bound above the other's upper bound, or a
/// centred-form bound on their difference (from gradient enclosures, for
/// spheres, planes, lines, cylinders and constants), which proves far more
/// blocks empty in Apollonius diagrams. Undecided boxes are split in 8 up
/// to twice, and all parts must have the same owner.
///
/// ```
/// use septa::scene::{block_may_be_active_mi, Primitive};
/// let f = [Primitive::sphere([0.0; 3], 0.5), Primitive::sphere([2.0, 0.0, 0.0], 0.5)];
/// assert!(!block_may_be_active_mi(&f, [-0.2; 3], [0.2; 3]));
/// assert!(block_may_be_active_mi(&f, [0.9, -0.1, -0.1], [1.1, 0.1, 0.1]));
/// ```
pub fn block_may_be_active_mi(functions: &[Primitive], min: V3, max: V3) -> bool {
    functions.len() >= 2 && mi_owner(functions, min, max, REFINE).is_none()
}

/// [`block_may_be_active_ia`] without splitting the box: for the sub-boxes
/// of a sampled block, which are small enough that one bound decides most.
pub(crate) fn box_may_be_active_ia(functions: &[Primitive], min: V3, max: V3) -> bool {
    functions.iter().any(|f| ia_sign(f, min, max, 0).is_none())
}

/// [`block_may_be_active_mi`] without splitting the box and with the
/// functions' own bounds only: a sub-box is owned when one function's lower
/// bound exceeds every other one's upper bound. The centred-form bounds on
/// differences prove more, but cost more than sampling the few vertices
/// they would spare.
pub(crate) fn box_may_be_active_mi(functions: &[Primitive], min: V3, max: V3) -> bool {
    if functions.len() < 2 {
        return false;
    }
    // The owner, if any, has the largest lower bound; the bounds enclose
    // every rounded value `eval` returns in the box (`rounding.rs`), and
    // finite bounds prove every sample finite.
    let (mut best, mut second_upper, mut owner_upper) = (f64::NEG_INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
    for f in functions {
        let (l, h) = f.bounds(min, max);
        if !(l.is_finite() && h.is_finite()) {
            return true;
        }
        if l > best {
            second_upper = second_upper.max(owner_upper);
            best = l;
            owner_upper = h;
        } else {
            second_upper = second_upper.max(h);
        }
    }
    !(best > second_upper)
}
