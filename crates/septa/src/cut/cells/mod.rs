//! Stages 9 and 10 (`cells`, `faces`), cut-cells: half-faces joined across each
//! cut-edge by exact face-cycle order (`cells`, TopoCut Sec. 5, eq. 11), voids
//! attached to their enclosing cell by exact plane-side signatures or an exact
//! ray (`voids`, `void_rays`), and the exact sign of each cell's volume
//! (`volume`, with the filter `volume_filter`).
//!
//! Enters: cut-face loops, and the exact boxes of the rounded cut-vertices
//! (`embed::round`). Leaves: the cell on each side of every cut-face, the
//! cell count, attached voids, and the cells' exact volume signs.

pub(crate) mod cells;
pub(crate) mod void_rays;
pub(crate) mod voids;
pub(crate) mod volume;
pub(crate) mod volume_filter;
