//! Bottom-up splitting of every element by one plane (Du et al. Sec. 4.1).
//!
//! Given the sign of the new plane at every vertex, edges whose ends have
//! opposite signs get a cut-vertex, faces with both signs get a cut-edge
//! between their two zero vertices, and cells with both signs get a
//! cut-face from the loop of zero edges on their boundary. Zero-signed
//! vertices are the degenerate case: an element is split only if it has a
//! strictly positive and a strictly negative vertex, and cut-edges and
//! cut-faces may run through existing zero vertices and zero edges.
//!
//! With exact signs every split is unambiguous (convexity: a plane meets a
//! convex polygon's boundary in at most two points). With the naive
//! floating-point signs it can fail; that is reported as
//! [`BuildError::Ambiguous`], the paper's Type II failure.

use smallvec::SmallVec;

use super::build::BuildError;
use super::predicate::Predicates;
use super::types::{Complex, Edge, Face, Mode, Plane, Vertex, NONE};

/// Per-build scratch arrays, reused across functions and tets.
#[derive(Clone, Debug, Default)]
pub(crate) struct Scratch {
    pub edge_cut: Vec<u32>,
    pub edge_child: Vec<u32>,
    pub edge_material: Vec<u16>,
    pub face_side: Vec<i8>,
    pub face_child: Vec<u32>,
    pub face_cut_edge: Vec<u32>,
    pub cell_side: Vec<i8>,
    // Plain vectors: reused across builds, so a push is one length check
    // (a SmallVec also tests whether it has spilled on every access).
    pub loop_v: Vec<u32>,
    pub loop_e: Vec<u32>,
    pub directed: Vec<(u32, u32, u32)>,
    pub merge: super::merge::MergeBuffers,
}

/// The vertex where three planes meet, named by the tet element it lies on
/// and the union of the functions of its planes (Sec. 5.1).
pub(crate) fn vertex_from_planes(planes: [Plane; 3]) -> Vertex {
    let mut simplex = 0b1111u8;
    // At most 6 functions from 3 pair planes, distinct ones first-come.
    let mut funcs = [0u16; 6];
    let mut n = 0;
    let mut add = |f: u16| {
        if !funcs[..n].contains(&f) {
            funcs[n] = f;
            n += 1;
        }
    };
    for p in planes {
        match p {
            Plane::TetFace(i) => simplex &= !(1 << i),
            Plane::Function(f) => add(f),
            Plane::Pair(a, b) => {
                add(a);
                add(b)
            }
        }
    }
    Vertex::new(simplex, &funcs[..n.min(4)])
}

impl Complex {
    /// Splits every element by the plane of function `new` (IA) or by the
    /// planes `f_j = f_new` with `j` the material of each element (MI),
    /// using the signs in `self.vsign`. Afterwards `scratch.cell_side`
    /// holds `+1`/`-1` per cell.
    pub(crate) fn split(&mut self, preds: &Predicates, new: u16, s: &mut Scratch) -> Result<(), BuildError> {
        let mode = preds.mode;
        if mode == Mode::Mi {
            s.edge_material.clear();
            s.edge_material.resize(self.edges.len(), 0);
            for cell in &self.cells {
                for &f in &cell.faces {
                    for &e in &self.faces[f as usize].edges {
                        s.edge_material[e as usize] = cell.material;
                    }
                }
            }
        }
        let cut_plane = |j: u16| match mode {
            Mode::Ia => Plane::Function(new),
            Mode::Mi => Plane::pair(j, new).0,
        };

        // 1. Edges with ends of opposite signs get a cut-vertex.
        let n_edges = self.edges.len();
        s.edge_cut.clear();
        s.edge_cut.resize(n_edges, NONE);
        s.edge_child.clear();
        s.edge_child.resize(n_edges, NONE);
        for e in 0..n_edges {
            let Edge { vertices: [a, b], planes } = self.edges[e];
            if self.vsign[a as usize] * self.vsign[b as usize] >= 0 {
                continue;
            }
            // MI: any function maximal along the edge names the cut plane;
            // one already among the edge's planes keeps the vertex's
            // function set to the d + 1 that meet there (ties along whole
            // edges make several cells' materials maximal on it).
            let j = match planes {
                _ if mode == Mode::Ia => 0,
                [Plane::Pair(p, _), _] | [_, Plane::Pair(p, _)] => p,
                _ => s.edge_material[e],
            };
            let v = vertex_from_planes([planes[0], planes[1], cut_plane(j)]);
            let orient = preds.orient(&v);
            if orient == 0 {
                return Err(BuildError::Ambiguous { function: new as usize, element: "cut-vertex" });
            }
            let c = self.vertices.len() as u32;
            self.vertices.push(v);
            self.orient.push(orient);
            self.vsign.push(0);
            self.edges[e].vertices = [a, c];
            s.edge_cut[e] = c;
            s.edge_child[e] = self.edges.len() as u32;
            self.edges.push(Edge { vertices: [c, b], planes });
        }

        // 2. Faces with both signs get a cut-edge between their zero vertices.
        let n_faces = self.faces.len();
        s.face_side.clear();
        s.face_side.resize(n_faces, 0);
        s.face_child.clear();
        s.face_child.resize(n_faces, NONE);
        s.face_cut_edge.clear();
        s.face_cut_edge.resize(n_faces, NONE);
        for f in 0..n_faces {
            // Most faces neither gain a cut-vertex nor change sign: decide
            // those from the stored loop without copying it (cut-vertices
            // have sign 0, so they never change `pos`/`neg`).
            let (mut pos, mut neg) = (false, false);
            let mut cut = false;
            {
                let face = &self.faces[f];
                for (&v, &e) in face.vertices.iter().zip(&face.edges) {
                    pos |= self.vsign[v as usize] > 0;
                    neg |= self.vsign[v as usize] < 0;
                    cut |= s.edge_cut[e as usize] != NONE;
                }
            }
            if cut || (pos && neg) {
                self.insert_cut_vertices(f, s);
            }
            if !(pos && neg) {
                s.face_side[f] = if pos {
                    1
                } else if neg {
                    -1
                } else {
                    0
                };
                continue;
            }
            let face = &self.faces[f];
            let (plane, cells) = (face.plane, face.cells);
            let j = if mode == Mode::Mi {
                let c = if cells[0] != NONE { cells[0] } else { cells[1] };
                self.cells[c as usize].material
            } else {
                0
            };
            let ambiguous = BuildError::Ambiguous { function: new as usize, element: "face" };
            let n = s.loop_v.len();
            let mut zeros: SmallVec<[usize; 4]> = SmallVec::new();
            for k in 0..n {
                if self.vsign[s.loop_v[k] as usize] == 0 {
                    zeros.push(k);
                }
            }
            if zeros.len() != 2 || zeros[1] - zeros[0] < 2 || zeros[0] + n - zeros[1] < 2 {
                return Err(ambiguous);
            }
            let (i, k) = (zeros[0], zeros[1]);
            let first_positive = self.vsign[s.loop_v[i + 1] as usize] > 0;
            // The run i..=k and the run k..=i (cyclic) must each be of one sign.
            let run_sign = |from: usize, to: usize, s: &Scratch| {
                let mut m = from + 1;
                let mut sign = 0i8;
                while m % n != to % n {
                    let sv = self.vsign[s.loop_v[m % n] as usize];
                    if sv == 0 || (sign != 0 && sv != sign) {
                        return 0;
                    }
                    sign = sv;
                    m += 1;
                }
                sign
            };
            let (r1, r2) = (run_sign(i, k, s), run_sign(k, i + n, s));
            if r1 == 0 || r2 == 0 || r1 == r2 {
                return Err(ambiguous);
            }
            let (zi, zk) = (s.loop_v[i], s.loop_v[k]);
            let ne = self.edges.len() as u32;
            self.edges.push(Edge { vertices: [zi, zk], planes: [plane, cut_plane(j)] });
            // Part A: i..=k then the cut-edge back to i. Part B: k..=i (cyclic) then the cut-edge back to k.
            // Part A stays in face f's buffers (written in place), part B
            // is the new child face; which is positive decides the order.
            // Built by `collect` and `from_slice` (one reservation, then
            // plain copies) rather than by `extend_from_slice`, whose
            // general insertion was a measurable share of the split.
            let cyclic = |l: &[u32], last: u32| -> SmallVec<[u32; 8]> {
                l[k..].iter().chain(&l[..i]).copied().chain(std::iter::once(last)).collect()
            };
            let mut b_v = cyclic(&s.loop_v, zi);
            let mut b_e = cyclic(&s.loop_e, ne);
            let face = &mut self.faces[f];
            face.vertices = SmallVec::from_slice(&s.loop_v[i..=k]);
            face.edges = s.loop_e[i..k].iter().copied().chain(std::iter::once(ne)).collect();
            if !first_positive {
                std::mem::swap(&mut face.vertices, &mut b_v);
                std::mem::swap(&mut face.edges, &mut b_e);
            }
            let child = self.faces.len() as u32;
            self.faces.push(Face { plane, vertices: b_v, edges: b_e, cells });
            s.face_side[f] = 1;
            s.face_side.push(-1);
            s.face_child[f] = child;
            s.face_cut_edge[f] = ne;
        }

        // 3. Cells with both signs get a cut-face bounded by the zero edges of their positive faces.
        let n_cells = self.cells.len();
        s.cell_side.clear();
        s.cell_side.resize(n_cells, 0);
        for c in 0..n_cells {
            let (mut pos, mut neg) = (false, false);
            for &f in &self.cells[c].faces {
                let side = s.face_side[f as usize];
                pos |= side > 0 || s.face_child[f as usize] != NONE;
                neg |= side < 0 || s.face_child[f as usize] != NONE;
            }
            if !(pos && neg) {
                s.cell_side[c] = if pos { 1 } else { -1 };
                if mode == Mode::Ia {
                    self.cells[c].set_sign(new, pos);
                }
                continue;
            }
            self.split_cell(c as u32, new, cut_plane(self.cells[c].material), s)?;
        }
        Ok(())
    }

    /// Loads face `f`'s loop into `s.loop_v`/`s.loop_e` with the new
    /// cut-vertices inserted, and stores it back into the face.
    fn insert_cut_vertices(&mut self, f: usize, s: &mut Scratch) {
        s.loop_v.clear();
        s.loop_e.clear();
        let face = &self.faces[f];
        let mut changed = false;
        for (&v, &e) in face.vertices.iter().zip(face.edges.iter()) {
            s.loop_v.push(v);
            let c = s.edge_cut[e as usize];
            if c == NONE {
                s.loop_e.push(e);
                continue;
            }
            changed = true;
            let child = s.edge_child[e as usize];
            // After the split, edge e runs (a, c) and its child (c, b).
            if self.edges[e as usize].vertices[0] == v {
                s.loop_e.push(e);
                s.loop_v.push(c);
                s.loop_e.push(child);
            } else {
                s.loop_e.push(child);
                s.loop_v.push(c);
                s.loop_e.push(e);
            }
        }
        if changed {
            let face = &mut self.faces[f];
            face.vertices = SmallVec::from_slice(&s.loop_v);
            face.edges = SmallVec::from_slice(&s.loop_e);
        }
    }

    /// Splits cell `c` (which has both signs) by a new face on `plane`.
    fn split_cell(&mut self, c: u32, new: u16, plane: Plane, s: &mut Scratch) -> Result<(), BuildError> {
        let ambiguous = BuildError::Ambiguous { function: new as usize, element: "cell" };
        // Faces of c after the face splits, with their sides.
        let mut pos_faces: SmallVec<[u32; 16]> = SmallVec::new();
        let mut neg_faces: SmallVec<[u32; 16]> = SmallVec::new();
        for &f in &self.cells[c as usize].faces {
            let child = s.face_child[f as usize];
            if child != NONE {
                pos_faces.push(f);
                neg_faces.push(child);
            } else if s.face_side[f as usize] > 0 {
                pos_faces.push(f);
            } else if s.face_side[f as usize] < 0 {
                neg_faces.push(f);
            } else {
                return Err(ambiguous);
            }
        }
        // The cut-face's edges are the zero edges of the positive faces. The
        // new face's normal points into the positive part, so it runs each
        // such edge against a positive face oriented into c, and along one
        // oriented out of c.
        s.directed.clear();
        for &g in &pos_faces {
            let face = &self.faces[g as usize];
            let inward = face.cells[0] == c;
            let (fv, fe): (&[u32], &[u32]) = (&face.vertices, &face.edges);
            let n = fv.len();
            for k in 0..n {
                let (p, q) = (fv[k], fv[if k + 1 == n { 0 } else { k + 1 }]);
                if self.vsign[p as usize] == 0 && self.vsign[q as usize] == 0 {
                    let e = fe[k];
                    s.directed.push(if inward { (q, p, e) } else { (p, q, e) });
                }
            }
        }
        let m = s.directed.len();
        if m < 3 {
            return Err(ambiguous);
        }
        let mut verts: SmallVec<[u32; 8]> = SmallVec::new();
        let mut edges: SmallVec<[u32; 8]> = SmallVec::new();
        let (start, mut to, e0) = s.directed[0];
        verts.push(start);
        edges.push(e0);
        while to != start {
            if verts.len() >= m {
                return Err(ambiguous);
            }
            let Some(&(from, next, e)) = s.directed.iter().find(|d| d.0 == to) else {
                return Err(ambiguous);
            };
            verts.push(from);
            edges.push(e);
            to = next;
        }
        if verts.len() != m {
            return Err(ambiguous);
        }
        let c2 = self.cells.len() as u32;
        let nf = self.faces.len() as u32;
        self.faces.push(Face { plane, vertices: verts, edges, cells: [c, c2] });
        for &f in &neg_faces {
            let cells = &mut self.faces[f as usize].cells;
            for x in cells.iter_mut() {
                if *x == c {
                    *x = c2;
                }
            }
        }
        let old = &self.cells[c as usize];
        let mut neg_cell =
            super::types::Cell { faces: SmallVec::new(), positive: old.positive.clone(), material: old.material };
        neg_cell.faces.extend_from_slice(&neg_faces);
        neg_cell.faces.push(nf);
        let cell = &mut self.cells[c as usize];
        cell.faces.clear();
        cell.faces.extend_from_slice(&pos_faces);
        cell.faces.push(nf);
        match plane {
            Plane::Function(_) => {
                cell.set_sign(new, true);
                neg_cell.set_sign(new, false);
            }
            _ => neg_cell.material = new,
        }
        self.cells.push(neg_cell);
        s.cell_side[c as usize] = 1;
        s.cell_side.push(-1);
        Ok(())
    }
}
