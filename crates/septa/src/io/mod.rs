//! Readers and writers.
//!
//! Every file is a private module; what users need is re-exported here
//! under one name each (`septa::io::write_network`,
//! `septa::io::read_mesh`, ...).

mod atomic;
mod cut_float;
mod cut_foam;
mod cut_out;
mod cut_vtu;
mod functions;
mod input;
mod mesh;
mod mesh_obj;
mod mesh_off;
mod mesh_ply;
mod mesh_stl;
mod msh;
mod names;
mod network_out;
mod npy_labels;
mod npz;
mod outdir;
mod planes;
mod ply_stream;
mod regions_out;
mod result;
mod result_mesh;
mod result_npz;
mod result_vtk;
mod safe_write;
mod summary_out;
mod viewer;
mod volume;
mod vtu_stream;

pub use atomic::{remove_pending_temps, set_durable, write_atomic, write_atomic_with};
pub use cut_foam::{poly_mesh, write_poly_mesh, PolyMesh};
pub use cut_out::{cut_cells_obj, cut_cells_obj_of, cut_cells_vtu, cut_cells_vtu_of};
pub use cut_vtu::{read_polyhedra, Polyhedra};
pub use functions::{read_tet_mesh_json, MeshData, RefError};
pub use input::{check_count, input_limit, open_regular, read_input, read_input_text};
pub use mesh::{read_mesh, IndexedMesh, ReadError};
pub use mesh_obj::parse_obj;
pub use mesh_off::parse_off;
pub use mesh_ply::parse_ply;
pub use mesh_stl::parse_stl;
pub use msh::{parse_msh, read_msh, MshError};
pub use names::{name_token, Names};
pub use network_out::{
    network_meta, write_network, write_network_formats, write_network_formats_with, ExtraFile, write_network_json, write_network_obj, write_network_ply,
    write_network_vtu,
};
pub use npz::{parse_npy, read_grid_input, read_npz, GridInput, NpyArray, NpzError};
pub use outdir::OutputDir;
pub use planes::{grid_planes, grid_planes_xyz, parse_planes, random_planes, read_planes};
pub use ply_stream::{PlyStreamSink, PlyStreamStats};
pub use regions_out::{regions_document, regions_face_normals, regions_summary, write_regions, write_regions_formats, write_regions_formats_with};
pub use result::{write_file, Annotations, Format, ResultView};
pub use safe_write::check_output_file;
pub use summary_out::write_summary_json;
pub use viewer::{
    folder_network, viewer_data_script, viewer_inline_page, write_result_viewer, write_viewer, ViewerError,
    VIEWER_INDEX_HTML, VIEWER_JS,
};
pub use volume::{check_placement, diagonal_affine, place_surfaces, read_label_volume, LabelVolume};
pub use vtu_stream::{StreamFile, VtuStreamSink};
