//! A box of `nx * ny * nz` cubes split into tets.

use super::Block;

/// How each cube is split.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Split {
    /// 5 tets per cube; the split alternates with the parity of `i + j + k`
    /// so that the diagonals of shared cube faces match (the reference's grid).
    Five,
    /// 6 tets around the main diagonal of every cube (Kuhn split).
    Six,
}

impl Split {
    /// Tets per cube.
    pub fn tets_per_cube(self) -> usize {
        match self {
            Split::Five => 5,
            Split::Six => 6,
        }
    }
}

impl TryFrom<u8> for Split {
    type Error = GridError;

    /// 5 or 6 tets per cube; any other number is an error naming it.
    fn try_from(n: u8) -> Result<Split, GridError> {
        match n {
            5 => Ok(Split::Five),
            6 => Ok(Split::Six),
            n => Err(GridError::Split(n)),
        }
    }
}

/// Why a box grid cannot be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum GridError {
    /// A resolution entry is 0.
    #[error("grid resolution along axis {axis} is 0")]
    ZeroResolution {
        /// 0, 1 or 2.
        axis: usize,
    },
    /// Min and max of an axis are not finite with min < max.
    #[error("grid bounds along axis {axis} are not increasing finite numbers: {lo} .. {hi}")]
    Bounds {
        /// 0, 1 or 2.
        axis: usize,
        /// The given min.
        lo: f64,
        /// The given max.
        hi: f64,
    },
    /// `(nx + 1) (ny + 1) (nz + 1)` does not fit 32-bit vertex ids.
    #[error("grid {res:?} has too many vertices for 32-bit ids")]
    TooManyVertices {
        /// The resolution asked for.
        res: [usize; 3],
    },
    /// The grid lines of an axis are not distinct finite doubles.
    #[error("grid bounds along axis {axis}, {lo:e} .. {hi:e} with {n} cubes: {reason}; give bounds whose width is finite and spacing representable")]
    Spacing {
        /// 0, 1 or 2.
        axis: usize,
        /// The given min.
        lo: f64,
        /// The given max.
        hi: f64,
        /// Cubes along the axis.
        n: usize,
        /// What goes wrong.
        reason: String,
    },
    /// A cube split other than 5 or 6.
    #[error("a cube splits into 5 or 6 tets, not {0}")]
    Split(u8),
}

/// Coordinate of grid line `i` of `n` cubes over `[lo, hi]`: `lo + (hi - lo)
/// * i / n` (the reference data's formula, bit-identical vertices), and
/// exactly `hi` at `i = n` (the formula can miss it by an ulp).
pub fn grid_coordinate(lo: f64, hi: f64, i: usize, n: usize) -> f64 {
    if i == n {
        hi
    } else {
        lo + (hi - lo) * i as f64 / n as f64
    }
}

/// Local cube corner `(dx, dy, dz)` packed as `dx * 4 + dy * 2 + dz`.
const fn c(dx: u8, dy: u8, dz: u8) -> u8 {
    dx * 4 + dy * 2 + dz
}

/// 5-split of a cube with `i + j + k` even (same tets and vertex order as the
/// reference grid in the shared data folder (`isn/`); all positively oriented).
const FIVE_EVEN: [[u8; 4]; 5] = [
    [c(1, 0, 0), c(0, 1, 0), c(0, 0, 1), c(1, 1, 1)],
    [c(0, 0, 0), c(1, 0, 0), c(0, 1, 0), c(0, 0, 1)],
    [c(1, 1, 0), c(0, 1, 0), c(1, 0, 0), c(1, 1, 1)],
    [c(1, 0, 1), c(0, 0, 1), c(1, 1, 1), c(1, 0, 0)],
    [c(0, 1, 1), c(1, 1, 1), c(0, 0, 1), c(0, 1, 0)],
];
/// 5-split of a cube with `i + j + k` odd.
const FIVE_ODD: [[u8; 4]; 5] = [
    [c(1, 1, 0), c(0, 0, 0), c(1, 0, 1), c(0, 1, 1)],
    [c(0, 0, 0), c(1, 0, 0), c(1, 1, 0), c(1, 0, 1)],
    [c(1, 1, 0), c(0, 1, 0), c(0, 0, 0), c(0, 1, 1)],
    [c(1, 0, 1), c(0, 0, 1), c(0, 1, 1), c(0, 0, 0)],
    [c(0, 1, 1), c(1, 1, 1), c(1, 0, 1), c(1, 1, 0)],
];
/// Kuhn split: paths 000 -> +e_a -> +e_a+e_b -> 111 over the 6 axis
/// orders, with two vertices swapped where needed for positive orientation.
const SIX: [[u8; 4]; 6] = [
    [c(0, 0, 0), c(1, 0, 0), c(1, 1, 0), c(1, 1, 1)],
    [c(0, 0, 0), c(1, 0, 1), c(1, 0, 0), c(1, 1, 1)],
    [c(0, 0, 0), c(1, 1, 0), c(0, 1, 0), c(1, 1, 1)],
    [c(0, 0, 0), c(0, 1, 0), c(0, 1, 1), c(1, 1, 1)],
    [c(0, 0, 0), c(0, 0, 1), c(1, 0, 1), c(1, 1, 1)],
    [c(0, 0, 0), c(0, 1, 1), c(0, 0, 1), c(1, 1, 1)],
];

/// A box `bounds[0]..bounds[1]` of `res[0] * res[1] * res[2]` cubes.
///
/// Vertex `(i, j, k)` has id `i * (ny+1) * (nz+1) + j * (nz+1) + k`; cube
/// `(i, j, k)` has id `(i * ny + j) * nz + k` and owns the tets
/// `cube * per_cube .. (cube + 1) * per_cube`.
#[derive(Clone, Debug, PartialEq)]
pub struct BoxGrid {
    /// Cubes per axis.
    pub res: [usize; 3],
    /// Min and max corner.
    pub bounds: [[f64; 3]; 2],
    /// Cube split.
    pub split: Split,
}

impl BoxGrid {
    /// A box grid; `res` entries must be at least 1 and the bounds increasing.
    pub fn new(res: [usize; 3], bounds: [[f64; 3]; 2], split: Split) -> Result<BoxGrid, GridError> {
        for a in 0..3 {
            if res[a] == 0 {
                return Err(GridError::ZeroResolution { axis: a });
            }
            let increasing = bounds[0][a].partial_cmp(&bounds[1][a]) == Some(std::cmp::Ordering::Less);
            if !increasing || !bounds[0][a].is_finite() || !bounds[1][a].is_finite() {
                return Err(GridError::Bounds { axis: a, lo: bounds[0][a], hi: bounds[1][a] });
            }
        }
        // Checked: `--grid 18446744073709551615` must not wrap to a small grid.
        let n = (res[0].checked_add(1))
            .and_then(|x| x.checked_mul(res[1].checked_add(1)?))
            .and_then(|x| x.checked_mul(res[2].checked_add(1)?))
            .filter(|&x| x < u32::MAX as usize);
        if n.is_none() {
            return Err(GridError::TooManyVertices { res });
        }
        for a in 0..3 {
            let (lo, hi, n) = (bounds[0][a], bounds[1][a], res[a]);
            super::spacing::check_axis(lo, hi, n, |i| grid_coordinate(lo, hi, i, n))
                .map_err(|reason| GridError::Spacing { axis: a, lo, hi, n, reason })?;
        }
        Ok(BoxGrid { res, bounds, split })
    }

    /// Number of vertices.
    pub fn num_vertices(&self) -> usize {
        (self.res[0] + 1) * (self.res[1] + 1) * (self.res[2] + 1)
    }

    /// Number of cubes.
    pub fn num_cubes(&self) -> usize {
        self.res[0] * self.res[1] * self.res[2]
    }

    /// Number of tets.
    pub fn num_tets(&self) -> usize {
        self.num_cubes() * self.split.tets_per_cube()
    }

    /// Id of grid vertex `(i, j, k)`.
    pub fn vertex_index(&self, [i, j, k]: [usize; 3]) -> u32 {
        ((i * (self.res[1] + 1) + j) * (self.res[2] + 1) + k) as u32
    }

    /// `(i, j, k)` of vertex `v`.
    pub fn vertex_ijk(&self, v: u32) -> [usize; 3] {
        let v = v as usize;
        let (ny, nz) = (self.res[1] + 1, self.res[2] + 1);
        [v / (ny * nz), (v / nz) % ny, v % nz]
    }

    /// Position of vertex `v`.
    pub fn vertex(&self, v: u32) -> [f64; 3] {
        let ijk = self.vertex_ijk(v);
        let mut p = [0.0; 3];
        for a in 0..3 {
            p[a] = grid_coordinate(self.bounds[0][a], self.bounds[1][a], ijk[a], self.res[a]);
        }
        p
    }

    /// Id of cube `(i, j, k)`.
    pub fn cube_index(&self, [i, j, k]: [usize; 3]) -> usize {
        (i * self.res[1] + j) * self.res[2] + k
    }

    /// Tet `t`, positively oriented.
    pub fn tet(&self, t: usize) -> [u32; 4] {
        let per = self.split.tets_per_cube();
        let (cube, local) = (t / per, t % per);
        let k = cube % self.res[2];
        let j = (cube / self.res[2]) % self.res[1];
        let i = cube / (self.res[2] * self.res[1]);
        self.tet_corners([i, j, k], local).map(|p| {
            let d = [(p >> 2) as usize & 1, (p >> 1) as usize & 1, p as usize & 1];
            self.vertex_index([i + d[0], j + d[1], k + d[2]])
        })
    }

    /// The corners of tet `local` of cube `cube` as offsets from the cube's
    /// first corner, bit 2 / 1 / 0 set for +1 along i / j / k.
    pub fn tet_corners(&self, cube: [usize; 3], local: usize) -> [u8; 4] {
        match self.split {
            Split::Five if (cube[0] + cube[1] + cube[2]) % 2 == 0 => FIVE_EVEN[local],
            Split::Five => FIVE_ODD[local],
            Split::Six => SIX[local],
        }
    }

    /// Blocks of `size^3` cubes (smaller at the far sides).
    pub fn blocks(&self, size: usize) -> Vec<Block> {
        let mut out = Vec::new();
        for i in (0..self.res[0]).step_by(size) {
            for j in (0..self.res[1]).step_by(size) {
                for k in (0..self.res[2]).step_by(size) {
                    out.push(Block::Cubes {
                        lo: [i, j, k],
                        hi: [(i + size).min(self.res[0]), (j + size).min(self.res[1]), (k + size).min(self.res[2])],
                    });
                }
            }
        }
        out
    }

    /// Volume of the box.
    pub fn volume(&self) -> f64 {
        (0..3).map(|a| self.bounds[1][a] - self.bounds[0][a]).product()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn det(g: &BoxGrid, t: usize) -> f64 {
        let [a, b, c, d] = g.tet(t).map(|v| g.vertex(v));
        crate::grid::tet_volume(&a, &b, &c, &d)
    }

    #[test]
    fn splits_positive_and_fill_the_box() {
        for split in [Split::Five, Split::Six] {
            let g = BoxGrid::new([3, 2, 4], [[0.0; 3], [3.0, 2.0, 4.0]], split).unwrap();
            let mut vol = 0.0;
            for t in 0..g.num_tets() {
                let v = det(&g, t);
                assert!(v > 0.0, "{split:?} tet {t} volume {v}");
                vol += v;
            }
            assert!((vol - 24.0).abs() < 1e-12);
        }
    }

    #[test]
    fn cube_faces_match() {
        // Every tet face is shared by two tets or lies on the box boundary.
        use std::collections::HashMap;
        for split in [Split::Five, Split::Six] {
            let g = BoxGrid::new([3, 3, 3], [[0.0; 3], [1.0; 3]], split).unwrap();
            let mut faces: HashMap<[u32; 3], usize> = HashMap::new();
            for t in 0..g.num_tets() {
                let tet = g.tet(t);
                for skip in 0..4 {
                    let mut f: Vec<u32> = (0..4).filter(|&x| x != skip).map(|x| tet[x]).collect();
                    f.sort();
                    *faces.entry([f[0], f[1], f[2]]).or_default() += 1;
                }
            }
            let boundary = faces.values().filter(|&&n| n == 1).count();
            assert!(faces.values().all(|&n| n <= 2));
            assert_eq!(boundary, 6 * 9 * 2, "{split:?}");
        }
    }

    #[test]
    fn invalid_grids_are_typed_errors_naming_the_axis() {
        let unit = [[0.0; 3], [1.0; 3]];
        assert_eq!(BoxGrid::new([2, 0, 2], unit, Split::Five), Err(GridError::ZeroResolution { axis: 1 }));
        let flat = [[0.0, 0.0, 1.0], [1.0, 1.0, 1.0]];
        let e = BoxGrid::new([2; 3], flat, Split::Five).unwrap_err();
        assert_eq!(e, GridError::Bounds { axis: 2, lo: 1.0, hi: 1.0 });
        assert_eq!(e.to_string(), "grid bounds along axis 2 are not increasing finite numbers: 1 .. 1");
        let nan = [[0.0, f64::NAN, 0.0], [1.0; 3]];
        assert!(matches!(BoxGrid::new([2; 3], nan, Split::Six), Err(GridError::Bounds { axis: 1, .. })));
        let huge = [usize::MAX, 1, 1];
        assert_eq!(BoxGrid::new(huge, unit, Split::Five), Err(GridError::TooManyVertices { res: huge }));
        assert_eq!(Split::try_from(7), Err(GridError::Split(7)));
        assert_eq!(Split::try_from(6), Ok(Split::Six));
    }
}
