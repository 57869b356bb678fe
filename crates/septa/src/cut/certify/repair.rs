//! Certified repair of the written embedding (TopoCut Sec. 6.1 and its
//! Limitations, Sec. 8: "relax planarity"). The rounded cut-vertices are
//! kept; what changes is how a cut-face is written:
//!
//! 1. a face whose rounded vertices are not exactly coplanar is written as
//!    triangles of its own vertices (ear clipping with exact orientations,
//!    `triangulate`); faces with holes likewise (bridged);
//! 2. then the exact check ([`crate::cut::check::verify`]) runs on what would be
//!    written, and the faces holding an offending polygon (a triangle
//!    meeting another, a degenerate or non-planar polygon) are re-written,
//!    each step kept only if the exact check counts fewer violations:
//!    a. as their best-shaped triangulation (`triangulate_shaped`): ear
//!       clipping along a rounded, nearly straight chain of cut-vertices
//!       leaves slivers whose long side crosses the neighbouring face; the
//!       shaped one fans the chain from a vertex off it;
//!    b. as a fan of triangles around a new point, the mean of its
//!       vertices (each fan triangle joins two consecutive boundary
//!       vertices, so no diagonal runs along a chain);
//!    c. by certified vertex moves of a few ulps ([`crate::cut::certify::nudge`]).
//!
//! The final exact report is kept in [`RepairStats`]: the guarantee is that
//! report, not this heuristic. Steps a and b move no vertex, so their
//! re-check ([`crate::cut::check::verify::verify_cells_since`]) tests only the pairs
//! with a re-written triangle and takes the others from the previous check
//! (the same report as a full check); step c moves vertices and re-checks
//! everything.

use crate::cut::certify::nudge::nudge;
use crate::cut::check::verify::VerifyReport;
use crate::cut::triangles::triangulate::triangulate_shaped;
use crate::cut::{CutCellMesh, RepairStats};
use rustc_hash::FxHashMap;

fn sorted(p: &[u32]) -> Vec<u32> {
    let mut s = p.to_vec();
    s.sort_unstable();
    s
}

/// The cut-faces holding an offending polygon of `r` (each written
/// polygon, as a vertex set, names its cut-face).
fn offending_faces(out: &CutCellMesh, r: &VerifyReport) -> Vec<u32> {
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
    let mut faces: Vec<u32> = r.offending_polygons.iter().filter_map(|p| of.get(&sorted(p)).copied()).collect();
    faces.sort_unstable();
    faces.dedup();
    faces
}

/// The input mesh of a cut whose exact self-intersection check passed:
/// its vertices and triangles.
pub type CleanInput<'a> = Option<(&'a [[f64; 3]], &'a [[u32; 3]])>;

/// The exact check of `out`, sparing the pairs of unchanged input triangles
/// when the input is known clean ([`CutCellMesh::unchanged_input`]): the
/// same report as [`CutCellMesh::verify`].
fn check(out: &CutCellMesh, input: CleanInput) -> VerifyReport {
    match input {
        Some((v, t)) => out.verify_since(&out.unchanged_input(v, t)),
        None => out.verify(),
    }
}

/// Re-writes offending faces (shaped triangulations, then fans) until the
/// exact check is clean or stops improving (at most 8 rounds).
pub fn repair(out: &mut CutCellMesh, input: CleanInput) -> RepairStats {
    let mut st = RepairStats::default();
    let known = input.map(|(v, t)| out.unchanged_input(v, t));
    st.proven_input_triangles = known.as_ref().and_then(|k| k.memo.as_ref()).map_or(0, |m| m.triangles.len());
    let mut r = match &known {
        Some(k) => out.verify_since(k),
        None => out.verify(),
    };
    st.violations_before = r.violations();
    let mut fanned = vec![false; out.faces.len()];
    let mut shaped = vec![false; out.faces.len()];
    for _ in 0..8 {
        if r.violations() == 0 {
            break;
        }
        let offending = offending_faces(out, &r);
        // 1. the offending faces' best-shaped triangulation (no new vertices)
        let faces: Vec<(u32, Vec<[u32; 3]>)> = offending
            .iter()
            .filter(|&&f| !shaped[f as usize] && !fanned[f as usize])
            .filter_map(|&f| {
                let cf = &out.faces[f as usize];
                let t = triangulate_shaped(&out.vertices, &cf.loops, out.support_normal(cf))?;
                Some((f, t))
            })
            .filter(|(f, t)| !out.face_split[*f as usize] || out.face_triangles[*f as usize] != *t)
            .collect();
        if !faces.is_empty() {
            let saved: Vec<(bool, Vec<[u32; 3]>)> = faces
                .iter()
                .map(|(f, _)| (out.face_split[*f as usize], out.face_triangles[*f as usize].clone()))
                .collect();
            for (f, t) in &faces {
                out.face_triangles[*f as usize] = t.clone();
                out.face_split[*f as usize] = true;
            }
            let r2 = out.verify_since(&r);
            if r2.violations() < r.violations() {
                for (f, _) in &faces {
                    shaped[*f as usize] = true;
                }
                st.faces_reshaped += faces.len();
                st.rounds += 1;
                r = r2;
                continue;
            }
            for ((f, _), (s, t)) in faces.iter().zip(saved) {
                out.face_split[*f as usize] = s;
                out.face_triangles[*f as usize] = t;
            }
        }
        // 2. fans around a new centre point
        let faces: Vec<u32> = offending
            .iter()
            .copied()
            .filter(|&f| out.faces[f as usize].loops.len() == 1 && !fanned[f as usize])
            .collect();
        if faces.is_empty() {
            if !nudge_round(out, input, &mut r, &offending, &mut st) {
                break;
            }
            continue;
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
        let r2 = out.verify_since(&r);
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
            if !nudge_round(out, input, &mut r, &offending, &mut st) {
                break;
            }
        }
    }
    st.report = r;
    st
}

/// 3. certified vertex moves ([`nudge`]) on the offending faces; kept only
/// if the exact check of the whole result improves.
fn nudge_round(
    out: &mut CutCellMesh,
    input: CleanInput,
    r: &mut VerifyReport,
    offending: &[u32],
    st: &mut RepairStats,
) -> bool {
    let saved = (out.vertices.clone(), out.face_split.clone(), out.face_triangles.clone());
    let moved = nudge(out, offending);
    if moved == 0 {
        (out.vertices, out.face_split, out.face_triangles) = saved;
        return false;
    }
    let r2 = check(out, input);
    if r2.violations() < r.violations() {
        st.vertices_nudged += moved;
        st.rounds += 1;
        *r = r2;
        true
    } else {
        (out.vertices, out.face_split, out.face_triangles) = saved;
        false
    }
}
