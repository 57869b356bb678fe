//! A canonical form of a complex, independent of function order and of the
//! numbering of its elements, for comparing two builds (the paper's Type I
//! test, Sec. 8.1).
//!
//! Every vertex is keyed by its plane-based encoding with functions mapped
//! back to the caller's ids (an MI tet corner by its corner alone, since a
//! tie there may be encoded by either function); an edge by its two vertex
//! keys, a face by its plane and sorted vertex keys, a cell by its label and
//! sorted face keys. The form is the sorted list of each. Plane-based keys
//! are unique also with exact ties: a point where more planes meet than
//! define it is renamed by the point alone after the build (`ties.rs`).

use super::types::{Complex, Mode, Plane};

/// Sorted keys of all vertices, edges, faces and cells; compare with `==`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CanonicalForm {
    vertices: Vec<Vec<u32>>,
    edges: Vec<Vec<Vec<u32>>>,
    faces: Vec<(Vec<u32>, Vec<Vec<u32>>)>,
    cells: Vec<(Vec<u32>, Vec<(Vec<u32>, Vec<Vec<u32>>)>)>,
}

impl CanonicalForm {
    /// The canonical form of `c`, whose local function `i` is the caller's
    /// function `ids[i]`.
    pub fn new(c: &Complex, ids: &[u32]) -> CanonicalForm {
        let mi = c.mode == Some(Mode::Mi);
        let vkey = |v: u32| {
            let vert = &c.vertices[v as usize];
            let mut k = vec![vert.simplex() as u32];
            if !(mi && vert.dim() == 0) {
                let mut f: Vec<u32> = vert.functions().iter().map(|&i| ids[i as usize]).collect();
                f.sort_unstable();
                k.extend(f);
            }
            k
        };
        let pkey = |p: Plane| match p {
            Plane::TetFace(t) => vec![0, t as u32],
            Plane::Function(i) => vec![1, ids[i as usize]],
            Plane::Pair(a, b) => {
                let (a, b) = (ids[a as usize], ids[b as usize]);
                vec![2, a.min(b), a.max(b)]
            }
        };
        let fkey = |f: u32| {
            let face = &c.faces[f as usize];
            let mut vs: Vec<Vec<u32>> = face.vertices.iter().map(|&v| vkey(v)).collect();
            vs.sort();
            (pkey(face.plane), vs)
        };
        let mut vertices: Vec<Vec<u32>> = (0..c.vertices.len() as u32).map(vkey).collect();
        vertices.sort();
        let mut edges: Vec<Vec<Vec<u32>>> = c
            .edges
            .iter()
            .map(|e| {
                let mut k = vec![vkey(e.vertices[0]), vkey(e.vertices[1])];
                k.sort();
                k
            })
            .collect();
        edges.sort();
        let mut faces: Vec<_> = (0..c.faces.len() as u32).map(fkey).collect();
        faces.sort();
        let mut cells: Vec<_> = c
            .cells
            .iter()
            .map(|cell| {
                let label: Vec<u32> = if mi {
                    vec![ids[cell.material as usize]]
                } else {
                    let mut pos: Vec<u32> =
                        (0..c.num_functions as u16).filter(|&i| cell.is_positive(i)).map(|i| ids[i as usize]).collect();
                    pos.sort_unstable();
                    pos
                };
                let mut fs: Vec<_> = cell.faces.iter().map(|&f| fkey(f)).collect();
                fs.sort();
                (label, fs)
            })
            .collect();
        cells.sort();
        CanonicalForm { vertices, edges, faces, cells }
    }

    /// Numbers of vertices, edges, faces and cells.
    pub fn counts(&self) -> [usize; 4] {
        [self.vertices.len(), self.edges.len(), self.faces.len(), self.cells.len()]
    }
}
