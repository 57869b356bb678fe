//! `septa.cut_mesh`: planar cut-cell meshes (TopoCut), kept whole on the
//! Rust side so that `CutCells.save` writes through the same writers as
//! `septa cut` (binary polyhedral .vtu, .obj, OpenFOAM polyMesh).
use crate::InputError;
use numpy::{IntoPyArray, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use septa::cut::Support;
use septa::cut::{cut_mesh, CutCellMesh, CutOptions};
use std::path::Path;

/// The cut-cell mesh as computed (see `septa.CutCells`).
#[pyclass(module = "septa._septa", frozen)]
pub struct CutResult {
    mesh: CutCellMesh,
    summary: String,
}

const NONE: i64 = -1;

fn id(c: u32) -> i64 {
    if c == u32::MAX {
        NONE
    } else {
        c as i64
    }
}

#[pymethods]
impl CutResult {
    /// Counts, checks and what the embedding changed, as JSON text (the
    /// fields of `cut.json`).
    fn summary(&self) -> &str {
        &self.summary
    }

    /// The mesh as numpy arrays: `points`; cut-face loops (`loop_vertices`
    /// split by `loop_offsets`, loops of face `f` are
    /// `face_loop_offsets[f]..face_loop_offsets[f+1]`, the outer boundary
    /// first, counter-clockwise about the support normal, then holes);
    /// `face_cells` `(F, 2)` (the cell the face normal points out of, the
    /// cell it points into; -1 outside); `face_plane` / `face_triangle`
    /// (the support, -1 for the other kind); the written polygons of each
    /// face (`polygon_vertices`, `polygon_offsets`, `face_polygon_offsets`);
    /// `cell_volumes`, `planes`, `cut_vertices` (points from there on are
    /// face centres of the certified embedding).
    fn arrays<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let m = &self.mesh;
        let d = PyDict::new(py);
        let pts: Vec<f64> = m.vertices.iter().flatten().copied().collect();
        d.set_item("points", pts.into_pyarray(py).reshape([m.vertices.len(), 3])?)?;
        let (mut lv, mut lo, mut flo) = (Vec::new(), vec![0i64], vec![0i64]);
        let (mut pv, mut po, mut fpo) = (Vec::new(), vec![0i64], vec![0i64]);
        let (mut fc, mut fp, mut ft) = (Vec::new(), Vec::new(), Vec::new());
        for (i, f) in m.faces.iter().enumerate() {
            for l in &f.loops {
                lv.extend(l.iter().map(|&v| v as i64));
                lo.push(lv.len() as i64);
            }
            flo.push(lo.len() as i64 - 1);
            for p in m.face_polygons(i) {
                pv.extend(p.iter().map(|&v| v as i64));
                po.push(pv.len() as i64);
            }
            fpo.push(po.len() as i64 - 1);
            fc.extend([id(f.cells[0]), id(f.cells[1])]);
            let (p, t) = match f.support {
                Support::Plane(p) => (p as i64, NONE),
                Support::Tri(t) => (NONE, t as i64),
            };
            fp.push(p);
            ft.push(t);
        }
        d.set_item("loop_vertices", lv.into_pyarray(py))?;
        d.set_item("loop_offsets", lo.into_pyarray(py))?;
        d.set_item("face_loop_offsets", flo.into_pyarray(py))?;
        d.set_item("polygon_vertices", pv.into_pyarray(py))?;
        d.set_item("polygon_offsets", po.into_pyarray(py))?;
        d.set_item("face_polygon_offsets", fpo.into_pyarray(py))?;
        d.set_item("face_cells", fc.into_pyarray(py).reshape([m.faces.len(), 2])?)?;
        d.set_item("face_plane", fp.into_pyarray(py))?;
        d.set_item("face_triangle", ft.into_pyarray(py))?;
        d.set_item("cell_volumes", m.cell_volumes.clone().into_pyarray(py))?;
        let pl: Vec<f64> = m.planes.iter().flatten().copied().collect();
        d.set_item("planes", pl.into_pyarray(py).reshape([m.planes.len(), 4])?)?;
        d.set_item("cut_vertices", m.vertex_defs.len())?;
        Ok(d)
    }

    /// Writes `cells.vtu`'s format (binary `VTK_POLYHEDRON` cells with
    /// `cell_id` and `volume`) to `path`.
    fn write_vtu(&self, py: Python<'_>, path: &str) -> PyResult<()> {
        let text = py.detach(|| septa::io::cut_cells_vtu(&self.mesh));
        septa::io::write_atomic(Path::new(path), text.as_bytes())
            .map_err(|e| InputError::new_err(format!("cannot write {path}: {e}")))
    }

    /// Writes `cells.obj`'s format (a group per cell) to `path`.
    #[pyo3(signature = (path, explode = 0.0))]
    fn write_obj(&self, py: Python<'_>, path: &str, explode: f64) -> PyResult<()> {
        if !(explode.is_finite() && explode >= 0.0) {
            return Err(InputError::new_err(format!("explode: expected a number >= 0, not {explode}")));
        }
        let text = py.detach(|| septa::io::cut_cells_obj(&self.mesh, explode));
        septa::io::write_atomic(Path::new(path), text.as_bytes())
            .map_err(|e| InputError::new_err(format!("cannot write {path}: {e}")))
    }

    /// Writes the OpenFOAM polyMesh files into the folder `path`; returns
    /// the two cut-cells whose numbers the polyMesh trades, or `None`.
    fn write_foam(&self, py: Python<'_>, path: &str) -> PyResult<Option<(u32, u32)>> {
        py.detach(|| septa::io::write_poly_mesh(Path::new(path), &self.mesh)).map_err(InputError::new_err)
    }
}

/// cut(vertices, triangles, planes, threads=0, progress=None)
/// --
///
/// Cuts the closed, outward triangle mesh (`vertices` `(#V, 3) float64`,
/// `triangles` `(#T, 3) int64`) by `planes` `(#P, 4) float64`
/// (`a x + b y + c z + d = 0`). Returns a `CutResult`; the GIL is released
/// while it is computed. `progress(done, total)` is called as each stage
/// of the cut ends.
#[pyfunction]
#[pyo3(signature = (vertices, triangles, planes, threads = 0, progress = None))]
pub fn cut<'py>(
    py: Python<'py>,
    vertices: PyReadonlyArray2<'py, f64>,
    triangles: PyReadonlyArray2<'py, i64>,
    planes: PyReadonlyArray2<'py, f64>,
    threads: usize,
    progress: Option<Py<PyAny>>,
) -> PyResult<CutResult> {
    let progress = progress.map(crate::network::py_progress);
    let shape_err =
        |what: &str, n: usize, s: &[usize]| InputError::new_err(format!("{what}: expected shape (N, {n}), got {s:?}"));
    if vertices.shape()[1] != 3 {
        return Err(shape_err("vertices", 3, vertices.shape()));
    }
    if triangles.shape()[1] != 3 {
        return Err(shape_err("triangles", 3, triangles.shape()));
    }
    if planes.shape()[1] != 4 {
        return Err(shape_err("planes", 4, planes.shape()));
    }
    if threads > 1024 {
        return Err(InputError::new_err(format!("threads: {threads} is out of range 0..=1024")));
    }
    let contiguous = |what: &str| InputError::new_err(format!("{what}: array must be C-contiguous"));
    let v = vertices.as_slice().map_err(|_| contiguous("vertices"))?;
    let t = triangles.as_slice().map_err(|_| contiguous("triangles"))?;
    let p = planes.as_slice().map_err(|_| contiguous("planes"))?;
    let result: Result<CutResult, String> = py.detach(|| {
        let v: Vec<[f64; 3]> = v.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        let mut tris = Vec::with_capacity(t.len() / 3);
        for (i, c) in t.chunks_exact(3).enumerate() {
            let ok = |x: i64| x >= 0 && (x as usize) < v.len();
            if !(ok(c[0]) && ok(c[1]) && ok(c[2])) {
                return Err(format!("triangle {i} has a vertex index outside 0..{}", v.len()));
            }
            tris.push([c[0] as u32, c[1] as u32, c[2] as u32]);
        }
        let p: Vec<[f64; 4]> = p.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect();
        let m = cut_mesh(&v, &tris, &p, &CutOptions { threads, progress, ..Default::default() }).map_err(|e| e.to_string())?;
        let check = m.validate().map_err(|e| e.to_string())?;
        let c = m.counts;
        let s = &m.stats;
        let summary = serde_json::json!({
            "cut_vertices": c.cut_vertices, "cut_edges": c.cut_edges, "cut_faces": c.cut_faces, "cut_cells": c.cut_cells,
            "euler": check.euler, "volume_relative_error": check.volume_relative_error,
            "min_cell_volume": check.min_cell_volume, "holes": s.holes, "voids_attached": s.voids_attached,
            "dropped_planes": s.dropped_planes.len(), "moved_vertices": s.moved_vertices,
            "sidedness_violations": s.sidedness_violations, "line_order_violations": s.line_order_violations,
            "faces_split_nonplanar": s.faces_split_nonplanar, "faces_split_holes": s.faces_split_holes,
            "embedding": s.embedding,
        })
        .to_string();
        Ok(CutResult { mesh: m, summary })
    });
    result.map_err(InputError::new_err)
}
