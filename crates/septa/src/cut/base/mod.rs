//! The cut's vocabulary, below every stage: the exact cut-vertex (`geom`:
//! a face triple [`Def`], line directions, the input context `Ctx` with
//! its exact and filtered predicates), the errors a cut can fail with, and
//! what a cut returns (the cut-cell mesh and its statistics).
//!
//! Enters: nothing (types and predicates only). Leaves: [`Def`], `Ctx`,
//! [`CutError`], [`CutCellMesh`], [`CutStats`] to every stage above.
//!
//! [`Def`]: crate::cut::Def
//! [`CutError`]: crate::cut::CutError
//! [`CutCellMesh`]: crate::cut::CutCellMesh
//! [`CutStats`]: crate::cut::CutStats

pub(crate) mod error;
pub(crate) mod geom;
pub(crate) mod mesh;
pub(crate) mod stats;
