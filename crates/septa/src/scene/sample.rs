//! Sampling functions at grid vertices, and the block tests of sparse
//! evaluation (issue 6).

use rayon::prelude::*;

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
    let mut out = vec![0.0; points.len() * k];
    if k == 0 {
        return out;
    }
    // Chunks of rows keep the per-task overhead small.
    const ROWS: usize = 256;
    out.par_chunks_mut(ROWS * k).zip(points.par_chunks(ROWS)).for_each(|(rows, pts)| {
        for (row, p) in rows.chunks_mut(k).zip(pts) {
            for (v, f) in row.iter_mut().zip(functions) {
                *v = f.eval(*p);
            }
        }
    });
    out
}

/// IA block test: true unless every function provably keeps one strict
/// sign on the box `[min, max]` (then the box holds no part of the
/// arrangement and can be skipped before sampling).
///
/// ```
/// use septa::scene::{block_may_be_active_ia, Primitive};
/// let f = [Primitive::sphere([0.0; 3], 1.0)];
/// assert!(block_may_be_active_ia(&f, [0.9, -0.1, -0.1], [1.1, 0.1, 0.1]));
/// assert!(!block_may_be_active_ia(&f, [2.0, 2.0, 2.0], [3.0, 3.0, 3.0]));
/// ```
pub fn block_may_be_active_ia(functions: &[Primitive], min: V3, max: V3) -> bool {
    functions.iter().any(|f| {
        let (lo, hi) = f.bounds(min, max);
        lo <= 0.0 && 0.0 <= hi
    })
}

/// MI block test: false iff one function's lower bound exceeds every other
/// function's upper bound on the box (one material owns the whole box).
///
/// ```
/// use septa::scene::{block_may_be_active_mi, Primitive};
/// let f = [Primitive::sphere([0.0; 3], 0.5), Primitive::sphere([2.0, 0.0, 0.0], 0.5)];
/// assert!(!block_may_be_active_mi(&f, [-0.2; 3], [0.2; 3]));
/// assert!(block_may_be_active_mi(&f, [0.9, -0.1, -0.1], [1.1, 0.1, 0.1]));
/// ```
pub fn block_may_be_active_mi(functions: &[Primitive], min: V3, max: V3) -> bool {
    if functions.len() < 2 {
        return false;
    }
    let b: Vec<(f64, f64)> = functions.iter().map(|f| f.bounds(min, max)).collect();
    let owner = (0..b.len()).max_by(|&i, &j| b[i].0.total_cmp(&b[j].0)).unwrap_or(0);
    let dominated = b.iter().enumerate().all(|(j, &(_, hi))| j == owner || b[owner].0 > hi);
    !dominated
}
