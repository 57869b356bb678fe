//! Primitives built from other primitives: affine transforms, the Wyvill
//! blend (Bloomenthal 4.8.1 `Sigmoid`), and function-level combinators
//! (sum, scale, abs, min, max).

use super::interval::{norm3, offset_box, Interval};
use super::primitive::Primitive;
use super::shapes::lipschitz;
use super::vec3::*;

/// 3x3 matrix, row-major.
pub type Mat3 = [[f64; 3]; 3];

fn mat_vec(m: &Mat3, v: V3) -> V3 {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}

fn transpose(m: &Mat3) -> Mat3 {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| m[j][i]))
}

fn det(m: &Mat3) -> f64 {
    dot(m[0], cross(m[1], m[2]))
}

/// Inverse of `m`, or `None` when it is singular (or nearly so).
pub(crate) fn inverse(m: &Mat3) -> Option<Mat3> {
    let d = det(m);
    let scale_ = m.iter().map(|r| mag(*r)).fold(0.0, f64::max);
    if d.abs() <= 1e-12 * scale_.powi(3) || !d.is_finite() {
        return None;
    }
    // Rows of the inverse transpose are cross products of the rows.
    let c = [cross(m[1], m[2]), cross(m[2], m[0]), cross(m[0], m[1])];
    Some(transpose(&c).map(|r| r.map(|x| x / d)))
}

/// Rotation matrix about a unit `axis` by `angle` radians (Rodrigues).
pub fn rotation(axis: V3, angle: f64) -> Mat3 {
    let [x, y, z] = normalize(axis);
    let (s, c) = angle.sin_cos();
    let t = 1.0 - c;
    [
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
    ]
}

/// `f(p) = inner(A^-1 (p - t))`: the inner shape moved by `p -> A p + t`.
#[derive(Clone, Debug, PartialEq)]
pub struct Transform {
    /// Linear part `A` (forward).
    pub linear: Mat3,
    /// Translation `t`.
    pub translation: V3,
    /// `A^-1`, precomputed.
    pub(crate) inverse: Mat3,
    /// The transformed primitive.
    pub inner: Primitive,
}

impl Transform {
    /// Build; `None` when `linear` is singular.
    pub fn new(linear: Mat3, translation: V3, inner: Primitive) -> Option<Transform> {
        let inverse = inverse(&linear)?;
        Some(Transform { linear, translation, inverse, inner })
    }
    fn local(&self, p: V3) -> V3 {
        mat_vec(&self.inverse, sub(p, self.translation))
    }
    pub(crate) fn eval(&self, p: V3) -> f64 {
        self.inner.eval(self.local(p))
    }
    pub(crate) fn gradient(&self, p: V3) -> V3 {
        // grad f = A^-T grad inner (chain rule).
        let g = self.inner.gradient(self.local(p));
        mat_vec(&transpose(&self.inverse), g)
    }
    pub(crate) fn bounds(&self, lo: V3, hi: V3) -> Interval {
        // Box of the preimage of the box: interval matrix-vector product.
        let o = offset_box(lo, hi, self.translation);
        let q = [0, 1, 2].map(|i| {
            let m = self.inverse[i];
            o[0].scale(m[0]).add(o[1].scale(m[1])).add(o[2].scale(m[2]))
        });
        // `q` encloses the exact local coordinates; pad by the error of
        // computing them (rounding.rs), so the box holds every *computed*
        // `local(p)`. The inner bound encloses the inner `eval` at every
        // point of that box, hence this `eval` at every `p`: no further pad.
        let err = self.local_error(&o);
        let q = [0, 1, 2].map(|i| q[i].pad(err[i]));
        self.inner.bounds_interval(q.map(|x| x.lo), q.map(|x| x.hi))
    }
}

/// Wyvill et al.'s blend (Bloomenthal 4.8.1, `Sigmoid`):
/// `W(d) = 1 - (4 d^6 - 17 d^4 + 22 d^2) / 9` for `|d| <= 1`, else 0.
pub fn wyvill(d: f64) -> f64 {
    if d.abs() > 1.0 {
        0.0
    } else {
        let d2 = d * d;
        1.0 - (4.0 * d2 * d2 * d2 - 17.0 * d2 * d2 + 22.0 * d2) / 9.0
    }
}

/// Derivative of [`wyvill`].
pub fn wyvill_derivative(d: f64) -> f64 {
    if d.abs() > 1.0 {
        0.0
    } else {
        let d2 = d * d;
        -(24.0 * d2 * d2 * d - 68.0 * d2 * d + 44.0 * d) / 9.0
    }
}

/// `height * W(dist / radius)`, `dist` the distance to `center` or, with an
/// axis, to the line through `center` along it (Bloomenthal's saucer is
/// `0.35 W(1.4 sqrt(x^2 + y^2))`: axis z, radius 1/1.4, height 0.35).
#[derive(Clone, Debug, PartialEq)]
pub struct Wyvill {
    /// Centre of the bump.
    pub center: V3,
    /// Unit axis for a radial (cylindrical) bump, or none for a point bump.
    pub axis: Option<V3>,
    /// Support radius (positive).
    pub radius: f64,
    /// Value at the centre.
    pub height: f64,
}

impl Wyvill {
    fn offset(&self, p: V3) -> V3 {
        let v = sub(p, self.center);
        match self.axis {
            Some(u) => sub(v, scale(u, dot(u, v))),
            None => v,
        }
    }
    pub(crate) fn eval(&self, p: V3) -> f64 {
        self.height * wyvill(norm(self.offset(p)) / self.radius)
    }
    pub(crate) fn gradient(&self, p: V3) -> V3 {
        let w = self.offset(p);
        let d = norm(w);
        if d == 0.0 {
            return [0.0; 3];
        }
        let k = self.height * wyvill_derivative(d / self.radius) / (self.radius * d);
        scale(w, k)
    }
    pub(crate) fn bounds(&self, lo: V3, hi: V3) -> Interval {
        // `dist` encloses the computed distance: without an axis, by the
        // same expression in intervals (rounding.rs, kind 1); with one, by
        // a Lipschitz bound padded by the error of `offset` (the cylinder's
        // perpendicular part, same bound as the cylinder's).
        let dist = match self.axis {
            None => norm3(offset_box(lo, hi, self.center)),
            Some(u) => {
                let axis = super::shapes::Cylinder { point: self.center, axis: u, radius: 0.0, squared: false };
                let err = axis.rho_error(super::rounding::box_mag(lo, hi));
                lipschitz(|p| norm(self.offset(p)), 1.0, lo, hi, err)
            }
        };
        // W is non-increasing in d >= 0 (dW/du = -2(6u-11)(u-1)/9 <= 0 for
        // u = d^2 in [0, 1]), so its range is [W(d_hi), W(d_lo)]; `d / r`
        // is rounded monotonically, so the computed `d / r` lies in
        // [d_lo, d_hi]. The computed polynomial is within ~8u (4 + 17 + 22)
        // / 9 + 2u < 1e-14 of the exact one at any `d`, at the ends as at
        // the point: pad 4e-14. The final `height * W` rounds monotonically.
        let d_lo = (dist.lo.max(0.0) / self.radius) * (1.0 - 1e-15);
        let d_hi = (dist.hi / self.radius) * (1.0 + 1e-15);
        let w = Interval::new(wyvill(d_hi), wyvill(d_lo)).pad(4e-14);
        w.scale(self.height)
    }
}

/// Evaluate the combinators. Kept beside [`Transform`] because they share
/// the recursive structure.
pub(crate) fn sum_eval(terms: &[Primitive], p: V3) -> f64 {
    terms.iter().map(|t| t.eval(p)).sum()
}

pub(crate) fn sum_gradient(terms: &[Primitive], p: V3) -> V3 {
    terms.iter().fold([0.0; 3], |g, t| add(g, t.gradient(p)))
}

/// Encloses the computed sum: `sum_eval` adds left to right from 0, and so
/// do these intervals, each enclosing a term's computed values (rounding.rs).
pub(crate) fn sum_bounds(terms: &[Primitive], lo: V3, hi: V3) -> Interval {
    terms.iter().fold(Interval::point(0.0), |s, t| s.add(t.bounds_interval(lo, hi)))
}

/// Index of the term with the extreme value (`max = true`: largest);
/// first one on ties, so the result is deterministic.
pub(crate) fn extreme(terms: &[Primitive], p: V3, max: bool) -> (f64, usize) {
    let mut best = (terms[0].eval(p), 0);
    for (i, t) in terms.iter().enumerate().skip(1) {
        let v = t.eval(p);
        if (max && v > best.0) || (!max && v < best.0) {
            best = (v, i);
        }
    }
    best
}

pub(crate) fn extreme_bounds(terms: &[Primitive], lo: V3, hi: V3, max: bool) -> Interval {
    let mut it = terms.iter().map(|t| t.bounds_interval(lo, hi));
    let first = it.next().unwrap_or(Interval::ENTIRE);
    it.fold(first, |a, b| if max { a.max(b) } else { a.min(b) })
}
