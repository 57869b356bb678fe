//! Value and gradient enclosures of a Hermite RBF over a box, and its
//! rounding errors (`rbf.rs` has the function).
//!
//! The terms of an RBF fitted to a surface are large (coefficients of
//! size 10 times `r^3`) and cancel to a function of size 1, so bounding the
//! terms one by one, or cluster by cluster, gives enclosures as wide as
//! the terms: linear in the box, but with a constant 1e5 times the true
//! Hessian. The enclosures here are centred forms instead:
//!
//! - gradient: `grad f(m) + H (p - m)` with `H` an enclosure of every
//!   Hessian over the box, itself centred: `Hess f(m) + T (q - m)` with `T`
//!   enclosing the third derivatives, per cluster of centres, from the
//!   cluster's sums of positive and of negative coefficients times the
//!   range of the kernel's third derivative over the box minus the
//!   cluster's box. Near a centre the Hermite term's third derivative
//!   grows like `1/r` (and its Hessian jumps at the centre), so each
//!   cluster's centred Hessian is met with its plain Hessian bound, which
//!   stays valid there. So `H` is `Hess f(m)` plus `O(h)`, and the gradient
//!   enclosure `grad f(m) + Hess f(m) (p - m) + O(h^2)`: tight.
//! - value: `f(m) + G . (p - m)` with that gradient enclosure `G`.
//!
//! Each is also met with the per-cluster enclosure of the quantity itself,
//! which is the better one for large boxes.

use super::closed_form::mean_value;
use super::interval::Interval;
use super::interval_vec::*;
use super::rbf::{agg, Cluster, HermiteRbf};
use super::rounding::U;
use super::vec3::{dot, norm, sub, V3};

type M3 = [[Interval; 3]; 3];

fn delta(j: usize, k: usize) -> Interval {
    Interval::point(if j == k { 1.0 } else { 0.0 })
}

/// `U_j U_k`, tight on the diagonal.
fn uu(u: &IV3, j: usize, k: usize) -> Interval {
    if j == k {
        u[j].sqr()
    } else {
        u[j].mul(u[k])
    }
}

impl HermiteRbf {
    /// Each cluster with the box of offsets `p - x` (box minus the
    /// cluster's box) and the range of their lengths.
    fn offsets(&self, lo: V3, hi: V3) -> impl Iterator<Item = (&Cluster, IV3, Interval)> {
        let bx = box3(lo, hi);
        self.clusters.iter().map(move |c| {
            let d = sub3(bx, box3(c.lo, c.hi));
            let r = norm2(d).sqrt();
            (c, d, r)
        })
    }

    /// Error bounds `(value, gradient)` of the computed sums over the box.
    /// Each term is a dozen roundings of quantities no larger than its own
    /// magnitude bound (`|a| r^3 + 3 |b| r^2`; gradient `3 |a| r^2 + 6 |b|
    /// r`), so it errs by at most `16u` of it; the compensated sum adds at
    /// most `2u` of the total plus `4 N u^2` of the sum of magnitudes
    /// (Neumaier; Higham, Accuracy and Stability, 4.3). With `S` the sum of
    /// the terms' magnitudes: `(18u + 4 N u^2) S`, and twice that for margin.
    fn errors(&self, lo: V3, hi: V3) -> (f64, f64) {
        let (mut sv, mut sg) = (0.0, 0.0);
        for (c, _, r) in self.offsets(lo, hi) {
            let r = r.hi;
            sv += c.abs.0 * r * r * r + 3.0 * c.abs.1 * r * r;
            sg += 3.0 * c.abs.0 * r * r + 6.0 * c.abs.1 * r;
        }
        let pm = super::rounding::box_mag(lo, hi);
        let poly = self.poly[0].abs() + pm * (self.poly[1].abs() + self.poly[2].abs() + self.poly[3].abs());
        let k = 2.0 * (18.0 * U + 4.0 * (self.len() as f64 + 2.0) * U * U);
        (k * (sv + poly), k * (sg + poly))
    }

    /// A bound on `|eval - exact|` over the box.
    pub(crate) fn eval_error(&self, lo: V3, hi: V3) -> f64 {
        self.errors(lo, hi).0
    }

    /// An enclosure of the cluster's Hessians over the offsets `d`: with
    /// `r = |d|`, `u = d / r`, `3 a r (I + u u^T) + 3 (b u^T + u b^T + (b .
    /// u)(I - u u^T))`. (At `d = 0` the Hermite term's Hessian jumps; its
    /// gradient is Lipschitz there and `u` ranging over all directions
    /// holds its Clarke Jacobian.)
    fn cluster_hessian_bound(c: &Cluster, u: &IV3, r: Interval) -> M3 {
        let mut h = [[Interval::point(0.0); 3]; 3];
        for j in 0..3 {
            for k in j..3 {
                let q = uu(u, j, k);
                let mut e = agg(c.a, r.mul(delta(j, k).add(q)));
                e = e.add(agg(c.b[j], u[k])).add(agg(c.b[k], u[j]));
                let proj = delta(j, k).sub(q);
                for l in 0..3 {
                    e = e.add(agg(c.b[l], u[l].mul(proj)));
                }
                h[j][k] = e.scale(3.0);
                h[k][j] = h[j][k];
            }
        }
        h
    }

    /// `sum_l T_jkl s_l` for an enclosure `T` of the cluster's third
    /// derivatives over the offsets (`None` when the box may reach a
    /// centre, where they are unbounded): `3 a (u_l d_jk + d_jl u_k + u_j
    /// d_kl - u_j u_k u_l)` and `(3 / r) (b_k P_jl + b_j P_kl + (sum_m b_m
    /// P_ml) P_jk - (b . u)(P_jl u_k + u_j P_kl))`, `P = I - u u^T`.
    fn cluster_third_times(c: &Cluster, u: &IV3, r: Interval, s: &IV3) -> Option<M3> {
        if r.lo <= 0.0 {
            return None;
        }
        let inv_r = Interval::point(1.0).div(r);
        let p = |j: usize, k: usize| delta(j, k).sub(uu(u, j, k));
        let mut out = [[Interval::point(0.0); 3]; 3];
        for j in 0..3 {
            for k in j..3 {
                let mut acc = Interval::point(0.0);
                for l in 0..3 {
                    let a_part = u[l]
                        .mul(delta(j, k))
                        .add(delta(j, l).mul(u[k]))
                        .add(u[j].mul(delta(k, l)))
                        .sub(u[j].mul(u[k]).mul(u[l]));
                    let mut t = agg(c.a, a_part);
                    let mut bt = agg(c.b[k], p(j, l)).add(agg(c.b[j], p(k, l)));
                    let pjk = p(j, k);
                    let mix = p(j, l).mul(u[k]).add(u[j].mul(p(k, l)));
                    for m in 0..3 {
                        bt = bt.add(agg(c.b[m], p(m, l).mul(pjk))).sub(agg(c.b[m], u[m].mul(mix)));
                    }
                    t = t.add(bt.mul(inv_r));
                    acc = acc.add(t.scale(3.0).mul(s[l]));
                }
                out[j][k] = acc;
                out[k][j] = acc;
            }
        }
        Some(out)
    }

    /// The Hessian at `m` summed over the cluster's centres, as intervals
    /// padded by the sum's rounding error (`None` when `m` is a centre).
    fn cluster_hessian_at(&self, c: &Cluster, m: V3) -> Option<M3> {
        let mut h = [[0.0f64; 3]; 3];
        let mut mag = 0.0;
        for &i in &self.order[c.range.0..c.range.1] {
            let d = sub(m, self.centers[i]);
            let r = norm(d);
            if r == 0.0 {
                return None;
            }
            let u = d.map(|x| x / r);
            let (a, b) = (self.a[i], self.b[i]);
            let bu = dot(b, u);
            for j in 0..3 {
                for k in 0..3 {
                    let dl = if j == k { 1.0 } else { 0.0 };
                    h[j][k] +=
                        3.0 * a * r * (dl + u[j] * u[k]) + 3.0 * (b[j] * u[k] + u[j] * b[k] + bu * (dl - u[j] * u[k]));
                }
            }
            mag += 6.0 * a.abs() * r + 12.0 * b.iter().map(|x| x.abs()).sum::<f64>();
        }
        // A dozen roundings per term, at most LEAF terms summed.
        let err = 64.0 * U * mag;
        Some(h.map(|row| row.map(|x| Interval::point(x).pad(err))))
    }

    /// An enclosure of every Hessian over the box (see the module doc).
    fn hessian_bounds(&self, lo: V3, hi: V3, m: V3, step: &IV3) -> M3 {
        let mut h = [[Interval::point(0.0); 3]; 3];
        for (c, d, r) in self.offsets(lo, hi) {
            let u = unit3(d);
            let mut hc = Self::cluster_hessian_bound(c, &u, r);
            if let (Some(at), Some(t)) = (self.cluster_hessian_at(c, m), Self::cluster_third_times(c, &u, r, step)) {
                for j in 0..3 {
                    for k in 0..3 {
                        hc[j][k] = hc[j][k].meet(at[j][k].add(t[j][k]));
                    }
                }
            }
            for j in 0..3 {
                for k in 0..3 {
                    h[j][k] = h[j][k].add(hc[j][k]);
                }
            }
        }
        h
    }

    /// Per-cluster enclosures of the gradient itself: `3 a r d_j` and `3
    /// b_l (d_l u_j + r delta_lj)`.
    fn naive_gradient(&self, lo: V3, hi: V3) -> IV3 {
        let mut g = [1, 2, 3].map(|i| Interval::point(self.poly[i]));
        for (c, d, r) in self.offsets(lo, hi) {
            let u = unit3(d);
            for j in 0..3 {
                let mut e = agg(c.a, r.mul(d[j]));
                for l in 0..3 {
                    let t = d[l].mul(u[j]);
                    e = e.add(agg(c.b[l], if l == j { t.add(r) } else { t }));
                }
                g[j] = g[j].add(e.scale(3.0));
            }
        }
        g
    }

    pub(crate) fn grad_bounds(&self, lo: V3, hi: V3) -> IV3 {
        let m = [0, 1, 2].map(|i| 0.5 * (lo[i] + hi[i]));
        let step: IV3 = [0, 1, 2].map(|i| {
            let w = (hi[i] - m[i]).max(m[i] - lo[i]) * (1.0 + 1e-15);
            Interval::new(-w, w)
        });
        let h = self.hessian_bounds(lo, hi, m, &step);
        let gm = self.gradient(m);
        let err = self.errors(lo, hi).1;
        let centred: IV3 = [0, 1, 2].map(|j| {
            let mut v = Interval::point(gm[j]);
            for k in 0..3 {
                v = v.add(h[j][k].mul(step[k]));
            }
            v.pad(err)
        });
        meet3(centred, self.naive_gradient(lo, hi))
    }

    pub(crate) fn bounds(&self, lo: V3, hi: V3) -> Interval {
        let (ev, _) = self.errors(lo, hi);
        let mv = mean_value(|p| self.eval(p), self.grad_bounds(lo, hi), ev, lo, hi);
        // Per cluster: a r^3 and 3 r b . d, enclosing the exact value; pad
        // by the rounding error for the computed one.
        let bx = box3(lo, hi);
        let mut naive = Interval::point(self.poly[0])
            .add(bx[0].scale(self.poly[1]))
            .add(bx[1].scale(self.poly[2]))
            .add(bx[2].scale(self.poly[3]));
        for (c, d, r) in self.offsets(lo, hi) {
            naive = naive.add(agg(c.a, r.sqr().mul(r)));
            for l in 0..3 {
                naive = naive.add(agg(c.b[l], r.mul(d[l]).scale(3.0)));
            }
        }
        mv.meet(naive.pad(ev))
    }
}
