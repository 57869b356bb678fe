//! Filter hit rates (via `septa_exact::stats`) and input validation.

mod common;

use common::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use septa_exact::{check_finite, det_sign, det_sign_diff, stats, Sign};

const CASES: usize = 20_000;

fn filter_share<const N: usize>(seed: u64) -> (stats::Stats, stats::Stats) {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    stats::reset();
    for _ in 0..CASES {
        let m: [[f64; N]; N] = mat(&mut r, unit);
        det_sign(&m);
    }
    let ia = stats::snapshot();
    stats::reset();
    for _ in 0..CASES {
        let a: [[f64; N]; N] = mat(&mut r, unit);
        let b: [[f64; N]; N] = mat(&mut r, unit);
        det_sign_diff(&a, &b);
    }
    (ia, stats::snapshot())
}

#[test]
fn filter_decides_the_large_majority_of_random_cases() {
    for (n, (ia, mi)) in
        [(1, filter_share::<1>(1)), (2, filter_share::<2>(2)), (3, filter_share::<3>(3)), (4, filter_share::<4>(4))]
    {
        eprintln!("N={n} IA {ia:?} rate {:.5}; MI {mi:?} rate {:.5}", ia.filter_rate(), mi.filter_rate());
        assert_eq!(ia.total(), CASES as u64, "one count per call");
        assert_eq!(mi.total(), CASES as u64, "one count per call");
        assert!(ia.filter_rate() > 0.99, "N={n} IA filter rate {}", ia.filter_rate());
        assert!(mi.filter_rate() > 0.99, "N={n} MI filter rate {}", mi.filter_rate());
        assert_eq!(ia.bignum + mi.bignum, 0, "unit-scale inputs never need bignums");
    }
}

#[test]
fn each_tier_is_counted() {
    stats::reset();
    // Filter: well-conditioned.
    assert_eq!(det_sign(&[[2.0, 1.0, 0.0], [1.0, 3.0, 1.0], [0.0, 1.0, 4.0]]), Sign::Positive);
    // Exact zero row: decided by the filter through a zero permanent.
    assert_eq!(det_sign(&[[2.0, 1.0, 0.0], [0.0, 0.0, 0.0], [0.0, 1.0, 4.0]]), Sign::Zero);
    assert_eq!(stats::snapshot(), stats::Stats { filter: 2, expansion: 0, bignum: 0 });
    // Exact tier (i128 shortcut): exactly singular with a nonzero permanent.
    assert_eq!(det_sign(&[[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [7.0, 8.0, 9.0]]), Sign::Zero);
    assert_eq!(stats::snapshot().expansion, 1);
    // Exact tier (expansions): full-precision rows, exactly singular.
    let (x, y) = (0.1, 0.7);
    assert_eq!(det_sign(&[[x, y, 1.0], [x, y, 1.0], [0.3, 0.2, 0.9]]), Sign::Zero);
    assert_eq!(stats::snapshot().expansion, 2);
    // Subnormal entries in narrow rows: still the i128 shortcut.
    let tiny = f64::from_bits(3);
    assert_eq!(det_sign(&[[tiny, 0.0], [0.0, tiny]]), Sign::Positive);
    assert_eq!(stats::snapshot().expansion, 3);
    // Bignum: rows spanning 1e-300 .. 1, outside the exponent window.
    let m = [[1e-300, 1.0, 0.0], [0.0, 1.0, 1e-300], [1.0, 0.0, 1.0]];
    assert_eq!(det_sign(&m), Sign::Positive);
    assert_eq!(stats::snapshot(), stats::Stats { filter: 2, expansion: 3, bignum: 1 });
}

#[test]
fn counters_are_per_thread() {
    stats::reset();
    det_sign(&[[1.0, 2.0], [3.0, 4.0]]);
    let other = std::thread::spawn(|| {
        det_sign(&[[1.0, 2.0], [3.0, 4.0]]);
        det_sign(&[[1.0, 2.0], [3.0, 4.0]]);
        stats::snapshot().total()
    })
    .join()
    .unwrap();
    assert_eq!(other, 2);
    assert_eq!(stats::snapshot().total(), 1);
}

#[test]
fn check_finite_names_the_first_bad_index() {
    assert_eq!(check_finite(&[0.0, -1e308, 5e-324, 1.0]), Ok(()));
    assert_eq!(check_finite(&[]), Ok(()));
    let e = check_finite(&[1.0, 2.0, f64::INFINITY, f64::NAN]).unwrap_err();
    assert_eq!(e.index, 2);
    assert_eq!(e.value, f64::INFINITY);
    let e = check_finite(&[f64::NEG_INFINITY]).unwrap_err();
    assert_eq!(e.index, 0);
    let e = check_finite(&[0.5, f64::NAN]).unwrap_err();
    assert_eq!(e.index, 1);
    assert!(e.value.is_nan());
    assert!(e.to_string().contains("index 1"), "{e}");
    // Random positions.
    let mut r = ChaCha8Rng::seed_from_u64(9);
    for _ in 0..1000 {
        let mut v: Vec<f64> = (0..r.gen_range(1..40)).map(|_| unit(&mut r)).collect();
        let k = r.gen_range(0..v.len());
        v[k] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY][r.gen_range(0..3)];
        assert_eq!(check_finite(&v).unwrap_err().index, k);
    }
}

/// Filter share on near-singular matrices whose last row is a rounded
/// combination of the others plus a relative perturbation `2^-p`.
fn near_share<const N: usize>(p: i32, seed: u64) -> (f64, f64) {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    stats::reset();
    for _ in 0..CASES / 4 {
        let mut m: [[f64; N]; N] = mat(&mut r, unit);
        near_dependent(&mut r, &mut m, N - 1, Some(p));
        det_sign(&m);
    }
    let ia = stats::snapshot().filter_rate();
    stats::reset();
    for _ in 0..CASES / 4 {
        let mut x: [[f64; N]; N] = mat(&mut r, unit);
        near_dependent(&mut r, &mut x, N - 1, Some(p));
        let b: [[f64; N]; N] = mat(&mut r, unit);
        let a: [[f64; N]; N] = std::array::from_fn(|i| std::array::from_fn(|j| b[i][j] + x[i][j]));
        det_sign_diff(&a, &b);
    }
    (ia, stats::snapshot().filter_rate())
}

#[test]
fn filter_is_sharp_on_near_degenerate_input() {
    for (n, coarse, fine) in [
        (2, near_share::<2>(20, 11), near_share::<2>(80, 12)),
        (3, near_share::<3>(20, 13), near_share::<3>(80, 14)),
        (4, near_share::<4>(20, 15), near_share::<4>(80, 16)),
    ] {
        eprintln!("N={n}: filter share at 2^-20 (IA, MI) {coarse:?}, at 2^-80 {fine:?}");
        // A 2^-20 perturbation is far above the ~2^-50 resolution: decided.
        assert!(coarse.0 > 0.99 && coarse.1 > 0.99, "N={n}: {coarse:?}");
        // At 2^-80 the determinant is below any f64 error bound, so the
        // filter must decline (IA N=2 is decided by its monotone compare
        // whenever the two rounded products differ, which they usually do).
        if n > 2 {
            assert!(fine.0 < 0.05, "N={n}: IA filter decided {} below its resolution", fine.0);
        }
        assert!(fine.1 < 0.5, "N={n}: MI filter decided {} below its resolution", fine.1);
    }
}
