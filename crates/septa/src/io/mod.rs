//! Readers and writers.

mod atomic;
pub mod cut_foam;
pub mod cut_out;
pub mod cut_vtu;
pub mod functions;
pub mod mesh;
pub mod mesh_obj;
pub mod mesh_off;
pub mod mesh_ply;
pub mod mesh_stl;
pub mod msh;
pub mod network_out;
pub mod npz;
pub mod outdir;
pub mod planes;
pub mod ply_stream;
pub mod regions_out;
pub mod result;
pub mod result_mesh;
pub mod result_npz;
pub mod result_vtk;
pub mod summary_out;
mod viewer;
pub mod volume;
pub mod vtu_stream;

pub use atomic::{remove_pending_temps, write_atomic, write_atomic_with};
pub use outdir::OutputDir;
pub use viewer::{
    folder_network, viewer_data_script, viewer_inline_page, write_result_viewer, write_viewer, ViewerError,
    VIEWER_INDEX_HTML, VIEWER_JS,
};
