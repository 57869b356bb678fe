//! Checks of the filter's constants in exact rational arithmetic.

use super::*;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Pow};

fn q(x: f64) -> BigRational {
    BigRational::from_float(x).unwrap()
}

#[test]
fn error_constants_dominate_the_derived_bound() {
    // c >= (1 + u) gamma_{m'} / (1 - u)^(mP + 1), gamma_k = k u / (1 - k u).
    let u = q(U);
    let one = BigRational::one();
    for (name, _n, mp, mperm, c, _) in BOUNDS {
        let k = BigRational::from_integer(BigInt::from(mp));
        let gamma = &k * &u / (&one - &k * &u);
        let need = (&one + &u) * gamma / Pow::pow(&one - &u, mperm + 1);
        assert!(q(c) >= need, "{name}: constant {c:e} below the derived bound");
        // ... and not wastefully above it (within 1% of the first-order term).
        assert!(q(c) <= need * q(1.01), "{name}: constant far above the bound");
    }
}

#[test]
fn hot_constants_absorb_the_underflow_term() {
    // c_hot (1-u)/(1+u) >= gamma_{m'} (1 + r)/(1-u)^mP + r for r = 2^-70,
    // a safe cap on F / P^ given P^ >= P_MIN and S <= S_MAX.
    let (p_min, s_max) = HOT_LIMITS;
    let eta = q(2f64.powi(-1075 + 53) * 2f64.powi(-53)); // 2^-1075
    let f_cap = eta * (q(2.0) * q(s_max) * q(1.0001) + q(6.0)) * q(1.0001);
    let r = q(2f64.powi(-70));
    assert!(f_cap / q(p_min) <= r.clone(), "r = F / P^ must stay below 2^-70");
    let u = q(U);
    let one = BigRational::one();
    for (name, _n, mp, mperm, _, c_hot) in BOUNDS {
        let k = BigRational::from_integer(BigInt::from(mp));
        let gamma = &k * &u / (&one - &k * &u);
        let lhs = q(c_hot) * (&one - &u) / (&one + &u);
        let rhs = gamma * (&one + &r) / Pow::pow(&one - &u, mperm) + &r;
        assert!(lhs >= rhs, "{name}: hot constant too small");
    }
}

#[test]
fn windows_keep_intermediates_normal_and_finite() {
    for n in 1..=4usize {
        let (lo, hi) = window(n);
        let w = -(lo.log2() as i32);
        assert_eq!(hi.log2() as i32, w, "symmetric window");
        // Unit of an n-fold product of multiples of 2^(-w-52), times the
        // smallest bound constant (~2^-53), must stay normal.
        assert!(n as i32 * (w + 52) + 53 <= 1022, "N={n}: products may underflow");
        // n! * 2^(n(w+1)) (MI differences double the magnitude) well below
        // 2^995, where Veltkamp's split would overflow.
        let fact: f64 = (1..=n).map(|i| i as f64).product();
        assert!(fact.log2() + (n as f64) * (w as f64 + 1.0) < 995.0 - 60.0, "N={n}: may overflow");
    }
}

#[test]
fn window_check_accepts_zeros_and_rejects_subnormals_and_huge() {
    let (lo, hi) = window(4);
    assert!(in_window(&[0.0, -0.0, 1.0, -lo, hi], 4));
    assert!(!in_window(&[1.0, lo / 2.0], 4));
    assert!(!in_window(&[1.0, hi * 2.0], 4));
    assert!(!in_window(&[f64::from_bits(1)], 4));
    assert!(!in_window(&[f64::INFINITY], 4));
}
