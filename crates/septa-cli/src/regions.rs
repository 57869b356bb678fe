//! `septa regions` (in progress).
use crate::CliResult;

/// Arguments of `septa regions`.
#[derive(clap::Args)]
pub struct Args {}

/// Runs `septa regions`.
pub fn run(_args: Args) -> CliResult {
    Err("septa regions: not implemented yet".into())
}
