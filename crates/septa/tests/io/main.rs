//! The io tests as one test binary (one link step per area).

#[path = "../common/mod.rs"]
mod common;

mod atomic_failure;
mod hostile;
mod mesh_formats;
mod npy_volume;
mod readers_fuzz;
