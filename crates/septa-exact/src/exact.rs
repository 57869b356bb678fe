//! An exact dyadic number, `mantissa * 2^exponent`, for the slow path.
//!
//! Every finite `f64` is such a number, and sums, differences and products
//! of dyadic numbers stay dyadic, so any polynomial in `f64` inputs is
//! evaluated without error over the whole range of doubles, subnormals
//! included. It allocates; it is the last tier behind the filters.

use num_bigint::BigInt;
use num_traits::{Signed, Zero};
use std::ops::{Add, Mul, Neg, Sub};

use crate::Sign;

/// An exact value `mantissa * 2^exponent` with an arbitrary-precision mantissa.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Exact {
    mantissa: BigInt,
    exponent: i64,
}

impl Exact {
    /// Zero.
    pub fn zero() -> Exact {
        Exact { mantissa: BigInt::zero(), exponent: 0 }
    }

    /// The exact value of a finite `f64`.
    ///
    /// # Panics
    /// Never for finite input; NaN and infinities are a precondition
    /// violation (see [`crate::check_finite`]) and map to zero in release.
    pub fn from_f64(x: f64) -> Exact {
        debug_assert!(x.is_finite(), "Exact::from_f64 on a non-finite value");
        if x == 0.0 || !x.is_finite() {
            return Exact::zero();
        }
        let bits = x.to_bits();
        let negative = bits >> 63 == 1;
        let biased = ((bits >> 52) & 0x7ff) as i64;
        let fraction = bits & ((1u64 << 52) - 1);
        let (m, e) = if biased == 0 { (fraction, -1074) } else { (fraction | (1u64 << 52), biased - 1075) };
        let m = BigInt::from(m);
        Exact { mantissa: if negative { -m } else { m }, exponent: e }
    }

    /// The exact sign.
    pub fn sign(&self) -> Sign {
        if self.mantissa.is_zero() {
            Sign::Zero
        } else if self.mantissa.is_positive() {
            Sign::Positive
        } else {
            Sign::Negative
        }
    }

    /// Nearest-ish `f64` (for diagnostics and embeddings; not correctly rounded).
    pub fn to_f64_approx(&self) -> f64 {
        let bits = self.mantissa.bits() as i64;
        let shift = (bits - 60).max(0);
        let top: BigInt = &self.mantissa >> (shift as usize);
        let top = i64::try_from(&top).unwrap_or(0) as f64;
        top * 2f64.powi((self.exponent + shift).clamp(-2000, 2000) as i32)
    }

    /// `mantissa * 2^exponent` (for the expansion tier's conversion).
    pub(crate) fn from_parts(mantissa: BigInt, exponent: i64) -> Exact {
        Exact { mantissa, exponent }
    }

    fn aligned(a: &Exact, b: &Exact) -> (BigInt, BigInt, i64) {
        let e = a.exponent.min(b.exponent);
        let ma = &a.mantissa << ((a.exponent - e) as usize);
        let mb = &b.mantissa << ((b.exponent - e) as usize);
        (ma, mb, e)
    }
}

impl From<f64> for Exact {
    fn from(x: f64) -> Exact {
        Exact::from_f64(x)
    }
}

impl Add for &Exact {
    type Output = Exact;
    fn add(self, rhs: &Exact) -> Exact {
        if self.mantissa.is_zero() {
            return rhs.clone();
        }
        if rhs.mantissa.is_zero() {
            return self.clone();
        }
        let (a, b, e) = Exact::aligned(self, rhs);
        Exact { mantissa: a + b, exponent: e }
    }
}

impl Sub for &Exact {
    type Output = Exact;
    fn sub(self, rhs: &Exact) -> Exact {
        self + &(-rhs)
    }
}

impl Mul for &Exact {
    type Output = Exact;
    fn mul(self, rhs: &Exact) -> Exact {
        Exact { mantissa: &self.mantissa * &rhs.mantissa, exponent: self.exponent + rhs.exponent }
    }
}

impl Neg for &Exact {
    type Output = Exact;
    fn neg(self) -> Exact {
        Exact { mantissa: -&self.mantissa, exponent: self.exponent }
    }
}

impl Add for Exact {
    type Output = Exact;
    fn add(self, rhs: Exact) -> Exact {
        &self + &rhs
    }
}

impl Sub for Exact {
    type Output = Exact;
    fn sub(self, rhs: Exact) -> Exact {
        &self - &rhs
    }
}

impl Mul for Exact {
    type Output = Exact;
    fn mul(self, rhs: Exact) -> Exact {
        &self * &rhs
    }
}

impl Neg for Exact {
    type Output = Exact;
    fn neg(self) -> Exact {
        -&self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn subnormal_products_do_not_underflow() {
        let tiny = Exact::from_f64(f64::from_bits(1)); // 2^-1074
        let sq = &tiny * &tiny;
        assert_eq!(sq.sign(), Sign::Positive);
        let diff = &(&sq + &sq) - &(&sq * &Exact::from_f64(2.0));
        assert_eq!(diff.sign(), Sign::Zero);
    }

    #[test]
    fn sum_of_far_apart_values_is_exact() {
        let big = Exact::from_f64(1e300);
        let small = Exact::from_f64(1e-300);
        let s = &(&big + &small) - &big;
        assert_eq!(s, small);
    }
}
