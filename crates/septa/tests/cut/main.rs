//! The cut tests as one test binary (one link step per area).

#[path = "../common/mod.rs"]
mod common;

mod embedding;
mod expected;
mod invariance;
mod rational_oracle;
mod small;
mod verify;
