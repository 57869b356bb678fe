//! `bounded.rs` (the first tier of the generic predicates) against an
//! independent oracle: exact big rationals (`num-rational`), never the
//! crate's own `Exact`.
//!
//! What is checked, on random and adversarial doubles (subnormals, products
//! that underflow to zero or overflow, exact zeros, near-degenerate
//! determinants):
//! - every [`Bounded`] operation keeps `|exact - v| <= e` for exact
//!   operands anywhere within their bounds (the induction step of the
//!   module's proof), measured at the ends of the operands' ranges;
//! - a sign that [`Bounded::sign`] claims is the exact sign of whole
//!   expressions, and [`filtered_sign_bounded`] is always exact, with each
//!   of its three tiers exercised.
//!
//! Mutations these tests catch (tried by hand): the `2u |v|` term dropped
//! from sums or products, the subnormal `2^-1074` term dropped, the
//! division's denominator not reduced by `o.e`.
#![allow(clippy::needless_range_loop)]

mod common;

use common::{det3, det3_case, det3_q, pow2, q, sign_q, wide};
use num_rational::BigRational;
use num_traits::{Signed, Zero};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use septa_exact::{fallback_count, filtered_sign_bounded, Bounded, Exact, Interval, Ring, Sign};

fn adversarial(r: &mut ChaCha8Rng) -> f64 {
    let s = if r.gen_bool(0.5) { -1.0 } else { 1.0 };
    match r.gen_range(0..9) {
        0 => [0.0, -0.0][r.gen_range(0..2)],
        1 => s * f64::from_bits(r.gen_range(1..(1u64 << 52))),
        2 => s * f64::from_bits(r.gen_range(1..64u64)),
        // products below the normal range, and near overflow
        3 => wide(r, -560, -500, false),
        4 => wide(r, 505, 515, false),
        5 => s * r.gen_range(1..1000i64) as f64 * pow2(r.gen_range(-40..40)),
        6 => wide(r, -1074, 1023, false),
        _ => s * r.gen_range(0.0..1.0),
    }
}

/// An operand: a double and a bound (zero a third of the time).
fn operand(r: &mut ChaCha8Rng) -> Bounded {
    let v = adversarial(r);
    let e = match r.gen_range(0..3) {
        0 => 0.0,
        1 => v.abs() * r.gen_range(0.0..1e-14),
        _ => adversarial(r).abs() * r.gen_range(0.0..1.0),
    };
    Bounded { v, e }
}

/// `|x - b.v| <= b.e` in rationals, with the 2^-30 slack of `sign`; a
/// non-finite value or bound is a refusal and holds nothing.
fn within(b: &Bounded, x: &BigRational) -> bool {
    if !b.v.is_finite() || !b.e.is_finite() {
        return true;
    }
    let slack = q(b.e) * (BigRational::from_integer(1.into()) + q(pow2(-30)));
    (x - q(b.v)).abs() <= slack
}

#[test]
fn every_bounded_operation_keeps_the_exact_value_within_its_bound() {
    let mut r = ChaCha8Rng::seed_from_u64(0xb0_0d3d);
    let mut tight = 0usize;
    for i in 0..20_000 {
        let (a, b) = (operand(&mut r), operand(&mut r));
        if !(a.e.is_finite() && b.e.is_finite()) {
            continue;
        }
        // the exact operands at the ends of their ranges (the error of a sum
        // or product is largest at a corner of the box)
        for (sa, sb) in [(1, 1), (1, -1), (-1, 1), (-1, -1), (0, 0)] {
            let x = q(a.v) + q(a.e) * BigRational::from_integer(sa.into());
            let y = q(b.v) + q(b.e) * BigRational::from_integer(sb.into());
            let s = a.add(&b);
            assert!(within(&s, &(&x + &y)), "case {i}: {a:?} + {b:?} = {s:?}");
            let d = a.sub(&b);
            assert!(within(&d, &(&x - &y)), "case {i}: {a:?} - {b:?} = {d:?}");
            let p = a.mul(&b);
            assert!(within(&p, &(&x * &y)), "case {i}: {a:?} * {b:?} = {p:?}");
            if let Some(qt) = a.div(&b) {
                assert!(!y.is_zero(), "case {i}: {a:?} / {b:?} divided by a range holding zero");
                assert!(within(&qt, &(&x / &y)), "case {i}: {a:?} / {b:?} = {qt:?}");
            }
            // a bound of zero claims exactness: it must be
            if p.e == 0.0 && sa == 0 {
                assert_eq!(q(p.v), &x * &y, "case {i}: {a:?} * {b:?} claimed exact");
                tight += 1;
            }
        }
    }
    assert!(tight > 500, "only {tight} exact products");
}

#[test]
fn claimed_signs_are_exact_and_the_three_tiers_all_run() {
    let mut r = ChaCha8Rng::seed_from_u64(0x7_1e25);
    let before = fallback_count();
    let (mut by_bounded, mut by_interval, mut zeros) = (0usize, 0usize, 0usize);
    for i in 0..20_000 {
        let m = det3_case(&mut r, i, adversarial);
        let exact = det3_q(&m);
        let want = sign_q(&exact);
        let b: Bounded = det3(&m);
        assert!(within(&b, &exact), "det {m:?}: {b:?} misses the exact value");
        match b.sign() {
            Some(s) => {
                assert_eq!(s, want, "bounded sign of det {m:?}");
                by_bounded += 1;
            }
            None => by_interval += det3::<Interval>(&m).sign().is_some() as usize,
        }
        let got = filtered_sign_bounded(|| det3::<Bounded>(&m), || det3::<Interval>(&m), || det3::<Exact>(&m));
        assert_eq!(got, want, "filtered sign of det {m:?}");
        zeros += want.is_zero() as usize;
    }
    let exact_tier = fallback_count() - before;
    eprintln!("{by_bounded} by the bound, {by_interval} by intervals, {exact_tier} exact, {zeros} zeros");
    assert!(by_bounded > 8_000, "the bounded tier decided only {by_bounded}");
    assert!(by_interval > 500, "the interval tier decided only {by_interval}");
    assert!(exact_tier > 500, "the exact tier ran only {exact_tier} times");
}

#[test]
fn a_sign_is_never_claimed_from_an_overflowed_value() {
    let big = Bounded::of(1e300);
    let p = big.mul(&big);
    assert_eq!(p.sign(), None);
    let nan = p.sub(&p);
    assert_eq!(nan.sign(), None);
    // a product of two tiny non-zero doubles that rounds to zero is not a zero
    let tiny = Bounded::of(1e-200);
    let z = tiny.mul(&tiny);
    assert_eq!(z.v, 0.0);
    assert_eq!(z.sign(), None);
    assert_eq!(Bounded::of(3.0).mul(&Bounded::of(0.0)).sign(), Some(Sign::Zero));
}
