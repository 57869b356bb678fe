//! Vertex signs by the barycentric predicate (Du et al. Sec. 5.2, eq. 5-6).
//!
//! For a vertex `v` on the `d`-simplex `e = (s_0..s_d)` of the tet, on the
//! zero sets of `g_1..g_d`, the sign of a further function `g` at `v` is
//! `sign(det A') * sign(det A)` with `A = {g_1..g_d, 1}` and
//! `A' = {g_1..g_d, g}`, rows holding values at `s_0..s_d`. For MI every `g`
//! is a difference of two input functions, formed inside the predicate
//! ([`septa_exact::det_sign_diff`]) so its rounding never decides a sign.
//! `sign(det A)` depends on the vertex only and is cached at its creation.

use super::types::{Mode, Vertex};
use septa_exact::{det_sign, det_sign_diff, Sign};

/// The inputs of every predicate of one build: values of the active
/// functions at the 4 tet vertices, and the arithmetic to use.
pub(crate) struct Predicates<'a> {
    pub values: &'a [[f64; 4]],
    pub mode: Mode,
    /// Naive floating-point signs (the `--float` variant of the stress test).
    pub float: bool,
}

/// Rows of `A'` (or `A` when `last` is `None`) as `(a, b)` pairs: the
/// entries are `a - b` (IA: `b = 0`).
struct Rows {
    a: [[f64; 4]; 4],
    b: [[f64; 4]; 4],
    n: usize,
}

impl Predicates<'_> {
    /// `sign(det A)` of a vertex (eq. 4); nonzero for a well-defined vertex.
    pub fn orient(&self, v: &Vertex) -> i8 {
        self.answer(v, None)
    }

    /// Sign at `v` of `f_new` (IA) or of `f_m - f_new` where `f_m` is a
    /// function maximal at `v` (MI): positive means the old maximum wins.
    pub fn vertex_sign(&self, v: &Vertex, orient: i8, new: u16) -> i8 {
        self.answer(v, Some(new)) * orient
    }

    fn answer(&self, v: &Vertex, last: Option<u16>) -> i8 {
        match (self.mode, self.float) {
            (Mode::Ia, false) => self.ia_sign(v, last),
            _ => self.sign_of(self.rows(v, last)),
        }
    }

    /// [`Self::sign_of`] of [`Self::rows`] for IA, with the `n x n` matrix
    /// filled directly (the same entries: the vertex's functions, then
    /// `last` or ones): the two zeroed 4 x 4 arrays and their copies were
    /// most of a predicate's cost outside the determinant.
    fn ia_sign(&self, v: &Vertex, last: Option<u16>) -> i8 {
        let (s, n) = simplex_corners(v);
        let f = v.functions();
        fn fill<const N: usize>(values: &[[f64; 4]], s: &[usize; 4], f: &[u16], last: Option<u16>) -> [[f64; N]; N] {
            let mut m = [[0.0; N]; N];
            for (k, &g) in f.iter().enumerate().take(N - 1) {
                for j in 0..N {
                    m[k][j] = values[g as usize][s[j]];
                }
            }
            for j in 0..N {
                m[N - 1][j] = match last {
                    Some(g) => values[g as usize][s[j]],
                    None => 1.0,
                };
            }
            m
        }
        let sign = match n {
            1 => det_sign::<1>(&fill::<1>(self.values, &s, f, last)),
            2 => det_sign::<2>(&fill::<2>(self.values, &s, f, last)),
            3 => det_sign::<3>(&fill::<3>(self.values, &s, f, last)),
            _ => det_sign::<4>(&fill::<4>(self.values, &s, f, last)),
        };
        sign.as_i8()
    }

    fn rows(&self, v: &Vertex, last: Option<u16>) -> Rows {
        let mut r = Rows { a: [[0.0; 4]; 4], b: [[0.0; 4]; 4], n: 0 };
        let (s, n) = simplex_corners(v);
        r.n = n;
        let f = v.functions();
        let val = |func: u16, j: usize| self.values[func as usize][s[j]];
        match self.mode {
            Mode::Ia => {
                for (k, &g) in f.iter().enumerate() {
                    for j in 0..n {
                        r.a[k][j] = val(g, j);
                    }
                }
                for j in 0..n {
                    r.a[n - 1][j] = match last {
                        Some(g) => val(g, j),
                        None => 1.0,
                    };
                }
            }
            Mode::Mi => {
                let f0 = f[0];
                for (k, &g) in f.iter().skip(1).enumerate() {
                    for j in 0..n {
                        r.a[k][j] = val(g, j);
                        r.b[k][j] = val(f0, j);
                    }
                }
                for j in 0..n {
                    match last {
                        Some(g) => {
                            r.a[n - 1][j] = val(f0, j);
                            r.b[n - 1][j] = val(g, j);
                        }
                        None => r.a[n - 1][j] = 1.0,
                    }
                }
            }
        }
        r
    }

    fn sign_of(&self, r: Rows) -> i8 {
        if self.float {
            return naive_sign(&r);
        }
        let s = match (self.mode, r.n) {
            (Mode::Ia, 1) => det_sign::<1>(&sub::<1>(&r.a)),
            (Mode::Ia, 2) => det_sign::<2>(&sub::<2>(&r.a)),
            (Mode::Ia, 3) => det_sign::<3>(&sub::<3>(&r.a)),
            (Mode::Ia, _) => det_sign::<4>(&r.a),
            (Mode::Mi, 1) => det_sign_diff::<1>(&sub::<1>(&r.a), &sub::<1>(&r.b)),
            (Mode::Mi, 2) => det_sign_diff::<2>(&sub::<2>(&r.a), &sub::<2>(&r.b)),
            (Mode::Mi, 3) => det_sign_diff::<3>(&sub::<3>(&r.a), &sub::<3>(&r.b)),
            (Mode::Mi, _) => det_sign_diff::<4>(&r.a, &r.b),
        };
        s.as_i8()
    }
}

/// The tet corners of the vertex's simplex, ascending, and how many there
/// are (without allocating).
#[inline]
fn simplex_corners(v: &Vertex) -> ([usize; 4], usize) {
    let mut s = [0usize; 4];
    let mut n = 0;
    for i in 0..4 {
        if v.simplex() >> i & 1 == 1 {
            s[n] = i;
            n += 1;
        }
    }
    (s, n)
}

#[inline]
fn sub<const N: usize>(m: &[[f64; 4]; 4]) -> [[f64; N]; N] {
    let mut out = [[0.0; N]; N];
    for i in 0..N {
        out[i].copy_from_slice(&m[i][..N]);
    }
    out
}

/// The naive predicate: differences and determinant in `f64`, sign taken at
/// face value. Only for measuring what exactness buys (`--float`).
fn naive_sign(r: &Rows) -> i8 {
    let mut m = [[0.0; 4]; 4];
    for i in 0..r.n {
        for j in 0..r.n {
            m[i][j] = r.a[i][j] - r.b[i][j];
        }
    }
    Sign::of_f64(naive_det(&m, r.n)).as_i8()
}

fn naive_det(m: &[[f64; 4]; 4], n: usize) -> f64 {
    let d2 = |a: usize, b: usize, c: usize, d: usize| m[a][c] * m[b][d] - m[a][d] * m[b][c];
    match n {
        1 => m[0][0],
        2 => d2(0, 1, 0, 1),
        3 => {
            m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
        }
        _ => {
            let mut det = 0.0;
            for c in 0..4 {
                let cols: Vec<usize> = (0..4).filter(|&x| x != c).collect();
                let minor = m[1][cols[0]] * (m[2][cols[1]] * m[3][cols[2]] - m[2][cols[2]] * m[3][cols[1]])
                    - m[1][cols[1]] * (m[2][cols[0]] * m[3][cols[2]] - m[2][cols[2]] * m[3][cols[0]])
                    + m[1][cols[2]] * (m[2][cols[0]] * m[3][cols[1]] - m[2][cols[1]] * m[3][cols[0]]);
                det += if c % 2 == 0 { m[0][c] * minor } else { -m[0][c] * minor };
            }
            det
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The direct IA matrices give the signs of the general rows: every
    /// simplex, every vertex function set of the right size, `orient` and
    /// `vertex_sign`, on values with exact zeros and ties.
    #[test]
    fn direct_ia_signs_equal_the_general_rows() {
        let pool = [-2.0, -1.0, -0.5, 0.0, 0.5, 1.0, 3.0, 1e-300, -7e20];
        let mut rng = ChaCha8Rng::seed_from_u64(0x9e3779b97f4a7c15u64);
        let mut nonzero = 0;
        for _ in 0..3000 {
            let values = super::super::random_rows(&mut rng, &pool, 4);
            let p = Predicates { values: &values, mode: Mode::Ia, float: false };
            for simplex in 1..16u8 {
                let d = simplex.count_ones() as usize - 1;
                let funcs: Vec<u16> = (0..4u16).filter(|_| rng.gen::<u64>() % 2 == 0).take(d).collect();
                if funcs.len() != d {
                    continue;
                }
                let v = Vertex::new(simplex, &funcs);
                for last in [None, Some((rng.gen::<u64>() % 4) as u16)] {
                    let want = p.sign_of(p.rows(&v, last));
                    assert_eq!(p.ia_sign(&v, last), want, "{simplex:b} {funcs:?} {last:?} {values:?}");
                    nonzero += (want != 0) as usize;
                }
            }
        }
        assert!(nonzero > 1000, "{nonzero}");
    }
}
