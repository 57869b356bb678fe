//! One block of the grid: per-tet complexes (Du et al. Sec. 4-6) turned into
//! polygons with global plane-based keys, plus a summary of the block's
//! 3D regions and shell connectivity that merges with other blocks exactly
//! and in any order (`topology::merge`).
//!
//! Memory per block is proportional to its tets while it is processed; what
//! leaves the block is proportional to its active tets and to its surface.

mod active;
mod boxfast;
mod keys;
mod mask;
mod program;
mod run;
mod simple;
mod state;
mod types;
mod values;
mod voxel_complex;
mod voxels;
mod worker;

pub(crate) use active::active_functions;
pub(crate) use keys::vertex_key;
pub(crate) use mask::{applies as mask_applies, CubeMask, NO_ROW};
pub(crate) use state::FACE_OF;
pub(crate) use types::{BlockOut, FaceKey, HalfPoly, Label, OpenT, SRef};
pub(crate) use values::{BlockLabels, BlockValues, Ctx, PointValues, Values};
pub(crate) use worker::{tet_face_zero, Worker};
