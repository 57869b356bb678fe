//! `septa ia` and `septa mi`: the surface network of functions on a tet grid.
use std::path::PathBuf;
use std::time::Instant;

use septa::grid::{BoxGrid, Grid, Split, TetMesh};
use septa::io::{functions, network_out, npz};
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
    #[arg(long)]
    grid: Option<usize>,
    /// Tet mesh (Gmsh .msh 2.2/4.1, or a JSON `[vertices, tets]`) for a function JSON input.
    #[arg(long)]
    mesh: Option<PathBuf>,
    /// Box grid bounds: xmin ymin zmin xmax ymax zmax.
    #[arg(long, num_args = 6, allow_negative_numbers = true)]
    bounds: Option<Vec<f64>>,
    /// Tets per cube of a built-in grid (5 or 6).
    #[arg(long, default_value_t = 5)]
    split: u8,
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
    #[arg(long, default_value_t = 16)]
    block: usize,
    /// Sample every grid vertex (the dense path). By default, analytic
    /// functions on a box grid (a function JSON, reference config or scene)
    /// are evaluated sparsely: blocks the functions' bounds prove empty are
    /// skipped, the rest sampled block by block; the output is identical
    /// (the bounds enclose the rounded samples; docs/sparse.md).
    #[arg(long, conflicts_with = "sparse")]
    dense: bool,
    /// Accepted for compatibility: sparse evaluation is the default
    /// wherever it applies (no effect on `.npz` input or a tet mesh).
    #[arg(long)]
    sparse: bool,
    /// Stream the polygons to this binary PLY block by block, with memory
    /// bounded by a window of blocks (analytic functions on a box grid), and
    /// assemble the topology (patches, chains, corners, shells, cells) from
    /// block summaries on the way: faces carry `labels_0`, `labels_1`, `block`,
    /// `patch`, `cells_0`, `cells_1`; the topology goes to `OUT.topology.json`
    /// beside the PLY. Vertices are written once.
    #[arg(long, conflicts_with_all = ["dense", "no_output"])]
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
}

/// Whether the input is analytic functions on a box grid (sparse
/// evaluation applies): not sampled values (`.npz`), not a tet mesh (given
/// by `--mesh` or a reference config's `tetMeshFile`).
fn sparse_applies(args: &Args) -> bool {
    if args.mesh.is_some() || args.input.extension().and_then(|e| e.to_str()) == Some("npz") {
        return false;
    }
    let name = args.input.display().to_string();
    if name.starts_with("builtin:") {
        return true;
    }
    let Ok(text) = std::fs::read_to_string(&args.input) else { return false };
    match input_value(&text, &args.input) {
        Ok(json) => json.get("tetMeshFile").is_none(),
        Err(_) => false,
    }
}

/// Runs `septa ia|mi`.
pub fn run(args: Args, mode: Mode) -> CliResult {
    let t0 = Instant::now();
    let mode = match mode {
        Mode::Ia => network::Mode::Ia,
        Mode::Mi => network::Mode::Mi,
    };
    let mut opts = NetworkOptions::new(mode);
    opts.float = args.float;
    opts.lookup = !args.no_lookup;
    opts.block = args.block;
    opts.raytrace = matches!(args.cells, CellMethod::Raytrace);
    let bar = crate::progress::bar(args.out.json || args.out.quiet, "blocks");
    if let Some(bar) = &bar {
        let bar = bar.clone();
        opts.progress = Some(network::Progress(std::sync::Arc::new(move |done, total| {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
        })));
    }
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(t) = args.out.threads {
        pool = pool.num_threads(t.max(1));
    }
    let pool = pool.build()?;
    if let Some(out) = &args.stream {
        return run_stream(&args, out, mode, &opts, &pool, bar, t0);
    }
    // Sparse by default where it applies. Should the scene reader reject a
    // function file the reference reader accepts, the dense path reads it
    // (and reports its own error if it is bad).
    let sparse_input = if !args.dense && sparse_applies(&args) {
        match load_sparse(&args) {
            Ok(x) => Some(x),
            Err(e) if args.sparse => return Err(e),
            Err(_) => None,
        }
    } else {
        None
    };
    let (net, tets, t_read, stats) = if let Some((g, funcs)) = sparse_input {
        let t_read = t0.elapsed().as_secs_f64();
        let (net, stats) = pool.install(|| network::compute_sparse(&g, &funcs, &opts))?;
        (net, g.num_tets(), t_read, Some(stats))
    } else {
        let (grid, values, k) = load(&args)?;
        let t_read = t0.elapsed().as_secs_f64();
        (pool.install(|| network::compute(&grid, &values, k, &opts))?, grid.num_tets(), t_read, None)
    };
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    let mut extra = vec![("read", t_read)];
    if !args.no_output {
        let t = Instant::now();
        let quiet = args.out.json || args.out.quiet;
        crate::progress::during(quiet, &format!("writing {}", args.out.output.display()), || {
            network_out::write_formats(&net, &args.out.output, &args.out.format.0, &extra)
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
        obj.insert("cells_method".into(), cells_method.into());
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
        if let Some(s) = stats {
            println!("blocks: {}", sparse_json(&s));
        }
        println!("{:.3} s", t0.elapsed().as_secs_f64());
    }
    Ok(())
}

/// `septa ia|mi --stream OUT.ply`: polygons streamed to one PLY and the
/// topology assembled from block summaries (bounded memory).
fn run_stream(
    args: &Args,
    out: &std::path::Path,
    mode: network::Mode,
    opts: &NetworkOptions,
    pool: &rayon::ThreadPool,
    bar: Option<indicatif::ProgressBar>,
    t0: Instant,
) -> CliResult {
    let (g, funcs) = load_sparse(args).map_err(|e| format!("--stream: {e}"))?;
    let t_read = t0.elapsed().as_secs_f64();
    let mut sink =
        septa::io::ply_stream::PlyStreamSink::create(out, &g, mode, funcs.len())?.triangulated(args.triangles);
    let (stats, topology) = if args.polygons_only {
        (pool.install(|| network::stream_sparse(&g, &funcs, opts, args.window, &mut sink))?, None)
    } else {
        let (s, t) = pool.install(|| network::stream_topology(&g, &funcs, opts, args.window, &mut sink))?;
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
        septa::io::summary_out::write_summary_json(t, &topo_path, &secs)?;
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

/// `OUT.topology.json` beside the streamed `OUT.ply`.
fn topology_path(out: &std::path::Path) -> std::path::PathBuf {
    out.with_extension("topology.json")
}

/// The input file's value tree: JSON, or a TOML scene (`.toml`) read into
/// the same tree (the scene itself is parsed again by `Scene::load`, whose
/// errors name TOML lines).
fn input_value(text: &str, path: &std::path::Path) -> Result<serde_json::Value, String> {
    if path.extension().and_then(|e| e.to_str()) == Some("toml") {
        let v: toml::Value = toml::from_str(text).map_err(|e| format!("{}: not TOML: {e}", path.display()))?;
        return serde_json::to_value(v).map_err(|e| format!("{}: {e}", path.display()));
    }
    serde_json::from_str(text).map_err(|e| format!("{}: not JSON: {e}", path.display()))
}

fn split(args: &Args) -> Result<Split, String> {
    match args.split {
        5 => Ok(Split::Five),
        6 => Ok(Split::Six),
        s => Err(format!("--split must be 5 or 6, not {s}")),
    }
}

/// Reads the grid and values.
fn load(args: &Args) -> Result<(Grid, Vec<f64>, usize), Box<dyn std::error::Error>> {
    let ext = args.input.extension().and_then(|e| e.to_str()).unwrap_or("");
    if ext == "npz" {
        let input = npz::read_grid_input(&args.input)?;
        // A reference-style box grid is used implicitly when it matches the stored tets.
        if let (Some(r), Some(bbox)) = (input.grid_res, input.bbox) {
            if let Ok(g) = BoxGrid::new([r; 3], bbox, Split::Five) {
                let grid = Grid::Box(g);
                let same = grid.num_tets() == input.tets.len()
                    && grid.num_vertices() == input.vertices.len()
                    && input.tets.iter().enumerate().all(|(t, tet)| grid.tet(t).map(|v| v as i64) == *tet);
                if same {
                    return Ok((grid, input.values, input.k));
                }
            }
        }
        let mesh = TetMesh::new(input.vertices, &input.tets).map_err(|e| format!("{}: {e}", args.input.display()))?;
        return Ok((Grid::Mesh(mesh), input.values, input.k));
    }
    // A reference config JSON ({"funcFile", "tetMeshFile" | "gridResolution", "gridBbox"})
    // or a function list.
    let text = std::fs::read_to_string(&args.input).map_err(|e| format!("{}: {e}", args.input.display()))?;
    let json: serde_json::Value = input_value(&text, &args.input)?;
    if json.get("functions").is_some() {
        // A scene (JSON or TOML) on the dense path: its functions sampled at every vertex.
        let (g, funcs) = load_sparse(args)?;
        let grid = Grid::Box(g);
        let values = septa::scene::sample_grid(&funcs, &grid.vertices());
        return Ok((grid, values, funcs.len()));
    }
    let (funcs, mesh, grid_res, bounds) = if let Some(cfg) = json.as_object() {
        let dir = args.input.parent().unwrap_or(std::path::Path::new("."));
        let file = cfg
            .get("funcFile")
            .and_then(|v| v.as_str())
            .ok_or_else(|| format!("{}: config has no \"funcFile\"", args.input.display()))?;
        let funcs = functions::read_functions(&dir.join(file))?;
        let mesh = cfg.get("tetMeshFile").and_then(|v| v.as_str()).map(|m| dir.join(m));
        let res = cfg.get("gridResolution").and_then(|v| v.as_u64()).map(|r| r as usize);
        let bounds = cfg.get("gridBbox").and_then(|b| {
            let b: Vec<f64> = b
                .as_array()?
                .iter()
                .flat_map(|p| p.as_array().cloned().unwrap_or_default())
                .filter_map(|x| x.as_f64())
                .collect();
            (b.len() == 6).then_some(b)
        });
        (funcs, mesh.or(args.mesh.clone()), res.or(args.grid), bounds.or(args.bounds.clone()))
    } else {
        let funcs = functions::parse_functions(&text, &args.input.display().to_string())?;
        (funcs, args.mesh.clone(), args.grid, args.bounds.clone())
    };
    if let Some(mesh) = mesh {
        let ext = mesh.extension().and_then(|e| e.to_str()).unwrap_or("");
        let (vertices, tets) =
            if ext == "msh" { septa::io::msh::read_msh(&mesh)? } else { functions::read_tet_mesh_json(&mesh)? };
        let mesh = TetMesh::new(vertices, &tets).map_err(|e| format!("{}: {e}", mesh.display()))?;
        let values = functions::sample(&funcs, &mesh.vertices);
        return Ok((Grid::Mesh(mesh), values, funcs.len()));
    }
    let n = grid_res.ok_or("a function JSON input needs --grid N (and optionally --bounds) or --mesh FILE")?;
    let b = bounds.unwrap_or_else(|| vec![-1.0, -1.0, -1.0, 1.0, 1.0, 1.0]);
    let g = BoxGrid::new([n; 3], [[b[0], b[1], b[2]], [b[3], b[4], b[5]]], split(args)?)?;
    let grid = Grid::Box(g);
    let values = functions::sample_grid(&funcs, &grid);
    Ok((grid, values, funcs.len()))
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

/// Reads a box grid and analytic functions for sparse evaluation: a function
/// list sampled on `--grid`, or a reference config / scene file (its grid).
fn load_sparse(args: &Args) -> Result<(BoxGrid, Vec<septa::scene::Primitive>), Box<dyn std::error::Error>> {
    let name = args.input.display().to_string();
    if args.mesh.is_some() || args.input.extension().and_then(|e| e.to_str()) == Some("npz") {
        return Err(format!("{name}: sparse evaluation needs analytic functions on a box grid (a function JSON, config or scene), not sampled values or a tet mesh").into());
    }
    if name.starts_with("builtin:") {
        let scene = septa::scene::Scene::load(&name)?;
        let split = if scene.grid.split == 6 { Split::Six } else { Split::Five };
        return Ok((BoxGrid::new(scene.grid.resolution, scene.grid.bounds, split)?, scene.functions));
    }
    let text = std::fs::read_to_string(&args.input).map_err(|e| format!("{name}: {e}"))?;
    let json: serde_json::Value = input_value(&text, &args.input)?;
    if json.is_object() && json.get("input").is_none() {
        let scene = septa::scene::Scene::load(&name)?;
        // A reference config has no split: `--split`, as on the dense path.
        let split = match json.get("grid") {
            Some(_) if scene.grid.split == 6 => Split::Six,
            Some(_) => Split::Five,
            None => split(args)?,
        };
        let mut res = scene.grid.resolution;
        let mut bounds = scene.grid.bounds;
        if json.get("gridResolution").is_none() && json.get("grid").is_none() {
            if let Some(n) = args.grid {
                res = [n; 3];
            }
        }
        if json.get("gridBbox").is_none() && json.get("grid").is_none() {
            if let Some(b) = &args.bounds {
                bounds = [[b[0], b[1], b[2]], [b[3], b[4], b[5]]];
            }
        }
        return Ok((BoxGrid::new(res, bounds, split)?, scene.functions));
    }
    let funcs = septa::scene::load_function_list(&text, &name, args.input.parent())?;
    let n = args.grid.ok_or("a function JSON input needs --grid N (and optionally --bounds)")?;
    let b = args.bounds.clone().unwrap_or_else(|| vec![-1.0, -1.0, -1.0, 1.0, 1.0, 1.0]);
    let g = BoxGrid::new([n; 3], [[b[0], b[1], b[2]], [b[3], b[4], b[5]]], split(args)?)?;
    Ok((g, funcs))
}
