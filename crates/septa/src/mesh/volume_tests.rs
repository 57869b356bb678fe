//! The flux sign against big rationals, written independently (the whole
//! cross product and centroid in rationals), on random, nearly degenerate
//! and exactly degenerate (flat, zero-flux) triangle sets.

use super::flux_sign;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};
use rand::{Rng, SeedableRng};
use septa_exact::Sign;

fn q(x: f64) -> BigRational {
    BigRational::from_float(x).unwrap()
}

/// `sum (centroid_k - c) * 3 * (2 area vector)_k`, in rationals.
fn reference(x: &[[f64; 3]], tris: &[([u32; 3], bool)], k: usize, c: f64) -> Sign {
    let mut sum = BigRational::zero();
    for &(t, rev) in tris {
        let p: Vec<[BigRational; 3]> = t.iter().map(|&v| x[v as usize].map(q)).collect();
        let u: [BigRational; 3] = std::array::from_fn(|i| &p[1][i] - &p[0][i]);
        let w: [BigRational; 3] = std::array::from_fn(|i| &p[2][i] - &p[0][i]);
        let cross = [&u[1] * &w[2] - &u[2] * &w[1], &u[2] * &w[0] - &u[0] * &w[2], &u[0] * &w[1] - &u[1] * &w[0]];
        let centroid = (&p[0][k] + &p[1][k] + &p[2][k]) / BigRational::from_integer(BigInt::from(3));
        let term = (centroid - q(c)) * &cross[k] * BigRational::from_integer(BigInt::from(3));
        sum = if rev { sum - term } else { sum + term };
    }
    if sum.is_zero() {
        Sign::Zero
    } else if sum.is_positive() {
        Sign::Positive
    } else {
        Sign::Negative
    }
}

#[test]
fn flux_sign_matches_rationals() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(43);
    let mut zeros = 0;
    for case in 0..3000 {
        let n = rng.gen_range(4..12);
        let x: Vec<[f64; 3]> = (0..n)
            .map(|_| match case % 3 {
                // random points
                0 => std::array::from_fn(|_| rng.gen_range(-1.0..1.0)),
                // small integers: exact zeros are common
                1 => std::array::from_fn(|_| rng.gen_range(-2i32..3) as f64 * 0.25),
                // nearly flat: z a tiny multiple of x and y
                _ => {
                    let (a, b) = (rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0));
                    [a, b, 1e-17 * a + rng.gen_range(-1i32..2) as f64 * 1e-30]
                }
            })
            .collect();
        let m = rng.gen_range(1..8);
        let tris: Vec<([u32; 3], bool)> = (0..m)
            .map(|_| {
                let t = [0, 1, 2].map(|_| rng.gen_range(0..n) as u32);
                (t, rng.gen_bool(0.5))
            })
            .collect();
        let k = case % 3;
        let c = [0.0, -1.0, 0.5, 1e-3][case % 4];
        let want = reference(&x, &tris, k, c);
        zeros += (want == Sign::Zero) as usize;
        assert_eq!(flux_sign(&x, &tris, k, c), want, "case {case}");
    }
    assert!(zeros > 100, "exact zeros tested: {zeros}");
}
