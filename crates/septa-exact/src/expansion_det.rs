//! Exact determinant signs on stack expansions (the middle tier).
//!
//! Same Laplace schemes as the filters, but every entry, product and sum is
//! an exact expansion in a stack [`Arena`]. IA entries are single doubles;
//! MI entries are the exact difference `a - b` as a two-component
//! expansion (one component when the subtraction was exact, as it is for
//! nearby or integer values). Valid only inside the exponent window (see
//! `expansion.rs`). Returns `None` only if the arena is too small for the
//! data (possible for MI with N = 4 and long expansions), in which case the
//! caller uses the bignum tier.

use crate::expansion::{two_product, Arena, Ex};
use crate::Sign;

/// Arena size per N, ample for IA (worst case about 500 doubles at N = 4)
/// and for all but pathological MI data.
const CAP2: usize = 64;
const CAP3: usize = 256;
const CAP4: usize = 512;
/// Second attempt for long MI expansions before resorting to bignums.
const CAP_BIG: usize = 4096;

/// Column pairs `(i, j)`, `i < j`, indexing the 2x2 minors of rows 2,3.
const PAIRS: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];

/// `x[i0] x[i3] - x[i1] x[i2]` for entries `x` already in the arena.
#[inline]
fn minor<const C: usize>(ar: &mut Arena<C>, a: Ex, d: Ex, b: Ex, c: Ex) -> Option<Ex> {
    let ad = ar.product(a, d)?;
    let bc = ar.product(b, c)?;
    ar.sum(ad, bc, -1.0)
}

/// Exact `det` of the `n x n` matrix of arena entries `e` (row-major).
fn det<const C: usize>(ar: &mut Arena<C>, e: &[Ex], n: usize) -> Option<Sign> {
    match n {
        1 => Some(ar.sign(e[0])),
        2 => {
            let m = minor(ar, e[0], e[3], e[1], e[2])?;
            Some(ar.sign(m))
        }
        3 => {
            let m0 = minor(ar, e[4], e[8], e[5], e[7])?;
            let m1 = minor(ar, e[3], e[8], e[5], e[6])?;
            let m2 = minor(ar, e[3], e[7], e[4], e[6])?;
            let t = ar.product(e[0], m0)?;
            let mut acc = t;
            for (k, m, s) in [(1, m1, -1.0), (2, m2, 1.0)] {
                let t = ar.product(e[k], m)?;
                acc = ar.fold(acc, t, s)?;
            }
            Some(ar.sign(acc))
        }
        4 => {
            // Cofactors along row 0; 3x3 minors of rows 1..3 along row 1,
            // from the 2x2 minors of rows 2,3 (as in Shewchuk's exact
            // insphere): scaling by single entries needs no merging.
            let mut c = [Ex::default(); 6];
            for (k, &(i, j)) in PAIRS.iter().enumerate() {
                c[k] = minor(ar, e[8 + i], e[12 + j], e[8 + j], e[12 + i])?;
            }
            let pair = |i: usize, j: usize| c[PAIRS.iter().position(|&p| p == (i, j)).unwrap_or(0)];
            let mut acc = ar.push(0.0)?;
            for k in 0..4 {
                let [p, q, r] = match k {
                    0 => [1, 2, 3],
                    1 => [0, 2, 3],
                    2 => [0, 1, 3],
                    _ => [0, 1, 2],
                };
                let m0 = ar.product(e[4 + p], pair(q, r))?;
                let mut m = m0;
                for (col, cof, s) in [(q, pair(p, r), -1.0), (r, pair(p, q), 1.0)] {
                    let t = ar.product(e[4 + col], cof)?;
                    m = ar.fold(m, t, s)?;
                }
                let t = ar.product(e[k], m)?;
                // t sits above m; fold needs acc directly below t, so move
                // t down over m first.
                let t = ar.lower(t, m);
                acc = ar.fold(acc, t, if k % 2 == 0 { 1.0 } else { -1.0 })?;
            }
            Some(ar.sign(acc))
        }
        _ => None,
    }
}

#[inline(never)]
fn ia_in<const C: usize, const N: usize>(m: &[[f64; N]; N]) -> Option<Sign> {
    let mut ar = Arena::<C>::new();
    let mut e = [Ex::default(); 16];
    for (k, &x) in m.as_flattened().iter().enumerate() {
        e[k] = ar.push(x)?;
    }
    det(&mut ar, &e[..N * N], N)
}

#[inline(never)]
fn mi_in<const C: usize, const N: usize>(a: &[[f64; N]; N], b: &[[f64; N]; N]) -> Option<Sign> {
    let mut ar = Arena::<C>::new();
    let mut e = [Ex::default(); 16];
    for (k, (&x, &y)) in a.as_flattened().iter().zip(b.as_flattened()).enumerate() {
        e[k] = ar.push_diff(x, y)?;
    }
    det(&mut ar, &e[..N * N], N)
}

/// Exact sign of `det(m)`, inputs inside the window; `None` if the arena
/// overflowed (then use the bignum tier).
pub(crate) fn det_sign_ia<const N: usize>(m: &[[f64; N]; N]) -> Option<Sign> {
    match N {
        1 | 2 => ia_in::<CAP2, N>(m),
        3 => ia_in::<CAP3, N>(m).or_else(|| ia_in::<CAP_BIG, N>(m)),
        4 => ia_in::<CAP4, N>(m).or_else(|| ia_in::<CAP_BIG, N>(m)),
        _ => None,
    }
}

/// Exact sign of `det(a - b)`, inputs inside the window; `None` if the
/// arena overflowed (then use the bignum tier).
pub(crate) fn det_sign_mi<const N: usize>(a: &[[f64; N]; N], b: &[[f64; N]; N]) -> Option<Sign> {
    match N {
        1 | 2 => mi_in::<CAP2, N>(a, b),
        3 => mi_in::<CAP3, N>(a, b).or_else(|| mi_in::<CAP_BIG, N>(a, b)),
        4 => mi_in::<CAP4, N>(a, b).or_else(|| mi_in::<CAP_BIG, N>(a, b)),
        _ => None,
    }
}

/// IA, N = 2, when `fl(ad) == fl(bc)`: `ad - bc` equals the difference of
/// the exact product tails.
#[inline]
pub(crate) fn ia2_tie_sign(m: &[f64; 4]) -> Sign {
    let (p, ep) = two_product(m[0], m[3]);
    let (q, eq) = two_product(m[1], m[2]);
    debug_assert_eq!(p, q);
    // Rounding preserves the sign of a difference (and its zero).
    Sign::of_f64(ep - eq)
}

#[cfg(test)]
#[path = "expansion_det_tests.rs"]
mod tests;
