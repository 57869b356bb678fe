//! Per-vertex normals from analytic gradients (Bloomenthal 4.6 and
//! 4.5.3.2), and the scene-level block test of sparse evaluation.

use super::grid_spec::GridSpec;
use super::region_rule::RegionId;
use super::sample::{block_may_be_active_ia, block_may_be_active_mi};
use super::scene::{Mode, Scene};
use super::vec3::{normalize, sub, V3};

impl Scene {
    /// Unit normal at `p` of the zero set of function `f` (IA patches),
    /// pointing to where `f` grows (into the function's inside); zero where
    /// the gradient vanishes.
    pub fn normal_ia(&self, f: usize, p: V3) -> V3 {
        normalize(self.functions[f].gradient(p))
    }

    /// Unit normal at `p` of the interface between materials `i` and `j`
    /// (MI patches, where `f_i = f_j`): the gradient of `f_i - f_j`,
    /// pointing into material `i`.
    pub fn normal_mi(&self, i: usize, j: usize, p: V3) -> V3 {
        normalize(sub(self.functions[i].gradient(p), self.functions[j].gradient(p)))
    }

    /// Orient `n`, a normal pointing into `region_of_n` across a surface
    /// separating it from `other`, so that it points into the lesser region
    /// (the side from which polygons are counter-clockwise, Bloomenthal
    /// 4.5.2.4).
    pub fn toward_lesser(n: V3, region_of_n: RegionId, other: RegionId) -> V3 {
        if region_of_n > other {
            n.map(|x| -x)
        } else {
            n
        }
    }

    /// Sparse evaluation (docs/sparse.md): false when the block of grid cubes
    /// between grid vertices `first` and `last` (inclusive) provably holds
    /// no part of the network, by the primitives' bounds (IA: every
    /// function keeps one strict sign; MI: one material dominates).
    ///
    /// ```
    /// use septa::scene::Scene;
    /// let s = Scene::load("builtin:sphere-with-hole").unwrap();
    /// assert!(!s.block_may_be_active([0, 0, 0], [4, 4, 4]));
    /// assert!(s.block_may_be_active([12, 12, 12], [20, 20, 20]));
    /// ```
    pub fn block_may_be_active(&self, first: [usize; 3], last: [usize; 3]) -> bool {
        let (lo, hi) = self.grid.block_box(first, last);
        match self.mode {
            Mode::Ia => block_may_be_active_ia(&self.functions, lo, hi),
            Mode::Mi => block_may_be_active_mi(&self.functions, lo, hi),
        }
    }
}

impl Scene {
    /// The grid vertices and every function's value at them (row-major
    /// `(N, k)`, see [`super::sample_grid`]): the dense input of the
    /// IA / MI pipeline.
    pub fn sample(&self) -> (Vec<V3>, Vec<f64>) {
        let v = self.grid.vertices();
        let values = super::sample_grid(&self.functions, &v);
        (v, values)
    }
}

impl GridSpec {
    /// The box spanned by grid vertices `first ..= last`, with exactly the
    /// coordinates [`GridSpec::vertex`] gives (vertex coordinates are
    /// monotone in the index, so every vertex of the block is inside).
    pub fn block_box(&self, first: [usize; 3], last: [usize; 3]) -> (V3, V3) {
        (self.vertex(first), self.vertex(last))
    }
}
