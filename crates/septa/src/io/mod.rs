//! Readers and writers.

pub mod functions;
pub mod network_out;
pub mod npz;
