//! Floating-point measures of the output (volumes).

/// Signed volume contribution `sum det(x0, xi, xi+1) / 6` of a planar loop
/// (the divergence theorem term for the loop's normal side).
pub fn loop_volume(x: &[[f64; 3]], verts: &[u32]) -> f64 {
    let o = x[verts[0] as usize];
    let mut s = 0.0;
    for i in 1..verts.len().saturating_sub(1) {
        let a = x[verts[i] as usize];
        let b = x[verts[i + 1] as usize];
        // relative to o for accuracy; the closed surface sum is unchanged
        let (a, b) = ([a[0] - o[0], a[1] - o[1], a[2] - o[2]], [b[0] - o[0], b[1] - o[1], b[2] - o[2]]);
        let cr = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
        s += cr[0] * o[0] + cr[1] * o[1] + cr[2] * o[2];
    }
    s / 6.0
}

/// Signed volume of a closed triangle mesh.
pub fn mesh_volume(x: &[[f64; 3]], tris: &[[u32; 3]]) -> f64 {
    tris.iter().map(|t| loop_volume(x, t)).sum()
}

impl crate::cut::CutCellMesh {
    /// Every cut-face written as triangles without new vertices (`septa
    /// cut --triangulate`, TopoCut's `--is-triangulate`): faces already
    /// written so keep their triangles (those the certified embedding
    /// chose), the others are ear-clipped with exact orientations. The
    /// triangles of a planar polygon cover exactly its region, so the exact
    /// check of the written cells still holds. For output only: call after
    /// [`Self::validate`] (the counts are the cut-faces').
    pub fn triangulate_all(&mut self) {
        self.face_split.resize(self.faces.len(), false);
        self.face_triangles.resize(self.faces.len(), Vec::new());
        for i in 0..self.faces.len() {
            if self.face_split[i] && !self.face_triangles[i].is_empty() {
                continue;
            }
            let f = &self.faces[i];
            let t = crate::cut::triangles::triangulate::triangulate(&self.vertices, &f.loops, self.support_normal(f));
            self.face_split[i] = true;
            self.face_triangles[i] = t;
        }
    }

    /// The polygons written for each cell, oriented outwards (what
    /// `cells.vtu` and `cells.obj` hold and [`crate::cut::check::verify`] checks): a
    /// cut-face as one polygon, or as its triangles (no new vertices) when
    /// [`crate::cut::CutCellMesh::face_split`] says so (holes, or rounded
    /// vertices not exactly coplanar).
    pub fn cell_polygons(&self) -> Vec<Vec<Vec<u32>>> {
        // Each cell's list sized first and each polygon copied once, into
        // its cell (no per-face list, no regrowth of the cells' lists): the
        // writers and the exact check each form these polygons.
        let count = |i: usize| -> usize {
            let f = &self.faces[i];
            let split = self.face_split.get(i).copied().unwrap_or(f.loops.len() > 1);
            match self.face_triangles.get(i).filter(|t| split && !t.is_empty()) {
                Some(t) => t.len(),
                None if !split => 1,
                None => self.face_polygons(i).len(),
            }
        };
        let mut sizes = vec![0usize; self.num_cells];
        for (i, f) in self.faces.iter().enumerate() {
            let k = count(i);
            for &c in f.cells.iter().filter(|&&c| c != u32::MAX) {
                sizes[c as usize] += k;
            }
        }
        let mut cells: Vec<Vec<Vec<u32>>> = sizes.iter().map(|&n| Vec::with_capacity(n)).collect();
        for (i, f) in self.faces.iter().enumerate() {
            let split = self.face_split.get(i).copied().unwrap_or(f.loops.len() > 1);
            let tris = self.face_triangles.get(i).filter(|t| split && !t.is_empty());
            let computed;
            let polys: &[Vec<u32>] = match tris {
                Some(_) => &[],
                None if !split => std::slice::from_ref(&f.loops[0]),
                None => {
                    computed = self.face_polygons(i);
                    &computed
                }
            };
            // the face normal points away from cells[0] (negative side):
            // outward for it; reversed for cells[1] (listed first, as before)
            if f.cells[1] != u32::MAX {
                let c = &mut cells[f.cells[1] as usize];
                match tris {
                    Some(t) => c.extend(t.iter().map(|t| vec![t[2], t[1], t[0]])),
                    None => c.extend(polys.iter().map(|l| l.iter().rev().copied().collect::<Vec<u32>>())),
                }
            }
            if f.cells[0] != u32::MAX {
                let c = &mut cells[f.cells[0] as usize];
                match tris {
                    Some(t) => c.extend(t.iter().map(|t| t.to_vec())),
                    None => c.extend(polys.iter().cloned()),
                }
            }
        }
        cells
    }

    /// The polygons cut-face `i` is written as, counter-clockwise about its
    /// support normal: the face as one polygon, or its triangles (no new
    /// cut-vertices) when [`crate::cut::CutCellMesh::face_split`] says so.
    pub fn face_polygons(&self, i: usize) -> Vec<Vec<u32>> {
        let f = &self.faces[i];
        let split = self.face_split.get(i).copied().unwrap_or(f.loops.len() > 1);
        if !split {
            vec![f.loops[0].clone()]
        } else if let Some(t) = self.face_triangles.get(i).filter(|t| !t.is_empty()) {
            t.iter().map(|t| t.to_vec()).collect()
        } else {
            crate::cut::triangles::triangulate::triangulate(&self.vertices, &f.loops, self.support_normal(f))
                .iter()
                .map(|t| t.to_vec())
                .collect()
        }
    }

    /// [`Self::cell_polygons`] in flat form (the same polygons in the same
    /// order; no vector per polygon): what the exact check and the writers
    /// read.
    pub fn cell_polygons_flat(&self) -> crate::cut::CellPolygons {
        // each face's polygons once (oriented for `cells[0]`), then copied
        // into its cells: reversed for `cells[1]`, listed first, as in
        // `cell_polygons`
        let (mut fp_start, mut fp_verts): (Vec<u32>, Vec<u32>) = (vec![0], Vec::new());
        let mut face_first: Vec<u32> = Vec::with_capacity(self.faces.len() + 1);
        for (i, f) in self.faces.iter().enumerate() {
            face_first.push(fp_start.len() as u32 - 1);
            let split = self.face_split.get(i).copied().unwrap_or(f.loops.len() > 1);
            match self.face_triangles.get(i).filter(|t| split && !t.is_empty()) {
                Some(t) => {
                    for t in t {
                        fp_verts.extend_from_slice(t);
                        fp_start.push(fp_verts.len() as u32);
                    }
                }
                None if !split => {
                    fp_verts.extend_from_slice(&f.loops[0]);
                    fp_start.push(fp_verts.len() as u32);
                }
                None => {
                    for p in self.face_polygons(i) {
                        fp_verts.extend_from_slice(&p);
                        fp_start.push(fp_verts.len() as u32);
                    }
                }
            }
        }
        face_first.push(fp_start.len() as u32 - 1);
        let polys_of = |i: usize| face_first[i] as usize..face_first[i + 1] as usize;
        let (mut npoly, mut nvert) = (vec![0u32; self.num_cells + 1], vec![0u32; self.num_cells + 1]);
        for (i, f) in self.faces.iter().enumerate() {
            let k = polys_of(i);
            let nv = fp_start[k.end] - fp_start[k.start];
            for &c in f.cells.iter().filter(|&&c| c != u32::MAX) {
                npoly[c as usize + 1] += k.len() as u32;
                nvert[c as usize + 1] += nv;
            }
        }
        for c in 0..self.num_cells {
            npoly[c + 1] += npoly[c];
            nvert[c + 1] += nvert[c];
        }
        let total = *npoly.last().unwrap_or(&0) as usize;
        let mut poly_len = vec![0u32; total];
        let mut verts = vec![0u32; *nvert.last().unwrap_or(&0) as usize];
        let (mut next_poly, mut next_vert) = (npoly.clone(), nvert.clone());
        for (i, f) in self.faces.iter().enumerate() {
            for (c, reversed) in [(f.cells[1], true), (f.cells[0], false)] {
                if c == u32::MAX {
                    continue;
                }
                for p in polys_of(i) {
                    let src = &fp_verts[fp_start[p] as usize..fp_start[p + 1] as usize];
                    let at = next_vert[c as usize] as usize;
                    let dst = &mut verts[at..at + src.len()];
                    dst.copy_from_slice(src);
                    if reversed {
                        dst.reverse();
                    }
                    poly_len[next_poly[c as usize] as usize] = src.len() as u32;
                    next_poly[c as usize] += 1;
                    next_vert[c as usize] += src.len() as u32;
                }
            }
        }
        let mut poly_start = Vec::with_capacity(total + 1);
        poly_start.push(0u32);
        for l in poly_len {
            poly_start.push(poly_start.last().unwrap() + l);
        }
        crate::cut::CellPolygons { cell_start: npoly, poly_start, verts }
    }

    /// The exact check of [`crate::cut::check::verify`] on the polygons as written.
    pub fn verify(&self) -> crate::cut::check::verify::VerifyReport {
        crate::cut::check::verify::verify_flat(&self.vertices, &self.cell_polygons_flat(), None, &self.planes)
    }

    /// The input triangles written unchanged, as a report of the input's
    /// exact self-intersection check (which found none meeting): each
    /// triangle of `triangles` (into `vertices`, the cut's input) whose three
    /// corners are cut-vertices at exactly their input coordinates, in
    /// cut-vertex ids ([`crate::cut::check::verify::proven_disjoint`]). Only valid when
    /// that check ran and passed on this input.
    pub(crate) fn unchanged_input(
        &self,
        vertices: &[[f64; 3]],
        triangles: &[[u32; 3]],
    ) -> crate::cut::check::verify::VerifyReport {
        let mut of_input = vec![u32::MAX; vertices.len()];
        for (i, d) in self.vertex_defs.iter().enumerate() {
            if let crate::cut::Def::V(v) = *d {
                let same = (0..3).all(|k| self.vertices[i][k].to_bits() == vertices[v as usize][k].to_bits());
                if same {
                    of_input[v as usize] = i as u32;
                }
            }
        }
        crate::cut::check::verify::proven_disjoint(
            triangles.iter().map(|t| t.map(|v| of_input[v as usize])).filter(|t| !t.contains(&u32::MAX)),
        )
    }

    /// [`Self::verify`] after re-writing faces of the mesh that `prev`
    /// checked, no vertex moved ([`crate::cut::check::verify::verify_cells_since`]).
    pub fn verify_since(
        &self,
        prev: &crate::cut::check::verify::VerifyReport,
    ) -> crate::cut::check::verify::VerifyReport {
        crate::cut::check::verify::verify_flat(&self.vertices, &self.cell_polygons_flat(), Some(prev), &self.planes)
    }
}
