//! The scene tests as one test binary (one link step per area).

mod bounds_float;
mod files;
mod gradients;
mod network;
mod primitives;
mod print;
mod reference;
mod regions;
