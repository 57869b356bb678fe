//! Analytic shapes: value, analytic gradient and an interval bound over a
//! box for each. Convention (the reference implementation's): the value is
//! **positive inside** a solid; distance-like primitives without an inside
//! (line, segment, circle, point set) return the *negated* distance, so the
//! material interface (argmax) of several of them is their Voronoi diagram.
//!
//! Where a shape is also a primitive of the reference implementation
//! (plane, sphere, cylinder, line, cone, torus, circle) its value is computed
//! with the same sequence of `f64` operations, so sampled values agree to
//! the bit (checked against `ia4_R20.npz` in `tests/scene/reference.rs`).

use super::interval::{dot3, norm3, offset_box, Interval};
use super::rounding::box_mag;
use super::vec3::*;

/// Lipschitz enclosure of a function whose exact version is `l`-Lipschitz
/// and whose computed version errs by at most `err` on the box: over a box
/// of centre `c` and half-diagonal `r`, the exact value at any `p` is within
/// `l r` of the exact `f(c)`, itself within `err` of the computed `f(c)`;
/// the computed value at `p` is within `err` of the exact one. So
/// `f(c) ± (l r + 2 err)` encloses both the exact and the computed values
/// (rounding of the ends outward, and a relative `1e-15` on `l r`).
pub(crate) fn lipschitz(f: impl Fn(V3) -> f64, l: f64, lo: V3, hi: V3, err: f64) -> Interval {
    let (c, r) = box_center_radius(lo, hi);
    let v = f(c);
    let w = (l * r * (1.0 + 1e-15) + 2.0 * err) * (1.0 + 1e-15);
    Interval::rounded(v - w, v + w)
}

/// Plane `n . (p - point)` with unit normal `n` (reference `plane`).
#[derive(Clone, Debug, PartialEq)]
pub struct PlaneShape {
    /// A point on the plane.
    pub point: V3,
    /// Unit normal; the value grows along it.
    pub normal: V3,
}

impl PlaneShape {
    pub(crate) fn eval(&self, p: V3) -> f64 {
        dot(self.normal, sub(p, self.point))
    }
    pub(crate) fn gradient(&self, _p: V3) -> V3 {
        self.normal
    }
    pub(crate) fn bounds(&self, lo: V3, hi: V3) -> Interval {
        dot3(offset_box(lo, hi, self.point), self.normal)
    }
}

/// How a sphere's value depends on the distance `d` to its centre.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SphereKind {
    /// `r - d` (reference `sphere`).
    Signed,
    /// `r^2 - d^2` (reference `"squared": true`).
    Squared,
    /// `-|r - d|` (reference `sphere` with a negative radius).
    Unsigned,
}

/// Sphere of centre `center` and radius `radius`.
#[derive(Clone, Debug, PartialEq)]
pub struct Sphere {
    /// Centre.
    pub center: V3,
    /// Radius (non-negative).
    pub radius: f64,
    /// Which function of the distance.
    pub kind: SphereKind,
}

impl Sphere {
    pub(crate) fn eval(&self, p: V3) -> f64 {
        let v = sub(self.center, p);
        let d2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        match self.kind {
            SphereKind::Signed => self.radius - d2.sqrt(),
            SphereKind::Squared => self.radius * self.radius - d2,
            SphereKind::Unsigned => -(self.radius - d2.sqrt()).abs(),
        }
    }
    pub(crate) fn gradient(&self, p: V3) -> V3 {
        let v = sub(p, self.center);
        let d = norm(v);
        match self.kind {
            SphereKind::Squared => scale(v, -2.0),
            _ if d == 0.0 => [0.0; 3],
            SphereKind::Signed => scale(v, -1.0 / d),
            SphereKind::Unsigned => {
                if d < self.radius {
                    scale(v, 1.0 / d)
                } else {
                    scale(v, -1.0 / d)
                }
            }
        }
    }
    pub(crate) fn bounds(&self, lo: V3, hi: V3) -> Interval {
        // Per-axis |x - c| then the norm: exactly [min, max] distance.
        let d2 = {
            let o = offset_box(lo, hi, self.center);
            o[0].sqr().add(o[1].sqr()).add(o[2].sqr())
        };
        let r = Interval::point(self.radius);
        match self.kind {
            SphereKind::Signed => r.sub(d2.sqrt()),
            SphereKind::Squared => r.sqr().sub(d2),
            SphereKind::Unsigned => r.sub(d2.sqrt()).abs().neg(),
        }
    }
}

/// Ellipsoid, value `min(radii) * (1 - |q|)` with `q_i = (p_i - c_i) / r_i`:
/// zero on the ellipsoid, positive inside and 1-Lipschitz (not the exact
/// distance, which has no closed form).
#[derive(Clone, Debug, PartialEq)]
pub struct Ellipsoid {
    /// Centre.
    pub center: V3,
    /// Semi-axes along x, y, z (positive); rotate with a transform.
    pub radii: V3,
}

impl Ellipsoid {
    fn m(&self) -> f64 {
        self.radii[0].min(self.radii[1]).min(self.radii[2])
    }
    fn q(&self, p: V3) -> V3 {
        [0, 1, 2].map(|i| (p[i] - self.center[i]) / self.radii[i])
    }
    pub(crate) fn eval(&self, p: V3) -> f64 {
        self.m() * (1.0 - norm(self.q(p)))
    }
    pub(crate) fn gradient(&self, p: V3) -> V3 {
        let q = self.q(p);
        let n = norm(q);
        if n == 0.0 {
            return [0.0; 3];
        }
        [0, 1, 2].map(|i| -self.m() * q[i] / (n * self.radii[i]))
    }
    pub(crate) fn bounds(&self, lo: V3, hi: V3) -> Interval {
        let o = offset_box(lo, hi, self.center);
        let q = [0, 1, 2].map(|i| o[i].div(Interval::point(self.radii[i])));
        Interval::point(1.0).sub(norm3(q)).scale(self.m())
    }
}

/// Axis-aligned box, exact signed distance, positive inside.
#[derive(Clone, Debug, PartialEq)]
pub struct BoxShape {
    /// Centre.
    pub center: V3,
    /// Half side lengths (positive).
    pub half: V3,
}

impl BoxShape {
    fn q(&self, p: V3) -> V3 {
        [0, 1, 2].map(|i| (p[i] - self.center[i]).abs() - self.half[i])
    }
    pub(crate) fn eval(&self, p: V3) -> f64 {
        let q = self.q(p);
        let out = norm(q.map(|x| x.max(0.0)));
        let inside = q[0].max(q[1]).max(q[2]).min(0.0);
        -(out + inside)
    }
    pub(crate) fn gradient(&self, p: V3) -> V3 {
        let q = self.q(p);
        let s = [0, 1, 2].map(|i| if p[i] < self.center[i] { -1.0 } else { 1.0 });
        let m = q[0].max(q[1]).max(q[2]);
        if m > 0.0 {
            let o = q.map(|x| x.max(0.0));
            let n = norm(o);
            [0, 1, 2].map(|i| -s[i] * o[i] / n)
        } else {
            let k = (0..3).fold(0, |k, i| if q[i] > q[k] { i } else { k });
            let mut g = [0.0; 3];
            g[k] = -s[k];
            g
        }
    }
    pub(crate) fn bounds(&self, lo: V3, hi: V3) -> Interval {
        let o = offset_box(lo, hi, self.center);
        let q = [0, 1, 2].map(|i| o[i].abs().sub(Interval::point(self.half[i])));
        let z = Interval::point(0.0);
        let out = norm3(q.map(|x| x.max(z)));
        let inside = q[0].max(q[1]).max(q[2]).min(z);
        out.add(inside).neg()
    }
}

/// Infinite cylinder `r - rho` (rho: distance to the axis), reference
/// `cylinder`; with radius 0 it is the reference `line` (negated distance).
#[derive(Clone, Debug, PartialEq)]
pub struct Cylinder {
    /// A point on the axis.
    pub point: V3,
    /// Unit axis direction.
    pub axis: V3,
    /// Radius (0 for a line).
    pub radius: f64,
    /// `r^2 - rho^2` instead (reference `"squared": true`).
    pub squared: bool,
}

impl Cylinder {
    pub(crate) fn perp(&self, p: V3) -> V3 {
        let v = sub(p, self.point);
        let d = dot(self.axis, v);
        sub(v, scale(self.axis, d))
    }
    pub(crate) fn eval(&self, p: V3) -> f64 {
        let w = self.perp(p);
        if self.squared {
            self.radius * self.radius - dot(w, w)
        } else {
            self.radius - norm(w)
        }
    }
    pub(crate) fn gradient(&self, p: V3) -> V3 {
        let w = self.perp(p);
        if self.squared {
            return scale(w, -2.0);
        }
        scale(unit_or_zero(w), -1.0)
    }
    pub(crate) fn bounds(&self, lo: V3, hi: V3) -> Interval {
        let a = box_mag(lo, hi);
        if !self.squared {
            // Kind 2 (rounding.rs): the whole value is 1-Lipschitz.
            return lipschitz(|p| self.eval(p), 1.0, lo, hi, self.eval_error(a));
        }
        // Squared: the exact distance to the axis is enclosed by `rho`
        // (not the computed one: `eval` squares `w` itself), so
        // `r^2 - rho^2` encloses the exact value; pad by eval's error.
        let rho = lipschitz(|p| norm(self.perp(p)), 1.0, lo, hi, self.rho_error(a));
        let rho = rho.max(Interval::point(0.0));
        let r = Interval::point(self.radius);
        r.sqr().sub(rho.sqr()).pad(self.eval_error(a))
    }
}

/// Distance from `p` to the segment `a b`, and the closest point.
pub(crate) fn segment_closest(p: V3, a: V3, b: V3) -> (f64, V3) {
    let ab = sub(b, a);
    let l2 = dot(ab, ab);
    let t = if l2 > 0.0 { (dot(sub(p, a), ab) / l2).clamp(0.0, 1.0) } else { 0.0 };
    let q = add(a, scale(ab, t));
    (norm(sub(p, q)), q)
}

/// Capsule `r - dist(p, segment a b)`; with radius 0 the negated distance to
/// the segment.
#[derive(Clone, Debug, PartialEq)]
pub struct Capsule {
    /// First end of the segment.
    pub a: V3,
    /// Second end of the segment.
    pub b: V3,
    /// Radius (0 for a plain segment distance).
    pub radius: f64,
}

impl Capsule {
    pub(crate) fn eval(&self, p: V3) -> f64 {
        self.radius - segment_closest(p, self.a, self.b).0
    }
    pub(crate) fn gradient(&self, p: V3) -> V3 {
        let (_, q) = segment_closest(p, self.a, self.b);
        scale(unit_or_zero(sub(p, q)), -1.0)
    }
    pub(crate) fn bounds(&self, lo: V3, hi: V3) -> Interval {
        lipschitz(|p| self.eval(p), 1.0, lo, hi, self.eval_error(box_mag(lo, hi)))
    }
}

/// Capped cylinder between `a` and `b`, exact signed distance, positive
/// inside.
#[derive(Clone, Debug, PartialEq)]
pub struct CappedCylinder {
    /// Centre of one cap.
    pub a: V3,
    /// Centre of the other cap.
    pub b: V3,
    /// Radius.
    pub radius: f64,
}

impl CappedCylinder {
    /// (radial excess, axial excess, radial unit vector, axial unit sign).
    fn parts(&self, p: V3) -> (f64, f64, V3, V3) {
        let ab = sub(self.b, self.a);
        let len = norm(ab);
        let u = scale(ab, 1.0 / len);
        let mid = scale(add(self.a, self.b), 0.5);
        let v = sub(p, mid);
        let t = dot(v, u);
        let w = sub(v, scale(u, t));
        let rho = norm(w);
        let su = if t < 0.0 { scale(u, -1.0) } else { u };
        (rho - self.radius, t.abs() - 0.5 * len, unit_or_zero(w), su)
    }
    pub(crate) fn eval(&self, p: V3) -> f64 {
        let (dr, da, _, _) = self.parts(p);
        let out = (dr.max(0.0).powi(2) + da.max(0.0).powi(2)).sqrt();
        -(out + dr.max(da).min(0.0))
    }
    pub(crate) fn gradient(&self, p: V3) -> V3 {
        let (dr, da, wr, ua) = self.parts(p);
        if dr > 0.0 || da > 0.0 {
            let (x, y) = (dr.max(0.0), da.max(0.0));
            let n = (x * x + y * y).sqrt();
            scale(add(scale(wr, x / n), scale(ua, y / n)), -1.0)
        } else if dr > da {
            scale(wr, -1.0)
        } else {
            scale(ua, -1.0)
        }
    }
    pub(crate) fn bounds(&self, lo: V3, hi: V3) -> Interval {
        // An exact signed distance is 1-Lipschitz.
        lipschitz(|p| self.eval(p), 1.0, lo, hi, self.eval_error(box_mag(lo, hi)))
    }
}

/// Reference `cone`: `u . (p - apex) - cos(angle) |p - apex|`, positive
/// inside the cone of half-angle `angle` around the unit axis `u`.
#[derive(Clone, Debug, PartialEq)]
pub struct Cone {
    /// Apex.
    pub apex: V3,
    /// Unit axis.
    pub axis: V3,
    /// `cos` of the apex half-angle.
    pub cos_angle: f64,
}

impl Cone {
    pub(crate) fn eval(&self, p: V3) -> f64 {
        let v = sub(p, self.apex);
        let d = self.apex;
        let dist =
            ((p[0] - d[0]) * (p[0] - d[0]) + (p[1] - d[1]) * (p[1] - d[1]) + (p[2] - d[2]) * (p[2] - d[2])).sqrt();
        dot(self.axis, v) - self.cos_angle * dist
    }
    pub(crate) fn gradient(&self, p: V3) -> V3 {
        let v = sub(p, self.apex);
        let n = norm(v);
        if n == 0.0 {
            return [0.0; 3];
        }
        sub(self.axis, scale(v, self.cos_angle / n))
    }
    pub(crate) fn bounds(&self, lo: V3, hi: V3) -> Interval {
        // |grad| <= |u| + |cos| |v/|v||.
        lipschitz(|p| self.eval(p), 1.0 + self.cos_angle.abs(), lo, hi, self.eval_error(box_mag(lo, hi)))
    }
}

/// Weighted point set: `max_i (w_i - |p - x_i|)`, the negated distance to
/// the nearest point when all weights are 0 (additive weights give the
/// Apollonius diagram's distance).
#[derive(Clone, Debug, PartialEq)]
pub struct PointSet {
    /// Sites.
    pub points: Vec<V3>,
    /// Additive weight per site.
    pub weights: Vec<f64>,
}

impl PointSet {
    fn best(&self, p: V3) -> (f64, usize) {
        let mut best = (f64::NEG_INFINITY, 0);
        for (i, (x, w)) in self.points.iter().zip(&self.weights).enumerate() {
            let v = w - norm(sub(p, *x));
            if v > best.0 {
                best = (v, i);
            }
        }
        best
    }
    pub(crate) fn eval(&self, p: V3) -> f64 {
        self.best(p).0
    }
    pub(crate) fn gradient(&self, p: V3) -> V3 {
        let (_, i) = self.best(p);
        scale(unit_or_zero(sub(p, self.points[i])), -1.0)
    }
    pub(crate) fn bounds(&self, lo: V3, hi: V3) -> Interval {
        let mut r = Interval::point(f64::NEG_INFINITY);
        for (x, w) in self.points.iter().zip(&self.weights) {
            let d = norm3(offset_box(lo, hi, *x));
            r = r.max(Interval::point(*w).sub(d));
        }
        r
    }
}
