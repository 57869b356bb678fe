//! A timing entry point for `septa bench` (owned by the CLI lead): reads a
//! mesh and a plane file, cuts, and reports counts and seconds.

use crate::cut::{cut_mesh, CutCounts, CutOptions};
use crate::io::{read_mesh, read_planes};
use std::path::Path;
use std::time::Instant;

/// One timed cut.
#[derive(Clone, Debug, serde::Serialize)]
pub struct CutTiming {
    /// Counts of the result.
    pub counts: CutCounts,
    /// Seconds reading the two files.
    pub read_seconds: f64,
    /// Seconds in [`cut_mesh`] (checks included).
    pub cut_seconds: f64,
    /// Per-stage seconds inside the cut.
    pub stages: Vec<(String, f64)>,
}

/// Reads `mesh` and `planes` and cuts with `threads` workers (0: all).
pub fn time_case(
    mesh: &Path,
    planes: &Path,
    threads: usize,
) -> Result<CutTiming, Box<dyn std::error::Error + Send + Sync>> {
    let t0 = Instant::now();
    let m = read_mesh(mesh)?;
    let p = read_planes(planes)?;
    let read_seconds = t0.elapsed().as_secs_f64();
    let t1 = Instant::now();
    let out = cut_mesh(&m.vertices, &m.triangles, &p, &CutOptions { threads, ..Default::default() })?;
    Ok(CutTiming {
        counts: out.counts,
        read_seconds,
        cut_seconds: t1.elapsed().as_secs_f64(),
        stages: out.stats.seconds,
    })
}
