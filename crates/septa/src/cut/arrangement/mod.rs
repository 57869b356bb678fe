//! Stages 4 to 8 (`mesh_edges` to `plane_faces`), the exact arrangement:
//! cut-vertices as face triples merged when equal (`nodes`), sorted along every
//! mesh edge and plane-plane line (`lines`, TopoCut Sec. 3, App. B); cut-faces
//! inside triangles by clipping (`clip`, Sec. 4) and inside planes as loops of
//! the half-edge structure `H(p)` (`plane_graph`, App. C) with their holes
//! (`holes`, Sec. 2.2, 6.1).
//!
//! Enters: the checked input as a `Ctx`. Leaves: the distinct cut-vertices,
//! the vertex chains of every mesh edge and plane-plane line, and the
//! cut-face loops with the line of each edge.

pub(crate) mod clip;
pub(crate) mod holes;
pub(crate) mod lines;
pub(crate) mod nodes;
pub(crate) mod plane_graph;
