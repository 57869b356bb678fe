//! The double-word rounding against the exact one, on sums placed at the
//! steps of the rounding; the bound's zeros and range.

use super::*;
use crate::{Exact, Ring};
use rand::{Rng, SeedableRng};

/// The rounding of `a + b` against `Exact::to_f64_approx`, on sums
/// near powers of two (both sides), near the 60-bit steps and at random.
#[test]
fn rounding_of_a_sum_matches_the_exact_one() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0xd0b1e);
    let mut checked = 0;
    for i in 0..200_000 {
        let a: f64 = match i % 4 {
            0 => f64::powi(2.0, rng.gen_range(-60..60)),
            _ => rng.gen_range(-1.0..1.0) * f64::powi(2.0, rng.gen_range(-60..60)),
        };
        let a = if i % 8 == 0 { -a } else { a };
        let ulp = f64::from_bits(a.abs().to_bits() + 1) - a.abs();
        // b: a few 60-bit steps of `a`'s binade, a half step off, tiny, zero
        let step = ulp / 128.0;
        let b = match rng.gen_range(0..5) {
            0 => rng.gen_range(-64i32..64) as f64 * step,
            1 => (rng.gen_range(-64i32..64) as f64 + 0.5) * step,
            2 => rng.gen_range(-0.5..0.5) * ulp,
            3 => rng.gen_range(-1.0..1.0) * step * 1e-9,
            _ => 0.0,
        };
        let want = Exact::from_f64(a).add(&Exact::from_f64(b)).to_f64_approx();
        assert_eq!(sum_to_f64_approx(a, b), Some(want), "{a:e} + {b:e}");
        checked += 1;
    }
    assert_eq!(checked, 200_000);
}

/// The constants are the powers of two they name.
#[test]
fn constants() {
    assert_eq!(ETA, f64::powi(2.0, -1000));
    assert_eq!(SAFE_LO, f64::powi(2.0, -400));
    assert_eq!(SAFE_HI, f64::powi(2.0, 400));
    assert_eq!(CHARGE, 16.0 * f64::powi(2.0, -106));
}

/// A zero reached through rounded intermediates is not claimed exact: it
/// is left to the exact path, while an exact zero is answered.
#[test]
fn zeros() {
    let half = DoubleWord::of(0.5);
    let z = half.sub(&half);
    assert_eq!((z.hi, z.e), (0.0, 0.0));
    assert_eq!(z.to_f64_approx(), Some(0.0), "an exact difference of equal inputs");
    let tiny = DoubleWord::of(1e-300).mul(&DoubleWord::of(1e-10)); // leaves the safe range
    assert!(tiny.e.is_infinite());
    assert_eq!(tiny.to_f64_approx(), None);
    let x = DoubleWord::of(0.1).mul(&DoubleWord::of(0.3)); // inexact: e > 0
    assert!(x.e > 0.0);
    let zero = x.sub(&x).mul(&DoubleWord::of(1e-100));
    assert!(zero.e >= ETA, "{:e}", zero.e);
    assert_eq!(zero.to_f64_approx(), None);
}

/// The enclosure holds: `|exact - (hi + lo)| <= e`, checked with bignums on
/// random sums and products of up to five factors, with cancellations
/// (a value minus a near copy of itself) and magnitudes from 2^-200 to 2^200.
#[test]
fn the_bound_encloses_the_exact_value() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0xe2c1);
    let leaf = |rng: &mut rand_chacha::ChaCha8Rng| -> f64 {
        let x: f64 = rng.gen_range(-1.0..1.0);
        x * f64::powi(2.0, rng.gen_range(-40..40))
    };
    for _ in 0..20_000 {
        // (a b c - a' b' c') * d + e f, with a' b' c' close to a b c
        let xs: Vec<f64> = (0..6).map(|_| leaf(&mut rng)).collect();
        let near: Vec<f64> = xs[..3].iter().map(|&x| x * (1.0 + rng.gen_range(-1e-12..1e-12))).collect();
        let scale = f64::powi(2.0, rng.gen_range(-150..150) / 3);
        fn eval<R: crate::Ring>(xs: &[f64], near: &[f64], scale: f64) -> R {
            let p = |v: &[f64]| R::of(v[0] * scale).mul(&R::of(v[1])).mul(&R::of(v[2]));
            p(xs).sub(&p(near)).mul(&R::of(xs[3])).add(&R::of(xs[4]).mul(&R::of(xs[5])))
        }
        let dw: DoubleWord = eval(&xs, &near, scale);
        let exact: Exact = eval(&xs, &near, scale);
        assert!(dw.e.is_finite());
        let d = exact.sub(&Exact::from_f64(dw.hi)).sub(&Exact::from_f64(dw.lo));
        let e = Exact::from_f64(dw.e);
        assert!(d.sub(&e).sign() != crate::Sign::Positive, "{dw:?}");
        assert!(d.add(&e).sign() != crate::Sign::Negative, "{dw:?}");
        if let Some(x) = dw.to_f64_approx() {
            assert_eq!(x, exact.to_f64_approx());
        }
    }
}

/// Non-finite inputs, values out of the safe range and the `0 * inf` of a
/// product with such a value are never claimed.
#[test]
fn out_of_range_is_not_claimed() {
    for x in [f64::NAN, f64::INFINITY, -f64::INFINITY, 1e300, 1e-300, f64::MIN_POSITIVE / 4.0] {
        let d = DoubleWord::of(x);
        assert_eq!(d.to_f64_approx(), None, "{x:e}");
        assert_eq!(DoubleWord::of(0.0).mul(&d).to_f64_approx(), None, "0 * {x:e}");
        assert_eq!(DoubleWord::of(1.0).add(&d).to_f64_approx(), None, "1 + {x:e}");
    }
    // products leaving the range on either side
    let big = DoubleWord::of(2f64.powi(300));
    assert_eq!(big.mul(&big).to_f64_approx(), None);
    let small = DoubleWord::of(2f64.powi(-300));
    assert_eq!(small.mul(&small).to_f64_approx(), None);
}
