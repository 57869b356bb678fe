//! Certified repair of the written embedding (TopoCut Sec. 6.1 and its
//! Limitations, Sec. 8: "relax planarity"). The rounded cut-vertices are
//! kept; what changes is how a cut-face is written:
//!
//! 1. a face whose rounded vertices are not exactly coplanar is written as
//!    triangles of its own vertices (ear clipping with exact orientations,
//!    `triangulate`); faces with holes likewise (bridged);
//! 2. then the exact check ([`super::verify`]) runs on what would be
//!    written; every face holding an offending polygon (a triangle meeting
//!    another, a degenerate or non-planar polygon) is written instead as a
//!    fan of triangles around a new point, the mean of its vertices. Each
//!    fan triangle joins two consecutive boundary vertices, so no diagonal
//!    runs along a rounded chain of exactly collinear cut-vertices (where
//!    ear-clipped slivers poke into the neighbouring face). The round is
//!    kept only if the exact check counts fewer violations, and repeated.
//!
//! The final exact report is kept in [`RepairStats`]: the guarantee is that
//! report, not this heuristic.

use super::verify::VerifyReport;
use super::CutCellMesh;
use rustc_hash::FxHashMap;

/// What the repair changed and the final exact check.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct RepairStats {
    /// Violations of the exact check before the fans.
    pub violations_before: usize,
    /// Faces written as a fan around a new centre point.
    pub faces_fanned: usize,
    /// Rounds kept.
    pub rounds: usize,
    /// The exact check of the result (what `cells.vtu` holds).
    pub report: VerifyReport,
}

fn sorted(p: &[u32]) -> Vec<u32> {
    let mut s = p.to_vec();
    s.sort_unstable();
    s
}

/// Re-writes offending faces as fans until the exact check is clean or stops
/// improving (at most 4 rounds).
pub fn repair(out: &mut CutCellMesh) -> RepairStats {
    let mut st = RepairStats::default();
    let mut r = out.verify();
    st.violations_before = r.violations();
    let mut fanned = vec![false; out.faces.len()];
    for _ in 0..4 {
        if r.violations() == 0 {
            break;
        }
        // written polygon (as a vertex set) -> cut-face
        let mut of: FxHashMap<Vec<u32>, u32> = FxHashMap::default();
        for (i, f) in out.faces.iter().enumerate() {
            if out.face_split[i] {
                for t in &out.face_triangles[i] {
                    of.insert(sorted(t), i as u32);
                }
            } else {
                of.insert(sorted(&f.loops[0]), i as u32);
            }
        }
        let mut faces: Vec<u32> = r
            .offending_polygons
            .iter()
            .filter_map(|p| of.get(&sorted(p)).copied())
            .filter(|&f| out.faces[f as usize].loops.len() == 1 && !fanned[f as usize])
            .collect();
        faces.sort_unstable();
        faces.dedup();
        if faces.is_empty() {
            break;
        }
        let nv = out.vertices.len();
        let saved: Vec<(bool, Vec<[u32; 3]>)> =
            faces.iter().map(|&f| (out.face_split[f as usize], out.face_triangles[f as usize].clone())).collect();
        for &f in &faces {
            let l = &out.faces[f as usize].loops[0];
            let n = l.len() as f64;
            let c: [f64; 3] = std::array::from_fn(|k| l.iter().map(|&v| out.vertices[v as usize][k]).sum::<f64>() / n);
            let ci = out.vertices.len() as u32;
            let tris: Vec<[u32; 3]> = (0..l.len()).map(|i| [ci, l[i], l[(i + 1) % l.len()]]).collect();
            out.vertices.push(c);
            out.face_triangles[f as usize] = tris;
            out.face_split[f as usize] = true;
        }
        let r2 = out.verify();
        if r2.violations() < r.violations() {
            for &f in &faces {
                fanned[f as usize] = true;
            }
            st.faces_fanned += faces.len();
            st.rounds += 1;
            r = r2;
        } else {
            out.vertices.truncate(nv);
            for (&f, (s, t)) in faces.iter().zip(saved) {
                out.face_split[f as usize] = s;
                out.face_triangles[f as usize] = t;
            }
            break;
        }
    }
    st.report = r;
    st
}
