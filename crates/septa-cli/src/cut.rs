//! `septa cut` (in progress).
use crate::CliResult;

/// Arguments of `septa cut`.
#[derive(clap::Args)]
pub struct Args {}

/// Runs `septa cut`.
pub fn run(_args: Args) -> CliResult {
    Err("septa cut: not implemented yet".into())
}
