//! A cheaper first tier for the generic predicates of [`crate::plane`]: a
//! double carrying a bound on its distance from the exact value (forward
//! error analysis done as arithmetic, the "dynamic filter" of Burnikel,
//! Funke and Seel 2001, "Exact geometric computation using cascading",
//! Sec. 3), tried before [`Interval`].
//!
//! Every operation rounds once to nearest and adds its own rounding error
//! to the propagated bound, so one product costs a few multiplications
//! instead of the outward-rounded bounds and error-free tests of an
//! [`Interval`] product. The bound is looser than the interval (no exact
//! zeros, no tight products), so what it cannot decide goes on to the
//! interval and then the exact tier: the signs are the same, only cheaper
//! where the value is far from zero, which is nearly always.
//!
//! ## Proof that `|exact - v| <= e (1 + 2^-30)` after every operation
//!
//! `u = 2^-53`; round-to-nearest, gradual underflow (as the crate assumes).
//! For operands with `|x - a.v| <= a.e`, `|y - b.v| <= b.e`:
//! - sum: `|(x + y) - (a.v + b.v)| <= a.e + b.e`, and the rounded sum `v`
//!   differs from `a.v + b.v` by at most `u |v|` (a sum that rounds is in
//!   the normal range, where `|fl(s) - s| <= u |fl(s)|`; sums in the
//!   subnormal range are exact);
//! - product: `|xy - a.v b.v| <= |a.v| b.e + |b.v| a.e + a.e b.e`, and the
//!   rounded product differs from `a.v b.v` by at most `u |v|` when `|v|`
//!   is normal, by at most `2^-1075` below (added as `2^-1074`; a product of
//!   two non-zero doubles that rounds to zero is there too). The three
//!   products of the bound may underflow likewise: `2 * 2^-1074` more when
//!   an operand carries a bound.
//!
//! Each term is charged `2u |v|` instead of `u |v|`. The bounds themselves
//! are computed in floating point, each operation on them losing at most a
//! relative `6u` (sums and products of non-negative numbers), so in an
//! expression of `k` operations the computed bound is at least
//! `(1 - 6u)^k` times the true one (a product of two bounds multiplies
//! their deficits, whence `k` counts all operations, not the depth).
//! [`Bounded::sign`] compares `|v|` with the bound times `1 + 2^-30`, which
//! covers `k` up to a million operations; the predicates here have fewer
//! than a hundred.
//!
//! Overflow: any infinite or NaN value or bound gives no sign (`None`).

use crate::{Exact, Interval, Ring, Sign};

const TWO_U: f64 = f64::EPSILON; // 2u = 2^-52
const TINY: f64 = f64::from_bits(1); // 2^-1074, the smallest subnormal

/// A double `v` and a bound `e` with `|exact - v| <= e (1 + 2^-30)` (the
/// slack covers the rounding of the bound's own arithmetic; see the module
/// doc for the proof).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounded {
    /// The value computed in floating point.
    pub v: f64,
    /// A bound on its distance from the exact value.
    pub e: f64,
}

impl Bounded {
    /// The sign of the exact value when the bound proves it, else `None`.
    /// A zero is claimed only for an exact zero (`v = 0`, `e = 0`: every
    /// operation on the way was exact).
    #[inline]
    pub fn sign(&self) -> Option<Sign> {
        let e = self.e * (1.0 + 1.0 / (1u64 << 30) as f64);
        if !e.is_finite() || !self.v.is_finite() {
            return None;
        }
        if self.v > e {
            Some(Sign::Positive)
        } else if -self.v > e {
            Some(Sign::Negative)
        } else if self.v == 0.0 && self.e == 0.0 {
            Some(Sign::Zero)
        } else {
            None
        }
    }

    /// `self / o`, or `None` when `o` may be zero (`|o.v| <= o.e`) or the
    /// result is not finite. `|x/y - a/b| <= (a.e + |q| b.e) / (|b| - b.e)`
    /// for `|x - a| <= a.e`, `|y - b| <= b.e`, `q = a / b` (exact), and the
    /// rounded quotient is within `u |v|` of `q` (`2^-1075` when subnormal);
    /// the denominator is rounded down by a relative `4u` (charged as the
    /// factor `1 - 2^-50`).
    pub fn div(&self, o: &Bounded) -> Option<Bounded> {
        let den = (o.v.abs() - o.e) * (1.0 - 1.0 / (1u64 << 50) as f64);
        // a subnormal difference may be rounded up by more than a relative 4u
        if den.is_nan() || den < f64::MIN_POSITIVE {
            return None;
        }
        let v = self.v / o.v;
        // `qa >= |q|`: `|q| <= |v| (1 + u)` for a normal quotient, `|v| +
        // 2^-1075` for a subnormal one. The ratio `o.e / den` is formed
        // first, so no product below the double range is divided (a product
        // of tiny numbers rounded to zero, then divided by a small
        // denominator, lost its whole weight). Each term below the normal
        // range may lose up to 2^-1075 to underflow: the ratio (charged as
        // `r + 2^-1074`), the quotient `self.e / den`, the product with
        // `qa`, and `v` itself: three more `2^-1074`.
        let qa = v.abs() * (1.0 + TWO_U) + TINY;
        let r = o.e / den;
        let e = self.e / den + qa * (r + TINY) + TWO_U * v.abs() + 3.0 * TINY;
        (v.is_finite() && e.is_finite()).then_some(Bounded { v, e })
    }
}

impl Ring for Bounded {
    #[inline]
    fn of(x: f64) -> Self {
        Bounded { v: x, e: 0.0 }
    }
    #[inline]
    fn add(&self, o: &Self) -> Self {
        let v = self.v + o.v;
        Bounded { v, e: self.e + o.e + TWO_U * v.abs() }
    }
    #[inline]
    fn sub(&self, o: &Self) -> Self {
        let v = self.v - o.v;
        Bounded { v, e: self.e + o.e + TWO_U * v.abs() }
    }
    #[inline]
    fn mul(&self, o: &Self) -> Self {
        let v = self.v * o.v;
        let mut e = self.v.abs() * o.e + o.v.abs() * self.e + self.e * o.e + TWO_U * v.abs();
        // below the normal range a rounded product errs by up to 2^-1075
        // (also when it rounds to zero from two non-zero factors), and so
        // may each of the three products of the bound
        if v.abs() < f64::MIN_POSITIVE && self.v != 0.0 && o.v != 0.0 {
            e += TINY;
        }
        if self.e != 0.0 || o.e != 0.0 {
            e += 2.0 * TINY;
        }
        Bounded { v, e }
    }
    #[inline]
    fn neg(&self) -> Self {
        Bounded { v: -self.v, e: self.e }
    }
}

/// The exact sign of one expression given in three arithmetics: `bounded`
/// first, then `interval`, then `exact` (counted in
/// [`crate::fallback_count`]), each tried only when the one before cannot
/// tell. The three closures must evaluate the same expression.
#[inline]
#[track_caller]
pub fn filtered_sign_bounded(
    bounded: impl FnOnce() -> Bounded,
    interval: impl FnOnce() -> Interval,
    exact: impl FnOnce() -> Exact,
) -> Sign {
    match bounded().sign() {
        Some(s) => s,
        None => crate::plane::filtered_sign(interval, exact),
    }
}
