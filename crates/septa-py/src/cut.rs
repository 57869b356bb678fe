//! `septa.cut_mesh`: planar cut-cell meshes (TopoCut).
use crate::InputError;
use numpy::{PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use septa::cut::{cut_mesh, CutOptions};

/// cut(vertices, triangles, planes, threads=0)
/// --
///
/// Cuts the closed, outward triangle mesh (`vertices` `(#V, 3) float64`,
/// `triangles` `(#T, 3) int64`) by `planes` `(#P, 4) float64`
/// (`a x + b y + c z + d = 0`). Returns JSON text: counts, the
/// floating-point embedding of the cut-vertices, and each cell's boundary
/// polygons oriented outwards. The GIL is released while it is computed.
#[pyfunction]
#[pyo3(signature = (vertices, triangles, planes, threads = 0))]
pub fn cut<'py>(
    py: Python<'py>,
    vertices: PyReadonlyArray2<'py, f64>,
    triangles: PyReadonlyArray2<'py, i64>,
    planes: PyReadonlyArray2<'py, f64>,
    threads: usize,
) -> PyResult<String> {
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
    let result: Result<String, String> = py.detach(|| {
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
        let m = cut_mesh(&v, &tris, &p, &CutOptions { threads, ..Default::default() }).map_err(|e| e.to_string())?;
        let check = m.validate().map_err(|e| e.to_string())?;
        let c = m.counts;
        Ok(serde_json::json!({
            "cut_vertices": c.cut_vertices, "cut_edges": c.cut_edges, "cut_faces": c.cut_faces, "cut_cells": c.cut_cells,
            "euler": check.euler, "volume_relative_error": check.volume_relative_error,
            "points": m.vertices, "cells": septa::io::cut_out::cell_faces(&m), "cell_volumes": m.cell_volumes,
        })
        .to_string())
    });
    result.map_err(InputError::new_err)
}
