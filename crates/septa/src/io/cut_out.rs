//! Writers for cut-cell meshes: `cells.vtu` (VTK unstructured grid of
//! `VTK_POLYHEDRON` cells with a `cell_id` array), `cells.obj` (one group
//! per cell) and `cut.json`. Every file is written to a temporary name in
//! the same folder and renamed, so a reader never sees half a file.

use crate::cut::CutCellMesh;
use std::fmt::Write as _;

pub use super::atomic::write_atomic;

/// Boundary polygons of each cell, oriented outwards, each as a face of
/// one loop ([`CutCellMesh::cell_polygons`]: faces with holes or with
/// rounded vertices off their plane are written as their triangles).
pub fn cell_faces(m: &CutCellMesh) -> Vec<Vec<Vec<Vec<u32>>>> {
    m.cell_polygons().into_iter().map(|c| c.into_iter().map(|p| vec![p]).collect()).collect()
}

/// `cells.vtu`: one `VTK_POLYHEDRON` (type 42) per cut-cell.
pub fn vtu(m: &CutCellMesh) -> String {
    let cells = cell_faces(m);
    let mut s = String::new();
    let _ = writeln!(s, "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>");
    let _ = writeln!(s, "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">", m.vertices.len(), m.num_cells);
    s.push_str("<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
    for v in &m.vertices {
        let _ = writeln!(s, "{:?} {:?} {:?}", v[0], v[1], v[2]);
    }
    s.push_str("</DataArray></Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
    let mut offsets = Vec::new();
    let mut faces_stream = Vec::new();
    let mut face_offsets = Vec::new();
    let mut n = 0usize;
    for c in &cells {
        let mut used: Vec<u32> = c.iter().flatten().flatten().copied().collect();
        used.sort_unstable();
        used.dedup();
        for v in &used {
            let _ = write!(s, "{v} ");
        }
        s.push('\n');
        n += used.len();
        offsets.push(n);
        let nloops: usize = c.iter().map(|f| f.len()).sum();
        faces_stream.push(nloops);
        for f in c {
            for l in f {
                faces_stream.push(l.len());
                faces_stream.extend(l.iter().map(|&v| v as usize));
            }
        }
        face_offsets.push(faces_stream.len());
    }
    s.push_str("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
    for o in &offsets {
        let _ = write!(s, "{o} ");
    }
    s.push_str("\n</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    for _ in &cells {
        s.push_str("42 ");
    }
    s.push_str("\n</DataArray>\n<DataArray type=\"Int64\" Name=\"faces\" format=\"ascii\">\n");
    for x in &faces_stream {
        let _ = write!(s, "{x} ");
    }
    s.push_str("\n</DataArray>\n<DataArray type=\"Int64\" Name=\"faceoffsets\" format=\"ascii\">\n");
    for x in &face_offsets {
        let _ = write!(s, "{x} ");
    }
    s.push_str("\n</DataArray>\n</Cells>\n<CellData Scalars=\"cell_id\">\n<DataArray type=\"Int32\" Name=\"cell_id\" format=\"ascii\">\n");
    for i in 0..m.num_cells {
        let _ = write!(s, "{i} ");
    }
    s.push_str("\n</DataArray>\n<DataArray type=\"Float64\" Name=\"volume\" format=\"ascii\">\n");
    for v in &m.cell_volumes {
        let _ = write!(s, "{v:?} ");
    }
    s.push_str("\n</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
    s
}

/// `cells.obj`: a group `cell_<i>` per cut-cell with its faces oriented
/// outwards; with `explode > 0` each cell is moved away from the mesh centre
/// by that fraction of its centroid offset (exploded view).
pub fn obj(m: &CutCellMesh, explode: f64) -> String {
    let cells = cell_faces(m);
    let mut s = String::from("# septa cut-cell mesh\n");
    let centre = {
        let n = m.vertices.len().max(1) as f64;
        let mut c = [0.0; 3];
        for v in &m.vertices {
            for k in 0..3 {
                c[k] += v[k] / n;
            }
        }
        c
    };
    let mut base = 1usize;
    for (i, c) in cells.iter().enumerate() {
        let mut used: Vec<u32> = c.iter().flatten().flatten().copied().collect();
        used.sort_unstable();
        used.dedup();
        let mut cen = [0.0; 3];
        for &v in &used {
            for k in 0..3 {
                cen[k] += m.vertices[v as usize][k] / used.len() as f64;
            }
        }
        let shift: [f64; 3] = std::array::from_fn(|k| explode * (cen[k] - centre[k]));
        let _ = writeln!(s, "g cell_{i}");
        for &v in &used {
            let x = m.vertices[v as usize];
            let _ = writeln!(s, "v {:?} {:?} {:?}", x[0] + shift[0], x[1] + shift[1], x[2] + shift[2]);
        }
        let local = |v: u32| base + used.binary_search(&v).unwrap();
        for f in c {
            for l in f {
                s.push('f');
                for &v in l {
                    let _ = write!(s, " {}", local(v));
                }
                s.push('\n');
            }
        }
        base += used.len();
    }
    s
}
