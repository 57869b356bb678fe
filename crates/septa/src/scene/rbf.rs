//! Hermite radial basis function interpolant with the cubic kernel
//! `phi(r) = r^3` (the reference function library's `rbf`, fitted by
//! Hermite RBF reconstruction from points with normals):
//!
//! `f(p) = sum_i a_i |d_i|^3 + sum_i 3 |d_i| (b_i . d_i) + c_0 + c . p`,
//! `d_i = p - x_i`,
//!
//! the second sum being the Hermite terms `b_i . grad phi(|p - x_i|)`. The
//! function file names an `.xyz` file of the N centres and a coefficient
//! file whose first line holds 4N numbers (the N `a_i`, then the x, y, z
//! components of all `b_i` as three blocks of N) and whose second line
//! holds `c_0, c_x, c_y, c_z`.
//!
//! Bounds over a box (for the adaptive criterion): centred forms. The
//! gradient is enclosed by `grad f(m) + H (p - m)` with `H` an enclosure of
//! every Hessian over the box, built per cluster of centres from the
//! clusters' sums of positive and of negative coefficients (the Hessian of
//! a term is its coefficient times a function of `d` whose range over the
//! box minus the cluster's box is enclosed once per cluster); the value by
//! `f(m) + G . (p - m)` with that gradient enclosure. Both shrink linearly
//! with the box (the Hessian enclosure stays bounded), and both are met
//! with the same per-cluster sums applied to the value and gradient
//! directly, which is better for large boxes.

use super::interval::Interval;
use super::vec3::{dot, norm, sub, V3};

/// Centres per cluster.
const LEAF: usize = 8;

/// A leaf of the centres' hierarchy: its members, bounding box and the
/// sums of the positive and of the negative parts of their coefficients.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Cluster {
    pub lo: V3,
    pub hi: V3,
    /// Members: `order[range.0..range.1]`.
    pub range: (usize, usize),
    /// (sum of positive a_i, sum of negative a_i).
    pub a: (f64, f64),
    /// Per component j: (sum of positive b_ij, sum of negative b_ij).
    pub b: [(f64, f64); 3],
    /// sum |a_i| and sum |b_i|_1 (for error bounds).
    pub abs: (f64, f64),
}

/// A Hermite RBF (see the module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct HermiteRbf {
    /// Centres `x_i`.
    pub centers: Vec<V3>,
    /// Value weights `a_i`.
    pub a: Vec<f64>,
    /// Gradient weights `b_i`.
    pub b: Vec<V3>,
    /// `c_0, c_x, c_y, c_z` of the linear polynomial.
    pub poly: [f64; 4],
    /// Leaves of at most [`LEAF`] centres (median splits).
    pub(crate) clusters: Vec<Cluster>,
    /// Centre indices in leaf order.
    pub(crate) order: Vec<usize>,
}

/// `sum x_i v` for `x_i` of the given positive and negative sums and `v`
/// anywhere in `iv`: `[pos lo + neg hi, pos hi + neg lo]`.
pub(crate) fn agg(sums: (f64, f64), iv: Interval) -> Interval {
    iv.scale(sums.0).add(iv.scale(sums.1))
}

impl HermiteRbf {
    /// From centres, the 4N coefficients (N value weights, then the x, y
    /// and z gradient weights as blocks of N) and the polynomial; `Err`
    /// says what does not fit.
    pub fn new(centers: Vec<V3>, coeffs: &[f64], poly: [f64; 4]) -> Result<HermiteRbf, String> {
        let n = centers.len();
        if n == 0 {
            return Err("no centres".into());
        }
        if coeffs.len() != 4 * n {
            return Err(format!("{} coefficients for {n} centres (need 4N = {})", coeffs.len(), 4 * n));
        }
        if let Some(i) = coeffs.iter().chain(&poly).position(|x| !x.is_finite()) {
            return Err(format!("coefficient {i} is not a finite number"));
        }
        if let Some(i) = centers.iter().position(|c| c.iter().any(|x| !x.is_finite())) {
            return Err(format!("centre {i} is not finite"));
        }
        let a = coeffs[..n].to_vec();
        let b = (0..n).map(|i| [coeffs[n + i], coeffs[2 * n + i], coeffs[3 * n + i]]).collect();
        let mut r = HermiteRbf { centers, a, b, poly, clusters: vec![], order: (0..n).collect() };
        let mut idx = std::mem::take(&mut r.order);
        r.build(&mut idx, 0);
        r.order = idx;
        Ok(r)
    }

    /// Clusters of at most [`LEAF`] centres by recursive median splits
    /// along the widest axis.
    fn build(&mut self, idx: &mut [usize], start: usize) {
        let (lo, hi) = idx.iter().fold(([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]), |(l, h), &i| {
            let c = self.centers[i];
            ([0, 1, 2].map(|k| l[k].min(c[k])), [0, 1, 2].map(|k| h[k].max(c[k])))
        });
        if idx.len() <= LEAF {
            let range = (start, start + idx.len());
            let mut cl = Cluster { lo, hi, range, a: (0.0, 0.0), b: [(0.0, 0.0); 3], abs: (0.0, 0.0) };
            for &i in idx.iter() {
                let split = |x: f64, s: &mut (f64, f64)| if x > 0.0 { s.0 += x } else { s.1 += x };
                split(self.a[i], &mut cl.a);
                for j in 0..3 {
                    split(self.b[i][j], &mut cl.b[j]);
                }
                cl.abs.0 += self.a[i].abs();
                cl.abs.1 += self.b[i].iter().map(|x| x.abs()).sum::<f64>();
            }
            self.clusters.push(cl);
            return;
        }
        let axis = (0..3).max_by(|&x, &y| (hi[x] - lo[x]).total_cmp(&(hi[y] - lo[y]))).unwrap_or(0);
        let mid = idx.len() / 2;
        let centers = &self.centers;
        idx.select_nth_unstable_by(mid, |&x, &y| centers[x][axis].total_cmp(&centers[y][axis]));
        let (left, right) = idx.split_at_mut(mid);
        self.build(left, start);
        self.build(right, start + mid);
    }

    /// Number of centres.
    pub fn len(&self) -> usize {
        self.centers.len()
    }

    /// Whether there is no centre (never, for a built RBF).
    pub fn is_empty(&self) -> bool {
        self.centers.is_empty()
    }

    pub(crate) fn eval(&self, p: V3) -> f64 {
        let mut s = Neumaier::default();
        for ((x, a), b) in self.centers.iter().zip(&self.a).zip(&self.b) {
            let d = sub(p, *x);
            let r = norm(d);
            s.add(a * (r * r * r) + 3.0 * r * dot(*b, d));
        }
        s.add(self.poly[0] + self.poly[1] * p[0] + self.poly[2] * p[1] + self.poly[3] * p[2]);
        s.total()
    }

    pub(crate) fn gradient(&self, p: V3) -> V3 {
        // grad (a r^3) = 3 a r d; grad (3 r b.d) = 3 (r b + (b.d) d / r).
        let mut g = [1, 2, 3].map(|i| Neumaier { sum: self.poly[i], comp: 0.0 });
        for ((x, a), b) in self.centers.iter().zip(&self.a).zip(&self.b) {
            let d = sub(p, *x);
            let r = norm(d);
            let k = if r > 0.0 { 3.0 * dot(*b, d) / r } else { 0.0 };
            for j in 0..3 {
                g[j].add(3.0 * a * r * d[j] + 3.0 * r * b[j] + k * d[j]);
            }
        }
        g.map(|s| s.total())
    }
}

/// Neumaier's compensated sum: a running sum and the rounding errors of
/// its additions, added back at the end.
#[derive(Default, Clone, Copy)]
struct Neumaier {
    sum: f64,
    comp: f64,
}

impl Neumaier {
    fn add(&mut self, x: f64) {
        let t = self.sum + x;
        self.comp += if self.sum.abs() >= x.abs() { (self.sum - t) + x } else { (x - t) + self.sum };
        self.sum = t;
    }
    fn total(self) -> f64 {
        self.sum + self.comp
    }
}

/// Read the reference's `.xyz` file (a first number, the dimension 3, then
/// x y z per point) and coefficient file; errors name the file and line.
pub fn read_hermite_rbf(points: &std::path::Path, coeffs: &std::path::Path) -> Result<HermiteRbf, String> {
    let read =
        |p: &std::path::Path| crate::io::read_input_text(p).map_err(|e| format!("cannot read {}: {e}", p.display()));
    let text = read(points)?;
    let mut nums = vec![];
    let mut dim = None;
    for (ln, line) in text.lines().enumerate() {
        for tok in line.split_whitespace() {
            let x: f64 =
                tok.parse().map_err(|_| format!("{}:{}: `{tok}` is not a number", points.display(), ln + 1))?;
            if dim.is_none() {
                if x != 3.0 {
                    return Err(format!("{}:{}: dimension {x}, only 3 is supported", points.display(), ln + 1));
                }
                dim = Some(3);
            } else {
                nums.push(x);
            }
        }
    }
    if nums.len() % 3 != 0 {
        return Err(format!("{}: {} coordinates, not a multiple of 3", points.display(), nums.len()));
    }
    let centers: Vec<V3> = nums.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
    let text = read(coeffs)?;
    let mut lines = text.lines().filter(|l| !l.trim().is_empty());
    let parse = |line: &str, ln: usize| -> Result<Vec<f64>, String> {
        line.split_whitespace()
            .map(|t| t.parse::<f64>().map_err(|_| format!("{}:{ln}: `{t}` is not a number", coeffs.display())))
            .collect()
    };
    let a = parse(lines.next().ok_or_else(|| format!("{}: empty", coeffs.display()))?, 1)?;
    let b = parse(lines.next().ok_or_else(|| format!("{}:2: missing the polynomial line", coeffs.display()))?, 2)?;
    if b.len() != 4 {
        return Err(format!("{}:2: the polynomial needs 4 numbers (c0 cx cy cz), got {}", coeffs.display(), b.len()));
    }
    HermiteRbf::new(centers, &a, [b[0], b[1], b[2], b[3]])
        .map_err(|e| format!("{} with {}: {e}", points.display(), coeffs.display()))
}
