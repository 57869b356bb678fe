//! Exact signs of small determinants (N = 1..=4) of `f64` data.
//!
//! PLACEHOLDER: exact but slow (all on [`Exact`]); the filtered version
//! replaces the bodies without changing the signatures.

use crate::{Exact, Sign};

/// Sign of `det(m)` for an `N x N` matrix of input values, `N` in `1..=4`.
pub fn det_sign<const N: usize>(m: &[[f64; N]; N]) -> Sign {
    let e: Vec<Vec<Exact>> = m.iter().map(|r| r.iter().map(|&x| Exact::from_f64(x)).collect()).collect();
    det_exact(&e).sign()
}

/// Sign of `det(a - b)`, the differences formed exactly inside the predicate.
pub fn det_sign_diff<const N: usize>(a: &[[f64; N]; N], b: &[[f64; N]; N]) -> Sign {
    let e: Vec<Vec<Exact>> =
        (0..N).map(|i| (0..N).map(|j| &Exact::from_f64(a[i][j]) - &Exact::from_f64(b[i][j])).collect()).collect();
    det_exact(&e).sign()
}

fn det_exact(m: &[Vec<Exact>]) -> Exact {
    let n = m.len();
    if n == 1 {
        return m[0][0].clone();
    }
    let mut acc = Exact::zero();
    for c in 0..n {
        let minor: Vec<Vec<Exact>> = m[1..]
            .iter()
            .map(|r| r.iter().enumerate().filter(|&(j, _)| j != c).map(|(_, x)| x.clone()).collect())
            .collect();
        let t = &m[0][c] * &det_exact(&minor);
        acc = if c % 2 == 0 { &acc + &t } else { &acc - &t };
    }
    acc
}
