//! # Septa
//!
//! Septa partitions 3D space by many surfaces and returns the walls
//! (**patches**), the curves where walls meet (**chains**), their end points
//! (**corners**) and the regions they enclose (**cells**), with a
//! combinatorial structure that is exact for the given input numbers.
//!
//! Layers, bottom to top (nothing flows up):
//! - [`septa_exact`]: filtered exact signs.
//! - [`complex`]: the convex cell complex of one tetrahedron cut by the
//!   zero sets of k linear functions (implicit arrangement, IA) or by
//!   their upper envelope (material interface, MI).
//! - [`grid`]: tetrahedral grids (built-in boxes, any tet mesh).
//! - [`network`]: per-tet complexes assembled into one surface network.
//! - [`cut`]: planar cut-cell meshes of closed triangle meshes (TopoCut).
//! - [`scene`]: primitives, sampling and region rules.
//! - [`io`]: readers and writers.
//! - [`measure`]: volumes of cells, areas of patches, lengths of chains.
//! - [`mesh`]: the written doubles certified as an embedding of the exact network.
//! - [`job`]: one job model (grid, functions, mode) read from any input, for every front end.
//! - [`heap`]: free heap memory returned to the system between the grid pipeline's stages.
//!
//! What is exact: every combinatorial answer (which vertices, edges, faces
//! and cells exist and how they connect). What is floating point: vertex
//! coordinates, computed only for output.
#![warn(missing_docs)]

#[cfg(feature = "tools")]
pub mod adaptive;
pub mod baseline;
mod buckets;
pub mod complex;
pub mod cut;
pub mod grid;
pub mod heap;
pub mod io;
pub mod job;
pub mod measure;
pub mod mesh;
pub mod network;
mod progress;
pub mod regions;
pub mod scene;
mod uf;
pub use progress::Progress;
