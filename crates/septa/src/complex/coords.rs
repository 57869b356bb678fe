//! Vertex coordinates, computed only on request, for output.

use super::types::{Complex, Mode};

impl Complex {
    /// Barycentric coordinates (over the 4 tet vertices) of vertex `v`,
    /// solved in floating point from its plane-based encoding (eq. 4).
    /// `values` must be the array the complex was built from.
    pub fn vertex_barycentric(&self, v: usize, values: &[[f64; 4]]) -> [f64; 4] {
        let vert = &self.vertices[v];
        barycentric(self.mode, vert.simplex(), vert.functions(), values)
    }

    /// Position of vertex `v` in a tet with corners `tet`.
    pub fn vertex_position(&self, v: usize, tet: &[[f64; 3]; 4], values: &[[f64; 4]]) -> [f64; 3] {
        let b = self.vertex_barycentric(v, values);
        let mut p = [0.0; 3];
        for (i, corner) in tet.iter().enumerate() {
            for k in 0..3 {
                p[k] += b[i] * corner[k];
            }
        }
        p
    }
}

/// Barycentric coordinates of the vertex on tet element `simplex` (bit mask
/// of tet vertices) defined by `functions` (local indices into `values`),
/// solved in floating point from eq. 4. Shared by [`Complex::vertex_barycentric`]
/// and the network's single-polygon fast path, so both round identically.
pub(crate) fn barycentric(mode: Option<Mode>, simplex: u8, functions: &[u16], values: &[[f64; 4]]) -> [f64; 4] {
    let s: smallvec::SmallVec<[u8; 4]> = (0..4u8).filter(|i| simplex >> i & 1 == 1).collect();
    let n = s.len();
    // The functions in an order given by their values, not their ids, so
    // the rounded position does not depend on how the functions are
    // numbered (the same output for any permutation of them; invariant 2 of docs/architecture.md).
    let mut f: smallvec::SmallVec<[u16; 4]> = functions.into();
    let key = |g: u16| -> [u64; 4] {
        let mut k = [0; 4];
        for (j, &sj) in s.iter().enumerate() {
            k[j] = values[g as usize][sj as usize].to_bits();
        }
        k
    };
    if f.len() > 1 {
        // Equal keys mean equal rows: either order gives the same result.
        f.sort_unstable_by_key(|&g| key(g));
    }
    // Rows of A (eq. 4): g_1..g_d then ones; right-hand side e_n.
    let mut a = [[0.0f64; 4]; 4];
    for r in 0..n - 1 {
        for j in 0..n {
            a[r][j] = match mode {
                Some(Mode::Mi) => values[f[r + 1] as usize][s[j] as usize] - values[f[0] as usize][s[j] as usize],
                _ => values[f[r] as usize][s[j] as usize],
            };
        }
    }
    for j in 0..n {
        a[n - 1][j] = 1.0;
    }
    let x = if n == 2 {
        // On a tet edge: the zero of a linear function between two values of
        // opposite signs, in a form symmetric in the two ends (the same
        // rounding whichever tet, hence corner order, computes it).
        let (g0, g1) = (a[0][0], a[0][1]);
        normalize([g1 / (g1 - g0), g0 / (g0 - g1), 0.0, 0.0], 2)
    } else {
        solve(&mut a, n)
    };
    let mut out = [0.0; 4];
    for j in 0..n {
        out[s[j] as usize] = x[j];
    }
    out
}

/// Solves `A x = e_n` by Gaussian elimination with partial pivoting.
fn solve(a: &mut [[f64; 4]; 4], n: usize) -> [f64; 4] {
    let mut b = [0.0; 4];
    b[n - 1] = 1.0;
    for col in 0..n {
        let piv = (col..n).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs())).unwrap();
        a.swap(col, piv);
        b.swap(col, piv);
        let d = a[col][col];
        if d == 0.0 {
            continue;
        }
        for r in col + 1..n {
            let m = a[r][col] / d;
            for c in col..n {
                a[r][c] -= m * a[col][c];
            }
            b[r] -= m * b[col];
        }
    }
    let mut x = [0.0; 4];
    for r in (0..n).rev() {
        let mut s = b[r];
        for c in r + 1..n {
            s -= a[r][c] * x[c];
        }
        x[r] = if a[r][r] != 0.0 { s / a[r][r] } else { 0.0 };
    }
    normalize(x, n)
}

/// Clamps tiny rounding excursions so points stay in the tet.
fn normalize(mut x: [f64; 4], n: usize) -> [f64; 4] {
    let total: f64 = x[..n].iter().map(|v| v.max(0.0)).sum();
    for v in x[..n].iter_mut() {
        *v = v.max(0.0) / if total > 0.0 { total } else { 1.0 };
    }
    x
}
