//! `septa stress` (in progress).
use crate::CliResult;

/// Arguments of `septa stress`.
#[derive(clap::Args)]
pub struct Args {}

/// Runs `septa stress`.
pub fn run(_args: Args) -> CliResult {
    Err("septa stress: not implemented yet".into())
}
