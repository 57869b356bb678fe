//! Readers and writers.

pub mod functions;
pub mod msh;
pub mod network_out;
pub mod npz;
