//! Safe file access under every reader and writer: inputs read as bounded
//! regular files (`input`, the limit from the memory budget), outputs
//! checked before a write (`safe_write`: no symlink, device or folder in
//! the way), written atomically through a temporary file (`atomic`), and an
//! output folder written as a transaction with its manifest (`outdir`).
//!
//! Enters: paths. Leaves: bytes read, files written whole or not at all.

pub(crate) mod atomic;
pub(crate) mod input;
pub(crate) mod outdir;
pub(crate) mod safe_write;
