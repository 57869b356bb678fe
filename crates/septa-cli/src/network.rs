//! `septa ia` and `septa mi`: the surface network of functions on a tet grid.
use std::path::PathBuf;
use std::time::Instant;

use septa::grid::Split;
use septa::io::{write_network_formats_with, Annotations};
use septa::job::{GridOverride, Job};
use septa::network::{self, NetworkOptions};

use crate::CliResult;

/// Which network to compute.
pub enum Mode {
    /// Implicit arrangement.
    Ia,
    /// Material interface.
    Mi,
}

/// How cells are identified.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum CellMethod {
    /// Shoot rays through the network (exact, fast); falls back to grouping.
    Raytrace,
    /// Cell grouping across tet faces.
    Grouping,
}

/// Arguments of `septa ia|mi`.
#[derive(clap::Args)]
pub struct Args {
    /// Input: a scene (.json or .toml, see docs/scenes.md) or `builtin:NAME`
    /// (`septa regions --list`); a JSON list of functions (sphere, plane,
    /// ...) sampled on `--grid`; or an `.npz` with arrays vertices, tets and
    /// values (one column per function).
    input: PathBuf,
    #[command(flatten)]
    out: crate::output::Output,
    /// Box grid resolution (cubes per axis) for a function JSON input.
    #[arg(long, value_parser = crate::args::grid)]
    grid: Option<usize>,
    /// Tet mesh (Gmsh .msh 2.2/4.1, or a JSON `[vertices, tets]`) for a function JSON input.
    #[arg(long)]
    mesh: Option<PathBuf>,
    /// Box grid bounds: xmin ymin zmin xmax ymax zmax.
    // hyphen values: `-1e-300` is a number, not a flag (clap's negative
    // number test does not read exponents)
    #[arg(long, num_args = 6, allow_hyphen_values = true, value_parser = crate::args::finite)]
    bounds: Option<Vec<f64>>,
    /// Tets per cube of a box grid (5 or 6; default: the file's, else 5).
    #[arg(long, value_parser = clap::value_parser!(u8).range(5..=6))]
    split: Option<u8>,
    /// Do not use look-up tables (incremental construction in every tet).
    #[arg(long)]
    no_lookup: bool,
    /// Cell identification method.
    #[arg(long, value_enum, default_value = "raytrace")]
    cells: CellMethod,
    /// Naive floating-point predicates (for measuring only; may fail).
    #[arg(long)]
    float: bool,
    /// Compute everything, write nothing (for benchmarks).
    #[arg(long)]
    no_output: bool,
    /// Block edge in cubes.
    #[arg(long, default_value_t = 16, value_parser = crate::args::block)]
    block: usize,
    /// Sample every grid vertex (the dense path). By default, analytic
    /// functions on a box grid (a scene or a JSON list of functions)
    /// are evaluated sparsely: blocks the functions' bounds prove empty are
    /// skipped, the rest sampled block by block; the output is identical
    /// (the bounds enclose the rounded samples; docs/sparse.md).
    #[arg(long, conflicts_with = "sparse")]
    dense: bool,
    /// Accepted for compatibility: sparse evaluation is the default
    /// wherever it applies (no effect on `.npz` input or a tet mesh).
    #[arg(long)]
    sparse: bool,
    /// Stream the polygons to this file block by block, with memory
    /// bounded by a window of blocks (analytic functions on a box grid), and
    /// assemble the topology (patches, chains, corners, shells, cells) from
    /// block summaries on the way. A binary PLY, whose faces carry `labels_0`,
    /// `labels_1`, `block`, `patch`, `cells_0`, `cells_1`; or, for a name
    /// ending in .vtu (for meshio and ParaView), a VTK file with cell data
    /// `patch`, `labels`, `cells`, `block`. The topology goes to
    /// `OUT.topology.json` beside it. Vertices are written once.
    #[arg(long, conflicts_with_all = ["dense", "no_output", "adaptive"])]
    stream: Option<PathBuf>,
    /// With `--stream`: blocks computed at a time (0: four per thread).
    #[arg(long, default_value_t = 0, requires = "stream")]
    window: usize,
    /// With `--stream`: write each polygon as a fan of triangles (for
    /// readers that need one polygon size, such as trimesh).
    #[arg(long, requires = "stream")]
    triangles: bool,
    /// With `--stream`: polygons only, no topology (faces get patch and
    /// cells -1; no `.topology.json`).
    #[arg(long, requires = "stream")]
    polygons_only: bool,
    /// Move every vertex onto the true zero sets of the formulas (a scene or
    /// function list on a box grid), inside its grid element, keeping the
    /// exact network; moves that would break the exact check are left undone
    /// (`embedding.projection` in network.json and --json reports them and
    /// the largest |f|/|grad f| before and after).
    #[arg(long, conflicts_with_all = ["stream", "no_certify", "adaptive"])]
    project: bool,
    #[command(flatten)]
    adaptive: crate::adaptive::AdaptiveArgs,
}

/// The job the arguments describe (the library's one reader of inputs).
fn job(args: &Args) -> Result<Job, Box<dyn std::error::Error>> {
    let over = GridOverride {
        resolution: args.grid,
        bounds: args.bounds.as_ref().map(|b| [[b[0], b[1], b[2]], [b[3], b[4], b[5]]]),
        split: args.split.map(Split::try_from).transpose().map_err(|e| format!("--split: {e}"))?,
        mesh: args.mesh.clone(),
    };
    Ok(Job::load(&args.input.display().to_string(), &over)?)
}

/// Runs `septa ia|mi`.
pub fn run(args: Args, mode: Mode) -> CliResult {
    let t0 = Instant::now();
    let mode = match mode {
        Mode::Ia => septa::complex::Mode::Ia,
        Mode::Mi => septa::complex::Mode::Mi,
    };
    let mut opts = NetworkOptions::new(mode);
    opts.float = args.float;
    opts.lookup = !args.no_lookup;
    opts.block = args.block;
    opts.raytrace = matches!(args.cells, CellMethod::Raytrace);
    let bar = crate::progress::bar(args.out.json || args.out.quiet, "blocks");
    if let Some(bar) = &bar {
        let bar = bar.clone();
        opts.progress = Some(septa::Progress(std::sync::Arc::new(move |done, total| {
            crate::progress::blocks_then(&bar, done, total, "topology: patches, chains, corners, cells")
        })));
    }
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(t) = args.out.threads {
        pool = pool.num_threads(t.max(1));
    }
    let pool = pool.build()?;
    if let Some(out) = &args.stream {
        if args.out.remesh.is_some() {
            return Err("--remesh: not with --stream (remeshing needs the whole network in memory)".into());
        }
        return run_stream(&args, out, mode, &opts, &pool, bar, t0);
    }
    // Sparse by default where it applies (formulas on a box grid); the
    // output is identical on both paths.
    let mut job = job(&args)?;
    let t_read = t0.elapsed().as_secs_f64();
    let refined = match args.adaptive.adaptive {
        true => Some(
            pool.install(|| crate::adaptive::apply(&args.adaptive, &mut job, mode, args.out.json || args.out.quiet))?,
        ),
        false => None,
    };
    let (mut net, stats) = pool.install(|| job.run(&opts, args.dense || refined.is_some()))?;
    let tets = job.grid.num_tets();
    if !args.out.no_certify {
        let grid = match &job.grid {
            septa::grid::Grid::Box(b) => Some(b),
            septa::grid::Grid::Mesh(_) => None,
        };
        match (grid, &job.functions) {
            (Some(g), septa::job::Functions::Formulas(fs)) if args.project => {
                pool.install(|| septa::mesh::certify_network_on(&mut net, g, fs));
            }
            _ if args.project => {
                return Err(format!("--project: {} is not formulas on a box grid", args.input.display()).into())
            }
            _ => {
                pool.install(|| septa::mesh::certify_network(&mut net, grid));
            }
        }
    }
    let remeshed = match args.out.remesh {
        Some(l) => {
            let bounds = match &job.grid {
                septa::grid::Grid::Box(b) => Some(b.bounds),
                septa::grid::Grid::Mesh(_) => None,
            };
            let o = septa::mesh::RemeshOptions::new(l);
            // formulas on a box grid: new vertices on their true zero sets
            match (&job.functions, bounds) {
                (septa::job::Functions::Formulas(fs), Some(_)) => {
                    Some(pool.install(|| septa::mesh::remesh_network_on(&mut net, &o, bounds, fs))?)
                }
                _ => Some(pool.install(|| septa::mesh::remesh_network(&mut net, &o, bounds))?),
            }
        }
        None => None,
    };
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    let mut extra = vec![("read", t_read)];
    if let Some(r) = &refined {
        extra.push(("adaptive", r.seconds));
    }
    let t = Instant::now();
    let notes = Annotations::of_job(&job, &net);
    extra.push(("measure", t.elapsed().as_secs_f64()));
    if !args.no_output {
        let t = Instant::now();
        let quiet = args.out.json || args.out.quiet;
        let files = refined.as_ref().map(|r| r.files());
        let extra_files: Vec<septa::io::ExtraFile> = match &files {
            Some((vtu, json)) => vec![("grid.vtu", vtu.as_slice()), ("adaptive.json", json.as_slice())],
            None => vec![],
        };
        crate::progress::during(quiet, &format!("writing {}", args.out.output.display()), || {
            write_network_formats_with(&net, &notes, &args.out.output, &args.out.format.0, &extra, &extra_files)
        })?;
        extra.push(("write", t.elapsed().as_secs_f64()));
    }
    let cells_method = net.cells_method;
    if args.out.json {
        let mut obj = serde_json::Map::new();
        for (k, v) in net.counts() {
            obj.insert(k.into(), v.into());
        }
        obj.insert("tets".into(), tets.into());
        if let Some(s) = stats {
            obj.insert("blocks".into(), sparse_json(&s));
        }
        obj.insert("cells_method".into(), cells_method.as_str().into());
        if let Some(r) = &refined {
            obj.insert("adaptive".into(), r.json());
        }
        obj.insert("measures".into(), notes.measures.to_json());
        if !notes.names.is_empty() {
            obj.insert("names".into(), notes.names.to_json());
        }
        if let Some(e) = &net.embedding {
            obj.insert("embedding".into(), serde_json::to_value(e)?);
        }
        if let Some(r) = &remeshed {
            obj.insert("remesh".into(), serde_json::to_value(r)?);
        }
        let mut secs = serde_json::Map::new();
        for (k, v) in net.seconds.iter().chain(extra.iter()) {
            secs.insert((*k).into(), (*v).into());
        }
        secs.insert("total".into(), t0.elapsed().as_secs_f64().into());
        obj.insert("seconds".into(), secs.into());
        println!("{}", serde_json::Value::Object(obj));
    } else if args.out.talk() {
        let counts: Vec<String> = net.counts().iter().map(|(k, v)| format!("{k} {v}")).collect();
        println!("{}", counts.join(", "));
        print!("{}", crate::summary::network_text(&net, &notes));
        if let Some(r) = &refined {
            print!("{}", r.text());
        }
        args.out.tell_embedding(net.embedding.as_ref());
        args.out.tell_solids();
        args.out.tell_remesh(remeshed.as_ref());
        if let Some(s) = stats {
            println!("blocks: {}", sparse_json(&s));
        }
        println!("{:.3} s", t0.elapsed().as_secs_f64());
    }
    Ok(())
}

/// `septa ia|mi --stream OUT.ply|OUT.vtu`: polygons streamed to one file and the
/// topology assembled from block summaries (bounded memory).
fn run_stream(
    args: &Args,
    out: &std::path::Path,
    mode: septa::complex::Mode,
    opts: &NetworkOptions,
    pool: &rayon::ThreadPool,
    bar: Option<indicatif::ProgressBar>,
    t0: Instant,
) -> CliResult {
    let job = job(args)?;
    let (g, funcs) = job.box_formulas().ok_or_else(|| {
        format!("--stream: {} is not formulas on a box grid (a function list, config or scene)", args.input.display())
    })?;
    let t_read = t0.elapsed().as_secs_f64();
    // The stream's folder is made as `-o` folders are.
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("--stream: cannot create the folder {}: {e}", dir.display()))?;
    }
    // before the run: neither output may replace a link, FIFO or device
    septa::io::check_output_file(&topology_path(out))?;
    let mut sink = septa::io::StreamFile::create(out, &g, mode, funcs.len(), args.triangles)?;
    let (stats, topology) = if args.polygons_only {
        (pool.install(|| network::stream_sparse(g, funcs, opts, args.window, &mut sink))?, None)
    } else {
        let (s, t) = pool.install(|| network::stream_topology(g, funcs, opts, args.window, &mut sink))?;
        (s, Some(t))
    };
    let t_blocks = t0.elapsed().as_secs_f64() - t_read;
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    let ply = sink.finish_with(topology.as_ref())?;
    let t_ply = t0.elapsed().as_secs_f64() - t_read - t_blocks;
    let topo_path = topology_path(out);
    if let Some(t) = &topology {
        let secs = [("read", t_read), ("blocks", t_blocks), ("ply", t_ply)];
        septa::io::write_summary_json(t, &topo_path, &secs)?;
    }
    let sparse = network::SparseStats {
        blocks: stats.blocks,
        skipped: stats.skipped,
        sampled: stats.sampled,
        active: stats.active,
        sampled_vertices: stats.sampled_vertices,
        dense_fallback: false,
    };
    let total = t0.elapsed().as_secs_f64();
    let mut summary = serde_json::json!({
        "stream": out.display().to_string(),
        "faces": ply.polygons,
        "ply_faces": ply.faces,
        "vertices": ply.vertices,
        "active_tets": stats.active_tets,
        "tets": g.num_tets(),
        "window": stats.window,
        "peak_shared_keys": stats.peak_shared_keys,
        "blocks": sparse_json(&sparse),
        "seconds": {"read": t_read, "blocks": t_blocks, "ply": t_ply, "total": total},
    });
    if let Some(t) = &topology {
        let counts: serde_json::Map<String, serde_json::Value> =
            t.counts().into_iter().map(|(k, v)| (k.to_string(), v.into())).collect();
        summary["counts"] = counts.into();
        summary["topology"] = topo_path.display().to_string().into();
        summary["peak_open"] = stats.peak_open.into();
        summary["reruns"] = stats.reruns.into();
    }
    if args.out.json {
        println!("{summary}");
    } else if args.out.talk() {
        println!(
            "{}: {} faces ({} written), {} vertices (streamed)",
            out.display(),
            ply.polygons,
            ply.faces,
            ply.vertices
        );
        if let Some(t) = &topology {
            let counts: Vec<String> = t.counts().iter().map(|(k, v)| format!("{k} {v}")).collect();
            println!("{}: {}", topo_path.display(), counts.join(", "));
        }
        println!("blocks: {}", sparse_json(&sparse));
        println!("{total:.3} s");
    }
    Ok(())
}

/// `OUT.topology.json` beside the streamed `OUT.ply` or `OUT.vtu`.
fn topology_path(out: &std::path::Path) -> std::path::PathBuf {
    out.with_extension("topology.json")
}

/// `"blocks"` of the JSON summary of a sparse run.
pub fn sparse_json(s: &network::SparseStats) -> serde_json::Value {
    serde_json::json!({
        "total": s.blocks,
        "skipped": s.skipped,
        "sampled": s.sampled,
        "active": s.active,
        "sampled_vertices": s.sampled_vertices,
        "dense_fallback": s.dense_fallback,
    })
}
