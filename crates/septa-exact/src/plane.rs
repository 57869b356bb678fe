//! Filtered exact signs of polynomial expressions built from plane
//! coefficients and mesh-vertex coordinates (the predicates of planar
//! cutting, TopoCut App. B-C).
//!
//! Triangle planes are not representable in doubles, so the predicates of
//! planar cutting (a point given as a face triple against a plane, the order
//! of two points along a line, the cyclic order of directions around a
//! vertex or an edge) are polynomials of moderate degree in the input
//! doubles. Rather than derive a separate static bound for every one of
//! them, each predicate is written **once**, generically over [`Ring`], and
//! evaluated twice at most:
//!
//! 1. in [`Interval`] arithmetic with outward rounding. Every operation
//!    returns an interval that contains the exact result of the same
//!    operation on any reals inside its operands (the bound is the
//!    Shewchuk-style `|err| <= 1 ulp` of each rounded bound, applied
//!    per operation, so it is *proven* for the whole expression by
//!    induction over the expression tree). Bounds that were computed
//!    without rounding error (checked with error-free transformations,
//!    TwoSum and Dekker's TwoProduct) are not widened, so exactly zero
//!    expressions of small integers (the staircase case) are decided here.
//!    If the final interval excludes zero, or is the point `[0, 0]`, its
//!    sign is the exact sign.
//! 2. otherwise in [`Exact`] dyadic bignum arithmetic, which cannot err.
//!
//! [`fallback_count`] reports how often step 2 ran.
//!
//! Hot predicates put a cheaper tier in front of step 1:
//! [`crate::filtered_sign_bounded`] first evaluates the expression on
//! [`crate::Bounded`] (a double and a proven bound on its error, a few
//! multiplications per operation), and only what that cannot decide goes
//! on to the intervals and the exact tier.

use crate::expansion::{two_product, two_sum};
use crate::{Exact, Sign};
use std::sync::atomic::{AtomicU64, Ordering};

static FALLBACKS: AtomicU64 = AtomicU64::new(0);

/// Number of filtered signs that needed the exact fallback since start
/// (all threads; only the rare fallbacks touch this shared counter).
pub fn fallback_count() -> u64 {
    FALLBACKS.load(Ordering::Relaxed)
}

/// The arithmetic a generic predicate needs: a commutative ring containing
/// the doubles.
pub trait Ring: Clone + 'static {
    /// The value of a double.
    fn of(x: f64) -> Self;
    /// `self + o`.
    fn add(&self, o: &Self) -> Self;
    /// `self - o`.
    fn sub(&self, o: &Self) -> Self;
    /// `self * o`.
    fn mul(&self, o: &Self) -> Self;
    /// `-self`.
    fn neg(&self) -> Self;
}

impl Ring for Exact {
    #[inline]
    fn of(x: f64) -> Self {
        Exact::from_f64(x)
    }
    #[inline]
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    #[inline]
    fn sub(&self, o: &Self) -> Self {
        self - o
    }
    #[inline]
    fn mul(&self, o: &Self) -> Self {
        self * o
    }
    #[inline]
    fn neg(&self) -> Self {
        -self
    }
}

/// A closed interval `[lo, hi]` of reals with outward-rounded operations.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    /// Lower bound.
    pub lo: f64,
    /// Upper bound.
    pub hi: f64,
}

// Dekker's product is exact when |a|,|b| < 2^996 and the product's error
// term does not underflow; stay well inside (|p| in [2^-900, 2^900] or p == 0).
const SAFE_HI: f64 = 1e270;
const SAFE_LO: f64 = 1e-270;

#[inline]
fn add_down(a: f64, b: f64) -> f64 {
    let (s, e) = two_sum(a, b);
    if !s.is_finite() {
        return if s.is_nan() { f64::NEG_INFINITY } else { s.next_down() };
    }
    if e < 0.0 {
        s.next_down()
    } else {
        s
    }
}

#[inline]
fn add_up(a: f64, b: f64) -> f64 {
    let (s, e) = two_sum(a, b);
    if !s.is_finite() {
        return if s.is_nan() { f64::INFINITY } else { s.next_up() };
    }
    if e > 0.0 {
        s.next_up()
    } else {
        s
    }
}

/// Product rounded down (`up = false`) or up.
#[inline]
fn mul_round(a: f64, b: f64, up: bool) -> f64 {
    if a == 0.0 || b == 0.0 {
        return 0.0;
    }
    let p = a * b;
    let ap = p.abs();
    if !(SAFE_LO..=SAFE_HI).contains(&ap) || !p.is_finite() {
        // No error-free check possible: widen unconditionally.
        if p.is_nan() {
            return if up { f64::INFINITY } else { f64::NEG_INFINITY };
        }
        return if up { p.next_up() } else { p.next_down() };
    }
    // Significant bits of the factors (odd mantissas of m and n bits have a
    // product of m + n - 1 or m + n bits): above 54 the product is surely
    // rounded, so widen without the TwoProduct test; at most 53 it is exact.
    let sig = |x: f64| 53 - ((x.to_bits() & ((1u64 << 52) - 1)) | (1u64 << 52)).trailing_zeros();
    let bits = sig(a) + sig(b);
    if bits > 54 {
        return if up { p.next_up() } else { p.next_down() };
    }
    if bits <= 53 {
        return p;
    }
    let (_, e) = two_product(a, b);
    if up {
        if e > 0.0 {
            p.next_up()
        } else {
            p
        }
    } else if e < 0.0 {
        p.next_down()
    } else {
        p
    }
}

/// `(mul_round(a, b, false), mul_round(a, b, true))`, with the product, its
/// range check and its exactness test formed once.
#[inline]
fn mul_round_both(a: f64, b: f64) -> (f64, f64) {
    if a == 0.0 || b == 0.0 {
        return (0.0, 0.0);
    }
    let p = a * b;
    let ap = p.abs();
    if !(SAFE_LO..=SAFE_HI).contains(&ap) || !p.is_finite() {
        if p.is_nan() {
            return (f64::NEG_INFINITY, f64::INFINITY);
        }
        return (p.next_down(), p.next_up());
    }
    let sig = |x: f64| 53 - ((x.to_bits() & ((1u64 << 52) - 1)) | (1u64 << 52)).trailing_zeros();
    let bits = sig(a) + sig(b);
    if bits > 54 {
        return (p.next_down(), p.next_up());
    }
    if bits <= 53 {
        return (p, p);
    }
    let (_, e) = two_product(a, b);
    (if e < 0.0 { p.next_down() } else { p }, if e > 0.0 { p.next_up() } else { p })
}

impl Interval {
    /// The point interval of a double.
    #[inline]
    pub fn point(x: f64) -> Interval {
        Interval { lo: x, hi: x }
    }

    /// The sign if the interval decides it: excludes zero, or is exactly `[0,0]`.
    #[inline]
    pub fn sign(&self) -> Option<Sign> {
        if self.lo > 0.0 {
            Some(Sign::Positive)
        } else if self.hi < 0.0 {
            Some(Sign::Negative)
        } else if self.lo == 0.0 && self.hi == 0.0 {
            Some(Sign::Zero)
        } else {
            None
        }
    }

    /// `self / o`, or `None` when `o` contains zero. Each bound of a
    /// correctly rounded quotient is widened by one ulp outward.
    pub fn div(&self, o: &Interval) -> Option<Interval> {
        if o.lo <= 0.0 && o.hi >= 0.0 {
            return None;
        }
        let q = [self.lo / o.lo, self.lo / o.hi, self.hi / o.lo, self.hi / o.hi];
        let lo = q.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = q.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if !lo.is_finite() || !hi.is_finite() {
            return None;
        }
        Some(Interval { lo: lo.next_down(), hi: hi.next_up() })
    }

    /// Midpoint (an approximation of the value, for embeddings and pre-sorts).
    #[inline]
    pub fn mid(&self) -> f64 {
        0.5 * self.lo + 0.5 * self.hi
    }
}

impl Ring for Interval {
    #[inline]
    fn of(x: f64) -> Self {
        Interval::point(x)
    }
    #[inline]
    fn add(&self, o: &Self) -> Self {
        Interval { lo: add_down(self.lo, o.lo), hi: add_up(self.hi, o.hi) }
    }
    #[inline]
    fn sub(&self, o: &Self) -> Self {
        Interval { lo: add_down(self.lo, -o.hi), hi: add_up(self.hi, -o.lo) }
    }
    #[inline]
    fn mul(&self, o: &Self) -> Self {
        let (a, b, c, d) = (self.lo, self.hi, o.lo, o.hi);
        if a == b && c == d {
            // Two doubles (the inputs of most first products): in every
            // sign case below the bounds are `mul_round(a, c, down / up)`;
            // both come from one product and one exactness test.
            let (lo, hi) = mul_round_both(a, c);
            return Interval { lo, hi };
        }
        if a >= 0.0 && c >= 0.0 {
            return Interval { lo: mul_round(a, c, false), hi: mul_round(b, d, true) };
        }
        if b <= 0.0 && d <= 0.0 {
            return Interval { lo: mul_round(b, d, false), hi: mul_round(a, c, true) };
        }
        if a >= 0.0 && d <= 0.0 {
            return Interval { lo: mul_round(b, c, false), hi: mul_round(a, d, true) };
        }
        if b <= 0.0 && c >= 0.0 {
            return Interval { lo: mul_round(a, d, false), hi: mul_round(b, c, true) };
        }
        let lo =
            mul_round(a, d, false).min(mul_round(b, c, false)).min(mul_round(a, c, false)).min(mul_round(b, d, false));
        let hi = mul_round(a, c, true).max(mul_round(b, d, true)).max(mul_round(a, d, true)).max(mul_round(b, c, true));
        Interval { lo, hi }
    }
    #[inline]
    fn neg(&self) -> Self {
        Interval { lo: -self.hi, hi: -self.lo }
    }
}

/// The exact sign of an expression given twice: once over [`Interval`]
/// (the filter) and once over [`Exact`] (the fallback, run only when the
/// filter cannot decide).
#[inline]
#[track_caller]
pub fn filtered_sign(fast: impl FnOnce() -> Interval, exact: impl FnOnce() -> Exact) -> Sign {
    if let Some(s) = fast().sign() {
        return s;
    }
    FALLBACKS.fetch_add(1, Ordering::Relaxed);
    if std::env::var_os("SEPTA_TRACE").is_some() {
        let l = std::panic::Location::caller();
        let s = exact().sign();
        eprintln!("fallback {}:{} {:?}", l.file(), l.line(), s);
        return s;
    }
    exact().sign()
}

/// Sign of `n . x + d` for a plane `(n, d)` and a point `x` (TopoCut's
/// `T_pv`, App. B eq. 13), exact.
pub fn plane_point_sign(plane: &[f64; 4], x: &[f64; 3]) -> Sign {
    // Static filter: v = fl(fl(fl(fl(a x) + fl(b y)) + fl(c z)) + d). Each of
    // the 3 products and 3 sums commits a relative error <= u = 2^-53 of its
    // result, so |v - exact| <= (3u + 3u(1 + u)^3) * S <= 7u * S with
    // S = |a x| + |b y| + |c z| + |d| (all terms enter each partial sum at
    // most once; the (1+u)^k growth is absorbed by the spare u). Requires no
    // underflow: S is large enough or we fall through to the interval path.
    let t = [plane[0] * x[0], plane[1] * x[1], plane[2] * x[2]];
    let v = t[0] + t[1] + t[2] + plane[3];
    let s = t[0].abs() + t[1].abs() + t[2].abs() + plane[3].abs();
    let bound = 8.0 * f64::EPSILON * 0.5 * s;
    if s > 1e-250 && s < 1e250 && v.abs() > bound {
        return if v > 0.0 { Sign::Positive } else { Sign::Negative };
    }
    fn f<R: Ring>(p: &[f64; 4], x: &[f64; 3]) -> R {
        let mut acc = R::of(p[3]);
        for k in 0..3 {
            acc = acc.add(&R::of(p[k]).mul(&R::of(x[k])));
        }
        acc
    }
    filtered_sign(|| f::<Interval>(plane, x), || f::<Exact>(plane, x))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_products_match_the_general_bounds() {
        // the point fast path of `mul` against `mul_round` down and up, on
        // zeros, signs, exact and inexact products (52, 53, 54, 55 bits),
        // subnormals, values past the 1e-270 / 1e270 guards and overflow
        let mut vals = vec![0.0, -0.0, 1.0, -1.0, 3.0, 0.1, -0.7, 1.0 + f64::EPSILON, f64::MIN_POSITIVE, 5e-324];
        vals.extend([1e-200, 1e-100, 1e100, 1e200, 1e300, -1e300, f64::MAX, (1u64 << 27) as f64 + 1.0]);
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..4000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let m = (x >> 11) as f64 / (1u64 << 53) as f64;
            let e = ((x & 0xff) as i32) - 128;
            vals.push(if x & 0x100 == 0 { m } else { -m } * 2f64.powi(e));
            // short mantissas, where products are exact or just 54 bits
            vals.push(((x >> 40) as f64) * 2f64.powi(e / 4));
        }
        for &a in &vals {
            for &b in vals.iter().step_by(7) {
                let got = Interval::point(a).mul(&Interval::point(b));
                let (lo, hi) = (mul_round(a, b, false), mul_round(a, b, true));
                assert_eq!((got.lo.to_bits(), got.hi.to_bits()), (lo.to_bits(), hi.to_bits()), "{a:e} * {b:e}");
            }
        }
    }

    #[test]
    fn exact_zero_of_small_integers_is_decided_by_the_filter() {
        // plane x = 15 through the point (15, 3, 7): 1*15 + 0*3 + 0*7 - 15
        let v = Interval::point(1.0).mul(&Interval::point(15.0)).add(&Interval::point(-15.0));
        assert_eq!(v.sign(), Some(Sign::Zero));
        assert_eq!(plane_point_sign(&[1.0, 0.0, 0.0, -15.0], &[15.0, 3.0, 7.0]), Sign::Zero);
    }

    #[test]
    fn near_zero_falls_back_and_is_exact() {
        // 0.1*3 - 0.3 is not zero in binary; 0.1 + 0.2 - 0.3 neither.
        let s = plane_point_sign(&[0.1, 0.0, 0.0, -0.3], &[3.0, 0.0, 0.0]);
        let e = (&Exact::from_f64(0.1) * &Exact::from_f64(3.0)) - Exact::from_f64(0.3);
        assert_eq!(s, e.sign());
        let tiny = plane_point_sign(&[1.0, 1.0, 0.0, 0.0], &[1e-300, -1e-300, 0.0]);
        assert_eq!(tiny, Sign::Zero);
    }

    #[test]
    fn interval_contains_exact_value() {
        let a = Interval::point(0.1);
        let b = Interval::point(0.7);
        let c = a.mul(&b).sub(&Interval::point(0.07));
        let e = (&Exact::from_f64(0.1) * &Exact::from_f64(0.7)) - Exact::from_f64(0.07);
        let v = e.to_f64_approx();
        assert!(c.lo <= v && v <= c.hi);
    }
}
