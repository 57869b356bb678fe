//! Stage 11 (`embed`), the floating-point embedding (TopoCut Sec. 6.1): every
//! cut-vertex rounded with a box enclosing its exact point (`round`, with
//! `exact_round` for ill-conditioned triples), then moved by ulps until the
//! exact order along every line holds and every vertex of a cell lies on its
//! exact side of each face near it (`embed`, the vertex-face orders of Eq.
//! (13), decided by `sides` behind the filter `side_filter`).
//!
//! Enters: the cut-cell mesh with exact vertex definitions and the lines'
//! vertex chains. Leaves: the rounded coordinates (`CutCellMesh::vertices`)
//! and the counts of moves and remaining violations (`EmbedStats`).

pub(crate) mod embed;
#[cfg(test)]
mod embed_tests;
pub(crate) mod exact_round;
pub(crate) mod round;
pub(crate) mod side_filter;
#[cfg(test)]
mod side_filter_tests;
pub(crate) mod sides;
