//! Grid vertex ids to grid coordinates and positions without integer or
//! floating-point division per vertex: the block worker turns tens of
//! thousands of tet corners into indices and points per block.

use super::{grid_coordinate, BoxGrid};

/// Division of 32-bit integers by a fixed divisor `d >= 2` by one 64 x 64
/// bit multiplication: with `c = ceil(2^64 / d)`, `n / d = (c n) >> 64` for
/// every `n < 2^32` (Lemire, Kaser and Kurz, "Faster remainder by direct
/// computation", Software: Practice and Experience 49(6), 2019, Theorem 1
/// with N = 32, F = 64).
#[derive(Clone, Copy, Debug)]
pub(crate) struct FastDiv {
    d: u32,
    c: u64,
}

impl FastDiv {
    pub(crate) fn new(d: u32) -> FastDiv {
        assert!(d >= 2, "FastDiv needs a divisor of at least 2");
        FastDiv { d, c: u64::MAX / d as u64 + 1 }
    }

    /// `(n / d, n % d)`.
    #[inline]
    pub(crate) fn div_rem(self, n: u32) -> (u32, u32) {
        let q = ((self.c as u128 * n as u128) >> 64) as u32;
        (q, n - q * self.d)
    }
}

/// A box grid's vertex ids to `(i, j, k)` and to positions, the same values
/// as [`BoxGrid::vertex_ijk`] and [`BoxGrid::vertex`] (the positions are
/// read from per-axis tables computed by [`grid_coordinate`]).
#[derive(Clone, Debug)]
pub(crate) struct VertexLookup {
    yz: FastDiv,
    z: FastDiv,
    axes: [Vec<f64>; 3],
}

impl VertexLookup {
    pub(crate) fn new(g: &BoxGrid) -> VertexLookup {
        let n = g.res.map(|r| r as u32 + 1);
        VertexLookup {
            yz: FastDiv::new(n[1] * n[2]),
            z: FastDiv::new(n[2]),
            axes: [0, 1, 2].map(|a| {
                (0..=g.res[a]).map(|i| grid_coordinate(g.bounds[0][a], g.bounds[1][a], i, g.res[a])).collect()
            }),
        }
    }

    /// `(i, j, k)` of vertex `v`.
    #[inline]
    pub(crate) fn ijk(&self, v: u32) -> [usize; 3] {
        let (i, r) = self.yz.div_rem(v);
        let (j, k) = self.z.div_rem(r);
        [i as usize, j as usize, k as usize]
    }

    /// Position of vertex `v`.
    #[inline]
    pub(crate) fn position(&self, v: u32) -> [f64; 3] {
        let [i, j, k] = self.ijk(v);
        [self.axes[0][i], self.axes[1][j], self.axes[2][k]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::Split;

    #[test]
    fn fast_division_is_exact_on_every_32_bit_edge() {
        let mut state = 7u64;
        for d in [2u32, 3, 5, 7, 17, 101, 4097, 65_537, 1_000_003, u32::MAX / 3, u32::MAX - 1, u32::MAX] {
            let f = FastDiv::new(d);
            let check = |n: u32| assert_eq!(f.div_rem(n), (n / d, n % d), "{n} / {d}");
            for n in [0, 1, d - 1, d, d.wrapping_add(1), u32::MAX, u32::MAX - 1, u32::MAX - d] {
                check(n);
            }
            for _ in 0..10_000 {
                state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                check((state >> 32) as u32);
            }
        }
    }

    #[test]
    fn lookup_equals_the_grid() {
        let g = BoxGrid::new([7, 1, 12], [[-1.0, 0.3, 2.0], [0.9, 0.7, 3.1]], Split::Five).unwrap();
        let l = VertexLookup::new(&g);
        for v in 0..(8 * 2 * 13) as u32 {
            assert_eq!(l.ijk(v), g.vertex_ijk(v));
            assert_eq!(l.position(v).map(f64::to_bits), g.vertex(v).map(f64::to_bits));
        }
    }
}
