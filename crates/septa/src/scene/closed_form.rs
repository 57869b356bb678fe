//! The closed-form test functions of the 2024 adaptive-grid paper's
//! examples (types `Gaussian`, `smile`, `cyclide`, `wave`, `teardrop` of its
//! function files; no parameters: each is one fixed function on the unit
//! cube). docs/scenes.md defines them; here each is written once over
//! [`Scalar`] (`arith.rs`), which gives the value, an enclosure of the
//! values the `f64` formula returns over a box, and its rounding error.
//! Gradients are written out by hand (and checked against finite
//! differences in the tests).
//!
//! Notation: `(x, y, z)` the point; the constants are those of the data
//! files' source, to the digits it gives.

use super::arith::{Mag, Scalar};
use super::interval::Interval;
use super::interval_vec::IV3;
use super::vec3::V3;

/// Which closed form.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ClosedForm {
    /// A plane across the cube's diagonal with a Gaussian bump on it.
    Gaussian,
    /// Two quartic blobs (`smile`).
    Smile,
    /// A Dupin-cyclide-like quartic.
    Cyclide,
    /// A height field of three sine waves.
    Wave,
    /// A quintic teardrop.
    Teardrop,
}

/// The wave's three sines `sin(a + b x + c y)`, each `(a, b, c, sign)`.
const WAVES: [(f64, f64, f64, f64); 3] = [
    (15.343274134071653, -9.21125890435288, -18.2340614919869, 1.0),
    (4.801594243303487, 7.985828093490334, -10.314294288432725, 1.0),
    (6.54696301939958, -18.46419127184428, -1.2648908198491549, -1.0),
];

impl ClosedForm {
    /// The JSON `type` name.
    pub fn name(self) -> &'static str {
        match self {
            ClosedForm::Gaussian => "Gaussian",
            ClosedForm::Smile => "smile",
            ClosedForm::Cyclide => "cyclide",
            ClosedForm::Wave => "wave",
            ClosedForm::Teardrop => "teardrop",
        }
    }

    /// From the JSON `type` name.
    pub fn from_name(name: &str) -> Option<ClosedForm> {
        [ClosedForm::Gaussian, ClosedForm::Smile, ClosedForm::Cyclide, ClosedForm::Wave, ClosedForm::Teardrop]
            .into_iter()
            .find(|c| c.name() == name)
    }

    /// The value, in any arithmetic.
    pub(crate) fn value<T: Scalar>(self, p: [T; 3]) -> T {
        let [x, y, z] = p;
        match self {
            ClosedForm::Gaussian => {
                // 3.4641 - 2.3094 (x + y + z) + 2 exp(-21.3333 q),
                // q = x^2 + y^2 + z^2 - x y - y z - z x.
                let q = x.sqr().add(y.sqr()).add(z.sqr()).sub(x.mul(y)).sub(y.mul(z)).sub(z.mul(x));
                let plane = T::k(3.4641).sub(x.add(y).add(z).scale(2.3094));
                plane.add(q.scale(-21.3333).exp().scale(2.0))
            }
            ClosedForm::Smile => {
                // (1 + v - u^2 - v^2)^4 + (u^2 + v^2 + w^2)^4 - 1,
                // (u, v, w) = 2 (p - 0.51).
                let (u, v, w) =
                    (x.sub(T::k(0.51)).scale(2.0), y.sub(T::k(0.51)).scale(2.0), z.sub(T::k(0.51)).scale(2.0));
                let a = T::k(1.0).add(v).sub(u.sqr()).sub(v.sqr());
                let b = u.sqr().add(v.sqr()).add(w.sqr());
                a.sqr().sqr().add(b.sqr().sqr()).sub(T::k(1.0))
            }
            ClosedForm::Cyclide => {
                // 7984 + 2400 u - 20800 u^2 - 19200 v^2 + 19200 w^2
                //   + 10000 (u^2 + v^2 + w^2)^2, (u, v, w) = 3 (p - 0.5).
                let (u, v, w) = (x.sub(T::k(0.5)).scale(3.0), y.sub(T::k(0.5)).scale(3.0), z.sub(T::k(0.5)).scale(3.0));
                let s = u.sqr().add(v.sqr()).add(w.sqr());
                T::k(7984.0)
                    .add(u.scale(2400.0))
                    .sub(u.sqr().scale(20800.0))
                    .sub(v.sqr().scale(19200.0))
                    .add(w.sqr().scale(19200.0))
                    .add(s.sqr().scale(10000.0))
            }
            ClosedForm::Wave => {
                // 2 - 4 z + (1/3) sum_k sign_k sin(a_k + b_k x + c_k y).
                let mut sum = T::k(0.0);
                for (a, b, c, sign) in WAVES {
                    let s = T::k(a).add(x.scale(b)).add(y.scale(c)).sin();
                    sum = if sign > 0.0 { sum.add(s) } else { sum.sub(s) };
                }
                T::k(2.0).sub(z.scale(4.0)).add(sum.scale(1.0 / 3.0))
            }
            ClosedForm::Teardrop => {
                // (u^5 + u^4) / 2 - v^2 - w^2, (u, v, w) = 2 (p - 0.5).
                let (u, v, w) = (x.sub(T::k(0.5)).scale(2.0), y.sub(T::k(0.5)).scale(2.0), z.sub(T::k(0.5)).scale(2.0));
                let u4 = u.sqr().sqr();
                u4.mul(u).scale(0.5).add(u4.scale(0.5)).sub(v.sqr()).sub(w.sqr())
            }
        }
    }

    /// The gradient, in any arithmetic.
    pub(crate) fn grad<T: Scalar>(self, p: [T; 3]) -> [T; 3] {
        let [x, y, z] = p;
        match self {
            ClosedForm::Gaussian => {
                // -2.3094 + 2 e (-21.3333) dq/dx_i, dq/dx = 2x - y - z, ...
                let q = x.sqr().add(y.sqr()).add(z.sqr()).sub(x.mul(y)).sub(y.mul(z)).sub(z.mul(x));
                let e = q.scale(-21.3333).exp().scale(2.0 * -21.3333);
                let d = |a: T, b: T, c: T| T::k(-2.3094).add(e.mul(a.scale(2.0).sub(b).sub(c)));
                [d(x, y, z), d(y, z, x), d(z, x, y)]
            }
            ClosedForm::Smile => {
                // A = 1 + v - u^2 - v^2, B = u^2 + v^2 + w^2, d/dx = 2 d/du:
                // (16 u (B^3 - A^3), 8 (A^3 (1 - 2v) + 2 v B^3), 16 w B^3).
                let (u, v, w) =
                    (x.sub(T::k(0.51)).scale(2.0), y.sub(T::k(0.51)).scale(2.0), z.sub(T::k(0.51)).scale(2.0));
                let a = T::k(1.0).add(v).sub(u.sqr()).sub(v.sqr());
                let b = u.sqr().add(v.sqr()).add(w.sqr());
                let (a3, b3) = (a.sqr().mul(a), b.sqr().mul(b));
                [
                    u.mul(b3.sub(a3)).scale(16.0),
                    a3.mul(T::k(1.0).sub(v.scale(2.0))).add(v.mul(b3).scale(2.0)).scale(8.0),
                    w.mul(b3).scale(16.0),
                ]
            }
            ClosedForm::Cyclide => {
                // d/dx = 3 d/du: 3 (2400 - 41600 u + 40000 u s), 3 (-38400 v +
                // 40000 v s), 3 (38400 w + 40000 w s).
                let (u, v, w) = (x.sub(T::k(0.5)).scale(3.0), y.sub(T::k(0.5)).scale(3.0), z.sub(T::k(0.5)).scale(3.0));
                let s = u.sqr().add(v.sqr()).add(w.sqr());
                let s4 = s.scale(40000.0);
                [
                    T::k(2400.0).sub(u.scale(41600.0)).add(u.mul(s4)).scale(3.0),
                    v.mul(s4).sub(v.scale(38400.0)).scale(3.0),
                    w.mul(s4).add(w.scale(38400.0)).scale(3.0),
                ]
            }
            ClosedForm::Wave => {
                let (mut gx, mut gy) = (T::k(0.0), T::k(0.0));
                for (a, b, c, sign) in WAVES {
                    let cs = T::k(a).add(x.scale(b)).add(y.scale(c)).cos().scale(sign / 3.0);
                    gx = gx.add(cs.scale(b));
                    gy = gy.add(cs.scale(c));
                }
                let _ = z;
                [gx, gy, T::k(-4.0)]
            }
            ClosedForm::Teardrop => {
                // d/dx = 2 d/du: (5 u^4 + 4 u^3, -4 v, -4 w).
                let (u, v, w) = (x.sub(T::k(0.5)).scale(2.0), y.sub(T::k(0.5)).scale(2.0), z.sub(T::k(0.5)).scale(2.0));
                let u3 = u.sqr().mul(u);
                [u3.mul(u).scale(5.0).add(u3.scale(4.0)), v.scale(-4.0), w.scale(-4.0)]
            }
        }
    }

    pub(crate) fn eval(self, p: V3) -> f64 {
        self.value(p)
    }

    pub(crate) fn gradient(self, p: V3) -> V3 {
        self.grad(p)
    }

    /// A bound on `|eval - exact|` over the box (`Mag` arithmetic on the
    /// box, times 2 for margin).
    pub(crate) fn eval_error(self, lo: V3, hi: V3) -> f64 {
        let m = [0, 1, 2].map(|i| Mag::input(Interval::new(lo[i], hi[i])));
        2.0 * self.value(m).e
    }

    /// The gradient formula in intervals: an enclosure of the exact
    /// gradient over the box (and of the computed one), linear in the
    /// box's size.
    pub(crate) fn grad_bounds(self, lo: V3, hi: V3) -> IV3 {
        self.grad(super::interval_vec::box3(lo, hi))
    }

    /// The value formula in intervals (it holds every computed value), met
    /// with the mean value form around the box centre `c`: `f(c) + G . (p
    /// - c)` with `G` the gradient enclosure, widened by twice the rounding
    /// error (the computed `f(c)` and the computed value at `p` each differ
    /// from the exact ones by at most that). The first is tight for small
    /// boxes only to first order in the terms' sizes; the second to first
    /// order in the gradient's, which matters where terms cancel.
    pub(crate) fn bounds(self, lo: V3, hi: V3) -> Interval {
        let naive = self.value(super::interval_vec::box3(lo, hi));
        naive.meet(mean_value(|p| self.eval(p), self.grad_bounds(lo, hi), self.eval_error(lo, hi), lo, hi))
    }
}

/// `f(c) + G . (p - c)` over the box, widened by `2 err`: an enclosure of
/// both the exact and the computed values when `G` encloses the gradient
/// and `err` bounds `|computed - exact|` on the box.
pub(crate) fn mean_value(f: impl Fn(V3) -> f64, g: IV3, err: f64, lo: V3, hi: V3) -> Interval {
    let c = [0, 1, 2].map(|i| 0.5 * (lo[i] + hi[i]));
    let mut var = Interval::point(0.0);
    for a in 0..3 {
        let h = (hi[a] - c[a]).max(c[a] - lo[a]) * (1.0 + 1e-15);
        var = var.add(g[a].mul(Interval::new(-h, h)));
    }
    let v = f(c);
    if !v.is_finite() || !var.lo.is_finite() || !var.hi.is_finite() {
        return Interval::ENTIRE;
    }
    Interval::point(v).add(var).pad(2.0 * err)
}
