//! The exact check of a written polyhedral mesh (the floating-point
//! embedding of TopoCut Sec. 6.1 made a guarantee): on the very doubles
//! written, every cell is a closed, consistently oriented, non-self-
//! intersecting polyhedron of positive volume with planar faces.
//!
//! Enters: points and cells as flat lists of outward polygons
//! ([`CellPolygons`]), from a cut or from any polyhedral `.vtu`. Leaves: a
//! [`VerifyReport`] (counts of every violation; zero is a proof), used by
//! `certify/` and the writers.
//!
//! [`CellPolygons`]: crate::cut::CellPolygons
//! [`VerifyReport`]: crate::cut::VerifyReport

pub(crate) mod cell_polygons;
pub(crate) mod polygon;
pub(crate) mod tiling;
pub(crate) mod verify;
pub(crate) mod verify_volume;
