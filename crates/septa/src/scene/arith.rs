//! One formula, three arithmetics: a closed-form function written once
//! over [`Scalar`] gives its value in `f64`, a guaranteed enclosure over a
//! box in [`Interval`] (the same operations in the same order, so by the
//! argument of `rounding.rs` kind 1 it holds every value the `f64` formula
//! can return there, no error term needed), and a bound on the `f64`
//! formula's rounding error in [`Mag`] (the standard model
//! `fl(a op b) = (a op b)(1 + d)`, `|d| <= u`, carried through).

use super::interval::Interval;
use super::rounding::U;

/// The operations a closed-form formula may use.
pub(crate) trait Scalar: Copy {
    /// The constant `c` (an `f64`: the formula's constants are its definition).
    fn k(c: f64) -> Self;
    fn add(self, o: Self) -> Self;
    fn sub(self, o: Self) -> Self;
    fn mul(self, o: Self) -> Self;
    /// `self * self`.
    fn sqr(self) -> Self;
    fn exp(self) -> Self;
    fn sin(self) -> Self;
    fn cos(self) -> Self;
    /// `self * c`.
    fn scale(self, c: f64) -> Self {
        self.mul(Self::k(c))
    }
}

impl Scalar for f64 {
    fn k(c: f64) -> f64 {
        c
    }
    fn add(self, o: f64) -> f64 {
        self + o
    }
    fn sub(self, o: f64) -> f64 {
        self - o
    }
    fn mul(self, o: f64) -> f64 {
        self * o
    }
    fn sqr(self) -> f64 {
        self * self
    }
    fn exp(self) -> f64 {
        f64::exp(self)
    }
    fn sin(self) -> f64 {
        f64::sin(self)
    }
    fn cos(self) -> f64 {
        f64::cos(self)
    }
}

impl Scalar for Interval {
    fn k(c: f64) -> Interval {
        Interval::point(c)
    }
    fn add(self, o: Interval) -> Interval {
        Interval::add(self, o)
    }
    fn sub(self, o: Interval) -> Interval {
        Interval::sub(self, o)
    }
    fn mul(self, o: Interval) -> Interval {
        Interval::mul(self, o)
    }
    fn sqr(self) -> Interval {
        Interval::sqr(self)
    }
    fn exp(self) -> Interval {
        Interval::exp(self)
    }
    fn sin(self) -> Interval {
        Interval::sin(self)
    }
    fn cos(self) -> Interval {
        Interval::cos(self)
    }
}

/// An enclosure `v` of the exact value and a bound `e` on the computed
/// value's distance from it. Each rule is the standard model's: for `x~ =
/// x + ex`, `y~ = y + ey`, `fl(x~ op y~)` is within `|x~ op y~| u` of `x~ op
/// y~`, which is within the propagated error of `x op y`. `exp` and `sin`
/// add the library's error (under 2 ulps of the result).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Mag {
    /// Enclosure of the exact value.
    pub v: Interval,
    /// Bound on the rounding error so far.
    pub e: f64,
}

impl Mag {
    /// An input known exactly, anywhere in `v`.
    pub(crate) fn input(v: Interval) -> Mag {
        Mag { v, e: 0.0 }
    }
    fn round(v: Interval, e: f64) -> Mag {
        Mag { v, e: e + U * (v.mag() + e) }
    }
}

impl Scalar for Mag {
    fn k(c: f64) -> Mag {
        Mag { v: Interval::point(c), e: 0.0 }
    }
    fn add(self, o: Mag) -> Mag {
        Mag::round(self.v.add(o.v), self.e + o.e)
    }
    fn sub(self, o: Mag) -> Mag {
        Mag::round(self.v.sub(o.v), self.e + o.e)
    }
    fn mul(self, o: Mag) -> Mag {
        let (m, n) = (self.v.mag(), o.v.mag());
        Mag::round(self.v.mul(o.v), m * o.e + n * self.e + self.e * o.e)
    }
    fn sqr(self) -> Mag {
        let m = self.v.mag();
        Mag::round(self.v.sqr(), 2.0 * m * self.e + self.e * self.e)
    }
    fn exp(self) -> Mag {
        // |exp(a) - exp(b)| <= exp(max(a, b)) |a - b|.
        let top = (self.v.hi + self.e).exp();
        Mag { v: self.v.exp(), e: top * self.e + 2.0 * f64::EPSILON * top }
    }
    fn sin(self) -> Mag {
        // 1-Lipschitz.
        Mag { v: self.v.sin(), e: self.e + 2.0 * f64::EPSILON }
    }
    fn cos(self) -> Mag {
        Mag { v: self.v.cos(), e: self.e + 2.0 * f64::EPSILON }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A formula with cancellation: the `Mag` error bound holds the
    /// difference between the `f64` result and the same formula in exact
    /// rational arithmetic (through 128-bit integers on dyadic inputs).
    #[test]
    fn mag_bounds_the_rounding_error() {
        fn f<T: Scalar>(x: T, y: T) -> T {
            x.sqr().mul(x).sub(y.mul(x).scale(3.0)).add(y.sqr().scale(0.5))
        }
        for i in 0..200 {
            // Dyadic inputs with 20 fractional bits: exact in i128 up to 2^-60.
            let x = (i as f64 * 0.6180339887).fract() * 2.0 - 1.0;
            let y = (i as f64 * 0.4142135623).fract() * 2.0 - 1.0;
            let (x, y) = ((x * 1048576.0).round() / 1048576.0, (y * 1048576.0).round() / 1048576.0);
            let (xi, yi) = ((x * 1048576.0) as i128, (y * 1048576.0) as i128);
            // f scaled by 2^60: x^3 - 3xy + y^2/2.
            let exact = xi * xi * xi - 3 * xi * yi * 1048576 + yi * yi * 1048576 / 2;
            let exact = exact as f64 / 2f64.powi(60);
            let m = f(Mag::input(Interval::point(x)), Mag::input(Interval::point(y)));
            let got = f(x, y);
            assert!((got - exact).abs() <= m.e + 2.0 * U * exact.abs(), "{got} vs {exact}: error bound {}", m.e);
            assert!(m.v.contains(exact));
            let iv = f(Interval::point(x), Interval::point(y));
            assert!(iv.contains(got) && iv.contains(exact));
        }
    }
}
