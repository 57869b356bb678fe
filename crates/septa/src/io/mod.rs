//! Readers and writers.

pub mod npz;
