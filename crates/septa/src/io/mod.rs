//! Readers and writers, in three layers (each importing only those before it):
//! - `files/`: safe file access: bounded reads of regular input files
//!   (`input`), the checks before any write (`safe_write`), atomic writes
//!   (`atomic`), and the output folder as a transaction (`outdir`).
//! - `readers/`: inputs into the library's types: triangle meshes (OBJ,
//!   OFF, PLY, STL), plane lists, tetrahedral meshes (JSON, Gmsh `.msh`),
//!   `.npy`/`.npz` grids, label volumes, and the names of functions and
//!   regions.
//! - `writers/`: results out: networks, regions and cuts in every format
//!   (`result_*` through one [`ResultView`], `network_out`, `regions_out`,
//!   `cut_*`), streamed PLY and VTU, the summary, and the viewer.
//!
//! Every file is a module private to `io`; what users need is re-exported
//! here under one name each (`septa::io::write_network`,
//! `septa::io::read_mesh`, ...).

mod files;
mod readers;
mod writers;

pub use files::atomic::{remove_pending_temps, set_durable, write_atomic, write_atomic_with};
pub use files::input::{check_count, input_limit, open_regular, read_input, read_input_text};
pub use files::outdir::{check_complete, OutputDir};
pub use files::safe_write::check_output_file;
pub use readers::functions::{read_tet_mesh_json, MeshData, RefError};
pub use readers::mesh::{IndexedMesh, ReadError};
pub use readers::mesh_obj::parse_obj;
pub use readers::mesh_off::parse_off;
pub use readers::mesh_ply::parse_ply;
pub use readers::mesh_stl::parse_stl;
pub use readers::msh::{parse_msh, read_msh, MshError};
pub use readers::names::{name_token, Names};
pub use readers::npz::{parse_npy, read_grid_input, read_npz, GridInput, NpyArray, NpzError};
pub use readers::planes::{grid_planes, grid_planes_xyz, parse_planes, random_planes, read_planes};
pub use readers::read_mesh::read_mesh;
pub use readers::volume::{check_placement, diagonal_affine, place_surfaces, read_label_volume, LabelVolume};
pub use writers::cut_foam::{
    parse_box_side, poly_mesh, poly_mesh_patched, write_poly_mesh, BoundaryPatches, BoxSide, PolyMesh,
};
pub use writers::cut_out::{cut_cells_obj, cut_cells_obj_of, cut_cells_vtu, cut_cells_vtu_of};
pub use writers::cut_vtu::{read_polyhedra, Polyhedra};
pub use writers::foam_check::{check_poly_mesh, face_centres_and_areas, FoamCheck};
pub use writers::network_out::{
    network_meta, write_network, write_network_formats, write_network_formats_with, write_network_json,
    write_network_obj, write_network_ply, write_network_vtu, write_view_formats, ExtraFile,
};
pub use writers::ply_stream::{PlyStreamSink, PlyStreamStats};
pub use writers::regions_out::{
    regions_document, regions_face_normals, regions_summary, write_regions, write_regions_formats,
    write_regions_formats_with,
};
pub use writers::result::{Annotations, Format, ResultView, SolidFormat};
pub use writers::result_file::write_file;
pub use writers::result_vtk::vtk_face_order;
pub use writers::solids_out::{solid_stems, solids, write_solids, write_solids_into, SolidFile, SOLIDS_DIR};
pub use writers::summary_out::write_summary_json;
pub use writers::viewer::{
    folder_network, viewer_data_script, viewer_inline_page, write_result_viewer, write_viewer, ViewerError,
    VIEWER_INDEX_HTML, VIEWER_JS,
};
pub use writers::vtu_stream::{StreamFile, VtuStreamSink};
