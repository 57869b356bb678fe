//! The last tier: determinants on [`Exact`] dyadic bignums, valid for every
//! finite input (values spanning `1e-300 .. 1e300`, subnormals).

use crate::{Exact, Sign};

/// Exact sign of `det(m)` where `m` holds exact values (any size).
pub(crate) fn det_sign_exact(m: Vec<Vec<Exact>>) -> Sign {
    det_exact(&m).sign()
}

/// Laplace expansion along the first row, skipping zero entries.
fn det_exact(m: &[Vec<Exact>]) -> Exact {
    let n = m.len();
    match n {
        0 => return Exact::from_f64(1.0),
        1 => return m[0][0].clone(),
        2 => return &(&m[0][0] * &m[1][1]) - &(&m[0][1] * &m[1][0]),
        _ => {}
    }
    let mut acc = Exact::zero();
    for c in 0..n {
        if m[0][c].sign().is_zero() {
            continue;
        }
        let minor: Vec<Vec<Exact>> = m[1..]
            .iter()
            .map(|r| r.iter().enumerate().filter(|&(j, _)| j != c).map(|(_, x)| x.clone()).collect())
            .collect();
        let t = &m[0][c] * &det_exact(&minor);
        acc = if c % 2 == 0 { &acc + &t } else { &acc - &t };
    }
    acc
}

/// Exact sign of `det(m)`.
pub(crate) fn det_sign<const N: usize>(m: &[[f64; N]; N]) -> Sign {
    det_sign_exact(m.iter().map(|r| r.iter().map(|&x| Exact::from_f64(x)).collect()).collect())
}

/// Exact sign of `det(a - b)`.
pub(crate) fn det_sign_diff<const N: usize>(a: &[[f64; N]; N], b: &[[f64; N]; N]) -> Sign {
    det_sign_exact(
        (0..N).map(|i| (0..N).map(|j| &Exact::from_f64(a[i][j]) - &Exact::from_f64(b[i][j])).collect()).collect(),
    )
}
