//! Stage 12 (`output`), output: volumes by the divergence theorem and the
//! polygons each cell is written as (`output`), exact rational coordinates for
//! users who need them (`rational`), and the validation of a finished cut
//! against its input (`validate`).
//!
//! Enters: the embedded cut-cell mesh. Leaves: volumes, cell polygons,
//! exact coordinates, a [`Validation`] report.
//!
//! [`Validation`]: crate::cut::Validation

pub(crate) mod output;
pub(crate) mod rational;
pub(crate) mod validate;
