//! `septa regions`: surfaces and curves of interest of a scene's region rule.
use crate::CliResult;
use septa::io::{regions_summary, write_regions_formats_with};
use septa::regions::{region_surfaces, RegionOptions};
use septa::scene::{builtin, Scene};

/// Arguments of `septa regions`.
#[derive(clap::Args)]
pub struct Args {
    /// A scene file (JSON) or `builtin:NAME` (see `--list`).
    scene: Option<String>,
    #[command(flatten)]
    out: crate::output::Output,
    /// Move every vertex onto the true zero sets of the scene's functions
    /// (inside its grid element, keeping the exact network; moves that would
    /// break the exact check are left undone and counted in
    /// `embedding.projection`).
    #[arg(long, conflicts_with_all = ["no_certify", "adaptive"])]
    project: bool,
    #[command(flatten)]
    adaptive: crate::adaptive::AdaptiveArgs,
    /// Write the scene as a JSON file to edit (to this path, or `-` for the
    /// terminal) and exit: `septa regions builtin:cad-part --print part.json`.
    #[arg(long, value_name = "FILE")]
    print: Option<std::path::PathBuf>,
    /// Print the built-in scenes and exit.
    #[arg(long)]
    list: bool,
    /// Per-vertex normals from the analytic gradients (one vertex copy per
    /// region pair: `normals` in network.json, `vn` in surfaces.obj).
    #[arg(long)]
    normals: bool,
    /// Clean up small and thin triangles: collapse
    /// edges shorter than FACTOR times the smallest cube edge wherever that
    /// keeps every surface's topology, curve and corner; output triangles.
    #[arg(long, value_name = "FACTOR", num_args = 0..=1, default_missing_value = "0.2", value_parser = crate::args::finite_nonneg)]
    clean: Option<f64>,
    /// Sample every grid vertex. By default blocks the functions' bounds
    /// prove empty are skipped (identical output; memory follows the
    /// surface; docs/sparse.md).
    #[arg(long, conflicts_with = "sparse")]
    dense: bool,
    /// Kept only for compatibility with older scripts; does nothing:
    /// sparse evaluation is the default.
    #[arg(long)]
    sparse: bool,
}

/// Runs `septa regions`.
pub fn run(a: Args) -> CliResult {
    if a.list {
        for (name, what) in builtin::list() {
            println!("builtin:{name:<20} {what}");
        }
        return Ok(());
    }
    let Some(path) = a.scene else {
        return Err("septa regions needs a SCENE (a JSON file or builtin:NAME; see --list)".into());
    };
    let scene = Scene::load(&path)?;
    if let Some(to) = &a.print {
        let text = septa::scene::scene_text(&scene).map_err(|e| format!("{path}: {e}"))?;
        if to.as_os_str() == "-" {
            print!("{text}");
        } else {
            // atomically, and never through a link or into a special file
            septa::io::write_atomic(to, text.as_bytes()).map_err(|e| format!("{}: {e}", to.display()))?;
            if a.out.talk() {
                println!("wrote {} (edit it, then: septa regions {})", to.display(), to.display());
            }
        }
        return Ok(());
    }
    if let Some(f) = a.clean {
        if !(f.is_finite() && f >= 0.0) {
            return Err(format!("--clean: expected a factor >= 0, not {f}").into());
        }
    }
    let quiet = a.out.json || a.out.quiet;
    // A counted bar over the network's blocks, then a spinner naming the
    // stage after them.
    let (bar, progress) = crate::progress::block_bar(quiet, "region surfaces: topology, surfaces, curves");
    let options = RegionOptions { normals: a.normals, sparse: !a.dense, clean: a.clean, progress };
    let refined = match a.adaptive.adaptive {
        true => {
            let bounds = scene.grid.box_grid()?.bounds;
            let refined = a
                .out
                .install(|| crate::adaptive::refine_box(&a.adaptive, bounds, &scene.functions, scene.mode, quiet))??;
            let grid = septa::grid::Grid::Mesh(refined.mesh()?);
            Some((refined, grid))
        }
        false => None,
    };
    let r = match &refined {
        Some((_, grid)) => a.out.install(|| septa::regions::region_surfaces_on(&scene, grid, &options)),
        None => a.out.install(|| region_surfaces(&scene, &options)),
    };
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let mut r = r??;
    if !a.out.no_certify && refined.is_some() {
        let bounds = scene.grid.box_grid()?.bounds;
        a.out.install(|| septa::mesh::certify_regions(&mut r, None, Some(bounds)))?;
    } else if !a.out.no_certify {
        let grid = scene.grid.box_grid()?;
        if a.project {
            a.out.install(|| septa::mesh::certify_regions_on(&mut r, &grid, &scene.functions))?;
        } else {
            a.out.install(|| septa::mesh::certify_regions(&mut r, Some(&grid), Some(grid.bounds)))?;
        }
    }
    let remeshed = match a.out.remesh {
        Some(l) => {
            let bounds = scene.grid.box_grid()?.bounds;
            let o = septa::mesh::RemeshOptions::new(l);
            Some(a.out.install(|| septa::mesh::remesh_regions(&mut r, &o, Some(bounds)))??)
        }
        None => None,
    };
    let dir = &a.out.output;
    crate::progress::during(quiet, &format!("writing {}", dir.display()), || {
        let files = refined.as_ref().map(|(x, _)| x.files());
        let extra: Vec<septa::io::ExtraFile> = match &files {
            Some((vtu, json)) => vec![("grid.vtu", vtu.as_slice()), ("adaptive.json", json.as_slice())],
            None => vec![],
        };
        write_regions_formats_with(&r, dir, &a.out.format.0, &extra)
    })?;
    let mut summary = regions_summary(&r);
    if let (Some(s), Some(obj)) = (&r.sparse, summary.as_object_mut()) {
        obj.insert("blocks".into(), crate::network::sparse_json(s));
    }
    if let (Some((x, _)), Some(obj)) = (&refined, summary.as_object_mut()) {
        obj.insert("adaptive".into(), x.json());
    }
    if let (Some(m), Some(obj)) = (&remeshed, summary.as_object_mut()) {
        obj.insert("remesh".into(), serde_json::to_value(m)?);
    }
    if a.out.json {
        println!("{summary}");
    } else if a.out.talk() {
        print!("{}", crate::summary::regions_text(&path, &r));
        a.out.tell_embedding(r.embedding.as_ref());
        if let Some((x, _)) = &refined {
            print!("{}", x.text());
        }
        a.out.tell_solids();
        a.out.tell_remesh(remeshed.as_ref());
        println!("wrote {}", dir.display());
    }
    Ok(())
}
