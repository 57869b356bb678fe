//! Tetrahedral grids: built-in boxes of cubes split into 5 or 6 tets, and
//! arbitrary tet meshes (Du et al. 2022, Sec. 3: the background grid).
//!
//! Every grid hands out positively oriented tets (`det[v1-v0, v2-v0, v3-v0] > 0`)
//! and a decomposition into [`Block`]s, the unit of parallel work and of
//! the block-wise assembly of the network (docs/sparse.md: blocks merge exactly in
//! any order because every key is global).

mod boxgrid;
mod lookup;
pub mod memory;
mod mesh;
mod overlap;
mod spacing;

pub use boxgrid::{grid_coordinate, BoxGrid, GridError, Split};
pub(crate) use lookup::VertexLookup;
pub use mesh::{MeshError, TetMesh};

/// A tetrahedral grid.
#[derive(Clone, Debug)]
pub enum Grid {
    /// A box of cubes.
    Box(BoxGrid),
    /// An explicit tet mesh.
    Mesh(TetMesh),
}

/// A unit of work: a set of tets processed together.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Block {
    /// The cubes `lo[a] <= c[a] < hi[a]` of a [`BoxGrid`].
    Cubes {
        /// First cube per axis.
        lo: [usize; 3],
        /// One past the last cube per axis.
        hi: [usize; 3],
    },
    /// A range of tet ids of a [`TetMesh`].
    Tets(std::ops::Range<usize>),
}

impl Grid {
    /// Number of grid vertices.
    pub fn num_vertices(&self) -> usize {
        match self {
            Grid::Box(g) => g.num_vertices(),
            Grid::Mesh(m) => m.vertices.len(),
        }
    }

    /// Number of tets.
    pub fn num_tets(&self) -> usize {
        match self {
            Grid::Box(g) => g.num_tets(),
            Grid::Mesh(m) => m.tets.len(),
        }
    }

    /// Position of vertex `v`.
    pub fn vertex(&self, v: u32) -> [f64; 3] {
        match self {
            Grid::Box(g) => g.vertex(v),
            Grid::Mesh(m) => m.vertices[v as usize],
        }
    }

    /// All vertex positions, in vertex order.
    pub fn vertices(&self) -> Vec<[f64; 3]> {
        (0..self.num_vertices() as u32).map(|v| self.vertex(v)).collect()
    }

    /// The (positively oriented) tet `t`.
    pub fn tet(&self, t: usize) -> [u32; 4] {
        match self {
            Grid::Box(g) => g.tet(t),
            Grid::Mesh(m) => m.tets[t],
        }
    }

    /// Blocks covering every tet exactly once; `size` is the block edge in
    /// cubes for boxes (a mesh gets ranges of about `5 * size^3` tets).
    pub fn blocks(&self, size: usize) -> Vec<Block> {
        let size = size.max(1);
        match self {
            Grid::Box(g) => g.blocks(size),
            Grid::Mesh(m) => {
                let step = 5 * size * size * size;
                (0..m.tets.len()).step_by(step).map(|s| Block::Tets(s..(s + step).min(m.tets.len()))).collect()
            }
        }
    }

    /// Ids of the tets of a block, in a fixed order.
    pub fn block_tets(&self, block: &Block, out: &mut Vec<usize>) {
        out.clear();
        match (self, block) {
            (Grid::Box(g), Block::Cubes { lo, hi }) => {
                let per = g.split.tets_per_cube();
                for i in lo[0]..hi[0] {
                    for j in lo[1]..hi[1] {
                        for k in lo[2]..hi[2] {
                            let c = g.cube_index([i, j, k]);
                            out.extend(c * per..(c + 1) * per);
                        }
                    }
                }
            }
            (_, Block::Tets(r)) => out.extend(r.clone()),
            (Grid::Mesh(_), Block::Cubes { .. }) => {}
        }
    }

    /// Total volume of the tets (for the volume invariant).
    pub fn volume(&self) -> f64 {
        match self {
            Grid::Box(g) => g.volume(),
            Grid::Mesh(m) => (0..m.tets.len()).map(|t| self.tet_volume(t)).sum(),
        }
    }

    /// Volume of tet `t` (floating point, for output only).
    pub fn tet_volume(&self, t: usize) -> f64 {
        let [a, b, c, d] = self.tet(t).map(|v| self.vertex(v));
        tet_volume(&a, &b, &c, &d)
    }
}

/// Signed volume of a tet (floating point; output only).
pub fn tet_volume(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> f64 {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let w = [d[0] - a[0], d[1] - a[1], d[2] - a[2]];
    (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0
}
