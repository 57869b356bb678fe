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
const CAP3: usize = 512;
const CAP4: usize = 2048;

/// Column pairs `(i, j)`, `i < j`, of the two-row Laplace expansion, and the
/// signs of `s_ij * c_(complement)`.
const PAIRS: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
const SIGNS: [f64; 6] = [1.0, -1.0, 1.0, 1.0, -1.0, 1.0];

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
            let mut s = [Ex::default(); 6];
            let mut c = [Ex::default(); 6];
            for (k, &(i, j)) in PAIRS.iter().enumerate() {
                s[k] = minor(ar, e[i], e[4 + j], e[j], e[4 + i])?;
                c[k] = minor(ar, e[8 + i], e[12 + j], e[8 + j], e[12 + i])?;
            }
            let mut acc = ar.push(0.0)?;
            for k in 0..6 {
                let t = ar.product(s[k], c[5 - k])?;
                acc = ar.fold(acc, t, SIGNS[k])?;
            }
            Some(ar.sign(acc))
        }
        _ => None,
    }
}

fn ia_in<const C: usize, const N: usize>(m: &[[f64; N]; N]) -> Option<Sign> {
    let mut ar = Arena::<C>::new();
    let mut e = [Ex::default(); 16];
    for (k, &x) in m.as_flattened().iter().enumerate() {
        e[k] = ar.push(x)?;
    }
    det(&mut ar, &e[..N * N], N)
}

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
        3 => ia_in::<CAP3, N>(m),
        4 => ia_in::<CAP4, N>(m),
        _ => None,
    }
}

/// Exact sign of `det(a - b)`, inputs inside the window; `None` if the
/// arena overflowed (then use the bignum tier).
pub(crate) fn det_sign_mi<const N: usize>(a: &[[f64; N]; N], b: &[[f64; N]; N]) -> Option<Sign> {
    match N {
        1 | 2 => mi_in::<CAP2, N>(a, b),
        3 => mi_in::<CAP3, N>(a, b),
        4 => mi_in::<CAP4, N>(a, b),
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
