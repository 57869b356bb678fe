//! Readers and writers.

pub mod npz;
pub mod mesh;
pub mod mesh_obj;
pub mod mesh_off;
pub mod mesh_ply;
pub mod mesh_stl;
pub mod planes;
pub mod cut_out;
