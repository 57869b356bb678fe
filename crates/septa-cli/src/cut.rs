//! `septa cut MESH (--grid N [NY NZ] | --random N --seed S | --planes FILE) -o OUTDIR`:
//! cuts the domain of a closed triangle mesh by planes into cut-cells
//! (TopoCut) and writes `cells.vtu`, `cells.obj` (`--format`: also an
//! OpenFOAM `constant/polyMesh`) and `cut.json`.
use crate::CliResult;
use septa::cut::{cut_mesh, CutOptions};
use septa::io::{cut_cells_obj_of, cut_cells_vtu_of, grid_planes_xyz, random_planes, read_mesh, read_planes};
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `septa cut`.
#[derive(clap::Args)]
pub struct Args {
    /// Closed, outward-oriented triangle mesh (.obj, .off, .ply, .stl).
    pub mesh: PathBuf,
    /// Axis-aligned planes across the mesh's bounding box: N per axis, or
    /// NX NY NZ (TopoCut's `plane -s bound_box_xyz --nx --ny --nz`). On each
    /// axis the first and last planes lie on the box's faces and the others
    /// are evenly spaced between (N planes, N-1 slabs); a count of 1 puts one
    /// plane through the box's middle. Give the mesh before --grid.
    #[arg(long, num_args = 1..=3, value_name = "N", conflicts_with_all = ["random", "planes"], value_parser = crate::args::planes)]
    pub grid: Option<Vec<usize>>,
    /// N random planes, each through a random point of the bounding box's
    /// diagonal (the same planes for the same --seed).
    #[arg(long, conflicts_with = "planes", value_parser = crate::args::planes)]
    pub random: Option<usize>,
    /// Seed of --random.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Plane file: one plane `a b c d` (a x + b y + c z + d = 0) per line; a
    /// first line `N 4` (the number of planes) is allowed.
    #[arg(long)]
    pub planes: Option<PathBuf>,
    /// Output folder (cells.vtu, cells.obj, cut.json; default septa-out; not
    /// needed to --verify a .vtu).
    #[arg(short = 'o', long = "output", visible_alias = "out")]
    pub out: Option<PathBuf>,
    /// Worker threads (default: all cores; 0 also means all cores).
    #[arg(long, default_value_t = 0, value_parser = crate::args::threads_or_all)]
    pub threads: usize,
    /// Print one JSON object with counts, checks and timings.
    #[arg(long)]
    pub json: bool,
    /// Print nothing but errors (and the `--json` object if asked for).
    #[arg(short, long)]
    pub quiet: bool,
    /// Mesh files to write, comma-separated: vtu (cells.vtu), obj
    /// (cells.obj), foam (OpenFOAM constant/polyMesh: points, faces, owner,
    /// neighbour, boundary with the patch `surface`, faceZones per plane
    /// family), or all.
    #[arg(long, default_value = "vtu,obj", value_parser = parse_formats)]
    pub format: MeshFormats,
    /// Skip writing the mesh files (cut.json is always written).
    #[arg(long)]
    pub no_mesh_output: bool,
    /// Skip the exact self-intersection test of the input mesh.
    #[arg(long)]
    pub no_self_check: bool,
    /// Skip the exact check and repair of the written embedding (faster;
    /// cells.vtu then carries no guarantee beyond the exact combinatorics).
    #[arg(long)]
    pub no_certify: bool,
    /// Write every face as triangles (no new vertices) in cells.vtu,
    /// cells.obj and the OpenFOAM mesh (TopoCut's --is-triangulate). Faces
    /// with holes are always written as triangles.
    #[arg(long)]
    pub triangulate: bool,
    /// Name a boundary patch of the OpenFOAM mesh by a side of the input's
    /// bounding box: NAME=SIDE, SIDE one of xmin xmax ymin ymax zmin zmax
    /// (e.g. --patch inlet=xmin --patch outlet=xmax). The faces on input
    /// triangles lying in that side (all three corners exactly on it) form
    /// a `patch` NAME; the rest of the input surface stays the wall `surface`.
    #[arg(long = "patch", value_name = "NAME=SIDE", value_parser = parse_patch)]
    pub patches: Vec<(String, septa::io::BoxSide)>,
    /// Report OpenFOAM checkMesh's quantities for the polyMesh (computed as
    /// checkMesh computes them: cell volumes, face areas, non-orthogonality,
    /// skewness, face pyramids, volume ratio, and the checks checkMesh would
    /// fail); printed, and in cut.json as `check_mesh`.
    #[arg(long)]
    pub check_mesh: bool,
    /// Exploded view factor for cells.obj.
    #[arg(long, default_value_t = 0.0, value_parser = crate::args::finite_nonneg)]
    pub explode: f64,
    /// Prove the written embedding exactly (closed, consistently oriented,
    /// planar-faced, non-self-intersecting cells of positive volume on the
    /// written doubles; `verify` in cut.json); fails if anything is violated.
    /// With a `.vtu` as MESH: check that file's polyhedra instead of cutting.
    #[arg(long)]
    pub verify: bool,
    /// Also write `vertices_exact.json`: each cut-vertex's defining triple
    /// of input elements (mesh vertex, mesh edge and plane, triangle and two
    /// planes, or three planes) and its exact rational coordinates
    /// (`"numerator/denominator"` strings).
    #[arg(long)]
    pub exact_vertices: bool,
}

/// A mesh file `septa cut` writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    /// cells.vtu
    Vtu,
    /// cells.obj
    Obj,
    /// constant/polyMesh
    Foam,
}

/// The parsed `--format` list.
#[derive(Clone, Debug)]
pub struct MeshFormats(pub Vec<MeshFormat>);

impl Default for MeshFormats {
    fn default() -> Self {
        MeshFormats(vec![MeshFormat::Vtu, MeshFormat::Obj])
    }
}

fn parse_formats(s: &str) -> Result<MeshFormats, String> {
    let mut out = Vec::new();
    for w in s.split(',').map(str::trim) {
        let f: &[MeshFormat] = match w {
            "vtu" => &[MeshFormat::Vtu],
            "obj" => &[MeshFormat::Obj],
            "foam" => &[MeshFormat::Foam],
            "all" => &[MeshFormat::Vtu, MeshFormat::Obj, MeshFormat::Foam],
            _ => return Err(format!("unknown format '{w}': expected vtu, obj, foam or all")),
        };
        for f in f {
            if !out.contains(f) {
                out.push(*f);
            }
        }
    }
    Ok(MeshFormats(out))
}

fn parse_patch(s: &str) -> Result<(String, septa::io::BoxSide), String> {
    let (name, side) = s.split_once('=').ok_or_else(|| format!("'{s}': expected NAME=SIDE, e.g. inlet=xmin"))?;
    let side = septa::io::parse_box_side(side)
        .ok_or_else(|| format!("'{side}' is not a side: expected xmin, xmax, ymin, ymax, zmin or zmax"))?;
    Ok((name.to_string(), side))
}

/// `septa cut FILE.vtu --verify`: the exact check of a written polyhedral mesh.
fn verify_file(a: &Args) -> CliResult {
    let (points, cells) = septa::io::read_polyhedra(&a.mesh)?;
    let r = septa::cut::verify_cells(&points, &cells);
    let j = serde_json::json!({ "file": a.mesh.display().to_string(), "violations": r.violations(), "verify": r });
    if a.json {
        println!("{j}");
    } else if !a.quiet {
        println!(
            "{}: {} cells, {} faces, {} triangles checked exactly: {} violations",
            a.mesh.display(),
            r.cells,
            r.faces,
            r.triangles,
            r.violations()
        );
        for e in &r.examples {
            println!("  {e}");
        }
    }
    if r.violations() > 0 {
        return Err(format!("{}: {} violations of the exact check", a.mesh.display(), r.violations()).into());
    }
    Ok(())
}

/// Runs `septa cut`.
pub fn run(a: Args) -> CliResult {
    if a.verify && a.mesh.extension().is_some_and(|e| e.eq_ignore_ascii_case("vtu")) {
        return verify_file(&a);
    }
    let out_dir = a.out.clone().unwrap_or_else(|| PathBuf::from("septa-out"));
    // The cut's stages build and drop arrays of megabytes (vertex triples,
    // face loops, pairs of the checks): reusing freed heap instead of fresh
    // zeroed mappings took the system time of nefertiti R20 from about 15%
    // of the process to a few percent (docs/performance.md).
    crate::labels::keep_freed_memory();
    let t0 = Instant::now();
    let mesh = read_mesh(&a.mesh)?;
    let planes = match (&a.grid, a.random, &a.planes) {
        (Some(n), _, _) => match n[..] {
            [n] => grid_planes_xyz(&mesh.vertices, [n; 3]),
            [nx, ny, nz] => grid_planes_xyz(&mesh.vertices, [nx, ny, nz]),
            _ => return Err(format!("--grid takes one count or three (NX NY NZ), not {}", n.len()).into()),
        },
        (_, Some(n), _) => random_planes(&mesh.vertices, n, a.seed),
        (_, _, Some(f)) => read_planes(f)?,
        _ => return Err("give one of --grid N, --random N, --planes FILE".into()),
    };
    // named patches checked before any work
    let patches = septa::io::BoundaryPatches::by_side(&mesh.vertices, &mesh.triangles, &a.patches)?;
    let read_s = t0.elapsed().as_secs_f64();
    // With the global pool sized here, the cut runs in it (threads 0 below)
    // instead of starting a second pool of the same size. This thread is one
    // of the pool's: each parallel stage of the cut used to be handed from
    // here to a worker and back, and between stages the idle worker spun
    // (yields before sleeping) while this thread did the serial ones, about
    // 1-4 ms of CPU on a 20-90 ms cut (docs/history/performance-log.md, "Thirteenth
    // round"). With `--threads 1` there is now no other thread at all.
    // (`num_threads(0)` is rayon's default: all cores.)
    let global = rayon::ThreadPoolBuilder::new().num_threads(a.threads).use_current_thread().build_global().is_ok();
    let t1 = Instant::now();
    // A bar over the cut's stages (on a terminal only), moved by the library.
    let bar = crate::progress::bar(a.json || a.quiet, "cut stages");
    let progress = bar.clone().map(|b| {
        b.enable_steady_tick(std::time::Duration::from_millis(1000));
        septa::Progress(std::sync::Arc::new(move |done, total| {
            b.set_length(total as u64);
            b.set_position(done as u64);
        }))
    });
    let options = CutOptions {
        threads: if global { 0 } else { a.threads },
        skip_self_intersection_check: a.no_self_check,
        skip_certify: a.no_certify,
        progress,
    };
    let out = cut_mesh(&mesh.vertices, &mesh.triangles, &planes, &options);
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let out = out.map_err(|e| format!("{}: {e}", a.mesh.display()))?;
    let cut_s = t1.elapsed().as_secs_f64();
    for (d, k) in &out.stats.dropped_planes {
        eprintln!("warning: plane {d} duplicates plane {k}; dropped");
    }
    let check = crate::progress::during(a.json || a.quiet, "checking the cells", || out.validate());
    // how faces are written: after the checks, which count the cut-faces
    let mut out = out;
    if a.triangulate {
        out.triangulate_all();
    }
    let t2 = Instant::now();
    let writing = crate::progress::stage(a.json || a.quiet, &format!("writing {}", out_dir.display()));
    // One set: lock, stale temporaries removed, manifest last (io::outdir).
    let mut dir = septa::io::OutputDir::create(&out_dir, "cut")?;
    let wants = |f: MeshFormat| !a.no_mesh_output && a.format.0.contains(&f);
    // the cells' polygons formed once for both files
    let polys =
        if wants(MeshFormat::Vtu) || wants(MeshFormat::Obj) { out.cell_polygons_flat() } else { Default::default() };
    if wants(MeshFormat::Vtu) {
        dir.write("cells.vtu", cut_cells_vtu_of(&out, &polys).as_bytes())?;
    }
    if wants(MeshFormat::Obj) {
        dir.write("cells.obj", cut_cells_obj_of(&out, &polys, a.explode).as_bytes())?;
    }
    let mut foam_swapped = None;
    let mut check_mesh = None;
    if wants(MeshFormat::Foam) || a.check_mesh {
        let pm = septa::io::poly_mesh_patched(&out, &patches);
        if wants(MeshFormat::Foam) {
            for (name, text) in pm.files() {
                dir.write(&format!("constant/polyMesh/{name}"), text.as_bytes())?;
            }
            foam_swapped = Some(pm.swapped);
        }
        if a.check_mesh {
            check_mesh = Some((septa::io::check_poly_mesh(&pm), pm.patches.clone()));
        }
    }
    if a.exact_vertices {
        let defs: Vec<String> = out.vertex_defs.iter().map(|d| format!("{d:?}")).collect();
        let exact = septa::cut::exact_coordinates(&mesh.vertices, &mesh.triangles, &out.planes, &out.vertex_defs)?;
        let coords: Vec<[String; 3]> = exact.iter().map(|p| p.each_ref().map(septa::cut::fraction_string)).collect();
        let j = serde_json::json!({
            "about": "cut-vertex i of cells.vtu is defined by defs[i]: V(v) mesh vertex v; EP(e, p) mesh edge e (edges[e] = [u, v]) and plane p; TPP(t, p, q) triangle t and planes p, q; PPP(p, q, r) three planes. Planes index `planes` (a x + b y + c z + d = 0, the doubles used). coordinates[i] is its exact position, the rational intersection of these input elements: x, y, z as reduced fractions \"numerator/denominator\" (or an integer). Points of cells.vtu after the cut-vertices are face centres added by the certified embedding (not cut-vertices).",
            "defs": defs,
            "coordinates": coords,
            "planes": out.planes,
        });
        dir.write("vertices_exact.json", serde_json::to_string(&j)?.as_bytes())?;
    }
    // --verify: the exact check of the file as written (read back), else of
    // the polygons in memory
    let verify = if !a.verify {
        None
    } else if !wants(MeshFormat::Vtu) {
        Some(out.verify())
    } else {
        // errors name cells.vtu, the file the user will look at, not its staged name
        let staged = dir.staged_path("cells.vtu");
        let (points, cells) = septa::io::read_polyhedra(&staged).map_err(|e| {
            e.replace(&staged.display().to_string(), &dir.path().join("cells.vtu").display().to_string())
        })?;
        Some(septa::cut::verify_cells(&points, &cells))
    };
    let write_s = t2.elapsed().as_secs_f64();
    if let Some(bar) = writing {
        bar.finish_and_clear();
    }
    let c = out.counts;
    let mut seconds = serde_json::Map::new();
    seconds.insert("read".into(), read_s.into());
    for (k, v) in &out.stats.seconds {
        seconds.insert(k.clone(), (*v).into());
    }
    seconds.insert("cut".into(), cut_s.into());
    seconds.insert("write".into(), write_s.into());
    seconds.insert("total".into(), t0.elapsed().as_secs_f64().into());
    let (euler, vol_err, min_vol, check_msg) = match &check {
        Ok(v) => (v.euler, v.volume_relative_error, v.min_cell_volume, "ok".to_string()),
        Err(e) => (
            c.cut_vertices as i64 - c.cut_edges as i64 + c.cut_faces as i64 - c.cut_cells as i64,
            f64::NAN,
            f64::NAN,
            e.to_string(),
        ),
    };
    let j = serde_json::json!({
        "mesh": a.mesh.display().to_string(),
        "triangles": mesh.triangles.len(),
        "planes": planes.len(),
        "cut_vertices": c.cut_vertices,
        "cut_edges": c.cut_edges,
        "cut_faces": c.cut_faces,
        "cut_cells": c.cut_cells,
        "euler": euler,
        "volume_relative_error": vol_err,
        "min_cell_volume": min_vol,
        "holes": out.stats.holes,
        "voids_attached": out.stats.voids_attached,
        "domain_euler": check.as_ref().map(|v| v.domain_euler).ok(),
        "euler_by_cell": check.as_ref().map(|v| v.euler_by_cell).ok(),
        "non_ball_cells": check.as_ref().map(|v| v.non_ball_cells).ok(),
        "check": check_msg,
        "exact_fallbacks": out.stats.exact_fallbacks,
        "ordered_edges": out.stats.ordered_edges,
        "moved_vertices": out.stats.moved_vertices,
        "sidedness_moved": out.stats.sidedness_moved,
        "sidedness_violations_rounded": out.stats.sidedness_violations_rounded,
        "sidedness_violations": out.stats.sidedness_violations,
        "line_order_violations": out.stats.line_order_violations,
        "dropped_planes": out.stats.dropped_planes.len(),
        "faces_split_nonplanar": out.stats.faces_split_nonplanar,
        "faces_split_holes": out.stats.faces_split_holes,
        "embedding": out.stats.embedding,
        "verify_written_file": verify,
        "seconds": seconds,
    });
    let mut j = j;
    if let Some(s) = foam_swapped {
        // polyMesh cell numbers that differ from the cut-cells' (io::cut_foam)
        j["foam_cells_swapped"] = serde_json::json!(s);
    }
    if let Some((r, patches)) = &check_mesh {
        j["check_mesh"] = serde_json::json!(r);
        j["foam_patches"] = serde_json::json!(patches
            .iter()
            .map(|p| serde_json::json!({"name": p.0, "type": p.1, "faces": p.3}))
            .collect::<Vec<_>>());
    }
    dir.write("cut.json", serde_json::to_string_pretty(&j)?.as_bytes())?;
    dir.finish()?;
    if a.json {
        println!("{j}");
    } else if !a.quiet {
        println!(
            "{} cut-vertices, {} cut-edges, {} cut-faces, {} cut-cells; euler {euler}; volume error {vol_err:.2e}; {:.3} s",
            c.cut_vertices,
            c.cut_edges,
            c.cut_faces,
            c.cut_cells,
            t0.elapsed().as_secs_f64()
        );
    }
    if let (Some((r, patches)), false) = (&check_mesh, a.json || a.quiet) {
        print_check_mesh(r, patches);
    }
    // The process ends here: its memory goes back with it, so the cut's
    // many small vectors (face loops, cell lists) are not freed one by one
    // (about 1% of a small cut's time in `free`).
    std::mem::forget((out, polys, mesh));
    check?;
    if let Some(r) = &verify {
        for e in &r.examples {
            eprintln!("verify: {e}");
        }
        if r.violations() > 0 {
            return Err(format!("the exact check found {} violations in the written embedding", r.violations()).into());
        }
    }
    Ok(())
}

/// The `--check-mesh` report, in checkMesh's words.
fn print_check_mesh(r: &septa::io::FoamCheck, patches: &[(String, &'static str, usize, usize)]) {
    println!("check-mesh (OpenFOAM checkMesh's quantities):");
    let list: Vec<String> = patches.iter().map(|p| format!("{} ({} faces, {})", p.0, p.3, p.1)).collect();
    println!("  patches: {}", list.join(", "));
    println!(
        "  cells {}, faces {} ({} internal); max cell openness {:.3e}; max aspect ratio {:.4}",
        r.cells, r.faces, r.internal_faces, r.max_cell_openness, r.max_aspect_ratio
    );
    println!("  minimum face area {:.6e}, maximum {:.6e}", r.min_face_area, r.max_face_area);
    println!("  min volume {:.6e}, max volume {:.6e}, total volume {:.8}", r.min_volume, r.max_volume, r.total_volume);
    println!(
        "  non-orthogonality max {:.4} average {:.4} degrees ({} faces over 70)",
        r.max_non_orthogonality, r.average_non_orthogonality, r.severely_non_orthogonal
    );
    println!("  face pyramids: {} faces incorrectly oriented", r.wrong_pyramids);
    println!("  max skewness {:.4} ({} faces over 4)", r.max_skewness, r.highly_skew_faces);
    println!("  min volume ratio {:.4e} ({} faces under 0.01)", r.min_volume_ratio, r.small_volume_ratio_faces);
    if r.failed.is_empty() {
        println!("  mesh OK");
    } else {
        println!("  failed {} checks: {}", r.failed.len(), r.failed.join(", "));
    }
}
