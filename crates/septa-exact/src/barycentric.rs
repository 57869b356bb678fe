//! The barycentric predicate of Du et al. 2022, Sec. 5.2 (eq. 3-6).
//!
//! A vertex `v` of the per-tet cell complex lies on a `d`-dimensional element
//! `e` of the tetrahedron (`d = 0..3`: tet vertex, edge, face, interior) and
//! on the zero sets of `d` functions `g_1..g_d`. Each `g_i` is linear on `e`
//! and given by its values at the `d + 1` vertices of `e` (eq. 3). The
//! barycentric coordinates of `v` solve `A v = (0, .., 0, 1)` with
//! `A = {g_1, .., g_d, 1}` (eq. 4), and Cramer's rule gives
//!
//! ```text
//! g_{d+1}(v) = det(A') / det(A),   A' = {g_1, .., g_{d+1}}      (eq. 5)
//! sign(g_{d+1}(v)) = sign(det A') * sign(det A)                 (eq. 6)
//! ```
//!
//! Here both determinants are signed exactly by [`det_sign`] /
//! [`det_sign_diff`], so the result is exact for the given doubles.

use crate::{det_sign, det_sign_diff, det_sign_diff_f64_naive, det_sign_f64_naive, Sign};

/// IA form: `g[i][j]` is the value of function `g_{i+1}` at vertex `j` of
/// the element `e` holding `v` (`N = d + 1` rows and vertices). Rows
/// `0..N-1` are the functions whose zero sets meet at `v`; the last row is
/// the function being tested. Returns `sign(g_N(v))`.
///
/// If `det(A) = 0` (the first `d` zero sets do not meet in a single point of
/// `e`, which the cell complex's vertex encoding rules out) the result is
/// [`Sign::Zero`].
///
/// ```
/// use septa_exact::{barycentric_sign_ia, Sign};
/// // d = 0: v is a tet vertex, the sign is that of the value there.
/// assert_eq!(barycentric_sign_ia(&[[-2.0]]), Sign::Negative);
/// // d = 1: on an edge, g1 = (-1, 3) vanishes at t = 1/4 (from vertex 0);
/// // g2 = (1, -1) is 1 - 2t = 1/2 there.
/// assert_eq!(barycentric_sign_ia(&[[-1.0, 3.0], [1.0, -1.0]]), Sign::Positive);
/// // g2 = (0.5, 0.5 - 2^-52) is 0.5 - t*2^-52 > 0 at t = 1/4: positive, even
/// // though it almost vanishes along the whole edge.
/// let e = f64::EPSILON;
/// assert_eq!(barycentric_sign_ia(&[[-1.0, 3.0], [0.5, 0.5 - e]]), Sign::Positive);
/// // d = 2: on a face, g3 = 2 g1 vanishes wherever g1 does, so at v: zero.
/// let g = [[1.0, -1.0, 0.0], [0.0, 1.0, -1.0], [2.0, -2.0, 0.0]];
/// assert_eq!(barycentric_sign_ia(&g), Sign::Zero);
/// ```
#[inline]
pub fn barycentric_sign_ia<const N: usize>(g: &[[f64; N]; N]) -> Sign {
    if N == 1 {
        // A = (1): the sign of g_1 at the vertex.
        return det_sign(g);
    }
    let a: [[f64; N]; N] = std::array::from_fn(|i| if i + 1 == N { [1.0; N] } else { g[i] });
    let sa = det_sign(&a);
    if sa.is_zero() {
        return Sign::Zero;
    }
    det_sign(g) * sa
}

/// MI form: row `i` of the predicate is `g_{i+1} = f[i] - h[i]`, the
/// difference of two input functions' values at the `N = d + 1` vertices of
/// `e`, formed inside [`det_sign_diff`] so its rounding is tracked (the
/// paper's Sec. 5.2 remark on PCK). Rows `0..N-1` are the differences that
/// vanish at `v`, the last row the difference being tested; e.g. for the
/// material test "is `f_k` above `f_j` at `v`" use `f_k - f_j` there.
/// Returns `sign(g_N(v))`, or [`Sign::Zero`] if `det(A) = 0`.
///
/// ```
/// use septa_exact::{barycentric_sign_mi, Sign};
/// // d = 1 on an edge: materials f1 = (0, 1) and f2 = (1, 0) cross at t = 1/2;
/// // is f3 = (0.6, 0.6) above f1 there (f1 = 1/2)? Yes.
/// let f = [[0.0, 1.0], [0.6, 0.6]];
/// let h = [[1.0, 0.0], [0.0, 1.0]];
/// assert_eq!(barycentric_sign_mi(&f, &h), Sign::Positive);
/// // With f3 = (0.5, 0.5) the three materials meet at one point: zero.
/// let f = [[0.0, 1.0], [0.5, 0.5]];
/// assert_eq!(barycentric_sign_mi(&f, &h), Sign::Zero);
/// ```
#[inline]
pub fn barycentric_sign_mi<const N: usize>(f: &[[f64; N]; N], h: &[[f64; N]; N]) -> Sign {
    if N == 1 {
        return det_sign_diff(f, h);
    }
    let af: [[f64; N]; N] = std::array::from_fn(|i| if i + 1 == N { [1.0; N] } else { f[i] });
    let ah: [[f64; N]; N] = std::array::from_fn(|i| if i + 1 == N { [0.0; N] } else { h[i] });
    let sa = det_sign_diff(&af, &ah);
    if sa.is_zero() {
        return Sign::Zero;
    }
    det_sign_diff(f, h) * sa
}

/// [`barycentric_sign_ia`] with the naive floating-point determinant signs
/// ([`det_sign_f64_naive`]). **Not exact**: the paper's floating-point
/// baseline for the `--float` variant of the stress test (Sec. 8.1).
#[inline]
pub fn barycentric_sign_ia_f64_naive<const N: usize>(g: &[[f64; N]; N]) -> Sign {
    if N == 1 {
        return det_sign_f64_naive(g);
    }
    let a: [[f64; N]; N] = std::array::from_fn(|i| if i + 1 == N { [1.0; N] } else { g[i] });
    det_sign_f64_naive(g) * det_sign_f64_naive(&a)
}

/// [`barycentric_sign_mi`] with the naive floating-point determinant signs
/// (differences rounded first). **Not exact**; see
/// [`barycentric_sign_ia_f64_naive`].
#[inline]
pub fn barycentric_sign_mi_f64_naive<const N: usize>(f: &[[f64; N]; N], h: &[[f64; N]; N]) -> Sign {
    if N == 1 {
        return det_sign_diff_f64_naive(f, h);
    }
    let af: [[f64; N]; N] = std::array::from_fn(|i| if i + 1 == N { [1.0; N] } else { f[i] });
    let ah: [[f64; N]; N] = std::array::from_fn(|i| if i + 1 == N { [0.0; N] } else { h[i] });
    det_sign_diff_f64_naive(f, h) * det_sign_diff_f64_naive(&af, &ah)
}
