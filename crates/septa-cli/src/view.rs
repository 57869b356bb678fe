//! `septa view` (in progress).
use crate::CliResult;

/// Arguments of `septa view`.
#[derive(clap::Args)]
pub struct Args {}

/// Runs `septa view`.
pub fn run(_args: Args) -> CliResult {
    Err("septa view: not implemented yet".into())
}
