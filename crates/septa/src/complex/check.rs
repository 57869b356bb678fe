//! Invariant checks of a complex; every test calls them.

use super::types::{Complex, Mode, Plane, NONE};

impl Complex {
    /// Checks the combinatorial invariants: loops consistent with edges,
    /// face-cell incidences symmetric, every cell a closed and consistently
    /// oriented surface, Euler characteristic `V - E + F - C = 1` (a ball),
    /// and labels consistent with the planes of the faces between cells.
    pub fn check_invariants(&self) -> Result<(), String> {
        let nv = self.vertices.len() as u32;
        let mut edge_uses = vec![0u32; self.edges.len()];
        for (i, e) in self.edges.iter().enumerate() {
            if e.vertices[0] == e.vertices[1] || e.vertices.iter().any(|&v| v >= nv) {
                return Err(format!("edge {i} has bad vertices {:?}", e.vertices));
            }
        }
        for (fi, f) in self.faces.iter().enumerate() {
            let n = f.vertices.len();
            if n < 3 || f.edges.len() != n {
                return Err(format!("face {fi} has {n} vertices and {} edges", f.edges.len()));
            }
            for k in 0..n {
                let (a, b) = (f.vertices[k], f.vertices[(k + 1) % n]);
                let e = self.edges.get(f.edges[k] as usize).ok_or(format!("face {fi}: bad edge id"))?;
                if !(e.vertices == [a, b] || e.vertices == [b, a]) {
                    return Err(format!("face {fi}: edge {} is not ({a},{b})", f.edges[k]));
                }
                edge_uses[f.edges[k] as usize] += 1;
                if f.vertices[k + 1..].contains(&a) {
                    return Err(format!("face {fi} repeats vertex {a}"));
                }
            }
            if f.cells[0] == NONE || (f.plane.is_network() == (f.cells[1] == NONE)) {
                return Err(format!("face {fi} on {:?} has cells {:?}", f.plane, f.cells));
            }
            for &c in f.cells.iter().filter(|&&c| c != NONE) {
                let cell = self.cells.get(c as usize).ok_or(format!("face {fi}: bad cell {c}"))?;
                if !cell.faces.contains(&(fi as u32)) {
                    return Err(format!("cell {c} does not list its face {fi}"));
                }
            }
            self.check_labels(fi)?;
        }
        if let Some(e) = edge_uses.iter().position(|&u| u < 2) {
            return Err(format!("edge {e} is used by {} faces", edge_uses[e]));
        }
        for (ci, cell) in self.cells.iter().enumerate() {
            // Outward directed edges of the cell's faces: each must be matched by its reverse exactly once.
            let mut directed: Vec<(u32, u32)> = Vec::new();
            for &f in &cell.faces {
                let face = &self.faces[f as usize];
                if !face.cells.contains(&(ci as u32)) {
                    return Err(format!("cell {ci} lists face {f} which does not bound it"));
                }
                let inward = face.cells[0] == ci as u32;
                let n = face.vertices.len();
                for k in 0..n {
                    let (a, b) = (face.vertices[k], face.vertices[(k + 1) % n]);
                    directed.push(if inward { (b, a) } else { (a, b) });
                }
            }
            directed.sort_unstable();
            if directed.windows(2).any(|w| w[0] == w[1]) {
                return Err(format!("cell {ci}: an edge is traversed twice in one direction"));
            }
            if let Some(&(a, b)) = directed.iter().find(|&&(a, b)| directed.binary_search(&(b, a)).is_err()) {
                return Err(format!("cell {ci} is not closed at edge ({a},{b})"));
            }
        }
        let euler = nv as i64 - self.edges.len() as i64 + self.faces.len() as i64 - self.cells.len() as i64;
        if euler != 1 {
            return Err(format!("Euler characteristic {euler}, expected 1"));
        }
        Ok(())
    }

    fn check_labels(&self, fi: usize) -> Result<(), String> {
        let f = &self.faces[fi];
        let [c0, c1] = f.cells;
        if c1 == NONE {
            return Ok(());
        }
        let (p, n) = (&self.cells[c0 as usize], &self.cells[c1 as usize]);
        let ok = match (self.mode, f.plane) {
            (Some(Mode::Ia), Plane::Function(i)) => p.is_positive(i) && !n.is_positive(i),
            (Some(Mode::Mi), Plane::Pair(a, b)) => p.material == a && n.material == b,
            _ => false,
        };
        if ok {
            Ok(())
        } else {
            Err(format!("face {fi} on {:?} separates cells with inconsistent labels", f.plane))
        }
    }
}
