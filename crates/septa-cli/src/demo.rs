//! `septa demo`: runs the built-in scenes and writes everything under one
//! folder (default `./septa-demo/`), then prints a table of counts and
//! timings and how to open each result in the viewer.
//!
//! Jobs are added to [`jobs`] as the library grows them: a CAD-like
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
    #[arg(short = 'o', long = "output", visible_alias = "out", default_value = "septa-demo")]
    pub out: PathBuf,
    /// Grid resolution (cubes per side) of the grid scenes.
    #[arg(long, default_value_t = 64, value_parser = crate::args::grid)]
    pub grid: usize,
}

/// What one demo job reports for the table.
pub struct JobRow {
    /// Counts as in `--json` (vertices, faces, patches, chains, corners,
    /// shells, cells; surfaces and curves for region jobs).
    pub counts: serde_json::Value,
    /// Whether the folder gets a viewer (a streamed network is for files, not a browser).
    pub viewer: bool,
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

/// The demo jobs: one per job Septa does.
pub fn jobs() -> Vec<Job> {
    vec![
        Job {
            name: "cad-part",
            about: "a CAD part from half-spaces and cylinders: faces and sharp edges",
            run: cad_part,
        },
        Job { name: "apollonius-18", about: "Apollonius diagram of 18 spheres (MI)", run: apollonius },
        Job {
            name: "sphere-plane-hole",
            about: "Bloomenthal 4.8.3: non-manifold shape with surfaces and curves of interest",
            run: sphere_plane_hole,
        },
        Job { name: "cut-torus", about: "a torus mesh cut by a 6x6x6 grid of planes (TopoCut)", run: cut_torus },
        Job {
            name: "stream-ia18",
            about: "IA of 18 spheres on a grid 2x finer, streamed to a PLY, topology from block summaries",
            run: stream_ia18,
        },
    ]
}

type JobResult = Result<JobRow, Box<dyn std::error::Error>>;

fn counts(net: &septa::network::Network) -> serde_json::Value {
    net.counts().into_iter().map(|(k, v)| (k.to_string(), serde_json::json!(v))).collect()
}

/// The exact network of a built-in scene's functions (no region rule).
fn scene_network(name: &str, grid: Option<usize>, dir: &Path) -> JobResult {
    use septa::grid::Grid;
    use septa::network::{compute, NetworkOptions};
    let mut scene = septa::scene::Scene::load(&format!("builtin:{name}"))?;
    if let Some(n) = grid {
        scene.grid.resolution = [n; 3];
    }
    let g = Grid::Box(scene.grid.box_grid()?);
    let values = septa::scene::sample_grid(&scene.functions, &g.vertices());
    let mode = match scene.mode {
        septa::scene::Mode::Ia => septa::complex::Mode::Ia,
        septa::scene::Mode::Mi => septa::complex::Mode::Mi,
    };
    let mut net = compute(&g, &values, scene.functions.len(), &NetworkOptions::new(mode))?;
    if let septa::grid::Grid::Box(b) = &g {
        septa::mesh::certify_network(&mut net, Some(b));
    }
    let notes = septa::io::Annotations {
        names: scene.result_names(),
        measures: septa::measure::network_measures(
            &net,
            Some(&septa::measure::BoxDomain::of_box(&scene.grid.box_grid()?)),
        ),
    };
    septa::io::write_network(&net, &notes, dir, &[])?;
    Ok(JobRow { counts: counts(&net), viewer: true })
}

/// The part's solid (its CSG rule) from the exact arrangement of its
/// half-spaces and cylinders: its faces, and its sharp edges as curves.
fn cad_part(dir: &Path, _: &Args) -> JobResult {
    region_job("builtin:cad-part", dir)
}

fn apollonius(dir: &Path, a: &Args) -> JobResult {
    scene_network("apollonius-18", Some(a.grid), dir)
}

/// The 18 spheres of the IA benchmark (data/specs/ia18.json) streamed block by block: `stream.ply`
/// (faces with patch and cells) and `stream.topology.json`, in bounded memory.
fn stream_ia18(dir: &Path, a: &Args) -> JobResult {
    use septa::complex::Mode;
    use septa::network::{stream_topology, NetworkOptions};
    let spec = include_str!("../../../data/specs/ia18.json");
    let functions = septa::scene::load_function_list(spec, "data/specs/ia18.json", None)?;
    let n = 2 * a.grid;
    let grid = septa::grid::BoxGrid::new([n; 3], [[-1.0; 3], [1.0; 3]], septa::grid::Split::Five)?;
    let path = dir.join("stream.ply");
    let mut sink = septa::io::PlyStreamSink::create(&path, &grid, Mode::Ia, functions.len())?;
    let (_, summary) = stream_topology(&grid, &functions, &NetworkOptions::new(Mode::Ia), 0, &mut sink)?;
    sink.finish_with(Some(&summary))?;
    septa::io::write_summary_json(&summary, &dir.join("stream.topology.json"), &[])?;
    let counts = summary.counts().into_iter().map(|(k, v)| (k.to_string(), serde_json::json!(v))).collect();
    Ok(JobRow { counts, viewer: false })
}

fn sphere_plane_hole(dir: &Path, _: &Args) -> JobResult {
    region_job("builtin:sphere-plane-hole", dir)
}

/// A region job's row: the network's patches, chains, corners, shells and
/// cells in their own columns, the surfaces and curves of interest in theirs
/// (before, surfaces and curves were printed as patches and chains), and
/// the vertices and polygons written.
fn region_job(name: &str, dir: &Path) -> JobResult {
    let scene = septa::scene::Scene::load(name)?;
    let mut r = septa::regions::region_surfaces(&scene, &Default::default())?;
    let grid = scene.grid.box_grid()?;
    septa::mesh::certify_regions(&mut r, Some(&grid), Some(grid.bounds));
    septa::io::write_regions(&r, dir)?;
    let mut c = counts(&r.network);
    c["vertices"] = septa::io::regions_summary(&r)["vertices"].clone();
    c["faces"] = serde_json::json!(r.faces.len());
    c["surfaces"] = serde_json::json!(r.surfaces.len());
    c["curves"] = serde_json::json!(r.curves.len());
    Ok(JobRow { counts: c, viewer: true })
}

/// A closed, outward torus mesh (genus 1, so some cut-cells wrap its hole).
fn torus_obj(major: f64, minor: f64, nu: usize, nv: usize) -> String {
    use std::fmt::Write;
    let mut s = String::from("# torus generated by septa demo\n");
    for i in 0..nu {
        let u = std::f64::consts::TAU * i as f64 / nu as f64;
        for j in 0..nv {
            let v = std::f64::consts::TAU * j as f64 / nv as f64;
            let r = major + minor * v.cos();
            writeln!(s, "v {} {} {}", r * u.cos(), r * u.sin(), minor * v.sin()).unwrap();
        }
    }
    let id = |i: usize, j: usize| (i % nu) * nv + (j % nv) + 1;
    for i in 0..nu {
        for j in 0..nv {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            writeln!(s, "f {a} {b} {c}\nf {a} {c} {d}").unwrap();
        }
    }
    s
}

fn cut_torus(dir: &Path, _: &Args) -> JobResult {
    let mesh = dir.join("torus.obj");
    septa::io::write_atomic(&mesh, torus_obj(1.0, 0.4, 48, 24).as_bytes())?;
    crate::cut::run(crate::cut::Args {
        mesh,
        grid: Some(vec![6]),
        random: None,
        seed: 0,
        planes: None,
        out: Some(dir.to_path_buf()),
        threads: 0,
        json: false,
        quiet: false,
        format: Default::default(),
        no_mesh_output: false,
        no_self_check: false,
        explode: 0.0,
        patches: Vec::new(),
        triangulate: false,
        check_mesh: false,
        verify: false,
        exact_vertices: false,
        no_certify: false,
    })?;
    let j: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(dir.join("cut.json"))?)?;
    Ok(JobRow {
        counts: serde_json::json!({"vertices": j["cut_vertices"], "faces": j["cut_faces"], "cells": j["cut_cells"]}),
        viewer: true,
    })
}

/// The table's columns: the network's counts, then the region jobs' surfaces
/// and curves of interest (`-`: the job has none; a cut's `cells` are its cut-cells).
const COLUMNS: [&str; 9] =
    ["vertices", "faces", "patches", "chains", "corners", "shells", "cells", "surfaces", "curves"];

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
        if row.viewer {
            crate::view::write_viewer(&dir, job.name)?;
        }
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
        println!("(no demo jobs in this build yet: the grid, region and cut jobs are added here as they land)");
        println!("To try the viewer now: septa view tests/fixtures/two-planes");
    } else {
        println!("Open a result in the viewer: septa view {}/{}", args.out.display(), rows[0].0);
        println!("(each job folder but the streamed one already has viewer/index.html; `septa view` writes one for");
        println!(" the streamed one too, and stream.ply opens in ParaView coloured by its per-face patch or cells_0/cells_1)");
    }
    Ok(())
}
