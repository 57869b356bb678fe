//! `septa demo`: runs the built-in scenes and writes everything under one
//! folder (default `./septa-demo/`), then prints a table of counts and
//! timings and how to open each result in the viewer.
//!
//! Jobs are added to [`jobs`] as the library grows them (issue 4): a CAD-like
//! IA, an Apollonius MI, a Bloomenthal non-manifold shape, a planar cut of a
//! bundled mesh. Each writes the standard output folder (`network.json`, ...)
//! under the demo folder and returns its counts and seconds.
use crate::CliResult;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `septa demo`.
#[derive(clap::Args)]
pub struct Args {
    /// Folder that receives one sub-folder per job.
    #[arg(long, short, default_value = "septa-demo")]
    pub out: PathBuf,
    /// Grid resolution (cubes per side) of the grid scenes.
    #[arg(long, default_value_t = 64)]
    pub grid: usize,
}

/// What one demo job reports for the table.
pub struct JobRow {
    /// Counts as in `--json` (vertices, faces, patches, chains, corners, shells, cells).
    pub counts: serde_json::Value,
}

/// One built-in demo job: a name, what it shows, and how to run it into a folder.
pub struct Job {
    /// Sub-folder name and table row name.
    pub name: &'static str,
    /// One line about what it shows.
    pub about: &'static str,
    /// Runs the job, writing its outputs into the given folder.
    pub run: fn(&Path, &Args) -> Result<JobRow, Box<dyn std::error::Error>>,
}

/// The demo jobs available in this build (the lead adds one per job as it lands).
pub fn jobs() -> Vec<Job> {
    Vec::new()
}

const COLUMNS: [&str; 7] = [
    "vertices", "faces", "patches", "chains", "corners", "shells", "cells",
];

/// Runs `septa demo`.
pub fn run(args: Args) -> CliResult {
    std::fs::create_dir_all(&args.out)
        .map_err(|e| format!("cannot create {}: {e}", args.out.display()))?;
    let jobs = jobs();
    println!(
        "septa demo: {} job(s), writing under {}/",
        jobs.len(),
        args.out.display()
    );
    let mut rows = Vec::new();
    for (i, job) in jobs.iter().enumerate() {
        eprintln!("[{}/{}] {}: {}", i + 1, jobs.len(), job.name, job.about);
        let dir = args.out.join(job.name);
        std::fs::create_dir_all(&dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
        let t = Instant::now();
        let row = (job.run)(&dir, &args).map_err(|e| format!("demo job {}: {e}", job.name))?;
        let seconds = t.elapsed().as_secs_f64();
        crate::view::write_viewer(&dir, job.name)?;
        rows.push((job.name, row, seconds));
    }
    print!("{:<22}", "job");
    for c in COLUMNS {
        print!("{c:>10}");
    }
    println!("{:>10}", "seconds");
    for (name, row, seconds) in &rows {
        print!("{name:<22}");
        for c in COLUMNS {
            let v = row
                .counts
                .get(c)
                .map(|v| v.to_string())
                .unwrap_or_else(|| "-".into());
            print!("{v:>10}");
        }
        println!("{seconds:>10.2}");
    }
    if rows.is_empty() {
        println!("(no demo jobs in this build yet: the grid, region and cut jobs are added here as they land)");
        println!("To try the viewer now: septa view tests/fixtures/two-planes");
    } else {
        println!(
            "Open a result in the viewer: septa view {}/{}",
            args.out.display(),
            rows[0].0
        );
        println!("(each job folder already has viewer/index.html)");
    }
    Ok(())
}
