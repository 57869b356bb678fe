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

/// The demo jobs: each runs this same binary's subcommand with `--json`
/// into its own folder (so a job's output and summary are exactly what a
/// user gets from the command line) and reads the summary back.
pub fn jobs() -> Vec<Job> {
    vec![
        Job {
            name: "cad-part",
            about: "CAD-like part by CSG, implicit arrangement (Du et al. Fig. 19)",
            run: |d, _| regions(d, "cad-part"),
        },
        Job {
            name: "apollonius-18",
            about: "Apollonius diagram of 18 spheres, material interface (Fig. 15)",
            run: |d, _| regions(d, "apollonius-18"),
        },
        Job {
            name: "sphere-plane-hole",
            about: "Bloomenthal 4.8.3: non-manifold sphere and plane with a hole, curves of interest",
            run: |d, _| regions(d, "sphere-plane-hole"),
        },
        Job {
            name: "cut-icosphere",
            about: "planar cut-cells of a bundled icosphere mesh by a 4x4x4 plane grid (TopoCut)",
            run: cut_icosphere,
        },
    ]
}

fn run_self(args: &[&str]) -> Result<serde_json::Value, Box<dyn std::error::Error>> {
    let exe = std::env::current_exe()?;
    let out = std::process::Command::new(exe).args(args).output()?;
    if !out.status.success() {
        return Err(
            format!("`septa {}` failed: {}", args.join(" "), String::from_utf8_lossy(&out.stderr).trim()).into()
        );
    }
    Ok(serde_json::from_slice(&out.stdout)
        .map_err(|e| format!("`septa {}`: bad --json output: {e}", args.join(" ")))?)
}

fn regions(dir: &Path, scene: &str) -> Result<JobRow, Box<dyn std::error::Error>> {
    let j = run_self(&["regions", &format!("builtin:{scene}"), "-o", &dir.to_string_lossy(), "--json"])?;
    // The counts of the whole network (before keeping surfaces of interest).
    let counts = j.get("network").cloned().unwrap_or(j);
    Ok(JobRow { counts })
}

/// A closed, outward-oriented icosphere (icosahedron subdivided twice,
/// 320 triangles) written as OBJ: a mesh bundled in the binary by code.
fn icosphere_obj() -> String {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut v: Vec<[f64; 3]> = vec![
        [-1., t, 0.],
        [1., t, 0.],
        [-1., -t, 0.],
        [1., -t, 0.],
        [0., -1., t],
        [0., 1., t],
        [0., -1., -t],
        [0., 1., -t],
        [t, 0., -1.],
        [t, 0., 1.],
        [-t, 0., -1.],
        [-t, 0., 1.],
    ];
    let mut f: Vec<[usize; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let norm = |p: [f64; 3]| {
        let l = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        [p[0] / l, p[1] / l, p[2] / l]
    };
    for p in v.iter_mut() {
        *p = norm(*p);
    }
    for _ in 0..2 {
        let mut mid = std::collections::HashMap::new();
        let mut next = Vec::new();
        for tri in &f {
            let mut m = [0usize; 3];
            for e in 0..3 {
                let (a, b) = (tri[e].min(tri[(e + 1) % 3]), tri[e].max(tri[(e + 1) % 3]));
                m[e] = *mid.entry((a, b)).or_insert_with(|| {
                    let (p, q) = (v[a], v[b]);
                    v.push(norm([(p[0] + q[0]) / 2., (p[1] + q[1]) / 2., (p[2] + q[2]) / 2.]));
                    v.len() - 1
                });
            }
            next.extend([[tri[0], m[0], m[2]], [tri[1], m[1], m[0]], [tri[2], m[2], m[1]], [m[0], m[1], m[2]]]);
        }
        f = next;
    }
    let mut s = String::from("# icosphere, 2 subdivisions (septa demo)\n");
    for p in &v {
        s += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    for t in &f {
        s += &format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    s
}

fn cut_icosphere(dir: &Path, _: &Args) -> Result<JobRow, Box<dyn std::error::Error>> {
    let mesh = dir.join("icosphere.obj");
    crate::view::write_atomic(&mesh, icosphere_obj().as_bytes())?;
    let j = run_self(&["cut", &mesh.to_string_lossy(), "--grid", "4", "-o", &dir.to_string_lossy(), "--json"])?;
    let get = |k: &str| j.get(k).cloned().unwrap_or(serde_json::Value::Null);
    let counts =
        serde_json::json!({ "vertices": get("cut_vertices"), "faces": get("cut_faces"), "cells": get("cut_cells") });
    Ok(JobRow { counts })
}

const COLUMNS: [&str; 7] = ["vertices", "faces", "patches", "chains", "corners", "shells", "cells"];

/// Runs `septa demo`.
pub fn run(args: Args) -> CliResult {
    std::fs::create_dir_all(&args.out).map_err(|e| format!("cannot create {}: {e}", args.out.display()))?;
    let jobs = jobs();
    println!("septa demo: {} job(s), writing under {}/", jobs.len(), args.out.display());
    let mut rows = Vec::new();
    for (i, job) in jobs.iter().enumerate() {
        eprintln!("[{}/{}] {}: {}", i + 1, jobs.len(), job.name, job.about);
        let dir = args.out.join(job.name);
        std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
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
            let v = row.counts.get(c).map(|v| v.to_string()).unwrap_or_else(|| "-".into());
            print!("{v:>10}");
        }
        println!("{seconds:>10.2}");
    }
    if rows.is_empty() {
        println!("(no demo jobs in this build)");
    } else {
        println!("Open a result in the viewer: septa view {}/{}", args.out.display(), rows[0].0);
        println!("(each job folder already has viewer/index.html)");
    }
    Ok(())
}
