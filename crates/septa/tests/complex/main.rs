//! The complex tests as one test binary (one link step per area).

mod lookup_tables;
mod random;
mod stress;
mod vertex_sign_oracle;
