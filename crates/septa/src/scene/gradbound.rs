//! Interval enclosures of gradients over a box, for the first-order
//! (mean value) bound of a *difference* of two functions. The material
//! interface test of sparse evaluation needs `f_i - f_j > 0` on a block;
//! bounding each function separately loses the fact that far from their
//! sites both gradients nearly agree, so their difference varies little.

use super::interval::{offset_box, Interval};
use super::primitive::Primitive;
use super::shapes::{lipschitz, SphereKind};
use super::vec3::{box_center_radius, norm, sub, V3};

impl Primitive {
    /// An enclosure of every gradient (every Clarke gradient at kinks) of
    /// the function over the box, or `None` when the primitive has none.
    pub(crate) fn gradient_bounds(&self, lo: V3, hi: V3) -> Option<[Interval; 3]> {
        let pt = |v: V3| v.map(Interval::point);
        match self {
            Primitive::Constant(_) => Some(pt([0.0; 3])),
            Primitive::Plane(p) => Some(pt(p.normal)),
            Primitive::HalfSpace(p) => Some(pt(p.normal.map(|x| -x))),
            Primitive::Sphere(s) if s.kind == SphereKind::Signed => {
                // -(p - c)/|p - c| for p in the ball of radius R around the
                // box centre m: a cone of half-angle asin(R/d) around
                // a = (m - c)/d, so each component is within the chord
                // 2 sin(angle/2) of -a.
                let (m, r) = box_center_radius(lo, hi);
                let v = sub(m, s.center);
                let d = norm(v);
                if d.is_nan() || d <= r * (1.0 + 1e-12) {
                    return Some([Interval::new(-1.0, 1.0); 3]);
                }
                let sin = (r / d).min(1.0);
                // 2 sin(t/2) = s sqrt(2 / (1 + cos t)): no cancellation for small s.
                let cos = (1.0 - sin * sin).max(0.0).sqrt();
                let chord = sin * (2.0 / (1.0 + cos)).sqrt() * (1.0 + 1e-12) + 1e-15;
                Some(v.map(|x| Interval::point(-x / d).pad(chord)))
            }
            Primitive::Sphere(s) if s.kind == SphereKind::Squared => {
                Some(offset_box(lo, hi, s.center).map(|x| x.scale(-2.0)))
            }
            Primitive::Cylinder(c) if !c.squared => {
                let o = offset_box(lo, hi, c.point);
                let t = o[0].scale(c.axis[0]).add(o[1].scale(c.axis[1])).add(o[2].scale(c.axis[2]));
                let perp = [0, 1, 2].map(|a| o[a].sub(t.scale(c.axis[a])));
                // Encloses the exact distance to the axis (rounding.rs).
                let err = c.rho_error(super::rounding::box_mag(lo, hi));
                let rho = lipschitz(|p| norm(c.perp(p)), 1.0, lo, hi, err);
                Some(perp.map(|x| x.div(rho).neg()))
            }
            _ => None,
        }
    }
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
