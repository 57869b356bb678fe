//! `septa view OUTDIR`: writes a self-contained viewer folder for a job's
//! output and opens it.
//!
//! The viewer (three.js bundled with esbuild from `viewer/`) is committed as
//! a built bundle under `viewer/dist/` and embedded here, so the binary needs
//! neither node nor the network. The data goes into `data.js`, a classic
//! script setting `window.__SEPTA_DATA`, because pages opened from `file://`
//! may not fetch neighbouring files or load ES modules.
use crate::CliResult;
use std::path::{Path, PathBuf};

/// The built viewer page (from `viewer/src/index.html`).
pub const INDEX_HTML: &str = include_str!("../../../viewer/dist/index.html");
/// The bundled viewer script, three.js included.
pub const VIEWER_JS: &str = include_str!("../../../viewer/dist/viewer.js");

/// Arguments of `septa view`.
#[derive(clap::Args)]
pub struct Args {
    /// Output folder of `septa ia|mi|regions|cut` (holding network.json, or
    /// cells.obj and cut.json for a cut).
    pub outdir: PathBuf,
    /// Only write the viewer and print its path; do not start a browser.
    #[arg(long)]
    pub no_open: bool,
    /// Title shown in the viewer (default: the folder name).
    #[arg(long)]
    pub title: Option<String>,
}

/// Runs `septa view`.
pub fn run(args: Args) -> CliResult {
    let title = args.title.clone().unwrap_or_else(|| folder_name(&args.outdir));
    let index = write_viewer(&args.outdir, &title)?;
    println!("viewer: {}", index.display());
    if !args.no_open && has_display() {
        if let Err(e) = open_in_browser(&index) {
            eprintln!("could not start a browser ({e}); open the file above by hand");
        }
    } else if !args.no_open {
        println!("no display found: open the file above in a browser");
    }
    Ok(())
}

fn folder_name(dir: &Path) -> String {
    std::fs::canonicalize(dir)
        .ok()
        .and_then(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
        .unwrap_or_else(|| "Septa".to_string())
}

/// Writes `OUTDIR/viewer/{index.html, viewer.js, data.js}` and returns the
/// path of `index.html`. Used by `septa view` and `septa demo`.
pub fn write_viewer(outdir: &Path, title: &str) -> Result<PathBuf, Box<dyn std::error::Error>> {
    let network = load_network(outdir)?;
    let cut = match std::fs::read_to_string(outdir.join("cut.json")) {
        Ok(text) => Some(parse_json(&outdir.join("cut.json"), &text)?),
        Err(_) => None,
    };
    let data = serde_json::json!({ "title": title, "network": network, "cut": cut });
    // JSON is a subset of JavaScript expressions, so it embeds as is.
    let script = format!("window.__SEPTA_DATA = {};\n", serde_json::to_string(&data)?);
    let dir = outdir.join("viewer");
    std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    write_atomic(&dir.join("data.js"), script.as_bytes())?;
    write_atomic(&dir.join("viewer.js"), VIEWER_JS.as_bytes())?;
    write_atomic(&dir.join("index.html"), INDEX_HTML.as_bytes())?;
    Ok(std::fs::canonicalize(dir.join("index.html"))?)
}

/// The network to show: `network.json`, or for a cut (no network.json) the
/// cut-cells of `cells.obj`, each OBJ group becoming one cell.
fn load_network(outdir: &Path) -> Result<serde_json::Value, Box<dyn std::error::Error>> {
    // Only the current set counts: an interrupted run is refused, and after
    // `cut` then `ia` into one folder the manifest names the ia files only.
    let listed = septa::io::outdir::check_complete(outdir)?;
    let current = |name: &str| listed.as_ref().is_none_or(|l| l.iter().any(|n| n == name));
    let net_path = outdir.join("network.json");
    if current("network.json") {
        if let Some(bytes) = read_if_exists(&net_path)? {
            let text = String::from_utf8(bytes).map_err(|e| {
                format!(
                    "{}: not a septa network (not UTF-8 text: byte {})",
                    net_path.display(),
                    e.utf8_error().valid_up_to()
                )
            })?;
            let value = parse_json(&net_path, &text)?;
            check_network(&net_path, &value)?;
            return Ok(value);
        }
    }
    let obj_path = outdir.join("cells.obj");
    if current("cells.obj") {
        if let Some(bytes) = read_if_exists(&obj_path)? {
            let text = String::from_utf8(bytes).map_err(|_| format!("{}: not an OBJ text file", obj_path.display()))?;
            return Ok(obj_cells_to_network(&obj_path, &text)?);
        }
    }
    if let Some(topo) = stream_topology_file(outdir) {
        return stream_to_network(&topo);
    }
    Err(format!(
        "{} has neither network.json, cells.obj nor a stream's NAME.ply with NAME.topology.json: give the output folder of `septa ia|mi|regions|labels|cut` or of `--stream`",
        outdir.display()
    )
    .into())
}

/// The file's bytes, `None` when it does not exist, an error naming it otherwise.
fn read_if_exists(path: &Path) -> Result<Option<Vec<u8>>, String> {
    match std::fs::read(path) {
        Ok(b) => Ok(Some(b)),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(e) => Err(format!("{}: cannot read: {e}", path.display())),
    }
}

/// The network contract the viewer relies on: `points` rows of 3 finite
/// numbers, `faces` lists of at least 3 indices into `points` (before: a
/// face index -1 or 99999999 produced a viewer that fails in the browser).
fn check_network(path: &Path, v: &serde_json::Value) -> Result<(), String> {
    let bad = |what: String| format!("{}: {what}", path.display());
    let points =
        v.get("points").and_then(|p| p.as_array()).ok_or_else(|| bad("missing array field \"points\"".into()))?;
    for (i, p) in points.iter().enumerate() {
        let ok = p.as_array().is_some_and(|c| c.len() == 3 && c.iter().all(|x| x.as_f64().is_some_and(f64::is_finite)));
        if !ok {
            return Err(bad(format!("point {i} is not 3 finite numbers: {p}")));
        }
    }
    let faces = v.get("faces").and_then(|f| f.as_array()).ok_or_else(|| bad("missing array field \"faces\"".into()))?;
    for (i, f) in faces.iter().enumerate() {
        let ids = f.as_array().ok_or_else(|| bad(format!("face {i} is not a list of point indices")))?;
        if ids.len() < 3 {
            return Err(bad(format!("face {i} has {} point indices, at least 3 are needed", ids.len())));
        }
        for x in ids {
            if !x.as_u64().is_some_and(|j| (j as usize) < points.len()) {
                return Err(bad(format!("face {i} refers to point {x}, but there are {} points", points.len())));
            }
        }
    }
    Ok(())
}

/// The first `NAME.topology.json` (by name) in `dir` with its `NAME.ply` beside it.
fn stream_topology_file(dir: &Path) -> Option<PathBuf> {
    let mut found: Vec<PathBuf> = std::fs::read_dir(dir)
        .ok()?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.to_string_lossy().ends_with(".topology.json") && stream_ply_of(p).exists())
        .collect();
    found.sort();
    found.into_iter().next()
}

fn stream_ply_of(topology: &Path) -> PathBuf {
    PathBuf::from(topology.to_string_lossy().trim_end_matches(".topology.json").to_string() + ".ply")
}

/// A streamed network (its PLY's polygons, its topology file's patches,
/// chains, corners, shells and cells) in the network contract.
fn stream_to_network(topology: &Path) -> Result<serde_json::Value, Box<dyn std::error::Error>> {
    let text = std::fs::read_to_string(topology).map_err(|e| format!("{}: {e}", topology.display()))?;
    let mut value = parse_json(topology, &text)?;
    let ply = septa::io::ply_stream::read_stream_ply(&stream_ply_of(topology))?;
    let obj = value.as_object_mut().ok_or_else(|| format!("{}: not a JSON object", topology.display()))?;
    obj.insert("points".into(), serde_json::json!(ply.points));
    obj.insert("faces".into(), serde_json::json!(ply.faces));
    obj.insert("face_label".into(), serde_json::json!(ply.labels));
    obj.insert("face_patch".into(), serde_json::json!(ply.patch));
    obj.insert("face_cells".into(), serde_json::json!(ply.cells));
    obj.remove("piece_patch");
    obj.remove("piece_cells");
    Ok(value)
}

fn parse_json(path: &Path, text: &str) -> Result<serde_json::Value, String> {
    serde_json::from_str(text).map_err(|e| format!("{}:{}: invalid JSON: {e}", path.display(), e.line()))
}

/// Converts an OBJ of cut-cells (one `g`/`o` group per cell) into the
/// network contract: every face bounds its group's cell on the positive side.
fn obj_cells_to_network(path: &Path, text: &str) -> Result<serde_json::Value, String> {
    let mut points: Vec<[f64; 3]> = Vec::new();
    let mut faces: Vec<Vec<usize>> = Vec::new();
    let mut face_cell: Vec<i64> = Vec::new();
    let mut cell_names: Vec<String> = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let err = |what: &str| format!("{}:{}: {what}", path.display(), n + 1);
        let mut it = line.split_whitespace();
        match it.next() {
            Some("v") => {
                let c: Vec<f64> =
                    it.take(3).map(|s| s.parse::<f64>()).collect::<Result<_, _>>().map_err(|_| err("bad vertex"))?;
                if c.len() != 3 || c.iter().any(|x| !x.is_finite()) {
                    return Err(err("a vertex needs three finite coordinates"));
                }
                points.push([c[0], c[1], c[2]]);
            }
            Some("g") | Some("o") => cell_names.push(it.collect::<Vec<_>>().join(" ")),
            Some("f") => {
                let mut f = Vec::new();
                for tok in it {
                    let i: i64 = tok.split('/').next().unwrap_or("").parse().map_err(|_| err("bad face index"))?;
                    let i = if i < 0 { points.len() as i64 + i } else { i - 1 };
                    if i < 0 || i as usize >= points.len() {
                        return Err(err("face index out of range"));
                    }
                    f.push(i as usize);
                }
                if f.len() < 3 {
                    return Err(err("a face needs at least three vertices"));
                }
                if cell_names.is_empty() {
                    cell_names.push("cell 0".into());
                }
                faces.push(f);
                face_cell.push(cell_names.len() as i64 - 1);
            }
            _ => {}
        }
    }
    let cells: Vec<_> = (0..cell_names.len())
        .map(|c| serde_json::json!({ "shells": [], "label": [c], "name": cell_names[c] }))
        .collect();
    let patches: Vec<_> = (0..cell_names.len())
        .map(|c| serde_json::json!({ "label": [c], "faces": face_cell.iter().filter(|&&x| x == c as i64).count() }))
        .collect();
    let face_cells: Vec<[i64; 2]> = face_cell.iter().map(|&c| [c, -1]).collect();
    Ok(serde_json::json!({
        "mode": "cut",
        "points": points,
        "faces": faces,
        "face_patch": face_cell,
        "face_cells": face_cells,
        "patches": patches,
        "chains": [],
        "corners": [],
        "shells": [],
        "cells": cells,
        "counts": { "vertices": points.len(), "faces": faces.len(), "cells": cell_names.len() },
    }))
}

/// Atomic write (temporary sibling file, then rename) with a message naming the file.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), String> {
    septa::io::write_atomic(path, bytes).map_err(|e| format!("cannot write {}: {e}", path.display()))
}

fn has_display() -> bool {
    cfg!(target_os = "macos")
        || cfg!(windows)
        || std::env::var_os("DISPLAY").is_some()
        || std::env::var_os("WAYLAND_DISPLAY").is_some()
}

fn open_in_browser(index: &Path) -> std::io::Result<()> {
    let opener = if cfg!(target_os = "macos") {
        "open"
    } else if cfg!(windows) {
        "explorer"
    } else {
        "xdg-open"
    };
    std::process::Command::new(opener)
        .arg(index)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .map(|_| ())
}
