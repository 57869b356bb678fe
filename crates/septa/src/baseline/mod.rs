//! Baseline extractors for benchmarks (Du et al. Sec. 8.3): what Septa's
//! exact network is measured against, on the same input arrays.
//!
//! - [`marching_tets`]: the zero set of each function separately, by
//!   marching tetrahedra (Doi and Koide 1991), with no arrangement.
//! - [`label_separating`]: polygons separating grid vertices with
//!   different labels (IA: sign vectors; MI: argmax), as in Nielson and
//!   Franke 1997 and Dillard et al. 2007.
//!
//! Neither is exact nor used for anything but timing; both are written
//! plainly and single-threaded so that ratios compare algorithms.

mod label_separating;
mod marching;

pub use label_separating::label_separating;
pub use marching::marching_tets;

/// A polygon soup: points and polygons as CSR (`offsets`, `indices`).
#[derive(Clone, Debug, Default)]
pub struct Soup {
    /// Point coordinates.
    pub points: Vec<[f64; 3]>,
    /// Polygon `i` is `indices[offsets[i]..offsets[i + 1]]`.
    pub offsets: Vec<u32>,
    /// Point ids of all polygons.
    pub indices: Vec<u32>,
}

impl Soup {
    fn new() -> Soup {
        Soup { points: Vec::new(), offsets: vec![0], indices: Vec::new() }
    }

    fn push_polygon(&mut self, ids: &[u32]) {
        self.indices.extend_from_slice(ids);
        self.offsets.push(self.indices.len() as u32);
    }

    /// Number of polygons.
    pub fn num_polygons(&self) -> usize {
        self.offsets.len() - 1
    }
}
