//! Vertices moved onto the true zero sets of analytic functions (a scene's
//! formulas), keeping the exact network: each vertex stays inside the grid
//! element its key names and only its coordinates change.
//!
//! A network vertex lies where the linear interpolants of its functions
//! vanish on its grid element (Du et al. 2022, Sec. 5); Bloomenthal's
//! polygonizer instead converges each vertex onto the true surface. Here a
//! vertex on a grid edge (a patch vertex) is found by a safeguarded Newton
//! iteration inside the bracket of the edge's exact sign change; a vertex
//! in a triangle (a chain vertex: two equations) or a tet (a corner: three)
//! by a damped Newton iteration on the element's barycentric coordinates,
//! never leaving the element (the trust region). A vertex whose iteration
//! does not end strictly inside its element, or ends no closer to the zero
//! set, stays where it was.
//!
//! Moves are then checked exactly (`check.rs`): a moved vertex of a written
//! triangle that the moves made degenerate or crossing goes back, until no
//! moved vertex is part of a new violation (the vertices kept that way are
//! counted). Equations: IA, each function; MI, the differences of the first
//! function with the others (materials at equal strength).

use rayon::prelude::*;

use super::check::{check, Polygons};
use crate::grid::BoxGrid;
use crate::network::embedding::Projection;
use crate::network::VKey;
use crate::scene::Primitive;

/// The functions whose zero sets a network's vertices are on.
#[derive(Clone, Copy)]
pub struct Zeros<'a> {
    /// The formulas, by global function id.
    pub functions: &'a [Primitive],
    /// MI (differences of functions) rather than IA.
    pub mi: bool,
}

type V = [f64; 3];

fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl Zeros<'_> {
    /// The equations of a vertex defined by `funcs` (padded with `u16::MAX`)
    /// as pairs `(a, b)`: `f_a - f_b` (MI) or `f_a` (`b` none, IA).
    fn equations(&self, funcs: &[u16; 4]) -> Vec<(usize, Option<usize>)> {
        let f: Vec<usize> = funcs.iter().filter(|&&g| g != u16::MAX).map(|&g| g as usize).collect();
        if f.iter().any(|&g| g >= self.functions.len()) {
            return Vec::new();
        }
        if self.mi {
            f.iter().skip(1).map(|&b| (f[0], Some(b))).collect()
        } else {
            f.iter().map(|&a| (a, None)).collect()
        }
    }

    fn value_grad(&self, (a, b): (usize, Option<usize>), p: V) -> (f64, V) {
        let (fa, ga) = (self.functions[a].eval(p), self.functions[a].gradient(p));
        match b {
            None => (fa, ga),
            Some(b) => (fa - self.functions[b].eval(p), sub(ga, self.functions[b].gradient(p))),
        }
    }

    /// The largest `|g| / |grad g|` over the equations at `p` (infinite where
    /// a gradient vanishes away from the zero set).
    fn residual(&self, eqs: &[(usize, Option<usize>)], p: V) -> f64 {
        eqs.iter()
            .map(|&e| {
                let (g, d) = self.value_grad(e, p);
                let n = dot(d, d).sqrt();
                if g == 0.0 {
                    0.0
                } else if n > 0.0 {
                    g.abs() / n
                } else {
                    f64::INFINITY
                }
            })
            .fold(0.0, f64::max)
    }
}

/// The grid element of `key` as corner positions (1 to 4).
fn element(key: &VKey, grid: &BoxGrid) -> Vec<V> {
    key.grid.iter().filter(|&&g| g != u32::MAX).map(|&g| grid.vertex(g)).collect()
}

/// Solves the `d x d` system `a x = b` (`d <= 3`) by elimination with
/// partial pivoting; `None` when singular.
fn solve(mut a: [[f64; 3]; 3], mut b: [f64; 3], d: usize) -> Option<[f64; 3]> {
    for c in 0..d {
        let p = (c..d).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        if a[p][c] == 0.0 || !a[p][c].is_finite() {
            return None;
        }
        a.swap(c, p);
        b.swap(c, p);
        for r in c + 1..d {
            let m = a[r][c] / a[c][c];
            for k in c..d {
                a[r][k] -= m * a[c][k];
            }
            b[r] -= m * b[c];
        }
    }
    let mut x = [0.0; 3];
    for c in (0..d).rev() {
        let s: f64 = (c + 1..d).map(|k| a[c][k] * x[k]).sum();
        x[c] = (b[c] - s) / a[c][c];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// The point with barycentric parameters `t` (weights of corners 1..) of
/// the element `c`.
fn at(c: &[V], t: &[f64; 3]) -> V {
    let mut p = c[0];
    for m in 1..c.len() {
        for k in 0..3 {
            p[k] += t[m - 1] * (c[m][k] - c[0][k]);
        }
    }
    p
}

/// Strictly inside the element: every barycentric weight positive.
fn inside(t: &[f64; 3], d: usize) -> bool {
    t[..d].iter().all(|&x| x > 0.0) && t[..d].iter().sum::<f64>() < 1.0
}

/// The parameters of `p` in the element (least squares on its edges).
fn params(c: &[V], p: V) -> Option<[f64; 3]> {
    let d = c.len() - 1;
    let e: Vec<V> = (1..=d).map(|m| sub(c[m], c[0])).collect();
    let r = sub(p, c[0]);
    let mut g = [[0.0; 3]; 3];
    let mut b = [0.0; 3];
    for i in 0..d {
        for j in 0..d {
            g[i][j] = dot(e[i], e[j]);
        }
        b[i] = dot(e[i], r);
    }
    solve(g, b, d)
}

/// A patch vertex: the root of `g` on the edge `c[0]..c[1]` inside the
/// bracket of its sign change (Newton, bisection where Newton leaves it).
fn on_edge(z: &Zeros, e: (usize, Option<usize>), c: &[V], start: f64) -> Option<V> {
    let g = |t: f64| z.value_grad(e, at(c, &[t, 0.0, 0.0]));
    let dir = sub(c[1], c[0]);
    let (ga, gb) = (g(0.0).0, g(1.0).0);
    if !(ga < 0.0 && gb > 0.0 || ga > 0.0 && gb < 0.0) {
        return None;
    }
    let (mut lo, mut hi) = (0.0f64, 1.0f64); // g(lo) has ga's sign
    let mut t = if start > 0.0 && start < 1.0 { start } else { 0.5 };
    for _ in 0..200 {
        let (v, d) = g(t);
        if v == 0.0 {
            break;
        }
        if (v < 0.0) == (ga < 0.0) {
            lo = t;
        } else {
            hi = t;
        }
        let slope = dot(d, dir);
        let newton = t - v / slope;
        let (a, b) = (lo.min(hi), lo.max(hi));
        let next = if slope != 0.0 && newton > a && newton < b { newton } else { 0.5 * (lo + hi) };
        if next == t || (hi - lo).abs() <= f64::EPSILON * 4.0 {
            break;
        }
        t = next;
    }
    (t > 0.0 && t < 1.0).then(|| at(c, &[t, 0.0, 0.0]))
}

/// A chain or corner vertex: damped Newton on the element's parameters,
/// each step halved until it stays strictly inside and lowers the residual.
fn in_element(z: &Zeros, eqs: &[(usize, Option<usize>)], c: &[V], p: V) -> Option<V> {
    let d = c.len() - 1;
    let e: Vec<V> = (1..=d).map(|m| sub(c[m], c[0])).collect();
    let mut t = params(c, p)?;
    if !inside(&t, d) {
        return None;
    }
    let norm = |t: &[f64; 3]| -> f64 {
        let q = at(c, t);
        eqs.iter().map(|&q_| z.value_grad(q_, q).0.powi(2)).sum::<f64>()
    };
    let mut now = norm(&t);
    for _ in 0..60 {
        if now == 0.0 {
            break;
        }
        let q = at(c, &t);
        let mut a = [[0.0; 3]; 3];
        let mut b = [0.0; 3];
        for (i, &eq) in eqs.iter().enumerate() {
            let (v, grad) = z.value_grad(eq, q);
            for m in 0..d {
                a[i][m] = dot(grad, e[m]);
            }
            b[i] = -v;
        }
        let Some(step) = solve(a, b, d) else { break };
        let mut s = 1.0;
        let mut moved = false;
        for _ in 0..40 {
            let cand: [f64; 3] = std::array::from_fn(|k| t[k] + s * step[k]);
            if inside(&cand, d) {
                let n = norm(&cand);
                if n < now {
                    (t, now, moved) = (cand, n, true);
                    break;
                }
            }
            s *= 0.5;
        }
        if !moved {
            break;
        }
    }
    inside(&t, d).then(|| at(c, &t))
}

/// What the root finding found for one vertex.
enum Found {
    /// No equations for its element (a grid vertex, an unsupported key).
    Skip,
    /// Already on the zero sets (to the tolerance of [`converged`]).
    On,
    /// Not converged strictly inside its element: left in place.
    Kept,
    /// Converged there.
    At(V),
}

/// Converged: `|g| / |grad g|` within `2^-40` of the element's size (the
/// interpolants' error is of the order of the size squared).
fn converged(residual: f64, c: &[V]) -> bool {
    let size = c.iter().skip(1).map(|q| dot(sub(*q, c[0]), sub(*q, c[0])).sqrt()).fold(0.0, f64::max);
    residual <= size * (1.0 / (1u64 << 40) as f64)
}

/// Where the vertex `key` at `p` belongs on the true zero sets.
fn target(z: &Zeros, key: &VKey, grid: &BoxGrid, p: V) -> Found {
    let eqs = z.equations(&key.funcs);
    let c = element(key, grid);
    if eqs.is_empty() || c.len() < 2 || eqs.len() != c.len() - 1 {
        return Found::Skip;
    }
    if converged(z.residual(&eqs, p), &c) {
        return Found::On;
    }
    let q = if c.len() == 2 {
        let t = params(&c, p).map_or(0.5, |t| t[0]);
        on_edge(z, eqs[0], &c, t)
    } else {
        in_element(z, &eqs, &c, p)
    };
    match q {
        Some(q) if q.iter().all(|x| x.is_finite()) && converged(z.residual(&eqs, q), &c) => Found::At(q),
        _ => Found::Kept,
    }
}

/// The largest residual of the vertices in use (module doc).
pub(crate) fn largest_residual(z: &Zeros, points: &[V], keys: &[VKey], used: &[bool]) -> f64 {
    (0..points.len())
        .into_par_iter()
        .filter(|&v| used[v])
        .map(|v| {
            let eqs = z.equations(&keys[v].funcs);
            if eqs.is_empty() {
                0.0
            } else {
                z.residual(&eqs, points[v])
            }
        })
        .reduce(|| 0.0, f64::max)
}

/// Moves the vertices of `polys` onto the zero sets (module doc); the
/// report has `residual_after` of the moved points (the caller updates it
/// after any later repair).
pub(crate) fn project(points: &mut [V], keys: &[VKey], polys: &Polygons, grid: &BoxGrid, z: &Zeros) -> Projection {
    let mut used = vec![false; points.len()];
    for &v in polys.verts {
        used[v as usize] = true;
    }
    let mut out = Projection { residual_before: largest_residual(z, points, keys, &used), ..Default::default() };
    let base = check(points, polys, grid_bounds(grid));
    let bad_before: std::collections::HashSet<u32> = base.bad.iter().copied().collect();
    let found: Vec<Found> = (0..points.len())
        .into_par_iter()
        .map(|v| if used[v] { target(z, &keys[v], grid, points[v]) } else { Found::Skip })
        .collect();
    let not_converged = found.iter().filter(|f| matches!(f, Found::Kept)).count();
    let old: Vec<V> = points.to_vec();
    let mut moved = vec![false; points.len()];
    for (v, m) in found.iter().enumerate() {
        if let Found::At(q) = m {
            points[v] = *q;
            moved[v] = true;
        }
    }
    // back, a round at a time, the moved vertices of new violations
    let mut kept_by_check = 0;
    for round in 0..8 {
        let found = check(points, polys, grid_bounds(grid));
        let mut back: Vec<u32> = Vec::new();
        for &b in &found.bad {
            if !bad_before.contains(&b) || round >= 4 {
                back.extend(found.fans.tris[b as usize].iter().filter(|&&v| moved[v as usize]));
            }
        }
        back.extend(found.coincident.iter().flatten().filter(|&&v| moved[v as usize]));
        back.sort_unstable();
        back.dedup();
        if back.is_empty() {
            break;
        }
        for v in back {
            points[v as usize] = old[v as usize];
            moved[v as usize] = false;
            kept_by_check += 1;
        }
    }
    out.moved = moved.iter().filter(|&&m| m).count();
    out.kept_by_check = kept_by_check;
    out.kept = not_converged + kept_by_check;
    out.residual_after = largest_residual(z, points, keys, &used);
    out
}

fn grid_bounds(grid: &BoxGrid) -> Option<[[f64; 3]; 2]> {
    Some(grid.bounds)
}
