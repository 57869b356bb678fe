//! Conservative interval arithmetic for primitive bounds (docs/sparse.md, sparse
//! evaluation): every operation rounds its result outward by one ulp, so the
//! returned interval contains the exact result for any inputs inside the
//! operand intervals, and also any value a correctly rounded `f64`
//! evaluation of the same formula can produce.
//!
//! NaN never escapes: an operation that would produce NaN returns the whole
//! real line, which is always a valid (if useless) enclosure.

/// A closed interval `[lo, hi]` of reals, possibly with infinite ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    /// Lower end.
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
}

/// The next `f64` below `x` (hand-written because `f64::next_down` needs a
/// newer compiler than the workspace's minimum).
pub(crate) fn down(x: f64) -> f64 {
    if x.is_nan() {
        return f64::NEG_INFINITY;
    }
    if x == f64::NEG_INFINITY {
        return x;
    }
    if x == 0.0 {
        return -f64::from_bits(1);
    }
    let b = x.to_bits();
    if x > 0.0 {
        f64::from_bits(b - 1)
    } else {
        f64::from_bits(b + 1)
    }
}

/// The next `f64` above `x`.
pub(crate) fn up(x: f64) -> f64 {
    -down(-x)
}

impl Interval {
    /// The whole real line.
    pub const ENTIRE: Interval = Interval { lo: f64::NEG_INFINITY, hi: f64::INFINITY };

    /// `[lo, hi]`; a NaN end or `lo > hi` gives [`Interval::ENTIRE`].
    pub fn new(lo: f64, hi: f64) -> Interval {
        if lo.is_nan() || hi.is_nan() || lo > hi {
            Interval::ENTIRE
        } else {
            Interval { lo, hi }
        }
    }

    /// The single point `x` (exact, no widening).
    pub fn point(x: f64) -> Interval {
        Interval::new(x, x)
    }

    /// `[lo, hi]` widened outward by one ulp at each end.
    pub fn rounded(lo: f64, hi: f64) -> Interval {
        Interval::new(down(lo), up(hi))
    }

    /// Widen by `pad >= 0` at both ends, rounding outward.
    pub fn pad(self, pad: f64) -> Interval {
        Interval::rounded(self.lo - pad, self.hi + pad)
    }

    /// True when `x` lies in the interval.
    pub fn contains(self, x: f64) -> bool {
        self.lo <= x && x <= self.hi
    }

    /// Largest absolute value in the interval.
    pub fn mag(self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }

    /// Sum.
    pub fn add(self, o: Interval) -> Interval {
        Interval::rounded(self.lo + o.lo, self.hi + o.hi)
    }

    /// Difference.
    pub fn sub(self, o: Interval) -> Interval {
        Interval::rounded(self.lo - o.hi, self.hi - o.lo)
    }

    /// Negation (exact).
    pub fn neg(self) -> Interval {
        Interval::new(-self.hi, -self.lo)
    }

    /// Product.
    pub fn mul(self, o: Interval) -> Interval {
        let p = [self.lo * o.lo, self.lo * o.hi, self.hi * o.lo, self.hi * o.hi];
        if p.iter().any(|x| x.is_nan()) {
            return Interval::ENTIRE;
        }
        let lo = p.iter().cloned().fold(f64::INFINITY, f64::min);
        let hi = p.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        Interval::rounded(lo, hi)
    }

    /// Product with a constant.
    pub fn scale(self, k: f64) -> Interval {
        self.mul(Interval::point(k))
    }

    /// Quotient; the whole line when the divisor contains zero.
    pub fn div(self, o: Interval) -> Interval {
        if o.contains(0.0) {
            return Interval::ENTIRE;
        }
        let inv = Interval::rounded(1.0 / o.hi, 1.0 / o.lo);
        self.mul(inv)
    }

    /// Square (tight: never negative).
    pub fn sqr(self) -> Interval {
        let a = self.lo.abs();
        let b = self.hi.abs();
        let hi = a.max(b);
        let lo = if self.contains(0.0) { 0.0 } else { a.min(b) };
        let r = Interval::rounded(lo * lo, hi * hi);
        Interval::new(r.lo.max(0.0), r.hi)
    }

    /// Square root of the non-negative part.
    pub fn sqrt(self) -> Interval {
        let lo = self.lo.max(0.0);
        let hi = self.hi.max(0.0);
        let r = Interval::rounded(lo.sqrt(), hi.sqrt());
        Interval::new(r.lo.max(0.0), r.hi)
    }

    /// Absolute value (exact).
    pub fn abs(self) -> Interval {
        if self.lo >= 0.0 {
            self
        } else if self.hi <= 0.0 {
            self.neg()
        } else {
            Interval::new(0.0, self.mag())
        }
    }

    /// Pointwise minimum (exact).
    pub fn min(self, o: Interval) -> Interval {
        Interval::new(self.lo.min(o.lo), self.hi.min(o.hi))
    }

    /// Pointwise maximum (exact).
    pub fn max(self, o: Interval) -> Interval {
        Interval::new(self.lo.max(o.lo), self.hi.max(o.hi))
    }

    /// The smallest interval holding both (exact).
    pub fn hull(self, o: Interval) -> Interval {
        Interval::new(self.lo.min(o.lo), self.hi.max(o.hi))
    }

    /// The overlap of two enclosures of the same quantity; `self` if they
    /// are disjoint (impossible for two valid enclosures, but never empty).
    pub fn meet(self, o: Interval) -> Interval {
        let (lo, hi) = (self.lo.max(o.lo), self.hi.min(o.hi));
        if lo <= hi {
            Interval { lo, hi }
        } else {
            self
        }
    }

    /// Width `hi - lo` (rounded up; infinite for an unbounded interval).
    pub fn width(self) -> f64 {
        up(self.hi - self.lo)
    }

    /// `exp`: monotone; the library's `exp` errs by less than an ulp, so
    /// widening the exact ends' computed values by 4 ulps (relative)
    /// encloses both the exact and every computed value.
    pub fn exp(self) -> Interval {
        let k = 4.0 * f64::EPSILON;
        let lo = self.lo.exp();
        let hi = self.hi.exp();
        Interval::new((lo * (1.0 - k)).max(0.0), hi * (1.0 + k))
    }

    /// `sin`: the extremes are at the ends or at `pi/2 + k pi` inside;
    /// padded by `4e-16 + 4u |x|` for the library's error and the
    /// rounding of `pi` in locating the extremes.
    pub fn sin(self) -> Interval {
        self.shifted_cos(-std::f64::consts::FRAC_PI_2)
    }

    /// `cos` (as [`Interval::sin`]).
    pub fn cos(self) -> Interval {
        self.shifted_cos(0.0)
    }

    /// Range of `cos(x + shift)` over the interval (shift 0 or -pi/2).
    fn shifted_cos(self, shift: f64) -> Interval {
        let whole = Interval::new(-1.0, 1.0);
        if !(self.lo.is_finite() && self.hi.is_finite()) || self.hi - self.lo >= 6.3 {
            return whole;
        }
        let pi = std::f64::consts::PI;
        let f = |x: f64| if shift == 0.0 { x.cos() } else { x.sin() };
        let (a, b) = (f(self.lo), f(self.hi));
        let (mut lo, mut hi) = (a.min(b), a.max(b));
        // Extremes of cos(x + shift) at x + shift = k pi: maxima for even k.
        let (t0, t1) = ((self.lo + shift) / pi, (self.hi + shift) / pi);
        // A margin of a millionth of a period so a rounding of `t` never
        // hides an extreme (including one costs only width).
        let (k0, k1) = ((t0 - 1e-6).ceil() as i64, (t1 + 1e-6).floor() as i64);
        for k in k0..=k1 {
            if k.rem_euclid(2) == 0 {
                hi = 1.0;
            } else {
                lo = -1.0;
            }
        }
        let pad = 4e-16 + 4.0 * f64::EPSILON * self.mag();
        Interval::new(lo - pad, hi + pad).meet(whole.pad(pad))
    }
}

/// Interval enclosure of the Euclidean norm of a vector of intervals.
pub(crate) fn norm3(v: [Interval; 3]) -> Interval {
    v[0].sqr().add(v[1].sqr()).add(v[2].sqr()).sqrt()
}

/// Interval enclosure of a dot product with a constant vector.
pub(crate) fn dot3(v: [Interval; 3], k: [f64; 3]) -> Interval {
    v[0].scale(k[0]).add(v[1].scale(k[1])).add(v[2].scale(k[2]))
}

/// The box `[lo, hi]` translated by `-c`, as three intervals.
pub(crate) fn offset_box(lo: [f64; 3], hi: [f64; 3], c: [f64; 3]) -> [Interval; 3] {
    [0, 1, 2].map(|i| Interval::new(lo[i], hi[i]).sub(Interval::point(c[i])))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ulp_steps() {
        assert!(down(1.0) < 1.0 && up(1.0) > 1.0);
        assert!(down(0.0) < 0.0 && up(0.0) > 0.0);
        assert!(down(-1.0) < -1.0 && up(-1.0) > -1.0);
        assert_eq!(up(f64::INFINITY), f64::INFINITY);
        assert_eq!(down(f64::NEG_INFINITY), f64::NEG_INFINITY);
        assert_eq!(up(down(3.5)), 3.5);
    }

    #[test]
    fn ops_enclose_samples() {
        let a = Interval::new(-0.3, 1.7);
        let b = Interval::new(0.2, 0.9);
        for i in 0..=20 {
            for j in 0..=20 {
                let x = -0.3 + 2.0 * i as f64 / 20.0;
                let y = 0.2 + 0.7 * j as f64 / 20.0;
                let x = x.min(1.7);
                let y = y.min(0.9);
                assert!(a.add(b).contains(x + y));
                assert!(a.sub(b).contains(x - y));
                assert!(a.mul(b).contains(x * y));
                assert!(a.div(b).contains(x / y));
                assert!(a.sqr().contains(x * x));
                assert!(b.sqrt().contains(y.sqrt()));
                assert!(a.abs().contains(x.abs()));
            }
        }
        assert_eq!(b.div(a), Interval::ENTIRE);
        assert_eq!(a.sqr().lo, 0.0);
    }
}
