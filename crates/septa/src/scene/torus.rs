//! The torus (reference `torus`, and `circle` with minor radius 0):
//! `minor - D` with `D` the distance to the core circle, or with
//! `"squared": true` the smooth `minor^2 - D^2` (Septa's extension, by
//! analogy with the reference's squared sphere and cylinder: the same zero
//! set, a polynomial of degree 4, smooth everywhere but on the axis).

use super::interval::Interval;
use super::rounding::{box_mag, U};
use super::shapes::lipschitz;
use super::vec3::*;

/// Reference `torus`: `minor - sqrt((rho - major)^2 + h^2)`; with minor
/// radius 0 the reference `circle` (negated distance to the circle).
#[derive(Clone, Debug, PartialEq)]
pub struct Torus {
    /// Centre.
    pub center: V3,
    /// Unit axis.
    pub axis: V3,
    /// Major radius.
    pub major: f64,
    /// Minor radius (0 for a circle).
    pub minor: f64,
    /// `minor^2 - D^2` instead of `minor - D`.
    pub squared: bool,
}

impl Torus {
    fn split(&self, p: V3) -> (V3, V3, V3, f64) {
        let v = sub(p, self.center);
        let d = dot(self.axis, v);
        let para = scale(self.axis, d);
        let perp = sub(v, para);
        (v, para, perp, norm(perp))
    }
    /// `D^2`, computed as the reference computes it.
    fn arg(&self, p: V3) -> f64 {
        let (v, para, _, rho) = self.split(p);
        let r = self.major;
        if rho == 0.0 {
            dot(para, para) + r * r
        } else {
            r * (r - 2.0 * rho) + dot(v, v)
        }
    }
    pub(crate) fn eval(&self, p: V3) -> f64 {
        let arg = self.arg(p);
        if self.squared {
            self.minor * self.minor - arg
        } else {
            self.minor - arg.sqrt()
        }
    }
    pub(crate) fn gradient(&self, p: V3) -> V3 {
        let (v, para, perp, rho) = self.split(p);
        let r = self.major;
        // q = p - (closest point of the core circle); on the axis every
        // point of the circle is closest: q's mean over them, `para`.
        let q = if rho == 0.0 { para } else { sub(v, scale(perp, r / rho)) };
        if self.squared {
            return scale(q, -2.0);
        }
        let len = if rho == 0.0 { (dot(para, para) + r * r).sqrt() } else { norm(q) };
        if len == 0.0 {
            [0.0; 3]
        } else {
            scale(q, -1.0 / len)
        }
    }
    /// An enclosure of the exact distance to the core circle over the box
    /// (1-Lipschitz around the box centre), and the error bound used.
    fn distance_bounds(&self, lo: V3, hi: V3) -> Interval {
        // The computed sqrt(arg) cancels near the core circle (rounding.rs):
        // first the error bound valid everywhere, then, when that proves the
        // box away from the core circle, the much smaller one it allows.
        let a = box_mag(lo, hi);
        let d = |p| self.arg(p).sqrt();
        let wide = lipschitz(d, 1.0, lo, hi, self.distance_error(a, 0.0));
        if wide.lo > 0.0 {
            let narrow = lipschitz(d, 1.0, lo, hi, self.distance_error(a, wide.lo));
            return wide.meet(narrow);
        }
        wide
    }
    pub(crate) fn bounds(&self, lo: V3, hi: V3) -> Interval {
        let d = self.distance_bounds(lo, hi);
        if self.squared {
            // The computed value is within arg_error (plus the final two
            // roundings) of minor^2 - D^2, D in `d` (rounding.rs).
            let d = Interval::new(d.lo.max(0.0), d.hi.max(0.0));
            let m2 = self.minor * self.minor;
            let exact = Interval::point(m2).sub(d.sqr());
            return exact.pad(self.arg_error(box_mag(lo, hi)) + 4.0 * U * (m2 + d.hi * d.hi));
        }
        // `minor - D`: the distance bound holds the computed sqrt(arg), so
        // the interval subtraction holds the computed value.
        Interval::point(self.minor).sub(d)
    }
}
