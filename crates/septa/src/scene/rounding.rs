//! Rounding-error bounds of [`Primitive::eval`] (sparse evaluation, docs/sparse.md).
//!
//! Sparse evaluation skips a block when a bound proves that no grid vertex
//! of the block changes the network; the dense path decides on the *rounded*
//! samples `eval(p)`, so a bound must enclose every value `eval` can return
//! in the box, not only the mathematical one. Two kinds of bound do this:
//!
//! 1. **The same expression, in intervals.** When `bounds` evaluates
//!    exactly the operations of `eval`, in the same order, on intervals
//!    that enclose the operands, every rounded result is enclosed. Each
//!    [`Interval`] operation returns float ends `[l, h]` enclosing the exact
//!    result `x op y` for all `x`, `y` in the operand intervals (outward
//!    rounding); IEEE rounding is monotone and fixes floats, so `l <= x op y
//!    <= h` gives `l <= fl(x op y) <= h`: the rounded result is enclosed too,
//!    for `+ - * /`, `sqrt`, `abs`, `min`, `max` alike. By induction over the
//!    expression, the final interval encloses `eval`'s value. Rust never
//!    contracts `a * b + c` into a fused multiply-add, so `eval` performs
//!    exactly the operations written.
//!    Plane, half-space, sphere (all kinds), ellipsoid, box and point set are
//!    bounded this way, and the combinators (sum, scale, abs, min, max,
//!    transform) combine their operands' enclosures of the rounded values
//!    by the same operations, so they need no error term either.
//! 2. **An enclosure of the exact value, padded by a bound on eval's
//!    error** for the shapes bounded by a Lipschitz constant around the box
//!    centre, or by a different formula (cylinder, capped cylinder, capsule,
//!    cone, torus, mesh, patch, the axial Wyvill bump). This file states
//!    those error bounds. With the standard model
//!    `fl(a op b) = (a op b)(1 + d)`, `|d| <= u = 2^-53`, a chain of `n`
//!    roundings on quantities of magnitude at most `S` errs by about `n u S`;
//!    each bound below is such an estimate times a safety factor of at least
//!    4 (the constant [`K`]), over the largest magnitudes in the box.
//!    `tests/scene/bounds_float.rs` checks the result on boxes of a few ulps
//!    around sign changes, far from the origin, and on grid vertices exactly
//!    on the surface.

use super::composite::Transform;
use super::interval::Interval;
use super::patch::BicubicPatch;
use super::primitive::Primitive;
use super::shapes::{CappedCylinder, Capsule, Cone, Cylinder, SphereKind};
use super::torus::Torus;
use super::vec3::{mag, V3};

/// Unit roundoff of `f64`.
pub(crate) const U: f64 = f64::EPSILON / 2.0;

/// Error bounds are `K u S` for a magnitude `S` of the quantities involved;
/// the chains below round at most ~60 times (4x margin).
pub(crate) const K: f64 = 256.0;

/// Largest absolute coordinate of any point of the box `[lo, hi]`.
pub(crate) fn box_mag(lo: V3, hi: V3) -> f64 {
    mag(lo).max(mag(hi))
}

impl Cylinder {
    /// Error of the computed distance to the axis, `norm(perp(p))`, against
    /// the distance to the line along the *normalized* stored axis: `v = p -
    /// point` (|v_i| <= P = A + |point|), `d = a . v` (errs 5u sqrt(3) P),
    /// `w = v - a d` (~16u sqrt(3) P per component; a non-unit `|a| = 1 +
    /// O(u)` adds 2u |v|), the norm ~3u |w|: about 60u P in all.
    pub(crate) fn rho_error(&self, a: f64) -> f64 {
        K * U * (1.0 + a + mag(self.point))
    }
    /// Error of `eval`: `r - rho` adds one rounding; the squared form
    /// `r r - w . w` errs by `2 |w| err(w) + 3u |w|^2 + u r^2`, quadratic in
    /// the magnitudes.
    pub(crate) fn eval_error(&self, a: f64) -> f64 {
        let s = 1.0 + a + mag(self.point) + self.radius.abs();
        if self.squared {
            K * U * s * s
        } else {
            K * U * s
        }
    }
}

impl Capsule {
    /// `t = clamp(((p - a) . ab) / |ab|^2)` errs by ~5u |p - a| / |ab|, so
    /// the computed closest point `a + t ab` moves by ~5u |p - a| along the
    /// segment (the distance grows by at most that), plus ~4u (|a| + |ab|)
    /// for forming it, and the norm and `r - d` a few ulps more.
    pub(crate) fn eval_error(&self, a: f64) -> f64 {
        K * U * (1.0 + a + mag(self.a) + mag(self.b) + self.radius.abs())
    }
}

impl CappedCylinder {
    /// Unit axis, midpoint, axial and radial parts and the final norm: ~30
    /// roundings of quantities bounded by the box and the caps.
    pub(crate) fn eval_error(&self, a: f64) -> f64 {
        K * U * (1.0 + a + mag(self.a) + mag(self.b) + self.radius.abs())
    }
}

impl Cone {
    /// A dot product and a norm of `p - apex`: ~10 roundings.
    pub(crate) fn eval_error(&self, a: f64) -> f64 {
        K * U * (1.0 + a + mag(self.apex)) * (1.0 + self.cos_angle.abs())
    }
}

impl Torus {
    /// Error of the computed argument of the square root,
    /// `r (r - 2 rho) + v . v`, against `(rho - r)^2 + h^2`: every term is
    /// at most `Q^2`, `Q = 1 + A + |centre| + r` (3 |v|^2 <= 9 Q^2 with
    /// ~5u error, `2 r err(rho)` ~ 120 u Q^2, a non-unit axis 4u |v|^2), so
    /// `2 K u Q^2` holds with margin. The cancellation is real: the
    /// argument is small near the core circle.
    pub(crate) fn arg_error(&self, a: f64) -> f64 {
        let q = 1.0 + a + mag(self.center) + self.major.abs();
        2.0 * K * U * q * q
    }
    /// Error of the computed distance to the core circle `sqrt(arg)`:
    /// `|sqrt(x) - sqrt(y)| <= sqrt(|x - y|)` always, and `<= |x - y| /
    /// sqrt(y)` when the exact argument is at least `y`; `s_min` is a lower
    /// bound of the exact distance on the box (0 when unknown). Plus the
    /// final sqrt (a few ulps of the values).
    pub(crate) fn distance_error(&self, a: f64, s_min: f64) -> f64 {
        let e = self.arg_error(a);
        let root = if s_min > 0.0 { (e / s_min).min(e.sqrt()) } else { e.sqrt() };
        let q = 1.0 + a + mag(self.center) + self.major.abs() + self.minor.abs();
        root * (1.0 + 1e-12) + 8.0 * U * q
    }
    /// Error of `eval`: the distance's error (plus one subtraction, within
    /// the margin) for `minor - D`; the argument's error and the last two
    /// roundings for `minor^2 - D^2`.
    pub(crate) fn eval_error(&self, a: f64, s_min: f64) -> f64 {
        if self.squared {
            let q = 1.0 + a + mag(self.center) + self.major.abs() + self.minor.abs();
            self.arg_error(a) + 8.0 * U * q * q
        } else {
            self.distance_error(a, s_min)
        }
    }
}

impl BicubicPatch {
    /// Error of `eval = (z - h) / sqrt(1 + hx^2 + hy^2)` over the box
    /// whose parameters are `s`, `t`, given an enclosure `range` of its
    /// exact values. With `H` the largest control height and `G = (1 +
    /// 2|s|)(1 + 2|t|)`: the Bernstein values sum to at most `(|1-s| +
    /// |s|)^3 <= (1 + 2|s|)^3` in absolute value, so `h` is a sum of terms
    /// of total size `H G^3` rounded ~20 times (plus the rounding of `s`, `t`
    /// propagated through `dh/ds <= 6 H G^3`), and `h_x`, `h_y` likewise
    /// with `6 H G^3 / size`. Then `e = z - h` errs by `err(h) + u (|z| +
    /// |h|)`, and since `w >= 1` and `|h_x| / w <= 1`, the quotient errs by
    /// `err(e) + |e / w| (err(h_x) + err(h_y) + 4u)`.
    pub(crate) fn eval_error(&self, s: Interval, t: Interval, z_mag: f64, range: Interval) -> f64 {
        let hm = self.heights.iter().flatten().fold(0.0f64, |m, h| m.max(h.abs()));
        let g = (1.0 + 2.0 * s.mag()) * (1.0 + 2.0 * t.mag());
        let g3 = g * g * g;
        let dh = K * U * hm * g3;
        let dd = 6.0 * K * U * hm * g3 / self.size[0].min(self.size[1]);
        let de = dh + 2.0 * U * (z_mag + hm * g3);
        2.0 * de + range.mag().min(f64::MAX) * (2.0 * dd + 8.0 * U)
    }
}

impl Transform {
    /// Pad of the local coordinates `A^-1 (p - t)` of the box: each is a
    /// 3-term dot product of `p - t` (errs `u |p - t|`) with a row `m`,
    /// erring by at most `5u sum_j |m_j| |p_j - t_j|` (no relation to the
    /// size of the result: the rows may cancel).
    pub(crate) fn local_error(&self, o: &[Interval; 3]) -> [f64; 3] {
        [0, 1, 2].map(|i| {
            let m = self.inverse[i];
            let s: f64 = (0..3).map(|j| m[j].abs() * o[j].mag()).sum();
            16.0 * U * s
        })
    }
}

impl Primitive {
    /// A bound on `|eval(p) - f(p)|` over the box, `f` the primitive's
    /// exact function (with a normalized axis), for the mean value bound
    /// of [`super::gradbound::difference_lower`]; `None` where no bound is
    /// stated (bounds of kind 1 in the module doc do not need one).
    pub(crate) fn eval_error(&self, lo: V3, hi: V3) -> Option<f64> {
        let a = box_mag(lo, hi);
        match self {
            Primitive::Constant(_) => Some(0.0),
            // A 3-term dot product of `p - point`: ~6 roundings.
            Primitive::Plane(p) | Primitive::HalfSpace(p) => Some(K * U * (1.0 + a + mag(p.point))),
            // `d2` errs 5u d^2, `sqrt` 3u d, `r - d` one rounding; squared:
            // `r r - d2`, quadratic.
            Primitive::Sphere(s) => {
                let m = 1.0 + a + mag(s.center) + s.radius.abs();
                Some(if s.kind == SphereKind::Squared { K * U * m * m } else { K * U * m })
            }
            Primitive::Cylinder(c) => Some(c.eval_error(a)),
            Primitive::Capsule(c) => Some(c.eval_error(a)),
            Primitive::CappedCylinder(c) => Some(c.eval_error(a)),
            Primitive::Cone(c) => Some(c.eval_error(a)),
            Primitive::Torus(t) => Some(t.eval_error(a, 0.0)),
            Primitive::Mesh(m) => Some(super::mesh::mesh_error(m, a)),
            Primitive::ClosedForm(c) => Some(c.eval_error(lo, hi)),
            Primitive::Rbf(r) => Some(r.eval_error(lo, hi)),
            _ => None,
        }
    }
}
