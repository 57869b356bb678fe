//! Signed distance to a closed triangle mesh, positive inside.
//!
//! Inside/outside comes from the generalized winding number (sum of the
//! triangles' signed solid angles, Van Oosterom and Strackee's formula):
//! inside when it exceeds 1/2. These are *sampled values*, input data for
//! the exact pipeline, never a topological decision, so floating point is
//! the right tool here. A bounding volume hierarchy (`mesh_bvh.rs`) gives
//! the exact closest point and the fast winding number in about
//! logarithmic time per point.

use super::interval::Interval;
use super::mesh_bvh::{closest_on_triangle, solid_angle, Bvh};
use super::shapes::lipschitz;
use super::vec3::*;

/// A triangle mesh held in memory (0-based vertex indices), with its
/// search hierarchy.
#[derive(Clone, Debug)]
pub struct TriMesh {
    vertices: Vec<V3>,
    triangles: Vec<[u32; 3]>,
    bvh: Bvh,
    /// Every directed edge appears once and its reverse once: closed and
    /// consistently oriented, so the winding number is 0 or 1 off the
    /// surface and the sign of `eval` is trustworthy for bounds.
    closed: bool,
}

impl PartialEq for TriMesh {
    fn eq(&self, o: &TriMesh) -> bool {
        self.vertices == o.vertices && self.triangles == o.triangles
    }
}

impl TriMesh {
    /// A mesh from vertices and triangles (counter-clockwise seen from
    /// outside); `None` if an index is out of range or there is no triangle.
    pub fn new(vertices: Vec<V3>, triangles: Vec<[u32; 3]>) -> Option<TriMesh> {
        let n = vertices.len();
        if triangles.is_empty() || triangles.iter().flatten().any(|&i| i as usize >= n) {
            return None;
        }
        let bvh = Bvh::build(&vertices, &triangles);
        let mut directed: Vec<(u32, u32)> =
            triangles.iter().flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])]).collect();
        directed.sort_unstable();
        let unique = directed.windows(2).all(|w| w[0] != w[1]);
        let closed = unique && directed.iter().all(|&(a, b)| directed.binary_search(&(b, a)).is_ok());
        Some(TriMesh { vertices, triangles, bvh, closed })
    }

    /// Vertex positions.
    pub fn vertices(&self) -> &[V3] {
        &self.vertices
    }

    /// Triangles.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// Fast generalized winding number around `p` (about 1 inside a
    /// closed, outward-oriented mesh, 0 outside; exact near the surface).
    pub fn winding_number(&self, p: V3) -> f64 {
        self.bvh.winding(&self.vertices, &self.triangles, p)
    }

    /// The exact sum of the triangles' solid angles (linear time).
    pub fn winding_number_exact(&self, p: V3) -> f64 {
        let total: f64 = self
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.vertices[i as usize]);
                solid_angle(p, a, b, c)
            })
            .sum();
        total / (4.0 * std::f64::consts::PI)
    }

    /// Unsigned distance and closest point.
    fn closest(&self, p: V3) -> (f64, V3) {
        self.bvh.closest(&self.vertices, &self.triangles, p)
    }

    /// Distance and closest point by visiting every triangle (linear time;
    /// the reference for the hierarchy).
    pub fn closest_exhaustive(&self, p: V3) -> (f64, V3) {
        let mut best = (f64::INFINITY, p);
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| self.vertices[i as usize]);
            let q = closest_on_triangle(p, a, b, c);
            let d = norm(sub(p, q));
            if d < best.0 {
                best = (d, q);
            }
        }
        best
    }

    fn sign(&self, p: V3) -> f64 {
        if self.winding_number(p) > 0.5 {
            1.0
        } else {
            -1.0
        }
    }

    pub(crate) fn eval(&self, p: V3) -> f64 {
        self.sign(p) * self.closest(p).0
    }

    pub(crate) fn gradient(&self, p: V3) -> V3 {
        let (_, q) = self.closest(p);
        // f = s d: outside -d (grad -(p-q)/d), inside +d (grad (p-q)/d).
        scale(unit_or_zero(sub(p, q)), self.sign(p))
    }

    pub(crate) fn bounds(&self, lo: V3, hi: V3) -> Interval {
        if !self.closed {
            // The winding number of an open mesh can put the sign anywhere:
            // no bound (sparse evaluation samples every block near it).
            return Interval::ENTIRE;
        }
        let err = mesh_error(self, super::rounding::box_mag(lo, hi));
        lipschitz(|p| self.eval(p), 1.0, lo, hi, err)
    }

    /// Closed and consistently oriented (every directed edge once, its
    /// reverse once): the sign of [`TriMesh`]'s distance is trustworthy.
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// Largest absolute vertex coordinate.
    pub(crate) fn magnitude(&self) -> f64 {
        self.vertices.iter().map(|v| mag(*v)).fold(0.0, f64::max)
    }
}

/// Error of the computed signed distance against the exact one, for the
/// Lipschitz bound (signed distance is 1-Lipschitz). The closest point on a
/// triangle is a few dozen roundings of coordinates of size `A + |mesh|`,
/// so `1e-10` of that is a margin of about a million. The sign is the one
/// assumption: the winding number must be on the right side of 1/2. It is
/// computed exactly (sum of solid angles) near the surface and by a far
/// field expansion whose error is far below 1/2 elsewhere, for a closed,
/// consistently oriented mesh (an open mesh gets no bound at all).
pub(crate) fn mesh_error(m: &TriMesh, a: f64) -> f64 {
    1e-10 * (1.0 + a + m.magnitude())
}

/// Read a closed triangle mesh file (`.obj`, `.off`, `.ply`, `.stl`, by
/// extension) with the readers of [`crate::io::read_mesh`].
pub fn read_tri_mesh(path: &std::path::Path) -> Result<TriMesh, String> {
    let m = crate::io::read_mesh(path).map_err(|e| e.to_string())?;
    TriMesh::new(m.vertices, m.triangles).ok_or_else(|| format!("{}: no triangles", path.display()))
}
