//! `septa remesh OUT L`: remeshes a written result in place. Reads the
//! folder's `network.npz` (the exact doubles and every array), remeshes its
//! patches with `septa::mesh::remesh_written` (vertices kept on the
//! unremeshed patches: the placement for sampled inputs; the formulas of
//! `--remesh` on a job are not in the folder), and writes the same set of
//! files again as one transaction (`io::OutputDir`: the old set stays
//! whole until the new one is complete).
use std::borrow::Cow;
use std::path::{Path, PathBuf};

use septa::io::{Format, NpyArray, ResultView};
use serde_json::{json, Value};

use crate::CliResult;

/// Arguments of `septa remesh`.
#[derive(clap::Args)]
pub struct Args {
    /// Output folder of `septa ia|mi|regions|labels` (with network.npz).
    pub outdir: PathBuf,
    /// Target edge length.
    #[arg(value_parser = crate::args::positive)]
    pub length: f64,
    /// Rounds of split, collapse, flip and smoothing.
    #[arg(long, default_value_t = 8)]
    pub iterations: usize,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = crate::args::threads)]
    pub threads: Option<usize>,
    /// Print the report as one JSON object on standard output.
    #[arg(long)]
    pub json: bool,
    /// Print nothing but errors (and the `--json` object if asked for).
    #[arg(short, long)]
    pub quiet: bool,
}

fn bad(path: &Path, what: impl std::fmt::Display) -> Box<dyn std::error::Error> {
    format!("{}: {what}", path.display()).into()
}

/// The integer array `name` with `dims` dimensions.
fn ints(
    a: &std::collections::BTreeMap<String, NpyArray>,
    p: &Path,
    name: &str,
) -> Result<Vec<i64>, Box<dyn std::error::Error>> {
    match a.get(name) {
        Some(NpyArray::I64(_, x)) => Ok(x.clone()),
        Some(_) => Err(bad(p, format!("{name}: not an integer array"))),
        None => Err(bad(p, format!("{name}: missing (not a septa result)"))),
    }
}

fn u32s(p: &Path, name: &str, xs: &[i64]) -> Result<Vec<u32>, Box<dyn std::error::Error>> {
    xs.iter()
        .enumerate()
        .map(|(i, &x)| u32::try_from(x).map_err(|_| bad(p, format!("{name}[{i}]: {x} out of range"))))
        .collect()
}

fn pairs(p: &Path, name: &str, xs: &[i64]) -> Result<Vec<[i32; 2]>, Box<dyn std::error::Error>> {
    if xs.len() % 2 != 0 {
        return Err(bad(p, format!("{name}: not (n, 2)")));
    }
    Ok(xs.chunks_exact(2).map(|c| [c[0] as i32, c[1] as i32]).collect())
}

fn ragged(p: &Path, name: &str, offsets: &[i64], idx: &[i64]) -> Result<Vec<Vec<u32>>, Box<dyn std::error::Error>> {
    offsets
        .windows(2)
        .enumerate()
        .map(|(i, w)| {
            if w[0] < 0 || w[1] < w[0] || w[1] as usize > idx.len() {
                return Err(bad(p, format!("{name} {i}: offsets {}..{} out of range", w[0], w[1])));
            }
            u32s(p, name, &idx[w[0] as usize..w[1] as usize])
        })
        .collect()
}

/// The result in `network.npz` (the arrays `result_npz.rs` writes) and its
/// `meta` document.
fn read_npz(p: &Path) -> Result<(ResultView<'static>, Value), Box<dyn std::error::Error>> {
    let a = septa::io::read_npz(p)?;
    let meta: Value = match a.get("meta") {
        Some(NpyArray::Str(s)) => serde_json::from_str(s).map_err(|e| bad(p, format!("meta: not JSON: {e}")))?,
        _ => return Err(bad(p, "meta: missing (not a septa result)")),
    };
    let mode: &'static str = match meta["mode"].as_str() {
        Some("ia") => "ia",
        Some("mi") => "mi",
        Some("regions") => "regions",
        m => return Err(bad(p, format!("mode {m:?}: not ia, mi or regions"))),
    };
    let points = match a.get("points") {
        Some(NpyArray::F64(s, x)) if s.len() == 2 && s[1] == 3 => {
            x.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()
        }
        _ => return Err(bad(p, "points: missing or not (n, 3) floats")),
    };
    let floats = |name: &str| match a.get(name) {
        Some(NpyArray::F64(_, x)) => x.clone(),
        _ => Vec::new(),
    };
    let cell_labels = match a.get("cell_labels") {
        Some(NpyArray::I64(s, x)) if s.len() == 2 => {
            if s[1] == 0 {
                vec![Vec::new(); s[0]]
            } else {
                x.chunks_exact(s[1]).map(|c| c.to_vec()).collect()
            }
        }
        _ => return Err(bad(p, "cell_labels: missing or not 2-dimensional")),
    };
    let mut names = septa::io::Names::default();
    if let Some(fs) = meta["names"]["functions"].as_array() {
        names.functions = fs.iter().map(|f| f.as_str().map_or_else(|| f.to_string(), str::to_string)).collect();
    }
    if let Some(rs) = meta["names"]["regions"].as_object() {
        for (k, v) in rs {
            if let (Ok(r), Some(v)) = (k.trim().parse::<i64>(), v.as_str()) {
                names.regions.insert(r, v.to_string());
            }
        }
    }
    let g = |name: &str| ints(&a, p, name);
    let view = ResultView {
        mode,
        functions: meta["functions"].as_u64().unwrap_or(0) as usize,
        points: Cow::Owned(points),
        face_start: Cow::Owned(u32s(p, "offsets", &g("offsets")?)?),
        face_verts: Cow::Owned(u32s(p, "indices", &g("indices")?)?),
        patch: Cow::Owned(u32s(p, "patch", &g("patch")?)?),
        labels: pairs(p, "labels", &g("labels")?)?,
        cells: pairs(p, "cells", &g("cells")?)?,
        patch_labels: pairs(p, "patch_labels", &g("patch_labels")?)?,
        chains: Cow::Owned(ragged(p, "chain", &g("chain_offsets")?, &g("chain_indices")?)?),
        chain_patches: Cow::Owned(ragged(p, "chain_patch", &g("chain_patch_offsets")?, &g("chain_patch_indices")?)?),
        corners: Cow::Owned(u32s(p, "corners", &g("corners")?)?),
        shells: Cow::Owned(ragged(p, "shell", &g("shell_offsets")?, &g("shell_indices")?)?),
        cell_shells: ragged(p, "cell_shell", &g("cell_shell_offsets")?, &g("cell_shell_indices")?)?,
        cell_labels,
        names: Cow::Owned(names),
        measures: Cow::Owned(septa::measure::Measures {
            cell_volume: floats("cell_volume"),
            patch_area: floats("patch_area"),
            chain_length: floats("chain_length"),
        }),
    };
    view.validate().map_err(|e| bad(p, e))?;
    Ok((view, meta))
}

/// What to write again: the formats of the old set, `surfaces.obj`, and
/// files to carry over unchanged (the adaptive grid's); the viewer is
/// dropped (its data is the old result: `septa view` writes it again).
struct Set {
    formats: Vec<Format>,
    surfaces_obj: bool,
    carried: Vec<(String, Vec<u8>)>,
}

fn old_set(dir: &Path, listed: Option<Vec<String>>) -> Result<Set, Box<dyn std::error::Error>> {
    let names = match listed {
        Some(l) => l,
        // a folder written before manifests: the files that are there
        None => [
            "network.json",
            "network.npz",
            "network.ply",
            "network.plain.ply",
            "network.obj",
            "network.vtu",
            "network.vtm",
        ]
        .iter()
        .filter(|n| dir.join(n).is_file())
        .map(|n| n.to_string())
        .collect(),
    };
    let mut set = Set { formats: Vec::new(), surfaces_obj: false, carried: Vec::new() };
    for n in &names {
        let f = if let Some(rest) = n.strip_prefix("regions/") {
            match rest.rsplit_once('.').map(|x| x.1) {
                Some("stl") => Some(Format::Stl),
                Some("obj") => Some(Format::SolidObj),
                Some("ply") => Some(Format::SolidPly),
                _ => None,
            }
        } else if n.starts_with("network/") || n.starts_with("viewer/") {
            None
        } else if n == "surfaces.obj" {
            set.surfaces_obj = true;
            None
        } else if let Some(f) = n.strip_prefix("network.").and_then(|_| Format::of_path(Path::new(n))) {
            Some(f)
        } else {
            set.carried.push((n.clone(), std::fs::read(dir.join(n)).map_err(|e| bad(&dir.join(n), e))?));
            None
        };
        if let Some(f) = f {
            if !set.formats.contains(&f) {
                set.formats.push(f);
            }
        }
    }
    set.formats.sort_by_key(|f| Format::ALL.iter().position(|g| g == f));
    Ok(set)
}

/// `surfaces.obj` of a regions result (`regions_out.rs`): a group per
/// surface, curves as polylines (no vertex normals after remeshing).
fn surfaces_obj(v: &ResultView) -> String {
    use std::fmt::Write;
    let mut obj = String::from("# Septa region surfaces (remeshed): a group per surface, curves as polylines\n");
    for p in v.points.iter() {
        writeln!(obj, "v {} {} {}", p[0], p[1], p[2]).unwrap();
    }
    for (s, l) in v.patch_labels.iter().enumerate() {
        writeln!(obj, "g surface_{s}_regions_{}_{}", l[0], l[1]).unwrap();
        for f in (0..v.num_faces()).filter(|&f| v.patch[f] as usize == s) {
            let ids: Vec<String> = v.face(f).iter().map(|x| (x + 1).to_string()).collect();
            writeln!(obj, "f {}", ids.join(" ")).unwrap();
        }
    }
    for (i, c) in v.chains.iter().enumerate() {
        writeln!(obj, "g curve_{i}").unwrap();
        let ids: Vec<String> = c.iter().map(|x| (x + 1).to_string()).collect();
        writeln!(obj, "l {}", ids.join(" ")).unwrap();
    }
    obj
}

/// The number of distinct edges of polygons.
fn edges(v: &ResultView) -> usize {
    let mut e: Vec<(u32, u32)> = Vec::new();
    for f in 0..v.num_faces() {
        let l = v.face(f);
        for k in 0..l.len() {
            let (a, b) = (l[k], l[(k + 1) % l.len()]);
            e.push((a.min(b), a.max(b)));
        }
    }
    e.sort_unstable();
    e.dedup();
    e.len()
}

/// The old `network.json` with the remeshed geometry (the topology keys
/// are the same: patches, chains, corners, shells, cells).
fn json_doc(old: &mut Value, v: &ResultView, report: &Value, embedding: &Value) {
    let faces: Vec<Value> = (0..v.num_faces()).map(|f| json!(v.face(f))).collect();
    old["points"] = json!(v.points.as_ref());
    old["faces"] = Value::Array(faces);
    old["face_label"] = json!(v.labels);
    old["face_patch"] = json!(v.patch.as_ref());
    old["face_cells"] = json!(v.cells);
    old["chains"] = json!(v.chains.as_ref());
    old["corners"] = json!(v.corners.as_ref());
    let mut faces_per = vec![0usize; v.patch_labels.len()];
    for &p in v.patch.iter() {
        faces_per[p as usize] += 1;
    }
    let m = &v.measures;
    if let Some(ps) = old["patches"].as_array_mut() {
        for (p, n) in ps.iter_mut().zip(&faces_per) {
            p["faces"] = json!(n);
        }
    }
    if old.get("measures").is_some() {
        let nulls =
            |xs: &[f64]| -> Value { xs.iter().map(|x| if x.is_finite() { json!(x) } else { Value::Null }).collect() };
        old["measures"] = json!({"cell_volume": nulls(&m.cell_volume), "patch_area": nulls(&m.patch_area), "chain_length": nulls(&m.chain_length)});
    }
    let counts = &mut old["counts"];
    counts["vertices"] = json!(v.points.len());
    counts["faces"] = json!(v.num_faces());
    if counts.get("edges").is_some() {
        counts["edges"] = json!(edges(v));
    }
    if let Some(ss) = counts["surfaces"].as_array_mut() {
        for (s, (n, a)) in ss.iter_mut().zip(faces_per.iter().zip(&m.patch_area)) {
            s["faces"] = json!(n);
            s["area"] = json!(a);
        }
    }
    if let Some(cs) = counts["curves"].as_array_mut() {
        for (c, (path, l)) in cs.iter_mut().zip(v.chains.iter().zip(&m.chain_length)) {
            c["vertices"] = json!(path.len());
            c["length"] = json!(l);
        }
    }
    if counts.get("embedding").is_some() {
        counts["embedding"] = embedding.clone();
    }
    if old.get("embedding").is_some() {
        old["embedding"] = embedding.clone();
    }
    old["remesh"] = report.clone();
}

/// Runs `septa remesh`.
pub fn run(a: Args) -> CliResult {
    let t0 = std::time::Instant::now();
    let dir = &a.outdir;
    if !dir.is_dir() {
        return Err(bad(dir, "not a folder (give the output folder of septa ia|mi|regions|labels)"));
    }
    let listed = septa::io::check_complete(dir)?;
    let npz = dir.join("network.npz");
    if listed.as_ref().is_some_and(|l| !l.iter().any(|n| n == "network.npz")) || !npz.is_file() {
        return Err(bad(
            dir,
            "no network.npz in this result (septa remesh reads it: write the job with --format npz, the default)",
        ));
    }
    let (view, mut meta) = read_npz(&npz)?;
    let set = old_set(dir, listed)?;
    let job = match std::fs::read(dir.join("manifest.json")).ok().and_then(|b| serde_json::from_slice::<Value>(&b).ok())
    {
        Some(m) => m["job"].as_str().unwrap_or("network").to_string(),
        None => if view.mode == "regions" { "regions" } else { "network" }.to_string(),
    };
    let old_json = if set.formats.contains(&Format::Json) {
        let p = dir.join("network.json");
        let text = septa::io::read_input_text(&p).map_err(|e| bad(&p, e))?;
        Some(serde_json::from_str::<Value>(&text).map_err(|e| bad(&p, format!("not JSON: {e}")))?)
    } else {
        None
    };
    let cells: Vec<[u32; 2]> = view.cells.iter().map(|c| c.map(|x| if x < 0 { u32::MAX } else { x as u32 })).collect();
    let w = septa::mesh::Written {
        points: &view.points,
        face_start: &view.face_start,
        face_verts: &view.face_verts,
        face_patch: &view.patch,
        face_cells: &cells,
        face_label: &view.labels,
        patches: view.patch_labels.len(),
        cells: view.cell_labels.len(),
        chains: &view.chains,
        corners: &view.corners,
        cell_volume: &view.measures.cell_volume,
    };
    let mut opts = septa::mesh::RemeshOptions::new(a.length);
    opts.iterations = a.iterations;
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(t) = a.threads {
        pool = pool.num_threads(t.max(1));
    }
    let r = pool.build()?.install(|| septa::mesh::remesh_written(&w, &opts))?;
    let mut measures = r.measures.clone();
    // measures the result did not carry stay absent
    if view.measures.patch_area.is_empty() {
        measures = septa::measure::Measures::default();
    }
    let new = ResultView {
        points: Cow::Owned(r.points.clone()),
        face_start: Cow::Owned(r.face_start.clone()),
        face_verts: Cow::Owned(r.face_verts.clone()),
        patch: Cow::Owned(r.face_patch.clone()),
        labels: r.face_label.clone(),
        cells: r.face_cells.iter().map(|c| c.map(|x| if x == u32::MAX { -1 } else { x as i32 })).collect(),
        chains: Cow::Owned(r.chains.clone()),
        corners: Cow::Owned(r.corners.clone()),
        measures: Cow::Owned(measures),
        ..view.clone()
    };
    let report = serde_json::to_value(&r.report)?;
    let embedding = match &r.embedding {
        Some(e) => serde_json::to_value(e)?,
        None => meta.get("embedding").cloned().unwrap_or(meta["counts"]["embedding"].clone()),
    };
    if meta["counts"].is_object() {
        meta["counts"]["vertices"] = json!(new.points.len());
        meta["counts"]["faces"] = json!(new.num_faces());
        if meta["counts"].get("edges").is_some() {
            meta["counts"]["edges"] = json!(edges(&new));
        }
    }
    if meta.get("embedding").is_some() {
        meta["embedding"] = embedding.clone();
    }
    meta["remesh"] = report.clone();
    if let Some(s) = meta["seconds"].as_object_mut() {
        s.insert("remesh".into(), json!(r.report.seconds));
    }
    let mut out = septa::io::OutputDir::create(dir, &job)?;
    let carried: Vec<septa::io::ExtraFile> = set.carried.iter().map(|(n, b)| (n.as_str(), b.as_slice())).collect();
    septa::io::write_view_formats(&new, &mut out, &set.formats, &meta, &carried)?;
    if set.surfaces_obj {
        out.write("surfaces.obj", surfaces_obj(&new).as_bytes())?;
    }
    if let Some(mut doc) = old_json {
        json_doc(&mut doc, &new, &report, &embedding);
        out.write("network.json", doc.to_string().as_bytes())?;
    }
    out.finish()?;
    if a.json {
        println!("{}", json!({"remesh": report, "embedding": embedding, "seconds": t0.elapsed().as_secs_f64()}));
    } else if !a.quiet {
        let out = crate::output::Output {
            output: dir.clone(),
            format: crate::output::Formats(set.formats.clone()),
            threads: a.threads,
            json: false,
            quiet: false,
            no_certify: false,
            remesh: Some(a.length),
        };
        out.tell_remesh(Some(&r.report));
        println!("{} rewritten ({:.3} s)", dir.display(), t0.elapsed().as_secs_f64());
    }
    Ok(())
}
