//! Where the reference data lives: `$SEPTA_SHARED`, the `shared/` folder
//! beside the repository (as CI lays it out), or `/work/shared`. A missing
//! folder fails the test: reference checks must never pass vacuously.
#![allow(dead_code)]

use std::path::PathBuf;

/// The `shared/data` folder.
pub fn shared_data() -> PathBuf {
    let mut candidates = Vec::new();
    if let Ok(d) = std::env::var("SEPTA_SHARED") {
        candidates.push(PathBuf::from(d).join("data"));
    }
    candidates.push(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data"));
    candidates.push(PathBuf::from("/work/shared/data"));
    candidates
        .into_iter()
        .find(|d| d.join("isn/expected.json").exists())
        .expect("reference data shared/data not found: set SEPTA_SHARED to the shared/ folder")
}
