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
        Some(TriMesh { vertices, triangles, bvh })
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
        lipschitz(|p| self.eval(p), 1.0, lo, hi)
    }

    /// Largest absolute vertex coordinate.
    pub(crate) fn magnitude(&self) -> f64 {
        self.vertices.iter().map(|v| mag(*v)).fold(0.0, f64::max)
    }
}

/// Problem found while reading a mesh file.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshFileError {
    /// 1-based line number (0 when not line-based).
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

/// Read the `v` and `f` records of a Wavefront OBJ text (polygons are
/// fan-triangulated; `f 1/2/3` forms and negative indices are accepted;
/// other records are ignored).
pub fn parse_obj(text: &str) -> Result<TriMesh, MeshFileError> {
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let err = |message: String| MeshFileError { line: n + 1, message };
        let mut it = line.split_whitespace();
        match it.next() {
            Some("v") => {
                let c: Vec<f64> = it
                    .take(3)
                    .map(|s| s.parse::<f64>())
                    .collect::<Result<_, _>>()
                    .map_err(|e| err(format!("bad vertex coordinate: {e}")))?;
                if c.len() != 3 || c.iter().any(|x| !x.is_finite()) {
                    return Err(err("a vertex needs 3 finite coordinates".into()));
                }
                vertices.push([c[0], c[1], c[2]]);
            }
            Some("f") => {
                let mut idx = Vec::new();
                for s in it {
                    let first = s.split('/').next().unwrap_or("");
                    let i: i64 = first.parse().map_err(|_| err(format!("bad face index `{s}`")))?;
                    let nv = vertices.len() as i64;
                    let k = if i < 0 { nv + i } else { i - 1 };
                    if k < 0 || k >= nv {
                        return Err(err(format!("face index {i} out of range (have {nv} vertices)")));
                    }
                    idx.push(k as u32);
                }
                if idx.len() < 3 {
                    return Err(err("a face needs at least 3 vertices".into()));
                }
                for w in 1..idx.len() - 1 {
                    triangles.push([idx[0], idx[w], idx[w + 1]]);
                }
            }
            _ => {}
        }
    }
    if triangles.is_empty() {
        return Err(MeshFileError { line: 0, message: "no triangles".into() });
    }
    TriMesh::new(vertices, triangles).ok_or(MeshFileError { line: 0, message: "bad triangle".into() })
}

/// Read an STL file, binary or ASCII (a triangle soup: the winding number
/// and the distance need no shared vertices).
pub fn parse_stl(bytes: &[u8]) -> Result<TriMesh, MeshFileError> {
    let fail = |line: usize, message: String| MeshFileError { line, message };
    let binary_len = |n: usize| 84 + 50 * n;
    let is_binary = bytes.len() >= 84 && {
        let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
        binary_len(n) == bytes.len()
    };
    let mut vertices = Vec::new();
    if is_binary {
        let n = (bytes.len() - 84) / 50;
        for t in 0..n {
            let at = 84 + 50 * t + 12;
            for v in 0..3 {
                let c = [0, 1, 2].map(|a| {
                    let i = at + 12 * v + 4 * a;
                    f32::from_le_bytes([bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]]) as f64
                });
                if c.iter().any(|x| !x.is_finite()) {
                    return Err(fail(0, format!("triangle {t}: non-finite coordinate")));
                }
                vertices.push(c);
            }
        }
    } else {
        let text =
            std::str::from_utf8(bytes).map_err(|_| fail(0, "neither binary STL (size mismatch) nor text".into()))?;
        for (n, line) in text.lines().enumerate() {
            let mut it = line.split_whitespace();
            if it.next() == Some("vertex") {
                let c: Vec<f64> = it
                    .map(|s| s.parse::<f64>())
                    .collect::<Result<_, _>>()
                    .map_err(|e| fail(n + 1, format!("bad vertex coordinate: {e}")))?;
                if c.len() != 3 || c.iter().any(|x| !x.is_finite()) {
                    return Err(fail(n + 1, "a vertex needs 3 finite coordinates".into()));
                }
                vertices.push([c[0], c[1], c[2]]);
            }
        }
        if vertices.len() % 3 != 0 {
            return Err(fail(0, format!("{} vertices is not a multiple of 3", vertices.len())));
        }
    }
    if vertices.is_empty() {
        return Err(fail(0, "no triangles".into()));
    }
    let triangles = (0..vertices.len() as u32 / 3).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    TriMesh::new(vertices, triangles).ok_or(MeshFileError { line: 0, message: "bad triangle".into() })
}
