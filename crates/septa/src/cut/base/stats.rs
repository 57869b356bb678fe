//! What a cut reports besides its cells: the counts the reference program
//! prints, the timings and predicate statistics of every stage, and the
//! exact check of the written embedding with what its repair changed.

use crate::cut::check::verify::VerifyReport;

/// Counts of the cut-cell mesh.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct CutCounts {
    /// Cut-vertices.
    pub cut_vertices: usize,
    /// Cut-edges, counting like the reference one joining edge per hole of
    /// a cut-face (TopoCut Sec. 6.1 joins each hole to the outer boundary).
    pub cut_edges: usize,
    /// Cut-faces (a face with holes counts once).
    pub cut_faces: usize,
    /// Cut-cells.
    pub cut_cells: usize,
}

/// Timings and predicate statistics.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct CutStats {
    /// Seconds per stage.
    pub seconds: Vec<(String, f64)>,
    /// Filtered predicates that needed the exact fallback during this cut
    /// (process-wide counter: concurrent cuts in other threads add to it).
    pub exact_fallbacks: u64,
    /// Cut-edges whose face-cycle order was computed (more than two faces).
    pub ordered_edges: usize,
    /// Holes of cut-faces (each joined to its face's outer boundary; the
    /// reference counts one extra cut-edge per hole for that join).
    pub holes: usize,
    /// Holes whose face needed an exact containment test.
    pub hole_containment_tests: usize,
    /// Vertices whose rounded coordinates were nudged to keep the exact order
    /// along a mesh edge or plane-plane line (TopoCut Sec. 6.1 heuristic).
    pub moved_vertices: usize,
    /// Cut-vertices moved to keep the exact side of the supporting plane of
    /// every face of their cells near them (TopoCut Sec. 6.1, the orders of
    /// Eq. (13); "near" as in `embed.rs`).
    pub sidedness_moved: usize,
    /// Near (cut-vertex, supporting plane) pairs of a cell whose plainly rounded
    /// position (after the line-order moves) was on the wrong side or on the
    /// plane: what the sidedness moves repair.
    pub sidedness_violations_rounded: usize,
    /// Such pairs still wrong after the moves, decided exactly (expected 0).
    pub sidedness_violations: usize,
    /// Consecutive vertices of a mesh edge or plane-plane line still out of
    /// exact order in the embedding, decided exactly (expected 0).
    pub line_order_violations: usize,
    /// Void shells attached to their enclosing cell.
    pub voids_attached: usize,
    /// Void shells whose enclosing cell neither the plane sides nor the
    /// exact ray decided (left as separate, negative-volume cells, which
    /// `validate` reports; not expected for valid input).
    pub voids_unresolved: usize,
    /// Input planes dropped as duplicates `(dropped, duplicate_of)`.
    pub dropped_planes: Vec<(usize, usize)>,
    /// Cut-faces written as triangles because their rounded vertices are
    /// not exactly coplanar (TopoCut Sec. 8, Limitations: relax planarity).
    pub faces_split_nonplanar: usize,
    /// Cut-faces written as triangles because they have holes.
    pub faces_split_holes: usize,
    /// The exact check of the written embedding and what its repair changed
    /// (`None` with [`CutOptions::skip_certify`](crate::cut::CutOptions::skip_certify)).
    pub embedding: Option<RepairStats>,
}

/// What the repair changed and the final exact check.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct RepairStats {
    /// Violations of the exact check before the fans.
    pub violations_before: usize,
    /// Faces written as their best-shaped triangulation
    /// ([`triangulate_shaped`](crate::cut::triangles::triangulate::triangulate_shaped)) instead of ear clipping or one polygon.
    pub faces_reshaped: usize,
    /// Faces written as a fan around a new centre point.
    pub faces_fanned: usize,
    /// Vertices moved by a few ulps where the exact local check improved
    /// ([`nudge`](crate::cut::certify::nudge::nudge); cut-vertices and face centres, never input vertices).
    pub vertices_nudged: usize,
    /// Rounds kept.
    pub rounds: usize,
    /// The exact check of the result (what `cells.vtu` holds).
    pub report: VerifyReport,
    /// Written triangles that are input triangles, unchanged, whose pairs
    /// the input's self-intersection check had proven disjoint (not tested
    /// again; 0 when that check was skipped).
    #[serde(skip)]
    pub proven_input_triangles: usize,
}
