//! Checks of a cut-cell mesh (TopoCut Sec. 6.2): faces bound one or two
//! cells, volumes add up, Euler characteristic accounted per cell.

use crate::cut::triangles::radix::sort_u64;
use crate::cut::triangles::triangulate;
use crate::cut::{CutCellMesh, CutError, CutFace, Support};
use rayon::prelude::*;
use septa_exact::Sign;

/// Results of [`CutCellMesh::validate`].
#[derive(Clone, Debug, serde::Serialize)]
pub struct Validation {
    /// `V - E + F - C`.
    pub euler: i64,
    /// `|sum of cell volumes - mesh volume| / mesh volume`.
    pub volume_relative_error: f64,
    /// Smallest cell volume (floating point; may be 0 or negative for a
    /// cell too small to measure in `f64` whose exact volume is positive).
    pub min_cell_volume: f64,
    /// Euler characteristic of the domain, `chi(mesh) / 2`.
    pub domain_euler: i64,
    /// `V - E + F - sum_c chi(c)` with `chi(c) = chi(boundary of c) / 2`
    /// counted on each cell's own boundary: equals `domain_euler` when
    /// every cut-face is a disc (holes are joined by one edge each), whatever
    /// the topology of the cells (a cell around a handle has `chi = 0`).
    pub euler_by_cell: i64,
    /// Cells whose boundary is not a sphere (`chi(c) != 1`).
    pub non_ball_cells: usize,
}

impl CutCellMesh {
    /// The unit-free normal of a face's support (triangle outward normal or
    /// plane normal), from the input data.
    pub fn support_normal(&self, f: &CutFace) -> [f64; 3] {
        match f.support {
            Support::Plane(p) => {
                let q = self.planes[p as usize];
                [q[0], q[1], q[2]]
            }
            Support::Tri(t) => self.tri_normals[t as usize],
        }
    }

    /// Triangles of each cut-face (no new vertices; holes bridged), for
    /// output and rendering.
    pub fn triangulate_faces(&self) -> Vec<Vec<[u32; 3]>> {
        self.faces.iter().map(|f| triangulate::triangulate(&self.vertices, &f.loops, self.support_normal(f))).collect()
    }

    /// Checks: every cut-face bounds one (boundary) or two distinct
    /// (interior) cells, cell volumes are positive (exactly: the sign of
    /// each cell's volume from the exact cut-vertices) and sum to the mesh
    /// volume within `1e-9` relative.
    pub fn validate(&self) -> Result<Validation, CutError> {
        for (i, f) in self.faces.iter().enumerate() {
            match f.support {
                Support::Tri(_) => {
                    if f.cells[0] == u32::MAX || f.cells[1] != u32::MAX {
                        return Err(CutError::Inconsistent(format!(
                            "boundary face {i} does not bound exactly one cell"
                        )));
                    }
                }
                Support::Plane(_) => {
                    if f.cells[0] == u32::MAX || f.cells[1] == u32::MAX || f.cells[0] == f.cells[1] {
                        return Err(CutError::Inconsistent(format!(
                            "plane face {i} does not bound two distinct cells"
                        )));
                    }
                }
            }
        }
        let total: f64 = self.cell_volumes.iter().sum();
        // At 1e300 the volumes overflow (inf - inf: NaN, which passed
        // `err > 1e-9`); at 1e-200 they underflow (0 / 0). Then the sums at
        // the scale the cut ran at (a power of two, scale.rs) decide.
        let usable = |t: f64, m: f64| t.is_finite() && m.is_normal();
        let [t2, m2] = self.volume_sums_at_cut_scale;
        let (t, m) =
            if usable(total, self.mesh_volume) || !usable(t2, m2) { (total, self.mesh_volume) } else { (t2, m2) };
        let err = (t - m).abs() / m.abs();
        let min = self.cell_volumes.iter().copied().fold(f64::INFINITY, f64::min);
        if !(err <= 1e-9) {
            return Err(CutError::Inconsistent(format!(
                "cell volumes sum to {total}, mesh volume {} (at the cut's scale: {t2} and {m2})",
                self.mesh_volume
            )));
        }
        // Zero volume is decided exactly: a legitimate cell may be far too
        // small for its floating-point volume (volume.rs). Without exact
        // signs (a mesh not made by `cut_mesh`), the floating-point volume.
        if self.cell_volume_signs.len() == self.num_cells {
            if let Some(k) = self.cell_volume_signs.iter().position(|s| *s != Sign::Positive) {
                return Err(CutError::Inconsistent(format!(
                    "cell {k} has volume {} (exact sign {:?})",
                    self.cell_volumes[k], self.cell_volume_signs[k]
                )));
            }
        } else if min <= 0.0 {
            return Err(CutError::Inconsistent(format!("a cell has volume {min}")));
        }
        let c = &self.counts;
        // per-cell boundary complexes: each cell's vertices and edges
        // counted from its own faces (small sorted lists, not one global
        // sort of (cell, vertex) and (cell, edge) pairs), faces and join
        // edges (one per hole)
        let mut start = vec![0usize; self.num_cells + 1];
        for f in &self.faces {
            for &cell in f.cells.iter().filter(|&&x| x != u32::MAX) {
                start[cell as usize + 1] += 1;
            }
        }
        for k in 0..self.num_cells {
            start[k + 1] += start[k];
        }
        let mut faces_of = vec![0u32; start[self.num_cells]];
        let mut fill = start.clone();
        for (i, f) in self.faces.iter().enumerate() {
            for &cell in f.cells.iter().filter(|&&x| x != u32::MAX) {
                faces_of[fill[cell as usize]] = i as u32;
                fill[cell as usize] += 1;
            }
        }
        // vertices counted with a mark per vertex (the cell that last saw
        // it), edges by sorting their keys: one sort per cell instead of two
        let nv = self.vertices.len();
        let chunk = self.num_cells.div_ceil(4 * rayon::current_num_threads()).max(1);
        let (start, faces_of) = (&start, &faces_of);
        let chi2: Vec<i64> = (0..self.num_cells)
            .into_par_iter()
            .chunks(chunk)
            .flat_map_iter(|cells| {
                // one mark array per run of cells (not per rayon job)
                let (mut seen, mut es) = (vec![u32::MAX; nv], Vec::new());
                cells.into_iter().map(move |cell| {
                    es.clear();
                    let (mut chi, mut nverts) = (0i64, 0i64);
                    for &i in &faces_of[start[cell]..start[cell + 1]] {
                        let f = &self.faces[i as usize];
                        // a joined hole adds one edge and keeps one face: chi contribution 0
                        chi += 1 - (f.loops.len() as i64 - 1);
                        for l in &f.loops {
                            for (k, &v) in l.iter().enumerate() {
                                let w = l[(k + 1) % l.len()];
                                if v as usize >= seen.len() {
                                    seen.resize(v as usize + 1, u32::MAX); // an id past the points
                                }
                                if seen[v as usize] != cell as u32 {
                                    seen[v as usize] = cell as u32;
                                    nverts += 1;
                                }
                                es.push(u64::from(v.min(w)) << 32 | u64::from(v.max(w)));
                            }
                        }
                    }
                    sort_u64(&mut es);
                    es.dedup();
                    chi + nverts - es.len() as i64
                })
            })
            .collect();
        let sum_chi: i64 = chi2.iter().map(|x| x / 2).sum();
        let non_ball = chi2.iter().filter(|&&x| x != 2).count();
        Ok(Validation {
            euler: c.cut_vertices as i64 - c.cut_edges as i64 + c.cut_faces as i64 - c.cut_cells as i64,
            volume_relative_error: err,
            min_cell_volume: min,
            domain_euler: self.mesh_euler / 2,
            euler_by_cell: c.cut_vertices as i64 - c.cut_edges as i64 + c.cut_faces as i64 - sum_chi,
            non_ball_cells: non_ball,
        })
    }
}
