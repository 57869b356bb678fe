//! The regions tests as one test binary (one link step per area).

#[path = "../common/mod.rs"]
mod common;

mod builtin;
mod clean;
mod labels;
mod measures;
mod orientation;
