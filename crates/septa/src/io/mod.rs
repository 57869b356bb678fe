//! Readers and writers.

pub mod cut_out;
pub mod functions;
pub mod mesh;
pub mod mesh_obj;
pub mod mesh_off;
pub mod mesh_ply;
pub mod mesh_stl;
pub mod msh;
pub mod network_out;
pub mod npz;
pub mod planes;
pub mod regions_out;
