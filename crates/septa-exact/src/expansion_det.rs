//! Exact determinant signs on stack expansions (the middle tier).
//!
//! Same Laplace schemes as the filters, but every entry, product and sum is
//! an exact [`Expansion`]. Capacities are worst cases: with entries of at
//! most `E` components, a product of two entries has at most `2E^2`, a 2x2
//! minor `4E^2`, and so on (Scale-Expansion doubles, Expansion-Sum adds).
//! IA entries are single doubles (`E = 1`); MI entries are the exact
//! difference `a - b` as a two-component expansion (`E = 2`). Valid only
//! inside the exponent window (see `expansion.rs`).

use crate::expansion::{two_product, Expansion};
use crate::Sign;

/// Ping-pong accumulator for a signed sum of expansions.
struct Acc<const D: usize> {
    bufs: [[f64; D]; 2],
    len: usize,
    cur: usize,
}

impl<const D: usize> Acc<D> {
    fn new() -> Self {
        Acc { bufs: [[0.0; D]; 2], len: 0, cur: 0 }
    }

    fn add<const T: usize>(&mut self, t: &Expansion<T>, s: f64) {
        let (lo, hi) = self.bufs.split_at_mut(1);
        let (src, dst) = if self.cur == 0 { (&lo[0], &mut hi[0]) } else { (&hi[0], &mut lo[0]) };
        self.len = crate::expansion::sum(&src[..self.len], t.as_slice(), s, dst);
        self.cur = 1 - self.cur;
    }

    fn sign(&self) -> Sign {
        match self.len {
            0 => Sign::Zero,
            n => Sign::of_f64(self.bufs[self.cur][n - 1]),
        }
    }
}

/// `a d - b c` on expansions; `P` bounds one product, `M` the minor.
#[inline]
fn minor2<const E: usize, const P: usize, const M: usize>(
    a: &Expansion<E>,
    d: &Expansion<E>,
    b: &Expansion<E>,
    c: &Expansion<E>,
) -> Expansion<M> {
    let ad: Expansion<P> = Expansion::product_of(a, d);
    let bc: Expansion<P> = Expansion::product_of(b, c);
    Expansion::sum_of(&ad, &bc, -1.0)
}

fn det2<const E: usize, const P: usize, const M: usize>(e: &[[Expansion<E>; 2]; 2]) -> Sign {
    minor2::<E, P, M>(&e[0][0], &e[1][1], &e[0][1], &e[1][0]).sign()
}

fn det3<const E: usize, const P: usize, const M: usize, const T: usize, const D: usize>(
    e: &[[Expansion<E>; 3]; 3],
) -> Sign {
    let m0: Expansion<M> = minor2::<E, P, M>(&e[1][1], &e[2][2], &e[1][2], &e[2][1]);
    let m1: Expansion<M> = minor2::<E, P, M>(&e[1][0], &e[2][2], &e[1][2], &e[2][0]);
    let m2: Expansion<M> = minor2::<E, P, M>(&e[1][0], &e[2][1], &e[1][1], &e[2][0]);
    let mut acc = Acc::<D>::new();
    acc.add(&Expansion::<T>::product_of(&e[0][0], &m0), 1.0);
    acc.add(&Expansion::<T>::product_of(&e[0][1], &m1), -1.0);
    acc.add(&Expansion::<T>::product_of(&e[0][2], &m2), 1.0);
    acc.sign()
}

fn det4<const E: usize, const P: usize, const M: usize, const T: usize, const D: usize>(
    e: &[[Expansion<E>; 4]; 4],
) -> Sign {
    // Column pairs (i, j), i < j, and the complementary pair's index.
    const PAIRS: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
    const SIGNS: [f64; 6] = [1.0, -1.0, 1.0, 1.0, -1.0, 1.0];
    let s: [Expansion<M>; 6] = PAIRS.map(|(i, j)| minor2::<E, P, M>(&e[0][i], &e[1][j], &e[0][j], &e[1][i]));
    let c: [Expansion<M>; 6] = PAIRS.map(|(i, j)| minor2::<E, P, M>(&e[2][i], &e[3][j], &e[2][j], &e[3][i]));
    let mut acc = Acc::<D>::new();
    for k in 0..6 {
        if s[k].as_slice().is_empty() || c[5 - k].as_slice().is_empty() {
            continue;
        }
        acc.add(&Expansion::<T>::product_of(&s[k], &c[5 - k]), SIGNS[k]);
    }
    acc.sign()
}

/// Exact sign of `det(m)`, inputs inside the window.
pub(crate) fn det_sign_ia<const N: usize>(m: &[[f64; N]; N]) -> Sign {
    let e: [[Expansion<1>; N]; N] = m.map(|r| r.map(Expansion::from_f64));
    match N {
        0 => Sign::Positive,
        1 => e[0][0].sign(),
        2 => det2::<1, 2, 4>(&fix(&e)),
        3 => det3::<1, 2, 4, 8, 24>(&fix(&e)),
        4 => det4::<1, 2, 4, 32, 192>(&fix(&e)),
        _ => unreachable!("expansion tier is only used for N <= 4"),
    }
}

/// Exact sign of `det(a - b)`, inputs inside the window.
pub(crate) fn det_sign_mi<const N: usize>(a: &[[f64; N]; N], b: &[[f64; N]; N]) -> Sign {
    let e: [[Expansion<2>; N]; N] =
        std::array::from_fn(|i| std::array::from_fn(|j| Expansion::from_diff(a[i][j], b[i][j])));
    match N {
        0 => Sign::Positive,
        1 => e[0][0].sign(),
        2 => det2::<2, 8, 16>(&fix(&e)),
        3 => det3::<2, 8, 16, 64, 192>(&fix(&e)),
        4 => det4::<2, 8, 16, 512, 3072>(&fix(&e)),
        _ => unreachable!("expansion tier is only used for N <= 4"),
    }
}

/// IA, N = 2, when `fl(ad) == fl(bc)`: `ad - bc` equals the difference of
/// the exact product tails.
#[inline]
pub(crate) fn ia2_tie_sign(m: &[[f64; 2]; 2]) -> Sign {
    let (p, ep) = two_product(m[0][0], m[1][1]);
    let (q, eq) = two_product(m[0][1], m[1][0]);
    debug_assert_eq!(p, q);
    // Rounding preserves the sign of a difference (and its zero).
    Sign::of_f64(ep - eq)
}

fn fix<T: Copy, const N: usize, const K: usize>(m: &[[T; N]; N]) -> [[T; K]; K] {
    std::array::from_fn(|i| std::array::from_fn(|j| m[i][j]))
}
