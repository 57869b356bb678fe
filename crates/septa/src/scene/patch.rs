//! A bicubic tensor-product (Bezier) patch as a height field, for
//! Bloomenthal's "blend to a patch" (4.8.4). The patch is
//! `P(s, t) = (x0 + s sx, y0 + t sy, h(s, t))`, `h = sum H_ij B_i(s) B_j(t)`
//! with cubic Bernstein `B`. Its function is the first-order signed distance
//! `(z - h) / sqrt(1 + h_x^2 + h_y^2)`: zero exactly on the patch, positive
//! above, with unit gradient on the patch. (Bloomenthal projects onto the
//! patch by Newton steps; only the zero set and the sign matter for the
//! arrangement, and this form has a closed-form gradient and interval bound.)
//! Outside the parameter square the polynomial is simply continued; the
//! scene's region rule decides where the patch ends (Bloomenthal's `Beyond`).

use super::interval::Interval;
use super::vec3::V3;

/// Bicubic height-field patch.
#[derive(Clone, Debug, PartialEq)]
pub struct BicubicPatch {
    /// Corner `(x0, y0)` of the parameter square in x, y.
    pub origin: [f64; 2],
    /// Side lengths `(sx, sy)` (positive).
    pub size: [f64; 2],
    /// Control heights `H[i][j]`, `i` along x, `j` along y.
    pub heights: [[f64; 4]; 4],
}

fn bern(s: f64) -> [f64; 4] {
    let r = 1.0 - s;
    [r * r * r, 3.0 * s * r * r, 3.0 * s * s * r, s * s * s]
}

fn bern_d1(s: f64) -> [f64; 4] {
    let r = 1.0 - s;
    [-3.0 * r * r, 3.0 * r * r - 6.0 * s * r, 6.0 * s * r - 3.0 * s * s, 3.0 * s * s]
}

fn bern_d2(s: f64) -> [f64; 4] {
    let r = 1.0 - s;
    [6.0 * r, 6.0 * s - 12.0 * r, 6.0 * r - 12.0 * s, 6.0 * s]
}

fn bern_iv(s: Interval) -> [Interval; 4] {
    let one = Interval::point(1.0);
    let r = one.sub(s);
    let r2 = r.sqr();
    let s2 = s.sqr();
    [r2.mul(r), s.mul(r2).scale(3.0), s2.mul(r).scale(3.0), s2.mul(s)]
}

fn bern_d1_iv(s: Interval) -> [Interval; 4] {
    let r = Interval::point(1.0).sub(s);
    let sr = s.mul(r);
    [
        r.sqr().scale(-3.0),
        r.sqr().scale(3.0).sub(sr.scale(6.0)),
        sr.scale(6.0).sub(s.sqr().scale(3.0)),
        s.sqr().scale(3.0),
    ]
}

fn bern_d2_iv(s: Interval) -> [Interval; 4] {
    let r = Interval::point(1.0).sub(s);
    [r.scale(6.0), s.scale(6.0).sub(r.scale(12.0)), r.scale(6.0).sub(s.scale(12.0)), s.scale(6.0)]
}

impl BicubicPatch {
    /// Enclosures of `h` and its parameter derivatives `h_s, h_t, h_ss,
    /// h_st, h_tt` over the parameter rectangle `s x t` (Bernstein sums in
    /// intervals; for the gradient enclosure).
    #[allow(clippy::needless_range_loop)]
    pub(crate) fn derivatives_iv(&self, s: Interval, t: Interval) -> [Interval; 6] {
        let comb = |a: [Interval; 4], b: [Interval; 4]| {
            let mut v = Interval::point(0.0);
            for i in 0..4 {
                for j in 0..4 {
                    v = v.add(a[i].mul(b[j]).scale(self.heights[i][j]));
                }
            }
            v
        };
        let (b0s, b1s, b2s) = (bern_iv(s), bern_d1_iv(s), bern_d2_iv(s));
        let (b0t, b1t, b2t) = (bern_iv(t), bern_d1_iv(t), bern_d2_iv(t));
        [comb(b0s, b0t), comb(b1s, b0t), comb(b0s, b1t), comb(b2s, b0t), comb(b1s, b1t), comb(b0s, b2t)]
    }

    fn st(&self, p: V3) -> (f64, f64) {
        ((p[0] - self.origin[0]) / self.size[0], (p[1] - self.origin[1]) / self.size[1])
    }

    #[allow(clippy::needless_range_loop)]
    fn combine(&self, a: [f64; 4], b: [f64; 4]) -> f64 {
        let mut v = 0.0;
        for i in 0..4 {
            for j in 0..4 {
                v += self.heights[i][j] * a[i] * b[j];
            }
        }
        v
    }

    /// Height `h` and its x, y derivatives at `p`.
    fn height(&self, p: V3) -> (f64, f64, f64) {
        let (s, t) = self.st(p);
        let (bs, bt) = (bern(s), bern(t));
        let h = self.combine(bs, bt);
        let hx = self.combine(bern_d1(s), bt) / self.size[0];
        let hy = self.combine(bs, bern_d1(t)) / self.size[1];
        (h, hx, hy)
    }

    /// The surface point at parameters `(s, t)`.
    pub fn point(&self, s: f64, t: f64) -> V3 {
        [self.origin[0] + s * self.size[0], self.origin[1] + t * self.size[1], self.combine(bern(s), bern(t))]
    }

    pub(crate) fn eval(&self, p: V3) -> f64 {
        let (h, hx, hy) = self.height(p);
        (p[2] - h) / (1.0 + hx * hx + hy * hy).sqrt()
    }

    pub(crate) fn gradient(&self, p: V3) -> V3 {
        let (s, t) = self.st(p);
        let (bs, bt) = (bern(s), bern(t));
        let (ds, dt) = (bern_d1(s), bern_d1(t));
        let (sx, sy) = (self.size[0], self.size[1]);
        let h = self.combine(bs, bt);
        let hx = self.combine(ds, bt) / sx;
        let hy = self.combine(bs, dt) / sy;
        let hxx = self.combine(bern_d2(s), bt) / (sx * sx);
        let hyy = self.combine(bs, bern_d2(t)) / (sy * sy);
        let hxy = self.combine(ds, dt) / (sx * sy);
        let w = (1.0 + hx * hx + hy * hy).sqrt();
        let e = p[2] - h;
        // d = e / w; d_x = -h_x / w - e (h_x h_xx + h_y h_xy) / w^3.
        let w3 = w * w * w;
        [-hx / w - e * (hx * hxx + hy * hxy) / w3, -hy / w - e * (hx * hxy + hy * hyy) / w3, 1.0 / w]
    }

    #[allow(clippy::needless_range_loop)]
    pub(crate) fn bounds(&self, lo: V3, hi: V3) -> Interval {
        let s = Interval::new(lo[0], hi[0]).sub(Interval::point(self.origin[0])).div(Interval::point(self.size[0]));
        let t = Interval::new(lo[1], hi[1]).sub(Interval::point(self.origin[1])).div(Interval::point(self.size[1]));
        let comb = |a: [Interval; 4], b: [Interval; 4]| {
            let mut v = Interval::point(0.0);
            for i in 0..4 {
                for j in 0..4 {
                    v = v.add(a[i].mul(b[j]).scale(self.heights[i][j]));
                }
            }
            v
        };
        let (bs, bt) = (bern_iv(s), bern_iv(t));
        let h = comb(bs, bt);
        let hx = comb(bern_d1_iv(s), bt).div(Interval::point(self.size[0]));
        let hy = comb(bs, bern_d1_iv(t)).div(Interval::point(self.size[1]));
        // Tighter: the control nets of h, h_x, h_y restricted to the box's
        // parameter rectangle (blossoms), whose hulls bound them (convex
        // hull property). Both enclosures are valid; keep their overlap.
        let (net_h, net_x, net_y) = self.restricted_nets(s, t);
        let h = meet(h, net_h);
        let hx = meet(hx, net_x.scale(1.0 / self.size[0]).pad(1e-15 * net_x.mag() / self.size[0]));
        let hy = meet(hy, net_y.scale(1.0 / self.size[1]).pad(1e-15 * net_y.mag() / self.size[1]));
        let w = Interval::point(1.0).add(hx.sqr()).add(hy.sqr()).sqrt();
        // This encloses the exact values (a different formula from eval's
        // and the blossom nets): pad by eval's rounding error (rounding.rs).
        let exact = Interval::new(lo[2], hi[2]).sub(h).div(w);
        let z_mag = lo[2].abs().max(hi[2].abs());
        exact.pad(self.eval_error(s, t, z_mag, exact))
    }

    /// Hulls of the Bezier nets of `h`, `dh/ds`, `dh/dt` restricted to the
    /// parameter rectangle `s x t`, padded for rounding.
    fn restricted_nets(&self, s: Interval, t: Interval) -> (Interval, Interval, Interval) {
        if !(s.lo.is_finite() && s.hi.is_finite() && t.lo.is_finite() && t.hi.is_finite()) {
            return (Interval::ENTIRE, Interval::ENTIRE, Interval::ENTIRE);
        }
        let h = self.heights;
        // Derivative nets: 3 (H[i+1][j] - H[i][j]) (degree 2 in s) and
        // 3 (H[i][j+1] - H[i][j]) (degree 2 in t).
        let ds: Vec<Vec<f64>> = (0..3).map(|i| (0..4).map(|j| 3.0 * (h[i + 1][j] - h[i][j])).collect()).collect();
        let dt: Vec<Vec<f64>> = (0..4).map(|i| (0..3).map(|j| 3.0 * (h[i][j + 1] - h[i][j])).collect()).collect();
        let full: Vec<Vec<f64>> = h.iter().map(|r| r.to_vec()).collect();
        let hull = |net: Vec<Vec<f64>>| {
            let net = restrict_2d(&net, s, t);
            let (lo, hi) =
                net.iter().flatten().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
            let m = net.iter().flatten().fold(0.0f64, |a, &x| a.max(x.abs()));
            // de Casteljau at parameters up to |u| grows rounding errors by
            // at most (1 + 2|u|)^6 ulps of the largest coefficient.
            let u = 1.0 + s.mag().max(t.mag());
            Interval::new(lo, hi).pad(64.0 * f64::EPSILON * (1.0 + 2.0 * u).powi(6) * m)
        };
        (hull(full), hull(ds), hull(dt))
    }
}

/// Overlap of two enclosures of the same quantity.
fn meet(a: Interval, b: Interval) -> Interval {
    Interval::new(a.lo.max(b.lo), a.hi.min(b.hi))
}

/// Blossom of a Bezier polynomial with coefficients `c` at `u[0..n]`
/// (de Casteljau with a different parameter per level).
fn blossom(c: &[f64], u: &[f64]) -> f64 {
    let mut b = c.to_vec();
    for (level, &x) in u.iter().enumerate() {
        for i in 0..b.len() - 1 - level {
            b[i] = (1.0 - x) * b[i] + x * b[i + 1];
        }
    }
    b[0]
}

/// Bezier coefficients of the same polynomial over `[a, b]` (rescaled to
/// `[0, 1]`): the blossom at `(a, .., a, b, .., b)`.
fn restrict(c: &[f64], a: f64, b: f64) -> Vec<f64> {
    let n = c.len() - 1;
    (0..=n).map(|i| blossom(c, &[vec![a; n - i], vec![b; i]].concat())).collect()
}

/// Restrict a tensor net `net[i][j]` (i along s, j along t).
fn restrict_2d(net: &[Vec<f64>], s: Interval, t: Interval) -> Vec<Vec<f64>> {
    let (ni, nj) = (net.len(), net[0].len());
    let cols: Vec<Vec<f64>> =
        (0..nj).map(|j| restrict(&(0..ni).map(|i| net[i][j]).collect::<Vec<_>>(), s.lo, s.hi)).collect();
    (0..ni).map(|i| restrict(&(0..nj).map(|j| cols[j][i]).collect::<Vec<_>>(), t.lo, t.hi)).collect()
}
