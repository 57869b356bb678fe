//! An explicit tetrahedral mesh, validated and positively oriented.

use std::collections::HashMap;

use septa_exact::{det_sign_diff, Sign};

use super::overlap::find_overlap;

/// Why a tet mesh was rejected. Each variant names the element.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// A vertex coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate {value}")]
    NonFiniteVertex {
        /// Vertex id.
        vertex: usize,
        /// The coordinate.
        value: f64,
    },
    /// A tet refers to a vertex that does not exist.
    #[error("tet {tet} refers to vertex {index}, but there are only {count} vertices")]
    IndexOutOfRange {
        /// Tet id.
        tet: usize,
        /// The bad index.
        index: i64,
        /// Number of vertices.
        count: usize,
    },
    /// A tet has zero volume (exactly), e.g. a repeated vertex.
    #[error("tet {tet} {vertices:?} has zero volume")]
    Degenerate {
        /// Tet id.
        tet: usize,
        /// Its vertices.
        vertices: [u32; 4],
    },
    /// A triangle is shared by more than two tets, or two tets overlap across it.
    #[error("face {face:?} is shared by tets {tets:?}: the mesh is not a manifold with boundary")]
    NonManifold {
        /// The face's vertices (sorted).
        face: [u32; 3],
        /// Tets sharing it.
        tets: Vec<usize>,
    },
    /// Two tets share interior points (an extra tet laid over others):
    /// decided exactly, also for tets that share no face.
    #[error(
        "tets {first} and {second} overlap (their interiors intersect): a tet mesh must cover each point at most once"
    )]
    Overlap {
        /// The smaller tet id.
        first: usize,
        /// The other tet id.
        second: usize,
    },
    /// No tets (or no vertices): nothing to compute on.
    #[error("the mesh has {vertices} vertices and {tets} tets: at least one tet is needed")]
    Empty {
        /// Number of vertices.
        vertices: usize,
        /// Number of tets.
        tets: usize,
    },
    /// Two vertices used by tets have one position: the tets on either side
    /// would not share their faces (a seam that splits cells).
    #[error("vertices {first} and {second} are at the same position {point:?}: a tet mesh needs one id per point (merge them)")]
    Coincident {
        /// The smaller vertex id.
        first: u32,
        /// The other vertex id.
        second: u32,
        /// The position.
        point: [f64; 3],
    },
    /// More vertices than 32-bit ids allow.
    #[error("{count} vertices: at most 2^32 - 1 are supported")]
    TooLarge {
        /// Number of vertices.
        count: usize,
    },
}

/// A tet mesh: positions and positively oriented tets.
#[derive(Clone, Debug, PartialEq)]
pub struct TetMesh {
    /// Vertex positions.
    pub vertices: Vec<[f64; 3]>,
    /// Tets, each with `det[v1-v0, v2-v0, v3-v0] > 0`.
    pub tets: Vec<[u32; 4]>,
}

/// Exact orientation sign of a tet (`det[v1-v0, v2-v0, v3-v0]`).
pub fn orientation(p: &[[f64; 3]; 4]) -> Sign {
    let a = [p[1], p[2], p[3]];
    let b = [p[0], p[0], p[0]];
    det_sign_diff(&a, &b)
}

impl TetMesh {
    /// Validates a mesh: finite coordinates, indices in range, no zero-volume
    /// tet (exact test), every face shared by at most two tets lying on
    /// opposite sides of it, no two tets with a common interior point (exact
    /// test on every pair with overlapping bounding boxes). Inverted tets are re-oriented by swapping their
    /// last two vertices.
    pub fn new(vertices: Vec<[f64; 3]>, tets: &[[i64; 4]]) -> Result<TetMesh, MeshError> {
        if tets.is_empty() || vertices.is_empty() {
            // Before: an .npz of 0 vertices and 0 tets panicked in the network.
            return Err(MeshError::Empty { vertices: vertices.len(), tets: tets.len() });
        }
        if vertices.len() >= u32::MAX as usize {
            return Err(MeshError::TooLarge { count: vertices.len() });
        }
        for (v, p) in vertices.iter().enumerate() {
            if let Some(&value) = p.iter().find(|x| !x.is_finite()) {
                return Err(MeshError::NonFiniteVertex { vertex: v, value });
            }
        }
        let mut out = Vec::with_capacity(tets.len());
        for (t, tet) in tets.iter().enumerate() {
            let mut ids = [0u32; 4];
            for (slot, &index) in ids.iter_mut().zip(tet) {
                if index < 0 || index as usize >= vertices.len() {
                    return Err(MeshError::IndexOutOfRange { tet: t, index, count: vertices.len() });
                }
                *slot = index as u32;
            }
            let p = ids.map(|v| vertices[v as usize]);
            match orientation(&p) {
                Sign::Positive => {}
                Sign::Negative => ids.swap(2, 3),
                Sign::Zero => return Err(MeshError::Degenerate { tet: t, vertices: ids }),
            }
            out.push(ids);
        }
        check_coincident(&vertices, &out)?;
        check_manifold(&out)?;
        if let Some((first, second)) = find_overlap(&vertices, &out) {
            return Err(MeshError::Overlap { first, second });
        }
        Ok(TetMesh { vertices, tets: out })
    }
}

impl TetMesh {
    /// The first pair of tets whose interiors intersect (exact), if any;
    /// [`TetMesh::new`] refuses such meshes, so this is `None` for any
    /// mesh it built. Public for benchmarks and for checking meshes
    /// assembled by hand.
    pub fn first_overlap(&self) -> Option<(usize, usize)> {
        find_overlap(&self.vertices, &self.tets)
    }
}

/// No two vertices used by tets at one position (`-0.0` and `0.0` are one).
fn check_coincident(vertices: &[[f64; 3]], tets: &[[u32; 4]]) -> Result<(), MeshError> {
    let mut used = vec![false; vertices.len()];
    for &v in tets.iter().flatten() {
        used[v as usize] = true;
    }
    let mut at: HashMap<[u64; 3], u32> = HashMap::new();
    for (v, p) in vertices.iter().enumerate().filter(|&(v, _)| used[v]) {
        let key = p.map(|x| if x == 0.0 { 0 } else { x.to_bits() });
        if let Some(&first) = at.get(&key) {
            return Err(MeshError::Coincident { first, second: v as u32, point: *p });
        }
        at.insert(key, v as u32);
    }
    Ok(())
}

/// Each face at most twice, and with opposite orientations when twice
/// (then the two tets lie on opposite sides of it).
fn check_manifold(tets: &[[u32; 4]]) -> Result<(), MeshError> {
    // Value: (first tet, orientation parity of the face in it, count).
    let mut faces: HashMap<[u32; 3], (usize, bool, u8)> = HashMap::with_capacity(tets.len() * 2);
    for (t, tet) in tets.iter().enumerate() {
        for skip in 0..4 {
            let (key, parity) = face_key(tet, skip);
            let e = faces.entry(key).or_insert((t, parity, 0));
            e.2 += 1;
            if e.2 > 2 || (e.2 == 2 && e.1 == parity) {
                return Err(MeshError::NonManifold { face: key, tets: vec![e.0, t] });
            }
        }
    }
    Ok(())
}

/// Sorted vertices of the face opposite local vertex `skip`, and the parity
/// of the permutation that sorts its outward-oriented loop.
pub(crate) fn face_key(tet: &[u32; 4], skip: usize) -> ([u32; 3], bool) {
    // Loops counter-clockwise seen from inside, as in complex/ (TET_FACES).
    const LOOPS: [[usize; 3]; 4] = [[1, 3, 2], [0, 2, 3], [0, 3, 1], [0, 1, 2]];
    let mut f = LOOPS[skip].map(|i| tet[i]);
    let mut parity = false;
    for i in 0..3 {
        for j in 0..2 - i {
            if f[j] > f[j + 1] {
                f.swap(j, j + 1);
                parity = !parity;
            }
        }
    }
    (f, parity)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> Vec<[f64; 3]> {
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 1.0]]
    }

    #[test]
    fn reorients_and_rejects() {
        let m = TetMesh::new(unit(), &[[0, 2, 1, 3]]).unwrap();
        assert_eq!(orientation(&m.tets[0].map(|v| m.vertices[v as usize])), Sign::Positive);
        assert!(matches!(
            TetMesh::new(unit(), &[[0, 1, 2, 7]]),
            Err(MeshError::IndexOutOfRange { tet: 0, index: 7, .. })
        ));
        assert!(matches!(TetMesh::new(unit(), &[[0, 1, 2, 2]]), Err(MeshError::Degenerate { tet: 0, .. })));
        let mut bad = unit();
        bad[3][1] = f64::NAN;
        assert!(matches!(TetMesh::new(bad, &[[0, 1, 2, 3]]), Err(MeshError::NonFiniteVertex { vertex: 3, .. })));
        // Two tets on the same side of face (1,2,3): overlap.
        let mut v = unit();
        v.push([0.1, 0.1, 0.1]);
        assert!(matches!(TetMesh::new(v.clone(), &[[0, 1, 2, 3], [5, 1, 2, 3]]), Err(MeshError::NonManifold { .. })));
        assert!(TetMesh::new(v, &[[0, 1, 2, 3], [4, 1, 2, 3]]).is_ok());
    }
}
