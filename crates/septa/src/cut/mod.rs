//! Planar cut-cell meshes of closed triangle meshes (TopoCut, Fang et al.
//! 2022): the domain bounded by a closed, outward-oriented triangle mesh is
//! cut by planes into cut-cells whose combinatorics are those of exact
//! rational arithmetic.
//!
//! A tour, one folder per stage of the pipeline (`pipeline.rs` runs the 13
//! timed stages, [`CutStats::seconds`] names them; paper sections in
//! brackets), each folder importing only those listed before it:
//! - `triangles/`, `check/`: exact tests on triangles of doubles that know
//!   nothing of the cut (orientations, triangle pairs and their broad phase,
//!   ear clipping), and the exact check of any written polyhedral mesh
//!   ([`verify_cells`], [`VerifyReport`]).
//! - `base/`: the cut's vocabulary: cut-vertices as face triples ([`Def`]),
//!   the input context and its filtered predicates, [`CutError`], the
//!   [`CutCellMesh`] a cut returns and its [`CutStats`].
//! - `input/` (stages 1-3): input conditions [Sec. 2.1, App. A], each
//!   failure a [`CutError`] naming the element; duplicate planes dropped.
//! - `arrangement/` (stages 4-8): cut-vertices on mesh edges and plane-plane
//!   lines, exact line sorting, merging of equal triples [Sec. 3, App. B];
//!   cut-faces inside triangles by clipping [Sec. 4, `H(t)`] and inside
//!   planes as loops of `H(p)` with their holes [App. C, Sec. 2.2, 6.1].
//! - `embed/` (stage 11, and the rounding stage 10 needs): the
//!   floating-point embedding [Sec. 6.1]: rounded cut-vertices moved by ulps
//!   until the exact order along every mesh edge and plane-plane line holds
//!   and every vertex of a cell lies strictly on its exact side of the
//!   supporting plane of each face of the cell near it (the vertex-face
//!   orders of Eq. (13)); moves and remaining violations counted
//!   ([`CutStats::moved_vertices`], [`CutStats::sidedness_moved`],
//!   [`CutStats::sidedness_violations`]).
//! - `cells/` (stages 9-10): half-faces joined across each cut-edge
//!   [Sec. 5, eq. 11] (two faces topologically, others by exact face-cycle
//!   order, [`CutStats::ordered_edges`]); voids attached; exact volume signs.
//! - `output/` (stage 12): volumes, the polygons or triangles each face is
//!   written as, exact rational coordinates, [`Validation`].
//! - `certify/` (stage 13): the written embedding checked exactly and
//!   repaired ([`RepairStats`]).
//!
//! Difference from the paper: TopoCut inserts planes one at a time into the
//! half-face structure and infers most cycle orders topologically. Here all
//! cut-faces are built first (triangles by clipping, planes from their whole
//! line arrangement) and cells are assembled once; cycle orders are
//! evaluated by filtered predicates (an interval filter decides almost all;
//! [`CutStats::exact_fallbacks`] counts the rest), so the result is the
//! exact one whatever the input degeneracy.
//!
//! Counting conventions (those of the reference implementation): a cut-face
//! with holes counts once, and each hole adds one cut-edge (the edge that
//! joins it to the outer boundary); a cell with a void would count once.
//! Every sign deciding the combinatorics comes from a filtered exact
//! predicate (`septa_exact::filtered_sign` and Shewchuk-style static
//! filters with stated bounds).
//!
//! Voids (a mesh component inside one open arrangement cell) are attached
//! to their enclosing cell by exact plane-side signatures (`voids.rs`), or,
//! when nested shells leave several candidates (an island in the cavity),
//! by an exact ray from the void (`void_rays.rs`). TopoCut counts each such
//! void as a cell of its own: its count is `cut_cells + voids_attached`.

#[cfg(feature = "tools")]
pub mod bench;
mod pipeline;
#[cfg(test)]
mod test_rng;

mod arrangement;
mod base;
mod cells;
mod certify;
mod check;
mod embed;
mod input;
mod output;
mod triangles;

pub use base::error::CutError;
pub use base::geom::Def;
pub use base::mesh::{CutCellMesh, CutFace, Support};
pub use base::stats::{CutCounts, CutStats, RepairStats};
pub use check::cell_polygons::CellPolygons;
pub use check::polygon::polygon_planar;
pub use check::verify::{verify_cells, verify_cells_since, VerifyReport};
pub use output::rational::{exact_coordinates, fraction_string};
pub use output::validate::Validation;
pub use pipeline::{cut_mesh, CutOptions, STAGES};
// The exact triangle machinery the embedding check of grid networks and
// region surfaces shares (`crate::mesh`, a layer above both `cut` and
// `network`, so no import cycle).
pub(crate) use check::polygon::collinear;
pub(crate) use triangles::selfx::intersecting_pairs;
pub(crate) use triangles::tri_pair::pair_intersects;
