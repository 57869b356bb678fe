//! Interval 3-vectors for gradient enclosures (`gradbound*.rs`): boxes of
//! vectors, their unit directions, linear maps and hulls. Every function
//! returns an enclosure of the exact set it names, with outward rounding.

use super::interval::Interval;
use super::vec3::V3;

/// A box of vectors: one interval per component.
pub(crate) type IV3 = [Interval; 3];

/// The single vector `v`.
pub(crate) fn point3(v: V3) -> IV3 {
    v.map(Interval::point)
}

/// The box `[lo, hi]` as intervals.
pub(crate) fn box3(lo: V3, hi: V3) -> IV3 {
    [0, 1, 2].map(|i| Interval::new(lo[i], hi[i]))
}

/// Component-wise sum.
pub(crate) fn add3(a: IV3, b: IV3) -> IV3 {
    [0, 1, 2].map(|i| a[i].add(b[i]))
}

/// Component-wise difference.
pub(crate) fn sub3(a: IV3, b: IV3) -> IV3 {
    [0, 1, 2].map(|i| a[i].sub(b[i]))
}

/// Every component times the interval `k`.
pub(crate) fn mul3(a: IV3, k: Interval) -> IV3 {
    a.map(|x| x.mul(k))
}

/// Every component times the constant `k`.
pub(crate) fn scale3(a: IV3, k: f64) -> IV3 {
    a.map(|x| x.scale(k))
}

/// Component-wise hull.
pub(crate) fn hull3(a: IV3, b: IV3) -> IV3 {
    [0, 1, 2].map(|i| a[i].hull(b[i]))
}

/// Component-wise overlap of two enclosures of the same set.
pub(crate) fn meet3(a: IV3, b: IV3) -> IV3 {
    [0, 1, 2].map(|i| a[i].meet(b[i]))
}

/// Sum of squares: the exact range of `|v|^2` over a box (each component
/// appears once).
pub(crate) fn norm2(v: IV3) -> Interval {
    v[0].sqr().add(v[1].sqr()).add(v[2].sqr())
}

/// Dot product of a box with an interval box.
pub(crate) fn dot3i(a: IV3, b: IV3) -> Interval {
    a[0].mul(b[0]).add(a[1].mul(b[1])).add(a[2].mul(b[2]))
}

/// `m v` for a constant matrix `m` (rows): each component a sum in which
/// every interval appears once, so it is the exact range over the box.
pub(crate) fn mat_vec3(m: &[[f64; 3]; 3], v: IV3) -> IV3 {
    [0, 1, 2].map(|i| v[0].scale(m[i][0]).add(v[1].scale(m[i][1])).add(v[2].scale(m[i][2])))
}

/// `m^T v` for a constant matrix `m`.
pub(crate) fn mat_t_vec3(m: &[[f64; 3]; 3], v: IV3) -> IV3 {
    [0, 1, 2].map(|i| v[0].scale(m[0][i]).add(v[1].scale(m[1][i])).add(v[2].scale(m[2][i])))
}

/// The projector `I - a a^T` onto the plane normal to the unit `a`.
pub(crate) fn perp_projector(a: V3) -> [[f64; 3]; 3] {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| if i == j { 1.0 - a[i] * a[j] } else { -a[i] * a[j] }))
}

/// The range of one component `x / sqrt(x^2 + s)` of a unit vector over
/// `x` in `x_iv` and `s` (the other components' squared norm) in `s_iv`:
/// increasing in `x`; in `s`, decreasing where `x > 0` and increasing
/// where `x < 0`. So the extremes are at the ends, with the end of `s`
/// that pulls towards zero: the exact range, up to outward rounding.
pub(crate) fn unit_component(x: Interval, s: Interval) -> Interval {
    let one = Interval::new(-1.0, 1.0);
    if !(x.lo.is_finite() && x.hi.is_finite() && s.hi.is_finite()) {
        return one;
    }
    if s.hi <= 0.0 {
        // The other components are 0: the direction is the sign of x
        // (the zero vector itself is no direction; alone, it allows all).
        return match (x.lo >= 0.0, x.hi <= 0.0) {
            (true, true) => one,
            (true, false) => Interval::point(1.0),
            (false, true) => Interval::point(-1.0),
            (false, false) => one,
        };
    }
    let s_lo = Interval::point(s.lo.max(0.0));
    let s_hi = Interval::point(s.hi);
    let ratio = |v: f64, rest: Interval| -> Interval {
        if v == 0.0 {
            return Interval::point(0.0);
        }
        let v = Interval::point(v);
        let d = v.sqr().add(rest).sqrt();
        v.div(d)
    };
    // Largest value: at x.hi, with the least s if x.hi > 0, else the most.
    let hi = ratio(x.hi, if x.hi > 0.0 { s_lo } else { s_hi }).hi;
    let lo = ratio(x.lo, if x.lo < 0.0 { s_lo } else { s_hi }).lo;
    Interval::new(lo.max(-1.0), hi.min(1.0)).meet(one)
}

/// An enclosure of `{v / |v| : v in the box, v != 0}`, component by
/// component (exact per component, up to rounding). A box holding the
/// zero vector gives every direction it allows, which is also the Clarke
/// gradient set of `|v|` at 0 intersected with the box's cone: this is
/// what the enclosures of distance gradients need at their kinks.
pub(crate) fn unit3(v: IV3) -> IV3 {
    let sq = v.map(|x| x.sqr());
    [0, 1, 2].map(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        // Exactly zero components stay exactly zero (the outward rounding
        // of a sum would make them a subnormal, and a face direction loose).
        let zero = Interval::point(0.0);
        let rest = match (v[j] == zero, v[k] == zero) {
            (true, true) => zero,
            (true, false) => sq[k],
            (false, true) => sq[j],
            (false, false) => sq[j].add(sq[k]),
        };
        unit_component(v[i], rest)
    })
}

/// The sign of `x` over an interval: `[-1, -1]`, `[1, 1]` or `[-1, 1]`
/// (the Clarke derivative of `|x|`, with 0 inside when `x` may be 0).
pub(crate) fn sign_iv(x: Interval) -> Interval {
    if x.lo > 0.0 {
        Interval::point(1.0)
    } else if x.hi < 0.0 {
        Interval::point(-1.0)
    } else {
        Interval::new(-1.0, 1.0)
    }
}

/// The box `[lo, hi]` minus the point `c`.
pub(crate) fn offset3(lo: V3, hi: V3, c: V3) -> IV3 {
    sub3(box3(lo, hi), point3(c))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// `unit3` holds every sampled direction of random boxes, including
    /// boxes through the origin and boxes flat in one component, and is
    /// exact at the box's corners where the extremes lie.
    #[test]
    fn unit3_encloses_directions() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        for _ in 0..3000 {
            let c: V3 = [0, 1, 2].map(|_| rng.gen_range(-1.0..1.0));
            let h = 10f64.powf(rng.gen_range(-9.0..0.3));
            let mut lo = c.map(|x| x - h * rng.gen_range(0.0..1.0));
            let hi = c.map(|x| x + h * rng.gen_range(0.0..1.0));
            if rng.gen_bool(0.2) {
                lo[0] = hi[0];
            }
            let u = unit3(box3(lo, hi));
            for _ in 0..30 {
                let p: V3 = [0, 1, 2].map(|a| if lo[a] == hi[a] { lo[a] } else { rng.gen_range(lo[a]..=hi[a]) });
                let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                if n == 0.0 {
                    continue;
                }
                for a in 0..3 {
                    assert!(u[a].contains(p[a] / n), "{lo:?} {hi:?}: {p:?} gives {} outside {:?}", p[a] / n, u[a]);
                }
            }
        }
        let u = unit3(box3([-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]));
        assert!(u.iter().all(|x| x.lo == -1.0 && x.hi == 1.0));
        let u = unit3(box3([1.0, 0.0, 0.0], [1.0, 0.0, 0.0]));
        assert!(u[0].contains(1.0) && u[0].width() < 1e-15 && u[1] == Interval::point(0.0));
    }
}
