//! `septa demo` (in progress).
use crate::CliResult;

/// Arguments of `septa demo`.
#[derive(clap::Args)]
pub struct Args {}

/// Runs `septa demo`.
pub fn run(_args: Args) -> CliResult {
    Err("septa demo: not implemented yet".into())
}
