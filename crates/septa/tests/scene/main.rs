//! The scene tests as one test binary (one link step per area).

#[path = "../common/mod.rs"]
mod common;

mod anchor_csg;
mod anchor_types;
mod bounds_float;
mod files;
mod gradients;
mod network;
mod primitives;
mod print;
mod reference;
mod regions;
