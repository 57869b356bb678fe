//! The cut tests as one test binary (one link step per area).

#[path = "../common/mod.rs"]
mod common;

mod embedding;
mod expected;
mod invariance;
mod nesting;
mod nonmanifold;
mod rational_oracle;
mod shapes;
mod small;
mod verify;
