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
    sample_known(functions, points, &[])
}

/// Per function, the strict sign it provably keeps on the box `[min, max]`
/// (one bound, no splitting), or `None`: `BoundedField::ia_signs_on_box`.
pub(crate) fn ia_signs_on_box(functions: &[Primitive], min: V3, max: V3) -> Vec<Option<bool>> {
    functions.iter().map(|f| ia_sign(f, min, max, 0)).collect()
}

/// [`sample_grid`] at points of a box whose [`ia_signs_on_box`] are
/// `signs`, every function with a sign given as `1.0` or `-1.0`
/// (`BoundedField::sample_ia_with_signs`: IA reads such a function only
/// through its sign). The bound encloses every rounded value `eval` returns
/// in the box, so the stand-in has the sample's sign.
pub(crate) fn sample_grid_ia_with_signs(functions: &[Primitive], points: &[V3], signs: &[Option<bool>]) -> Vec<f64> {
    let known: Vec<Option<f64>> = signs.iter().map(|s| s.map(|p| if p { 1.0 } else { -1.0 })).collect();
    sample_known(functions, points, &known)
}

/// [`sample_grid`] with `known[j]` (when `known` is not empty and it is
/// `Some`) standing for every value of function `j`.
fn sample_known(functions: &[Primitive], points: &[V3], known: &[Option<f64>]) -> Vec<f64> {
    let k = functions.len();
    let known_at = |j: usize| known.get(j).copied().flatten();
    // Chunks of rows keep the per-task overhead small.
    const ROWS: usize = 256;
    // A block of sparse evaluation (17^3 points by default) runs on one
    // thread (the blocks themselves run in parallel): values appended in
    // order, without zeroing the array first or splitting it into tasks.
    if points.len() <= 32 * ROWS {
        // Function by function over runs of points, then interleaved into
        // rows: one choice of primitive per run, not per value.
        const RUN: usize = 64;
        let mut out = Vec::with_capacity(points.len() * k);
        let mut columns = vec![0.0; RUN * k];
        for (j, column) in columns.chunks_exact_mut(RUN).enumerate() {
            if let Some(x) = known_at(j) {
                column.fill(x);
            }
        }
        for run in points.chunks(RUN) {
            let n = run.len();
            for (j, (f, column)) in functions.iter().zip(columns.chunks_exact_mut(RUN)).enumerate() {
                if known_at(j).is_none() {
                    f.eval_into(run, &mut column[..n]);
                }
            }
            for i in 0..n {
                out.extend((0..k).map(|f| columns[f * RUN + i]));
            }
        }
        return out;
    }
    let mut out = vec![0.0; points.len() * k];
    if k == 0 {
        return out;
    }
    out.par_chunks_mut(ROWS * k).zip(points.par_chunks(ROWS)).for_each(|(rows, pts)| {
        for (row, p) in rows.chunks_mut(k).zip(pts) {
            for (j, (v, f)) in row.iter_mut().zip(functions).enumerate() {
                *v = known_at(j).unwrap_or_else(|| f.eval(*p));
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

/// [`box_may_be_active_ia`] on a sub-box of a box whose [`ia_signs_on_box`]
/// are `signs`: the functions with a sign keep it on the sub-box, so only
/// the others are bounded.
pub(crate) fn box_may_be_active_ia_with_signs(
    functions: &[Primitive],
    min: V3,
    max: V3,
    signs: &[Option<bool>],
) -> bool {
    functions.iter().zip(signs).any(|(f, s)| s.is_none() && ia_sign(f, min, max, 0).is_none())
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

#[cfg(test)]
mod tests {
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    use super::*;

    /// The stand-ins of `sample_grid_ia_with_signs` have the sign of every
    /// sample in the box, and the other functions their exact values, for
    /// every primitive type on boxes that straddle, touch and miss their
    /// zero sets (both kinds must occur, or the test proves nothing).
    #[test]
    fn stand_ins_keep_the_sign_of_every_sample_in_the_box() {
        let text = include_str!("../../tests/common/all_primitives.json");
        let functions = crate::scene::load_function_list(text, "all_primitives.json", None).unwrap();
        let k = functions.len();
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let (mut stood_in, mut sampled, mut empty_sub_boxes) = (0, 0, 0);
        for _ in 0..400 {
            let lo: V3 = [0; 3].map(|_| rng.gen_range(-1.5..1.5));
            let size = if rng.gen_bool(0.5) { rng.gen_range(0.01..0.2) } else { rng.gen_range(0.2..1.5) };
            let hi: V3 = lo.map(|x| x + size);
            // A 5^3 grid of the box, ends included, as a block's vertices.
            let at = |a: usize, i: usize| if i == 4 { hi[a] } else { lo[a] + (hi[a] - lo[a]) * i as f64 / 4.0 };
            let points: Vec<V3> = (0..125).map(|n| [at(0, n / 25), at(1, n / 5 % 5), at(2, n % 5)]).collect();
            // A sub-box: the functions with a sign on the box keep it there,
            // so skipping their bounds decides as bounding all of them.
            let signs = ia_signs_on_box(&functions, lo, hi);
            let mid = [0, 1, 2].map(|a| at(a, 2));
            for j in 0..k {
                let (f, s) = (&functions[j..j + 1], &signs[j..j + 1]);
                let plain = box_may_be_active_ia(f, lo, mid);
                assert_eq!(box_may_be_active_ia_with_signs(f, lo, mid, s), plain, "function {j} on {lo:?}..{mid:?}");
                empty_sub_boxes += !plain as usize;
            }
            let exact = sample_grid(&functions, &points);
            let given = sample_grid_ia_with_signs(&functions, &points, &signs);
            assert_eq!(exact.len(), given.len());
            for j in 0..k {
                let column = |v: &[f64]| (0..points.len()).map(|i| v[i * k + j]).collect::<Vec<_>>();
                let (e, g) = (column(&exact), column(&given));
                if e == g {
                    sampled += 1;
                    continue;
                }
                stood_in += 1;
                let s = g[0];
                assert!(s == 1.0 || s == -1.0, "function {j}: stand-in {s}");
                assert!(g.iter().all(|&x| x == s), "function {j}: one stand-in per box");
                assert!(e.iter().all(|&x| x * s > 0.0), "function {j} on {lo:?}..{hi:?}: a sample of the other sign");
            }
        }
        assert!(stood_in > 100 && sampled > 100, "stood in {stood_in}, sampled {sampled}");
        assert!(empty_sub_boxes > 100, "{empty_sub_boxes} sub-boxes proven empty");
    }
}
