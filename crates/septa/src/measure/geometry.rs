//! The geometry the measures rest on: the box a network was computed in
//! and the small vector sums (Newell's area vector) over written doubles.

use crate::grid::BoxGrid;

/// The box a network was computed in: its resolution (for the exact test
/// of which vertices lie on its faces) and its corner `origin` with its
/// three edge vectors (a parallelepiped: a label volume placed by an affine
/// voxel-to-world map).
#[derive(Clone, Debug, PartialEq)]
pub struct BoxDomain {
    /// Cubes per axis.
    pub res: [usize; 3],
    /// World position of grid vertex `(0, 0, 0)`.
    pub origin: [f64; 3],
    /// World vector from `origin` to the last grid vertex along each axis.
    pub edges: [[f64; 3]; 3],
}

impl BoxDomain {
    /// The domain of a box grid.
    pub fn of_box(g: &BoxGrid) -> BoxDomain {
        let [lo, hi] = g.bounds;
        let mut edges = [[0.0; 3]; 3];
        for (a, e) in edges.iter_mut().enumerate() {
            e[a] = hi[a] - lo[a];
        }
        BoxDomain { res: g.res, origin: lo, edges }
    }

    /// This domain mapped by `x -> M x + t` (`affine` rows `[M | t]`).
    pub fn mapped(&self, affine: &[[f64; 4]; 3]) -> BoxDomain {
        let lin = |v: [f64; 3]| -> [f64; 3] {
            std::array::from_fn(|r| affine[r][0] * v[0] + affine[r][1] * v[1] + affine[r][2] * v[2])
        };
        let o = lin(self.origin);
        BoxDomain { res: self.res, origin: std::array::from_fn(|r| o[r] + affine[r][3]), edges: self.edges.map(lin) }
    }

    /// The domain's volume.
    pub fn volume(&self) -> f64 {
        dot(self.edges[0], cross(self.edges[1], self.edges[2])).abs()
    }

    /// Whether the domain is a mirror image of its grid (a voxel-to-world
    /// map with a negative determinant): every polygon's counter-clockwise
    /// side is then its negative side in space.
    pub fn mirrored(&self) -> bool {
        dot(self.edges[0], cross(self.edges[1], self.edges[2])) < 0.0
    }
}

pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
pub(crate) fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// Twice the vector area of a planar polygon (Newell), pointing to the side
/// from which it is counter-clockwise: its positive side.
pub(crate) fn area_vector(points: &[[f64; 3]], poly: &[u32]) -> [f64; 3] {
    let p0 = points[poly[0] as usize];
    let mut n = [0.0; 3];
    for k in 1..poly.len() - 1 {
        let c = cross(sub(points[poly[k] as usize], p0), sub(points[poly[k + 1] as usize], p0));
        for i in 0..3 {
            n[i] += c[i];
        }
    }
    n
}

/// Twice the area of a planar polygon.
pub(crate) fn area_vector_len(points: &[[f64; 3]], poly: &[u32]) -> f64 {
    norm(area_vector(points, poly))
}

/// A polygon's cells as [the side its loop is counter-clockwise from in
/// space, the other]: swapped in a mirrored domain.
pub(crate) fn oriented(cells: [u32; 2], mirrored: bool) -> [u32; 2] {
    if mirrored {
        [cells[1], cells[0]]
    } else {
        cells
    }
}
