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
    on_edge(mode, simplex, functions, values).unwrap_or_else(|| general(mode, simplex, functions, values))
}

/// [`barycentric`] of any vertex: the rows of eq. 4 solved.
fn general(mode: Option<Mode>, simplex: u8, functions: &[u16], values: &[[f64; 4]]) -> [f64; 4] {
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

/// [`barycentric`] of the commonest vertex, a zero on a tet edge (IA: one
/// function; MI: two), without the general path's sorts and matrix: the
/// same operations on the same values, so the same bits. `None` for any
/// other vertex.
#[inline]
fn on_edge(mode: Option<Mode>, simplex: u8, functions: &[u16], values: &[[f64; 4]]) -> Option<[f64; 4]> {
    if simplex.count_ones() != 2 {
        return None;
    }
    let (s0, s1) = (simplex.trailing_zeros() as usize, 7 - simplex.leading_zeros() as usize);
    let row = |g: u16| &values[g as usize];
    let (g0, g1) = match (mode, functions) {
        (Some(Mode::Mi), &[p, q]) => {
            // the general path's order: by the values' bits at the edge's ends
            let key = |g: u16| [row(g)[s0].to_bits(), row(g)[s1].to_bits()];
            let (lo, hi) = if key(q) < key(p) { (q, p) } else { (p, q) };
            (row(hi)[s0] - row(lo)[s0], row(hi)[s1] - row(lo)[s1])
        }
        (Some(Mode::Ia) | None, &[f]) => (row(f)[s0], row(f)[s1]),
        _ => return None,
    };
    let x = normalize([g1 / (g1 - g0), g0 / (g0 - g1), 0.0, 0.0], 2);
    let mut out = [0.0; 4];
    (out[s0], out[s1]) = (x[0], x[1]);
    Some(out)
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

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The edge path gives the general path's bits: IA and MI, both edge
    /// orders, values of all signs, exact zeros, -0.0, ties between the
    /// two MI functions at one end, and equal rows.
    #[test]
    fn edge_path_is_bit_identical_to_the_general_path() {
        let pool = [-3.5, -1.0, -0.0, 0.0, 1e-300, 0.1, 0.3, 2.0, 7.25, -1e-17, 1e17];
        let mut rng = ChaCha8Rng::seed_from_u64(0x2545f4914f6cdd1du64);
        let mut compared = 0;
        for _ in 0..20_000 {
            let values = super::super::random_rows(&mut rng, &pool, 3);
            let a = (rng.gen::<u64>() % 4) as u8;
            let b = (a + 1 + (rng.gen::<u64>() % 3) as u8) % 4;
            let simplex = 1 << a | 1 << b;
            let (p, q) = ((rng.gen::<u64>() % 3) as u16, (rng.gen::<u64>() % 3) as u16);
            for (mode, funcs) in [(Some(Mode::Ia), vec![p]), (None, vec![q]), (Some(Mode::Mi), vec![p, q])] {
                let fast = on_edge(mode, simplex, &funcs, &values).expect("an edge vertex");
                let slow = general(mode, simplex, &funcs, &values);
                assert_eq!(fast.map(f64::to_bits), slow.map(f64::to_bits), "{mode:?} {simplex:b} {funcs:?} {values:?}");
                compared += 1;
            }
        }
        assert_eq!(compared, 60_000);
        // not an edge vertex: the general path
        let v = [[1.0, -2.0, 3.0, -4.0]];
        assert!(on_edge(Some(Mode::Ia), 0b0111, &[0], &v).is_none());
        assert!(on_edge(Some(Mode::Mi), 0b0011, &[0], &v).is_none());
    }
}
