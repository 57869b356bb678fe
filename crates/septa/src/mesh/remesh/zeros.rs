//! New vertices on the true zero sets of analytic functions (a scene's
//! formulas), where the network came from them: after the closest point on
//! the unremeshed patch, a patch vertex goes to the zero set of its patch's
//! function (IA `f`, MI `f_a - f_b`), a chain vertex to the common zero set
//! of the first two functions of the patches around it, a vertex on the
//! box's border to its patch's zero set within the box's side, each by
//! minimum-norm Newton steps (as `project.rs` does inside grid elements).
//! A point whose iteration does not converge (`|g| / |grad g|` within
//! `2^-40` of `L`) or goes further than `L / 2` stays at the closest point.

use super::soup::{dist, dot, sub, V};
use crate::scene::Primitive;

/// One equation: `f_a` (IA) or `f_a - f_b` (MI).
pub(super) type Eq = (usize, Option<usize>);

pub(super) struct Zeros<'a> {
    pub functions: &'a [Primitive],
    /// Per patch its equation.
    pub patch: Vec<Eq>,
    /// Per trace its equations (one or two) and the axes it may not move along.
    pub trace: Vec<(Vec<Eq>, [bool; 3])>,
    /// The target length.
    pub l: f64,
}

impl Zeros<'_> {
    fn value_grad(&self, (a, b): Eq, p: V) -> (f64, V) {
        let (fa, ga) = (self.functions[a].eval(p), self.functions[a].gradient(p));
        match b {
            None => (fa, ga),
            Some(b) => (fa - self.functions[b].eval(p), sub(ga, self.functions[b].gradient(p))),
        }
    }

    /// `p` moved onto the zero sets of `eqs` keeping the `fixed` axes, or
    /// `None` (module doc).
    pub fn onto(&self, eqs: &[Eq], fixed: [bool; 3], p0: V) -> Option<V> {
        let mut p = p0;
        let mask = |g: V| -> V { std::array::from_fn(|k| if fixed[k] { 0.0 } else { g[k] }) };
        for _ in 0..30 {
            let rows: Vec<(f64, V)> = eqs
                .iter()
                .map(|&e| {
                    let (v, g) = self.value_grad(e, p);
                    (v, mask(g))
                })
                .collect();
            let step: V = match rows.as_slice() {
                [(v, g)] => {
                    let n = dot(*g, *g);
                    if !(n > 0.0) {
                        return None;
                    }
                    std::array::from_fn(|k| -v * g[k] / n)
                }
                [(v1, g1), (v2, g2)] => {
                    // J^T (J J^T)^-1 g, J J^T = [[a, b], [b, c]]
                    let (a, b, c) = (dot(*g1, *g1), dot(*g1, *g2), dot(*g2, *g2));
                    let det = a * c - b * b;
                    if !(det.abs() > 1e-300) {
                        return None;
                    }
                    let y1 = (c * v1 - b * v2) / det;
                    let y2 = (a * v2 - b * v1) / det;
                    std::array::from_fn(|k| -(y1 * g1[k] + y2 * g2[k]))
                }
                _ => return None,
            };
            let q: V = std::array::from_fn(|k| if fixed[k] { p0[k] } else { p[k] + step[k] });
            if !q.iter().all(|x| x.is_finite()) {
                return None;
            }
            let done = dist(q, p) <= self.l * f64::EPSILON;
            p = q;
            if done {
                break;
            }
        }
        let tol = self.l / (1u64 << 40) as f64;
        let ok = eqs.iter().all(|&e| {
            let (v, g) = self.value_grad(e, p);
            let n = dot(g, g).sqrt();
            v == 0.0 || (n > 0.0 && v.abs() / n <= tol)
        });
        (ok && dist(p, p0) <= 0.5 * self.l).then_some(p)
    }
}
