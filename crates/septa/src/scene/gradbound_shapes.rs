//! Gradient enclosures of the analytic shapes over a box ([`Primitive::
//! gradient_bounds`](super::Primitive::gradient_bounds)). Every shape's
//! gradient is a unit direction (a distance's), a linear map of the offset
//! (a squared distance's) or a combination; the direction of a box of
//! vectors is enclosed exactly per component by `unit3`, and the offset's
//! box is exact per component when it enters once (`mat_vec3`). So each
//! enclosure is within a constant factor of the true range: linear in the
//! box's size away from kinks. At kinks (a sphere's centre, a box's
//! medial planes, a capsule's segment) the enclosure is the Clarke hull.

use super::interval::Interval;
use super::interval_vec::*;
use super::mesh::TriMesh;
use super::shapes::*;
use super::torus::Torus;
use super::vec3::{box_center_radius, norm, sub, V3};

impl Sphere {
    pub(crate) fn grad_bounds(&self, lo: V3, hi: V3) -> IV3 {
        let o = offset3(lo, hi, self.center);
        match self.kind {
            SphereKind::Squared => scale3(o, -2.0),
            SphereKind::Signed => {
                // -(p - c)/|p - c| for p in the ball of radius R around the
                // box centre m: a cone of half-angle asin(R/d) around
                // a = (m - c)/d, so each component is within the chord
                // 2 sin(angle/2) of -a. Both this and the per-component
                // range are valid; keep their overlap.
                let exact = scale3(unit3(o), -1.0);
                let (m, r) = box_center_radius(lo, hi);
                let v = sub(m, self.center);
                let d = norm(v);
                if d.is_nan() || d <= r * (1.0 + 1e-12) {
                    return exact;
                }
                let sin = (r / d).min(1.0);
                // 2 sin(t/2) = s sqrt(2 / (1 + cos t)): no cancellation for small s.
                let cos = (1.0 - sin * sin).max(0.0).sqrt();
                let chord = sin * (2.0 / (1.0 + cos)).sqrt() * (1.0 + 1e-12) + 1e-15;
                meet3(exact, v.map(|x| Interval::point(-x / d).pad(chord)))
            }
            SphereKind::Unsigned => {
                // -|r - d|: +(p - c)/d inside, -(p - c)/d outside, both on
                // the sphere (Clarke hull).
                let u = unit3(o);
                let d = norm2(o).sqrt();
                if d.hi < self.radius {
                    u
                } else if d.lo > self.radius {
                    scale3(u, -1.0)
                } else {
                    hull3(u, scale3(u, -1.0))
                }
            }
        }
    }
}

impl Ellipsoid {
    pub(crate) fn grad_bounds(&self, lo: V3, hi: V3) -> IV3 {
        // grad = -m q / (|q| r) component-wise, q = (p - c) / r.
        let o = offset3(lo, hi, self.center);
        let q: IV3 = [0, 1, 2].map(|i| o[i].div(Interval::point(self.radii[i])));
        let m = self.radii[0].min(self.radii[1]).min(self.radii[2]);
        let u = unit3(q);
        [0, 1, 2].map(|i| u[i].scale(-m / self.radii[i]))
    }
}

impl BoxShape {
    pub(crate) fn grad_bounds(&self, lo: V3, hi: V3) -> IV3 {
        // q_i = |p_i - c_i| - h_i. Outside (some q_i > 0) the gradient is
        // -unit(max(q, 0)) times the signs of p - c; inside, -sign_k e_k
        // for the largest q_k. The hull of whichever can occur.
        let o = offset3(lo, hi, self.center);
        let q: IV3 = [0, 1, 2].map(|i| o[i].abs().sub(Interval::point(self.half[i])));
        let s: IV3 = o.map(sign_iv);
        let zero = Interval::point(0.0);
        let mut out: Option<IV3> = None;
        if q.iter().any(|x| x.hi > 0.0) {
            let u = unit3(q.map(|x| x.max(zero)));
            out = Some([0, 1, 2].map(|i| u[i].mul(s[i]).neg()));
        }
        if q.iter().all(|x| x.lo <= 0.0) {
            let g = argmax_axis_gradient(&q, &s);
            out = Some(out.map_or(g, |o| hull3(o, g)));
        }
        out.unwrap_or([Interval::new(-1.0, 1.0); 3])
    }
}

/// Inside a box (all `q_i <= 0`): `-s_k e_k` for the axes `k` whose `q_k`
/// can be the largest; the hull of those.
fn argmax_axis_gradient(q: &IV3, s: &IV3) -> IV3 {
    let best = q.iter().map(|x| x.lo).fold(f64::NEG_INFINITY, f64::max);
    let cands: Vec<usize> = (0..3).filter(|&i| q[i].hi >= best).collect();
    [0, 1, 2].map(|i| {
        if !cands.contains(&i) {
            Interval::point(0.0)
        } else if cands.len() == 1 {
            s[i].neg()
        } else {
            s[i].neg().hull(Interval::point(0.0))
        }
    })
}

impl Cylinder {
    /// The part of the offset from the axis point normal to the axis, as
    /// a box exact per component (`(I - a a^T)(p - point)`).
    pub(crate) fn perp_box(&self, lo: V3, hi: V3) -> IV3 {
        mat_vec3(&perp_projector(self.axis), offset3(lo, hi, self.point))
    }
    pub(crate) fn grad_bounds(&self, lo: V3, hi: V3) -> IV3 {
        let w = self.perp_box(lo, hi);
        if self.squared {
            // r^2 - |w|^2: gradient -2 w.
            scale3(w, -2.0)
        } else {
            // r - |w|: gradient -w/|w| (the unit disc normal to the axis on it).
            scale3(unit3(w), -1.0)
        }
    }
}

impl CappedCylinder {
    pub(crate) fn grad_bounds(&self, lo: V3, hi: V3) -> IV3 {
        // The box distance in the (radial, axial) plane: dr = rho - r,
        // da = |t| - len/2; outside -(x w_r + y u_a)/|(x, y)| with x, y the
        // positive parts, inside -w_r or -u_a for the larger of dr, da.
        let ab = sub(self.b, self.a);
        let len = norm(ab);
        let u = ab.map(|x| x / len);
        let mid = [0, 1, 2].map(|i| 0.5 * (self.a[i] + self.b[i]));
        let o = offset3(lo, hi, mid);
        let t = dot3i(o, point3(u));
        let w = mat_vec3(&perp_projector(u), o);
        let rho = norm2(w).sqrt();
        let dr = rho.sub(Interval::point(self.radius));
        let da = t.abs().sub(Interval::point(0.5 * len)).pad(4.0 * f64::EPSILON * len);
        let wr = unit3(w);
        let ua = mul3(point3(u), sign_iv(t));
        let zero = Interval::point(0.0);
        let mut out: Option<IV3> = None;
        if dr.hi > 0.0 || da.hi > 0.0 {
            let (x, y) = (dr.max(zero), da.max(zero));
            let cx = unit_component(x, y.sqr());
            let cy = unit_component(y, x.sqr());
            out = Some(add3(mul3(wr, cx), mul3(ua, cy)).map(|g| g.neg()));
        }
        if dr.lo <= 0.0 && da.lo <= 0.0 {
            let radial = dr.hi >= da.lo;
            let axial = da.hi >= dr.lo;
            let g = match (radial, axial) {
                (true, false) => scale3(wr, -1.0),
                (false, true) => scale3(ua, -1.0),
                _ => hull3(scale3(wr, -1.0), scale3(ua, -1.0)),
            };
            out = Some(out.map_or(g, |o| hull3(o, g)));
        }
        out.unwrap_or([Interval::new(-1.0, 1.0); 3])
    }
}

impl Cone {
    pub(crate) fn grad_bounds(&self, lo: V3, hi: V3) -> IV3 {
        // u - cos(angle) (p - apex)/|p - apex|.
        let d = unit3(offset3(lo, hi, self.apex));
        sub3(point3(self.axis), scale3(d, self.cos_angle))
    }
}

impl Torus {
    /// An enclosure of `q = p - (closest point of the core circle)` =
    /// `v - R w/|w|` (`v = p - centre`, `w` its part normal to the axis).
    pub(crate) fn core_offset_box(&self, lo: V3, hi: V3) -> IV3 {
        let v = offset3(lo, hi, self.center);
        let w = mat_vec3(&perp_projector(self.axis), v);
        sub3(v, scale3(unit3(w), self.major))
    }
    pub(crate) fn grad_bounds(&self, lo: V3, hi: V3) -> IV3 {
        let q = self.core_offset_box(lo, hi);
        if self.squared {
            // minor^2 - |q|^2.
            scale3(q, -2.0)
        } else {
            scale3(unit3(q), -1.0)
        }
    }
}

impl Capsule {
    pub(crate) fn grad_bounds(&self, lo: V3, hi: V3) -> IV3 {
        // -(p - closest)/|p - closest|, closest = a + t (b - a) with t the
        // clamped projection parameter.
        let ab = sub(self.b, self.a);
        let l2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
        let o = offset3(lo, hi, self.a);
        let t = if l2 > 0.0 {
            let t = dot3i(o, point3(ab)).div(Interval::point(l2));
            Interval::new(t.lo.clamp(0.0, 1.0), t.hi.clamp(0.0, 1.0))
        } else {
            Interval::point(0.0)
        };
        let q = sub3(o, mul3(point3(ab), t));
        scale3(unit3(q), -1.0)
    }
}

impl PointSet {
    pub(crate) fn grad_bounds(&self, lo: V3, hi: V3) -> IV3 {
        // max_i (w_i - |p - x_i|): the hull of -unit(p - x_k) over the sites
        // k that can be the largest somewhere in the box.
        let offs: Vec<IV3> = self.points.iter().map(|x| offset3(lo, hi, *x)).collect();
        let vals: Vec<Interval> =
            offs.iter().zip(&self.weights).map(|(o, w)| Interval::point(*w).sub(norm2(*o).sqrt())).collect();
        let best = vals.iter().map(|v| v.lo).fold(f64::NEG_INFINITY, f64::max);
        let mut out: Option<IV3> = None;
        for (o, v) in offs.iter().zip(&vals) {
            if v.hi >= best {
                let g = scale3(unit3(*o), -1.0);
                out = Some(out.map_or(g, |a| hull3(a, g)));
            }
        }
        out.unwrap_or([Interval::new(-1.0, 1.0); 3])
    }
}

impl TriMesh {
    /// A closed mesh's signed distance is 1-Lipschitz: every (Clarke)
    /// gradient lies in the unit ball. No tighter bound is attempted (the
    /// closest feature changes across the medial axis); an open mesh's
    /// sign is not trustworthy, so it gets none.
    pub(crate) fn grad_bounds(&self) -> Option<IV3> {
        self.is_closed().then_some([Interval::new(-1.0, 1.0); 3])
    }
}
