//! What the criterion knows of one function on one tet (a *term*): its
//! computed values at the corners, enclosures of its values and gradients
//! over the tet's bounding box, and the gradient of its linear interpolant.
//!
//! For a material interface the terms are the differences `f_i - f_j` of
//! the functions that can win in the tet (Du et al. Sec. 3: the interface
//! of materials i and j is where `f_i = f_j` is the maximum).

use crate::scene::{Interval, Primitive};

/// A point or vector.
pub type V3 = [f64; 3];

/// The tet the criterion looks at.
pub struct Tet {
    /// Corners, positively oriented.
    pub p: [V3; 4],
    /// Bounding box.
    pub lo: V3,
    /// Bounding box.
    pub hi: V3,
}

impl Tet {
    /// The tet with corners `p`.
    pub fn new(p: [V3; 4]) -> Tet {
        let mut lo = p[0];
        let mut hi = p[0];
        for q in &p[1..] {
            for k in 0..3 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
        Tet { p, lo, hi }
    }

    /// The box's centre.
    pub fn centre(&self) -> V3 {
        [0, 1, 2].map(|k| 0.5 * (self.lo[k] + self.hi[k]))
    }

    /// The longest edge's length (the diameter of a tet).
    pub fn diameter(&self) -> f64 {
        let mut d: f64 = 0.0;
        for (a, b) in super::lattice::EDGES {
            d = d.max(norm(sub(self.p[b], self.p[a])));
        }
        d
    }

    /// Bounding box of some corners.
    pub fn sub_box(&self, corners: &[usize]) -> (V3, V3) {
        let mut lo = self.p[corners[0]];
        let mut hi = lo;
        for &c in &corners[1..] {
            for k in 0..3 {
                lo[k] = lo[k].min(self.p[c][k]);
                hi[k] = hi[k].max(self.p[c][k]);
            }
        }
        (lo, hi)
    }
}

/// A term's function, for enclosures on the parts of a tet (its edges and
/// faces): one primitive (IA) or the difference of two (MI).
#[derive(Clone, Copy)]
pub enum Local<'a> {
    /// `f`.
    One(&'a Primitive),
    /// `f - g`.
    Diff(&'a Primitive, &'a Primitive),
}

impl Local<'_> {
    /// Values over the box.
    pub fn bound(&self, lo: V3, hi: V3) -> Interval {
        match self {
            Local::One(f) => f.bounds_interval(lo, hi),
            Local::Diff(f, g) => f.bounds_interval(lo, hi).sub(g.bounds_interval(lo, hi)),
        }
    }

    /// Whether the function is affine (a plane, half-space or constant, or
    /// a difference of two): its interpolant is itself.
    pub fn affine(&self) -> bool {
        use Primitive::{Constant, HalfSpace, Plane};
        let one = |f: &Primitive| matches!(f, Plane(_) | HalfSpace(_) | Constant(_));
        match self {
            Local::One(f) => one(f),
            Local::Diff(f, g) => one(f) && one(g),
        }
    }

    /// The computed value at `p` with a bound on its rounding error.
    pub fn eval(&self, p: V3, lo: V3, hi: V3) -> Interval {
        let one = |f: &Primitive| {
            let v = f.eval(p);
            let e = f.eval_error(lo, hi).unwrap_or(f64::INFINITY);
            Interval::new(v - e, v + e)
        };
        match self {
            Local::One(f) => one(f),
            Local::Diff(f, g) => one(f).sub(one(g)),
        }
    }

    /// Gradients over the box.
    pub fn grad(&self, lo: V3, hi: V3) -> Option<[Interval; 3]> {
        match self {
            Local::One(f) => f.gradient_bounds(lo, hi),
            Local::Diff(f, g) => {
                let (a, b) = (f.gradient_bounds(lo, hi)?, g.gradient_bounds(lo, hi)?);
                Some([0, 1, 2].map(|k| a[k].sub(b[k])))
            }
        }
    }
}

/// One function (or difference of two) on one tet.
pub struct Term {
    /// The computed values at the corners (what the extraction uses).
    pub vals: [f64; 4],
    /// Values over the bounding box.
    pub bound: Interval,
    /// Gradients of the function over the bounding box.
    pub g: [Interval; 3],
    /// `g` widened to hold the interpolant's gradient too, so it holds the
    /// gradient of every `(1 - t) L + t f` (the homotopy of docs/adaptive.md).
    pub gp: [Interval; 3],
    /// The interpolant's gradient (padded for its rounding).
    pub gl: [Interval; 3],
    /// The value at the box's centre (computed, rounding included) hulled
    /// with the interpolant's there.
    pub at_centre: Interval,
    /// A bound on the rounding of the corner values.
    pub rounding: f64,
    /// The function is affine, so its interpolant is itself.
    pub affine: bool,
}

impl Term {
    /// Builds a term from its parts; `None` when the gradient has no
    /// enclosure or the interpolant's gradient is not finite.
    pub fn new(
        tet: &Tet,
        vals: [f64; 4],
        bound: Interval,
        g: [Interval; 3],
        fc: Interval,
        rounding: f64,
        affine: bool,
    ) -> Option<Term> {
        let gl = interpolant_gradient(&tet.p, &vals)?;
        let scale = gl.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        // The 3x3 solve in doubles: a relative pad far above its error on
        // the bounded shapes bisection makes (condition numbers below 10).
        let pad = 1e-9 * scale + f64::MIN_POSITIVE;
        let gl_iv = gl.map(|x| Interval::new(x - pad, x + pad));
        let gp = [0, 1, 2].map(|k| g[k].hull(gl_iv[k]));
        let c = tet.centre();
        let lc = vals[0] + dot(gl, sub(c, tet.p[0]));
        let lc = Interval::new(
            lc - pad * norm(sub(c, tet.p[0])) - 1e-12 * lc.abs(),
            lc + pad * norm(sub(c, tet.p[0])) + 1e-12 * lc.abs(),
        );
        Some(Term { vals, bound, g, gp, gl: gl_iv, at_centre: fc.hull(lc), rounding, affine })
    }

    /// Whether the zero set can meet the tet.
    pub fn crosses(&self) -> bool {
        self.bound.contains(0.0)
    }
}

/// The gradient of the linear interpolant of `vals` on the tet.
pub fn interpolant_gradient(p: &[V3; 4], vals: &[f64; 4]) -> Option<V3> {
    let e = [sub(p[1], p[0]), sub(p[2], p[0]), sub(p[3], p[0])];
    let df = [vals[1] - vals[0], vals[2] - vals[0], vals[3] - vals[0]];
    // Cramer's rule on e g = df.
    let det = dot(e[0], cross(e[1], e[2]));
    let col = |i: usize| {
        let mut m = e;
        for r in 0..3 {
            m[r][i] = df[r];
        }
        dot(m[0], cross(m[1], m[2])) / det
    };
    let g = [col(0), col(1), col(2)];
    g.iter().all(|x| x.is_finite()).then_some(g)
}

/// Value, rounding bound and gradient enclosure of one primitive on a box.
pub fn primitive_parts(f: &Primitive, lo: V3, hi: V3) -> Option<(Interval, [Interval; 3], f64)> {
    let g = f.gradient_bounds(lo, hi)?;
    let b = f.bounds_interval(lo, hi);
    let err = f.eval_error(lo, hi).unwrap_or(f64::INFINITY);
    Some((b, g, err))
}

pub(crate) fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(crate) fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn cross(a: V3, b: V3) -> V3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

pub(crate) fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}

/// `v . G` over the box `G`, outward rounded.
pub(crate) fn dot_iv(v: V3, g: &[Interval; 3]) -> Interval {
    g[0].scale(v[0]).add(g[1].scale(v[1])).add(g[2].scale(v[2]))
}

/// The smallest absolute value in an interval.
pub(crate) fn mig(x: Interval) -> f64 {
    if x.lo > 0.0 {
        x.lo
    } else if x.hi < 0.0 {
        -x.hi
    } else {
        0.0
    }
}

/// The largest norm of a vector in the box.
pub(crate) fn max_norm(g: &[Interval; 3]) -> f64 {
    (g[0].mag().powi(2) + g[1].mag().powi(2) + g[2].mag().powi(2)).sqrt() * (1.0 + 1e-15)
}

/// The Euclidean norm of the box's half-widths: every vector of the box is
/// within it of the box's centre.
pub(crate) fn radius(g: &[Interval; 3]) -> f64 {
    let h = |x: Interval| 0.5 * (x.hi - x.lo);
    (h(g[0]).powi(2) + h(g[1]).powi(2) + h(g[2]).powi(2)).sqrt() * (1.0 + 1e-15)
}

/// The interval cross product of two boxes.
pub(crate) fn cross_iv(a: &[Interval; 3], b: &[Interval; 3]) -> [Interval; 3] {
    [a[1].mul(b[2]).sub(a[2].mul(b[1])), a[2].mul(b[0]).sub(a[0].mul(b[2])), a[0].mul(b[1]).sub(a[1].mul(b[0]))]
}

/// An enclosure of `a + s b` (`s` = 1 or -1) over a box by the centred
/// form: its computed value at the centre and its gradients over the box.
pub fn centred_combo(a: Local<'_>, b: Local<'_>, s: f64, lo: V3, hi: V3) -> Option<Interval> {
    let c = [0, 1, 2].map(|k| 0.5 * (lo[k] + hi[k]));
    let (ga, gb) = (a.grad(lo, hi)?, b.grad(lo, hi)?);
    let mut v = a.eval(c, lo, hi).add(b.eval(c, lo, hi).scale(s));
    for k in 0..3 {
        let h = 0.5 * (hi[k] - lo[k]) * (1.0 + 1e-15);
        v = v.add(ga[k].add(gb[k].scale(s)).mul(Interval::new(-h, h)));
    }
    Some(v)
}
