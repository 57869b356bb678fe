//! Stage 13 (`certify`), certification: the written embedding checked exactly
//! (`check/`), and what fails repaired by re-writing faces as triangles and by
//! certified vertex moves of a few ulps (`repair`, `nudge`).
//!
//! Enters: the cut-cell mesh as written (coordinates, faces, triangulated
//! faces). Leaves: the repaired mesh and [`RepairStats`] with the final
//! exact report.
//!
//! [`RepairStats`]: crate::cut::RepairStats

pub(crate) mod nudge;
pub(crate) mod repair;
