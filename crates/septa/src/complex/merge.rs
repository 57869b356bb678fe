//! The merging step of the material-interface update (Du et al. Sec. 4.2).
//!
//! After splitting by `f_j - f_new`, every cell lies on one side: cells with
//! a negative vertex are where the new function wins. Their union is convex
//! (the region where `f_new` is maximal), so they merge into one cell: faces
//! between two of them disappear, their faces on each tet face merge into
//! one convex face, and vertices strictly inside the new region disappear
//! (tet corners stay, now labelled by the new function), merging the tet
//! edge segments around them.

use smallvec::SmallVec;

use super::split::Scratch;
use super::types::{Cell, Complex, Edge, Face, Plane, Vertex, NONE};

/// Buffers of [`Complex::merge`], kept between calls.
#[derive(Clone, Debug, Default)]
pub(crate) struct MergeBuffers {
    faces: Vec<Face>,
    cells: Vec<Cell>,
    edges: Vec<Edge>,
    vertices: Vec<Vertex>,
    orient: Vec<i8>,
    vsign: Vec<i8>,
    face_map: Vec<u32>,
    cell_map: Vec<u32>,
    edge_map: Vec<u32>,
    vertex_map: Vec<u32>,
}

impl Complex {
    /// Merges the negative cells of the last split into one cell of material `new`.
    pub(crate) fn merge(&mut self, new: u16, s: &mut Scratch) {
        let neg = |c: u32| c != NONE && s.cell_side[c as usize] < 0;
        if !(0..self.cells.len() as u32).any(neg) {
            return;
        }
        let keep_vertex = |v: u32, this: &Complex| !(this.vsign[v as usize] < 0 && this.vertices[v as usize].dim() > 0);

        // Buffers reused across calls: the old arrays become next call's buffers.
        let mut faces = std::mem::take(&mut s.merge.faces);
        faces.clear();
        let mut face_map = std::mem::take(&mut s.merge.face_map);
        face_map.clear();
        face_map.resize(self.faces.len(), NONE);
        let mut new_cell_faces: SmallVec<[u32; 8]> = SmallVec::new();
        // Directed boundary edges of the negative sub-faces of each tet face.
        let mut groups: [SmallVec<[(u32, u32, u32); 12]>; 4] = Default::default();
        let new_cell = NONE - 1; // placeholder id, fixed below
        for (f, face) in self.faces.iter().enumerate() {
            let [c0, c1] = face.cells;
            match face.plane {
                Plane::TetFace(t) if neg(c0) => {
                    let n = face.vertices.len();
                    for k in 0..n {
                        groups[t as usize].push((face.vertices[k], face.vertices[(k + 1) % n], face.edges[k]));
                    }
                }
                _ if neg(c0) && neg(c1) => {}
                _ if neg(c0) || neg(c1) => {
                    let mut face = face.clone();
                    let (pos_cell, pos_first) = if neg(c0) { (c1, false) } else { (c0, true) };
                    let involves_new = matches!(face.plane, Plane::Pair(_, b) if b == new);
                    if !involves_new {
                        // A face on which f_new ties with both old materials:
                        // it now separates the positive cell's material from f_new.
                        let m = self.cells[pos_cell as usize].material;
                        face.plane = Plane::pair(m, new).0;
                    }
                    if !pos_first {
                        reverse_loop(&mut face);
                    }
                    face.cells = [pos_cell, new_cell];
                    face_map[f] = faces.len() as u32;
                    new_cell_faces.push(faces.len() as u32);
                    faces.push(face);
                }
                _ => {
                    face_map[f] = faces.len() as u32;
                    faces.push(face.clone());
                }
            }
        }

        // One merged face per tet face: the boundary of the union of its
        // negative sub-faces, with vertices inside the new region dropped.
        let mut merged_edges: SmallVec<[(u32, u32, u32); 8]> = SmallVec::new();
        let mut extra_edges: Vec<Edge> = Vec::new();
        let n_old_edges = self.edges.len() as u32;
        for (t, group) in groups.iter().enumerate() {
            if group.is_empty() {
                continue;
            }
            let boundary: SmallVec<[(u32, u32, u32); 12]> =
                group.iter().copied().filter(|&(a, b, _)| !group.iter().any(|&(p, q, _)| p == b && q == a)).collect();
            // Chain the boundary into a loop starting at a kept vertex.
            let Some(start) = boundary.iter().position(|&(a, _, _)| keep_vertex(a, self)) else {
                continue;
            };
            let mut verts: SmallVec<[u32; 8]> = SmallVec::new();
            let mut edges: SmallVec<[u32; 8]> = SmallVec::new();
            let (mut cur, mut to, mut first_edge) = boundary[start];
            let mut span = 1;
            loop {
                if keep_vertex(to, self) {
                    let e = if span == 1 {
                        first_edge
                    } else {
                        merged_edge(cur, to, first_edge, &mut merged_edges, &mut extra_edges, self, n_old_edges)
                    };
                    verts.push(cur);
                    edges.push(e);
                    cur = to;
                    if cur == boundary[start].0 {
                        break;
                    }
                    let &(_, nt, ne) = boundary.iter().find(|d| d.0 == cur).expect("closed boundary");
                    to = nt;
                    first_edge = ne;
                    span = 1;
                } else {
                    let &(_, nt, _) = boundary.iter().find(|d| d.0 == to).expect("closed boundary");
                    to = nt;
                    span += 1;
                }
                if verts.len() > boundary.len() {
                    break;
                }
            }
            new_cell_faces.push(faces.len() as u32);
            faces.push(Face { plane: Plane::TetFace(t as u8), vertices: verts, edges, cells: [new_cell, NONE] });
        }

        // Cells: the positive ones keep their faces; the new one is appended.
        let mut cells = std::mem::take(&mut s.merge.cells);
        cells.clear();
        let mut cell_map = std::mem::take(&mut s.merge.cell_map);
        cell_map.clear();
        cell_map.resize(self.cells.len(), NONE);
        for (c, cell) in self.cells.iter().enumerate() {
            if neg(c as u32) {
                continue;
            }
            let mut cell = cell.clone();
            cell.faces = cell.faces.iter().map(|&f| face_map[f as usize]).filter(|&f| f != NONE).collect();
            cell_map[c] = cells.len() as u32;
            cells.push(cell);
        }
        let new_id = cells.len() as u32;
        let mut template = self.cells[0].clone();
        template.faces = new_cell_faces;
        template.material = new;
        cells.push(template);
        for face in &mut faces {
            for c in &mut face.cells {
                *c = match *c {
                    NONE => NONE,
                    x if x == new_cell => new_id,
                    x => cell_map[x as usize],
                };
            }
        }

        // Keep only the edges and vertices that surviving faces use.
        let mut all_edges = std::mem::take(&mut self.edges);
        all_edges.extend(extra_edges);
        let mut edge_map = std::mem::take(&mut s.merge.edge_map);
        edge_map.clear();
        edge_map.resize(all_edges.len(), NONE);
        let mut edges = std::mem::take(&mut s.merge.edges);
        edges.clear();
        let mut vertex_map = std::mem::take(&mut s.merge.vertex_map);
        vertex_map.clear();
        vertex_map.resize(self.vertices.len(), NONE);
        let mut vertices = std::mem::take(&mut s.merge.vertices);
        vertices.clear();
        let mut orient = std::mem::take(&mut s.merge.orient);
        orient.clear();
        let mut vsign = std::mem::take(&mut s.merge.vsign);
        vsign.clear();
        for face in &mut faces {
            for e in face.edges.iter_mut() {
                if edge_map[*e as usize] == NONE {
                    edge_map[*e as usize] = edges.len() as u32;
                    let mut edge = all_edges[*e as usize];
                    for v in edge.vertices.iter_mut() {
                        if vertex_map[*v as usize] == NONE {
                            vertex_map[*v as usize] = vertices.len() as u32;
                            let mut vert = self.vertices[*v as usize];
                            if self.vsign[*v as usize] < 0 {
                                vert.set_functions(&[new]); // a tet corner now of material f_new
                            }
                            vertices.push(vert);
                            orient.push(self.orient[*v as usize]);
                            vsign.push(self.vsign[*v as usize]);
                        }
                        *v = vertex_map[*v as usize];
                    }
                    edges.push(edge);
                }
                *e = edge_map[*e as usize];
            }
            for v in face.vertices.iter_mut() {
                *v = vertex_map[*v as usize];
            }
        }
        let m = &mut s.merge;
        m.vertices = std::mem::replace(&mut self.vertices, vertices);
        m.orient = std::mem::replace(&mut self.orient, orient);
        m.vsign = std::mem::replace(&mut self.vsign, vsign);
        self.edges = edges;
        m.edges = all_edges;
        m.faces = std::mem::replace(&mut self.faces, faces);
        m.cells = std::mem::replace(&mut self.cells, cells);
        (m.face_map, m.cell_map, m.edge_map, m.vertex_map) = (face_map, cell_map, edge_map, vertex_map);
    }
}

/// The edge replacing a run of tet-edge segments from `a` to `b` through
/// dropped vertices; shared by the two tet faces along that tet edge.
fn merged_edge(
    a: u32,
    b: u32,
    first: u32,
    merged: &mut SmallVec<[(u32, u32, u32); 8]>,
    extra: &mut Vec<Edge>,
    this: &Complex,
    base: u32,
) -> u32 {
    let key = (a.min(b), a.max(b));
    if let Some(&(_, _, e)) = merged.iter().find(|m| (m.0, m.1) == key) {
        return e;
    }
    let e = base + extra.len() as u32;
    extra.push(Edge { vertices: [a, b], planes: this.edges[first as usize].planes });
    merged.push((key.0, key.1, e));
    e
}

/// Reverses a face's loop in place, keeping `edges[i]` between `vertices[i]` and `vertices[i+1]`.
pub(crate) fn reverse_loop(face: &mut Face) {
    let n = face.vertices.len();
    let v: SmallVec<[u32; 8]> = (0..n).map(|i| face.vertices[(n - i) % n]).collect();
    let e: SmallVec<[u32; 8]> = (0..n).map(|i| face.edges[(2 * n - 1 - i) % n]).collect();
    face.vertices = v;
    face.edges = e;
}
