//! `septa ia` and `septa mi` (in progress).
use crate::CliResult;

/// Which network to compute.
pub enum Mode {
    /// Implicit arrangement.
    Ia,
    /// Material interface.
    Mi,
}

/// Arguments of `septa ia|mi`.
#[derive(clap::Args)]
pub struct Args {}

/// Runs `septa ia|mi`.
pub fn run(_args: Args, _mode: Mode) -> CliResult {
    Err("septa ia/mi: not implemented yet".into())
}
