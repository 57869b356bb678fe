//! Gradient enclosures of the composite primitives: the Wyvill bump, the
//! bicubic patch and affine transforms (sums, scales, `abs`, `min` and
//! `max` are in `gradbound.rs`).

use super::composite::{Transform, Wyvill};
use super::interval::Interval;
use super::interval_vec::*;
use super::patch::BicubicPatch;
use super::vec3::V3;

impl Wyvill {
    pub(crate) fn grad_bounds(&self, lo: V3, hi: V3) -> IV3 {
        // height W(d / R) with W'(u) = u g(u^2), g(s) = -(4/9)(6s - 11)(s - 1):
        // the gradient is (height / R^2) g(d^2 / R^2) w (w the offset,
        // normal to the axis for an axial bump), 0 beyond R (g(1) = 0).
        // g increases from -44/9 to 0 on [0, 1].
        let v = offset3(lo, hi, self.center);
        let w = match self.axis {
            Some(a) => mat_vec3(&perp_projector(a), v),
            None => v,
        };
        let s = norm2(w).div(Interval::point(self.radius * self.radius));
        let g = |s: f64| -(4.0 / 9.0) * (6.0 * s - 11.0) * (s - 1.0);
        if s.lo >= 1.0 {
            return point3([0.0; 3]);
        }
        let (a, b) = (s.lo.max(0.0), s.hi.min(1.0));
        // g's rounding: a few ulps of 44/9.
        let gi = Interval::new(g(a), g(b)).pad(1e-14);
        mul3(w, gi.scale(self.height / (self.radius * self.radius)).pad(1e-14 * self.height.abs()))
    }
}

impl BicubicPatch {
    /// Interval evaluation of the analytic gradient (`patch.rs`) over the
    /// box: `(-h_x / w - e (h_x h_xx + h_y h_xy) / w^3, -h_y / w - e (h_x
    /// h_xy + h_y h_yy) / w^3, 1 / w)` with `e = z - h`, `w = sqrt(1 +
    /// h_x^2 + h_y^2)`, each Bernstein sum in intervals.
    pub(crate) fn grad_bounds(&self, lo: V3, hi: V3) -> IV3 {
        let (sx, sy) = (self.size[0], self.size[1]);
        let s = Interval::new(lo[0], hi[0]).sub(Interval::point(self.origin[0])).div(Interval::point(sx));
        let t = Interval::new(lo[1], hi[1]).sub(Interval::point(self.origin[1])).div(Interval::point(sy));
        let d = self.derivatives_iv(s, t);
        let [h, hx, hy, hxx, hxy, hyy] = d;
        let hx = hx.div(Interval::point(sx));
        let hy = hy.div(Interval::point(sy));
        let hxx = hxx.div(Interval::point(sx * sx)).pad(4.0 * f64::EPSILON * hxx.mag() / (sx * sx));
        let hyy = hyy.div(Interval::point(sy * sy)).pad(4.0 * f64::EPSILON * hyy.mag() / (sy * sy));
        let hxy = hxy.div(Interval::point(sx * sy)).pad(4.0 * f64::EPSILON * hxy.mag() / (sx * sy));
        let w = Interval::point(1.0).add(hx.sqr()).add(hy.sqr()).sqrt();
        let e = Interval::new(lo[2], hi[2]).sub(h);
        let w3 = w.sqr().mul(w);
        let gx = hx.div(w).neg().sub(e.mul(hx.mul(hxx).add(hy.mul(hxy))).div(w3));
        let gy = hy.div(w).neg().sub(e.mul(hx.mul(hxy).add(hy.mul(hyy))).div(w3));
        let gz = Interval::point(1.0).div(w);
        [gx, gy, gz.meet(Interval::new(0.0, 1.0))]
    }
}

impl Transform {
    pub(crate) fn grad_bounds(&self, lo: V3, hi: V3) -> Option<IV3> {
        // grad f(p) = A^-T grad inner(A^-1 (p - t)): the inner enclosure over
        // the preimage box (as in `bounds`, padded for its rounding).
        let o = offset3(lo, hi, self.translation);
        let q = mat_vec3(&self.inverse, o);
        let err = self.local_error(&o);
        let q = [0, 1, 2].map(|i| q[i].pad(err[i]));
        let g = self.inner.gradient_bounds(q.map(|x| x.lo), q.map(|x| x.hi))?;
        Some(mat_t_vec3(&self.inverse, g))
    }
}
