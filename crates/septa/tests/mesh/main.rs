//! The mesh layer's tests as one test binary: certification of the written
//! doubles (`septa::mesh`).

#[path = "../common/mod.rs"]
mod common;

mod certify;

mod project;

mod remesh;
