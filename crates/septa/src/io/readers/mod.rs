//! Inputs read into the library's types; every error names the file (and
//! line, where there is one).
//!
//! Enters: files (read through `files/input`). Leaves: triangle meshes
//! (`IndexedMesh`, `read_mesh` choosing the format), plane lists,
//! tetrahedral meshes with functions, `.npy`/`.npz` grids, label volumes,
//! and function and region `Names`.

pub(crate) mod functions;
pub(crate) mod mesh;
pub(crate) mod mesh_obj;
pub(crate) mod mesh_off;
pub(crate) mod mesh_ply;
pub(crate) mod mesh_stl;
pub(crate) mod msh;
pub(crate) mod names;
pub(crate) mod npy_labels;
pub(crate) mod npz;
pub(crate) mod planes;
pub(crate) mod read_mesh;
pub(crate) mod volume;
