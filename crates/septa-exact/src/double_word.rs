//! Double-word arithmetic with a proven error bound: a value is an
//! unevaluated sum `hi + lo` of two doubles (about 106 bits) and a bound
//! `e` on its distance from the exact value of the same polynomial, so it
//! encloses that value in `[hi + lo - e, hi + lo + e]`.
//!
//! Its use is [`DoubleWord::to_f64_approx`]: the double that
//! [`Exact::to_f64_approx`] gives the exact value (floored to its top 60
//! bits, then rounded to the nearest double), found without the exact
//! value. That rounding is a monotonic function of the value, so when both
//! ends of the enclosure round to the same double, that is the double of
//! the exact value. When they do not (a value within about 2^-100 relative
//! of one of the function's steps), or an intermediate left the safe
//! exponent range, it answers `None` and the caller computes exactly.
//!
//! Error bounds (u = 2^-53): the sum of two double-words by Joldes, Muller
//! and Popescu's "AccurateDWPlusDW" errs by at most `3u^2 / (1 - 4u)`
//! relative, their product without a fused multiply-add ("DWTimesDW1",
//! Dekker's exact product of the high parts) by at most `7u^2 / (1 - ...)`
//! (M. Joldes, J.-M. Muller, V. Popescu, "Tight and rigorous error bounds
//! for basic building blocks of double-word arithmetic", ACM TOMS 44(2),
//! 2017, Algorithms 6 and 10). Each operation here charges `16u^2` of its
//! result, and the propagated bound (`|a| e_b + |b| e_a + e_a e_b` for a
//! product, `e_a + e_b` for a sum) is formed in doubles and enlarged by a
//! relative `2^-40` to cover its own rounding. Dekker's product (or the
//! fused multiply-add) is exact only away from overflow and underflow:
//! every value is kept in `[2^-400, 2^400]` in magnitude (or zero), else
//! the bound becomes infinite (or NaN, as `0 * inf`) and nothing is
//! claimed. The bound itself may underflow when its terms are tiny; every
//! nonzero propagated bound is raised by `2^-1000` to cover that, far
//! above the few `2^-1075` it can lose. A bound of exactly zero means an
//! exact value: every nonzero result is charged, and a zero result of
//! exact operands is exactly zero (the relative bounds above).

use crate::expansion::{two_product, two_sum};
use crate::plane::Ring;
#[cfg(doc)]
use crate::Exact;

const U2: f64 = 1.0 / (1u128 << 106) as f64; // u^2 = 2^-106
const CHARGE: f64 = 16.0 * U2;
const SLACK: f64 = 1.0 + 1.0 / (1u64 << 40) as f64;
const SAFE_LO: f64 =
    1.0 / (1u128 << 100) as f64 / (1u128 << 100) as f64 / (1u128 << 100) as f64 / (1u128 << 100) as f64;
const SAFE_HI: f64 = 1.0 / SAFE_LO;
/// Covers underflow while forming a nonzero propagated bound (its terms
/// can fall below the normal range; each loses at most 2^-1075).
const ETA: f64 = f64::from_bits(23 << 52); // 2^-1000: biased exponent 1023 - 1000

/// `a + b = s + e` exactly when `|a| >= |b|` (or `a = 0`; Dekker's Fast2Sum).
#[inline]
fn fast_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

/// `hi + lo` (with `|lo| <= ulp(hi) / 2`) and a bound `e` on its distance
/// from the exact value; `e = inf` once anything left the safe range.
#[derive(Clone, Copy, Debug)]
pub struct DoubleWord {
    hi: f64,
    lo: f64,
    e: f64,
}

impl DoubleWord {
    /// The result `(hi, lo)` of an operation with propagated bound `e`:
    /// its own error charged, the range checked.
    #[inline]
    fn done(hi: f64, lo: f64, e: f64) -> DoubleWord {
        let m = hi.abs();
        let safe = m == 0.0 || (SAFE_LO..=SAFE_HI).contains(&m);
        // a zero result with a nonzero bound keeps at least `ETA`, which
        // leaves its rounding to the exact path
        let eta = if e > 0.0 { ETA } else { 0.0 };
        let e = if safe { (e + eta + CHARGE * m * 2.0) * SLACK } else { f64::INFINITY };
        DoubleWord { hi, lo, e }
    }
}

impl Ring for DoubleWord {
    fn of(x: f64) -> Self {
        let safe = x == 0.0 || (SAFE_LO..=SAFE_HI).contains(&x.abs());
        DoubleWord { hi: x, lo: 0.0, e: if safe { 0.0 } else { f64::INFINITY } }
    }

    fn add(&self, o: &Self) -> Self {
        // AccurateDWPlusDW (Joldes, Muller, Popescu 2017, Algorithm 6)
        let (sh, sl) = two_sum(self.hi, o.hi);
        let (th, tl) = two_sum(self.lo, o.lo);
        let c = sl + th;
        let (vh, vl) = fast_two_sum(sh, c);
        let w = tl + vl;
        let (zh, zl) = fast_two_sum(vh, w);
        DoubleWord::done(zh, zl, self.e + o.e)
    }

    fn sub(&self, o: &Self) -> Self {
        self.add(&o.neg())
    }

    fn mul(&self, o: &Self) -> Self {
        // DWTimesDW1 (Algorithm 10 there, Dekker's product for the high parts)
        let (ch, cl1) = two_product(self.hi, o.hi);
        let tl = self.hi * o.lo;
        let tr = self.lo * o.hi;
        let cl2 = tl + tr;
        let cl3 = cl1 + cl2;
        let (zh, zl) = fast_two_sum(ch, cl3);
        let (a, b) = (self.hi.abs() * (1.0 + 1e-15), o.hi.abs() * (1.0 + 1e-15));
        DoubleWord::done(zh, zl, a * o.e + b * self.e + self.e * o.e)
    }

    fn neg(&self) -> Self {
        DoubleWord { hi: -self.hi, lo: -self.lo, e: self.e }
    }
}

/// `Exact::to_f64_approx` of the real `a + b` (any two finite doubles,
/// first made non-overlapping by TwoSum): floored to the grid of 60
/// significant bits of its binade, then rounded to the nearest double (ties
/// to even). `None` outside the safe range.
pub(crate) fn sum_to_f64_approx(a: f64, b: f64) -> Option<f64> {
    let (a, b) = two_sum(a, b);
    if a == 0.0 {
        return Some(0.0);
    }
    let m = a.abs();
    if !(SAFE_LO..=SAFE_HI).contains(&m) {
        return None;
    }
    // the binade 2^E of |a + b|: that of `a`, one lower when `a` is a power
    // of two and `b` takes the sum below it
    // (`m` is normal: its biased exponent field is its binade)
    let mut e = ((m.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    if m.to_bits() & ((1u64 << 52) - 1) == 0 && b != 0.0 && (b < 0.0) != (a < 0.0) {
        e -= 1;
    }
    // the grid 2^(E - 59); `a` is a multiple of it (ulp(a) >= 2^(E - 52)),
    // so the floor of the sum is `a` plus the floor of `b`, and the sum of
    // those two, rounded once, is the double
    let g = f64::powi(2.0, e - 59);
    let fb = (b / g).floor() * g;
    Some(a + fb)
}

impl DoubleWord {
    /// [`Exact::to_f64_approx`] of the exact value this encloses, when every
    /// value of the enclosure rounds to the same double; `None` sends the
    /// caller to the exact value. The bound is relative to the operands, so
    /// after a cancellation of about 50 bits the enclosure spans several
    /// doubles and the answer is `None`.
    ///
    /// ```
    /// use septa_exact::{DoubleWord, Exact, Ring};
    /// let dw = |a: f64, b: f64, c: f64| DoubleWord::of(a).mul(&DoubleWord::of(b)).sub(&DoubleWord::of(c));
    /// let exact = |a: f64, b: f64, c: f64| Exact::from_f64(a).mul(&Exact::from_f64(b)).sub(&Exact::from_f64(c));
    /// assert_eq!(dw(0.37, 0.91, 0.3).to_f64_approx(), Some(exact(0.37, 0.91, 0.3).to_f64_approx()));
    /// // 0.1 * 0.7 - 0.07 is about 2^-57: its enclosure is too wide
    /// assert_eq!(dw(0.1, 0.7, 0.07).to_f64_approx(), None);
    /// ```
    pub fn to_f64_approx(&self) -> Option<f64> {
        let x = self;
        if !x.e.is_finite() {
            return None;
        }
        if x.e == 0.0 {
            // exact (inputs, and sums and products that lost nothing)
            return sum_to_f64_approx(x.hi, x.lo);
        }
        // the ends `hi + (lo -+ e)`, `lo -+ e` rounded outwards
        let down = (x.lo - x.e).next_down();
        let up = (x.lo + x.e).next_up();
        let (l, h) = (sum_to_f64_approx(x.hi, down)?, sum_to_f64_approx(x.hi, up)?);
        (l == h).then_some(l)
    }
}

#[cfg(test)]
#[path = "double_word_tests.rs"]
mod tests;
