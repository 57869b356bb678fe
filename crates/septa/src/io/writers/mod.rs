//! Results written: a network's or regions' result read through one
//! `ResultView` and written per format (`result_mesh`, `result_npz`,
//! `result_vtk`; `result_file` picks one), the output folders of networks
//! and regions (`network_out`, `regions_out`, `summary_out`), cut-cell
//! meshes (`cut_*`; `foam_check`: checkMesh's quantities of a polyMesh),
//! streamed PLY and VTU (`ply_stream`, `vtu_stream`), and the viewer.
//!
//! Enters: results of the library (networks, regions, cuts). Leaves: files
//! and output folders (through `files/`), named by `readers/names`.

pub(crate) mod cut_float;
pub(crate) mod cut_foam;
pub(crate) mod cut_out;
pub(crate) mod cut_vtu;
pub(crate) mod foam_check;
pub(crate) mod network_out;
pub(crate) mod ply_stream;
pub(crate) mod regions_out;
pub(crate) mod result;
pub(crate) mod result_file;
pub(crate) mod result_mesh;
pub(crate) mod result_npz;
pub(crate) mod result_vtk;
pub(crate) mod solids_out;
pub(crate) mod summary_out;
pub(crate) mod viewer;
pub(crate) mod vtu_stream;
