//! Jobs on functions given as formulas on a box grid: sparse evaluation
//! (`run`: blocks proven empty by bounds are skipped, the rest sampled
//! block by block, `sample`; a job is three public steps so blocks can run anywhere),
//! block results as bytes (`wire`, for the distributed path) and
//! continuation from seeds for functions without bounds (`continuation`).

pub(crate) mod continuation;
mod run;
mod sample;
pub(crate) mod wire;

pub(crate) use run::{block_at, check_functions, ctx, cubes, run_block_with};
pub use run::{compute_sparse, finish_sparse, plan_sparse, run_block, BlockResult, JobKey, SparsePlan, SparseStats};
