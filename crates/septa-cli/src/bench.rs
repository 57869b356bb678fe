//! `septa bench` (in progress).
use crate::CliResult;

/// Arguments of `septa bench`.
#[derive(clap::Args)]
pub struct Args {}

/// Runs `septa bench`.
pub fn run(_args: Args) -> CliResult {
    Err("septa bench: not implemented yet".into())
}
