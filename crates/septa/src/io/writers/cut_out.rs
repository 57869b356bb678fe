//! Writers for cut-cell meshes: `cells.vtu` (binary VTK unstructured grid of
//! `VTK_POLYHEDRON` cells, fewest points first, with `cell_id` and `volume`
//! arrays), `cells.obj` (one group per cell) and `cut.json`. Every file is written to a temporary name in
//! the same folder and renamed, so a reader never sees half a file.

use crate::cut::{CellPolygons, CutCellMesh};
use crate::io::writers::cut_float::FloatText;

/// `cells.vtu`: one `VTK_POLYHEDRON` (type 42) per cut-cell, binary
/// (inline base64), with cell data `cell_id` (the cut-cell each row is) and
/// `volume`. Cells are written by their number of distinct points, fewest
/// first, in id order among equals: meshio reads polyhedra into one block
/// per point count in the order the counts first occur but hands out the
/// cell data by ascending count, so any other order gives it misaligned
/// (or refused) cell data. The blocks are then those of `CutCells.to_meshio`.
pub fn cut_cells_vtu(m: &CutCellMesh) -> String {
    cut_cells_vtu_of(m, &m.cell_polygons_flat())
}

/// [`cut_cells_vtu`] of the cells' polygons already formed
/// (`CutCellMesh::cell_polygons_flat`; once for both files when both are
/// written).
pub fn cut_cells_vtu_of(m: &CutCellMesh, polys: &CellPolygons) -> String {
    let mut points = cell_points(polys, m.vertices.len());
    let mut order: Vec<usize> = (0..polys.num_cells()).collect();
    // stable: id order among cells with as many points
    order.sort_by_key(|&c| points[c].len());
    let ids: Vec<i64> = order.iter().map(|&c| c as i64).collect();
    let volumes: Vec<f64> = order.iter().map(|&c| m.cell_volumes[c]).collect();
    let cells: Vec<Vec<&[u32]>> = order.iter().map(|&c| polys.cell(c).collect()).collect();
    let points: Vec<Vec<u32>> = order.iter().map(|&c| std::mem::take(&mut points[c])).collect();
    crate::io::writers::cut_vtu::polyhedra_vtu(
        &m.vertices,
        &cells,
        &points,
        &[("volume", &volumes)],
        &[("cell_id", &ids)],
    )
}

/// The distinct points of each cell, ascending (what `sort` + `dedup` of
/// its polygons' corners gives): a stamp per mesh vertex keeps each point's
/// first corner, so only the distinct ids, about a third of the corners,
/// are sorted.
fn cell_points(cells: &CellPolygons, vertices: usize) -> Vec<Vec<u32>> {
    let mut stamp = vec![usize::MAX; vertices];
    (0..cells.num_cells())
        .map(|i| {
            let mut used = Vec::new();
            for &v in cells.cell(i).flatten() {
                if stamp[v as usize] != i {
                    stamp[v as usize] = i;
                    used.push(v);
                }
            }
            used.sort_unstable();
            used
        })
        .collect()
}

/// `cells.obj`: a group `cell_<i>` per cut-cell with its faces oriented
/// outwards; with `explode > 0` each cell is moved away from the mesh centre
/// by that fraction of its centroid offset (exploded view).
pub fn cut_cells_obj(m: &CutCellMesh, explode: f64) -> String {
    cut_cells_obj_of(m, &m.cell_polygons_flat(), explode)
}

/// [`cut_cells_obj`] of the cells' polygons already formed: the boundary
/// polygons of each cell, oriented outwards, each written as a face of one
/// loop (`CutCellMesh::cell_polygons_flat`: faces with holes or with
/// rounded vertices off their plane come as their triangles).
pub fn cut_cells_obj_of(m: &CutCellMesh, cells: &CellPolygons, explode: f64) -> String {
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
    // the text `{:?}` and `{}` give, without the formatting machinery
    let (mut float, mut int) = (FloatText::default(), itoa::Buffer::new());
    let mut base = 1usize;
    let points = cell_points(cells, m.vertices.len());
    // unexploded and finite, a point's line is the same text in every cell
    // it is written in (the shift is a zero): formed once per point. Only
    // a coordinate -0.0 depends on the zero's sign and is formed in place.
    let (mut line_start, mut lines) = (Vec::new(), String::new());
    if explode == 0.0 && m.vertices.iter().flatten().all(|c| c.is_finite()) {
        line_start.reserve(m.vertices.len() + 1);
        line_start.push(0);
        for x in &m.vertices {
            lines.push('v');
            for &c in x {
                lines.push(' ');
                float.push_f64(&mut lines, c + 0.0);
            }
            lines.push('\n');
            line_start.push(lines.len());
        }
    }
    let negative_zero = |x: &[f64; 3]| x.iter().any(|c| c.to_bits() == (-0.0f64).to_bits());
    // the file's number of each point of the cell being written
    let mut local = vec![0usize; m.vertices.len()];
    for (i, used) in points.iter().enumerate() {
        let mut cen = [0.0; 3];
        for &v in used {
            for k in 0..3 {
                cen[k] += m.vertices[v as usize][k] / used.len() as f64;
            }
        }
        let shift: [f64; 3] = std::array::from_fn(|k| explode * (cen[k] - centre[k]));
        s.push_str("g cell_");
        s.push_str(int.format(i));
        s.push('\n');
        for (j, &v) in used.iter().enumerate() {
            local[v as usize] = base + j;
            let x = m.vertices[v as usize];
            if !line_start.is_empty() && !negative_zero(&x) {
                s.push_str(&lines[line_start[v as usize]..line_start[v as usize + 1]]);
                continue;
            }
            s.push('v');
            for k in 0..3 {
                s.push(' ');
                float.push_f64(&mut s, x[k] + shift[k]);
            }
            s.push('\n');
        }
        for l in cells.cell(i) {
            s.push('f');
            for &v in l {
                s.push(' ');
                s.push_str(int.format(local[v as usize]));
            }
            s.push('\n');
        }
        base += used.len();
    }
    s
}
