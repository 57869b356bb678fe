//! Interval enclosures of gradients over a box, for the first-order
//! (mean value) bound of a *difference* of two functions. The material
//! interface test of sparse evaluation needs `f_i - f_j > 0` on a block;
//! bounding each function separately loses the fact that far from their
//! sites both gradients nearly agree, so their difference varies little.

use super::interval::Interval;
use super::interval_vec::{hull3, point3, scale3, IV3};
use super::primitive::Primitive;
use super::vec3::V3;

/// Relative widening of every gradient enclosure, so that it also holds
/// the *computed* analytic gradient ([`Primitive::gradient`], a few
/// roundings away from the exact one) wherever the gradient's own formula
/// does not cancel badly (within about 1e-3 of a cylinder's or torus's
/// axis relative to the coordinates' size, the computed direction can err
/// by more).
const GRAD_PAD: f64 = 1e-12;

impl Primitive {
    /// An enclosure of every gradient of the function over the box `[lo,
    /// hi]`, and of every Clarke generalized gradient where it has a kink
    /// (the convex hull of the limits of nearby gradients: at a sphere's
    /// centre the unit ball, where `max` switches the hull of both sides'),
    /// or `None` when there is none to give (an open triangle mesh).
    ///
    /// Each component is an [`Interval`] with outward rounding. Away from
    /// kinks the enclosure tightens linearly as the box shrinks (width
    /// about the Hessian's size times the box's), which is what the
    /// adaptive criterion needs (a gradient cone bounded away from 0 on a
    /// small enough box). Boxes holding a kink keep the hull.
    ///
    /// ```
    /// use septa::scene::Primitive;
    /// let s = Primitive::sphere([0.0; 3], 1.0);
    /// let g = s.gradient_bounds([0.9, -0.01, -0.01], [1.1, 0.01, 0.01]).unwrap();
    /// assert!(g[0].hi < -0.99 && g[1].contains(0.0));
    /// let c = s.gradient_bounds([-0.1; 3], [0.1; 3]).unwrap(); // holds the centre
    /// assert!(c[0].lo <= -1.0 && c[0].hi >= 1.0);
    /// ```
    pub fn gradient_bounds(&self, lo: V3, hi: V3) -> Option<[Interval; 3]> {
        use Primitive::*;
        let g: IV3 = match self {
            Constant(_) => point3([0.0; 3]),
            Plane(p) => point3(p.normal),
            HalfSpace(p) => point3(p.normal.map(|x| -x)),
            Sphere(s) => s.grad_bounds(lo, hi),
            Ellipsoid(s) => s.grad_bounds(lo, hi),
            Box(s) => s.grad_bounds(lo, hi),
            Cylinder(s) => s.grad_bounds(lo, hi),
            CappedCylinder(s) => s.grad_bounds(lo, hi),
            Cone(s) => s.grad_bounds(lo, hi),
            Torus(s) => s.grad_bounds(lo, hi),
            Capsule(s) => s.grad_bounds(lo, hi),
            Points(s) => s.grad_bounds(lo, hi),
            Mesh(m) => m.grad_bounds()?,
            Patch(s) => s.grad_bounds(lo, hi),
            Wyvill(s) => s.grad_bounds(lo, hi),
            ClosedForm(s) => s.grad_bounds(lo, hi),
            Rbf(s) => s.grad_bounds(lo, hi),
            Transform(t) => t.grad_bounds(lo, hi)?,
            Sum(ts) => {
                let mut acc = point3([0.0; 3]);
                for t in ts {
                    acc = super::interval_vec::add3(acc, t.gradient_bounds(lo, hi)?);
                }
                acc
            }
            Scale(k, t) => scale3(t.gradient_bounds(lo, hi)?, *k),
            Abs(t) => {
                // |g|: the sign of g where it is known, both where it may be 0.
                let v = t.bounds_interval(lo, hi);
                let g = t.gradient_bounds(lo, hi)?;
                if v.lo > 0.0 {
                    g
                } else if v.hi < 0.0 {
                    scale3(g, -1.0)
                } else {
                    hull3(g, scale3(g, -1.0))
                }
            }
            Min(ts) => extreme_gradient(ts, lo, hi, false)?,
            Max(ts) => extreme_gradient(ts, lo, hi, true)?,
        };
        Some(g.map(|x| x.pad(GRAD_PAD * (1.0 + x.mag().min(f64::MAX)))))
    }
}

/// The hull of the gradient enclosures of the terms that can be the
/// extreme somewhere in the box (by their value bounds): every gradient of
/// `max`/`min`, and its Clarke gradients where terms tie.
fn extreme_gradient(terms: &[Primitive], lo: V3, hi: V3, max: bool) -> Option<IV3> {
    let b: Vec<Interval> = terms.iter().map(|t| t.bounds_interval(lo, hi)).collect();
    let mut out: Option<IV3> = None;
    if max {
        let best = b.iter().map(|x| x.lo).fold(f64::NEG_INFINITY, f64::max);
        for (t, v) in terms.iter().zip(&b) {
            if v.hi >= best {
                let g = t.gradient_bounds(lo, hi)?;
                out = Some(out.map_or(g, |o| hull3(o, g)));
            }
        }
    } else {
        let best = b.iter().map(|x| x.hi).fold(f64::INFINITY, f64::min);
        for (t, v) in terms.iter().zip(&b) {
            if v.lo <= best {
                let g = t.gradient_bounds(lo, hi)?;
                out = Some(out.map_or(g, |o| hull3(o, g)));
            }
        }
    }
    out
}

/// A lower bound of the *computed* `f.eval(p) - g.eval(p)` over the box
/// (rounding included): the better of `lo(f) - hi(g)` and the mean value
/// form `(f - g)(c) - |grad(f - g)| r` around the box centre `c`.
pub(crate) fn difference_lower(f: &Primitive, g: &Primitive, lo: V3, hi: V3) -> f64 {
    let bf = f.bounds_interval(lo, hi);
    let bg = g.bounds_interval(lo, hi);
    let mut best = bf.sub(bg).lo;
    if let (Some(gf), Some(gg)) = (f.gradient_bounds(lo, hi), g.gradient_bounds(lo, hi)) {
        // Centred form: D(p) - D(c) = grad D(xi) . (p - c) with xi in the box.
        let c = [0, 1, 2].map(|a| 0.5 * (lo[a] + hi[a]));
        let mut var = Interval::point(0.0);
        for a in 0..3 {
            let h = (hi[a] - c[a]).max(c[a] - lo[a]) * (1.0 + 1e-15);
            var = var.add(gf[a].sub(gg[a]).abs().mul(Interval::point(h)));
        }
        // The mean value form holds for the exact functions; the computed
        // values at `c` and at the point each differ from them by at most
        // eval_error (rounding.rs).
        if let (Some(ef), Some(eg)) = (f.eval_error(lo, hi), g.eval_error(lo, hi)) {
            let err = 2.0 * (ef + eg);
            let at_c = Interval::point(f.eval(c)).sub(Interval::point(g.eval(c)));
            let mv = at_c.sub(Interval::point(var.hi)).pad(err).lo;
            if mv.is_finite() {
                best = best.max(mv);
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// `difference_lower` is below `f - g` at every sample of the box,
    /// and it is sharp enough to be useful (often positive when the true
    /// minimum is).
    #[test]
    fn difference_lower_is_a_lower_bound() {
        let mut rng = ChaCha8Rng::seed_from_u64(4);
        let mut rp = |r: f64| [0, 1, 2].map(|_| rng.gen_range(-r..r));
        let fs = [
            Primitive::sphere(rp(0.8), 0.2),
            Primitive::sphere(rp(0.8), 0.05),
            Primitive::sphere(rp(0.8), 0.3),
            Primitive::line(rp(0.5), rp(1.0)),
            Primitive::cylinder(rp(0.5), rp(1.0), 0.1),
            Primitive::plane(rp(0.5), rp(1.0)),
            Primitive::half_space(rp(0.5), rp(1.0)),
            Primitive::Constant(0.1),
        ];
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let (mut useful, mut positive) = (0, 0);
        for _ in 0..4000 {
            let i = rng.gen_range(0..fs.len());
            let j = rng.gen_range(0..fs.len());
            let c: V3 = [0, 1, 2].map(|_| rng.gen_range(-1.0..1.0));
            let h = 10f64.powf(rng.gen_range(-10.0..-0.5));
            let (lo, hi) = (c.map(|x| x - h), c.map(|x| x + h));
            let bound = difference_lower(&fs[i], &fs[j], lo, hi);
            let n = 6;
            let mut min = f64::INFINITY;
            for x in 0..=n {
                for y in 0..=n {
                    for z in 0..=n {
                        let t = [x, y, z];
                        let p =
                            [0, 1, 2].map(|a| if t[a] == n { hi[a] } else { lo[a] + 2.0 * h * t[a] as f64 / n as f64 });
                        min = min.min(fs[i].eval(p) - fs[j].eval(p));
                    }
                }
            }
            assert!(bound <= min, "pair {i} {j}: bound {bound} above sampled min {min}");
            if min > 0.0 {
                positive += 1;
                if bound > 0.0 {
                    useful += 1;
                }
            }
        }
        assert!(useful * 10 > positive * 8, "{useful} of {positive}");
    }
}
