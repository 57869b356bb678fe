//! Exact tests on triangles given as doubles, knowing nothing of the cut:
//! orientation signs (`orient`), the triangle-pair intersection test
//! (`tri_pair`), the broad phase that finds candidate pairs (`pair_grid`,
//! `sweep_frame`, `box_contact`, `plane_separation`, `radix`), all
//! intersecting pairs of a triangle set (`selfx`, TopoCut App. A), and the
//! ear clipping of a face polygon into triangles (`triangulate`).
//!
//! Enters: coordinates and triangles as index triples. Leaves: exact signs,
//! intersecting pairs, triangulations: the input check (`input/`) and the
//! check of the written mesh (`check/`) are made of them.

pub(crate) mod box_contact;
pub(crate) mod orient;
pub(crate) mod pair_grid;
pub(crate) mod plane_separation;
pub(crate) mod radix;
pub(crate) mod selfx;
pub(crate) mod sweep_frame;
pub(crate) mod tri_pair;
pub(crate) mod triangulate;
