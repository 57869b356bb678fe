//! The browser viewer of a result: one writer for `septa view`, `septa demo`
//! and Python's `septa.view` / notebooks (before, the command line and Python
//! each assembled the page and its data their own way).
//!
//! The viewer (three.js bundled with esbuild from `viewer/`) is committed as a
//! built bundle under `viewer/dist/` and embedded here, so neither the binary
//! nor the wheel needs node or the network. A result goes into `data.js`, a
//! classic script setting `window.__SEPTA_DATA` to `{title, network, cut}`,
//! because pages opened from `file://` may not fetch neighbouring files or
//! load ES modules. `network` is the `network.json` contract (docs/results.md):
//! `points`, `faces`, `face_patch`, `face_cells`, `face_label`, `patches`,
//! `chains`, `corners`, `shells`, `cells`.
//!
//! A result folder is read by [`folder_network`]: its `network.json`; for a
//! cut, the cut-cells of `cells.obj`; for a stream (`septa ia|mi --stream
//! OUT.ply|OUT.vtu`), the streamed polygons with `OUT.topology.json`.

use std::path::{Path, PathBuf};

use serde_json::{json, Value};

use crate::io::files::atomic::write_atomic;
use crate::io::writers::ply_stream::{read_stream_ply, StreamPly};
use crate::io::writers::vtu_stream::read_stream_vtu;

/// The built viewer page (from `viewer/src/index.html`).
pub const VIEWER_INDEX_HTML: &str = include_str!("../../../../../viewer/dist/index.html");
/// The bundled viewer script, three.js included.
pub const VIEWER_JS: &str = include_str!("../../../../../viewer/dist/viewer.js");

/// Why no viewer could be written.
#[derive(Debug, thiserror::Error)]
pub enum ViewerError {
    /// The folder holds no result the viewer shows.
    #[error("{} has neither network.json, cells.obj nor a stream's NAME.ply or NAME.vtu with NAME.topology.json: give the output folder of `septa ia|mi|regions|labels|cut` or of `--stream`", .0.display())]
    NoResult(PathBuf),
    /// A result file is not what it should be; `what` says how.
    #[error("{}: {what}", path.display())]
    Invalid {
        /// The file.
        path: PathBuf,
        /// What is wrong, in its words (line, element, index).
        what: String,
    },
    /// A JSON file does not parse.
    #[error("{}:{line}: invalid JSON: {message}", path.display())]
    Json {
        /// The file.
        path: PathBuf,
        /// The line of the error.
        line: usize,
        /// The parser's message.
        message: String,
    },
    /// A stream file is not one Septa wrote (the message names it).
    #[error("{0}")]
    Stream(String),
    /// Reading or writing a file failed.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The failure.
        #[source]
        source: std::io::Error,
    },
}

fn invalid(path: &Path, what: impl Into<String>) -> ViewerError {
    ViewerError::Invalid { path: path.to_path_buf(), what: what.into() }
}

fn io_error(path: &Path) -> impl FnOnce(std::io::Error) -> ViewerError + '_ {
    move |source| ViewerError::Io { path: path.to_path_buf(), source }
}

/// `data.js`: the result as a script setting `window.__SEPTA_DATA`.
pub fn viewer_data_script(title: &str, network: &Value, cut: Option<&Value>) -> String {
    let data = json!({ "title": title, "network": network, "cut": cut });
    // JSON is a subset of JavaScript expressions, so it embeds as is.
    format!("window.__SEPTA_DATA = {data};\n")
}

/// The viewer as one self-contained HTML page (data and script inline, as
/// `<script>` elements whose text cannot close them early): what a notebook
/// shows in an `<iframe srcdoc>`.
pub fn viewer_inline_page(title: &str, network: &Value, cut: Option<&Value>) -> String {
    let script = |js: &str| format!("<script>{}</script>", escape_script_end(js));
    // Every `<` of the data is inside a JSON string, where `\u003c` is the
    // same character: no `</script>`, `</SCRIPT >` or `<!--` of a loaded
    // result can end or change the data script.
    let data = viewer_data_script(title, network, cut).replace('<', "\\u003c");
    VIEWER_INDEX_HTML
        .replace(r#"<script src="data.js"></script>"#, &script(&data))
        .replace(r#"<script src="viewer.js"></script>"#, &script(VIEWER_JS))
}

/// `js` with every `</script` (in any letter case: HTML ends a script at
/// `</SCRIPT` too) written `<\/script`, the same text inside a JavaScript
/// string or comment.
fn escape_script_end(js: &str) -> String {
    let mut out = String::with_capacity(js.len());
    let mut rest = js;
    while let Some(i) = rest.find("</") {
        let after = &rest[i + 2..];
        let is_end = after.len() >= 6 && after.as_bytes()[..6].eq_ignore_ascii_case(b"script");
        out.push_str(&rest[..i]);
        out.push_str(if is_end { "<\\/" } else { "</" });
        rest = after;
    }
    out.push_str(rest);
    out
}

/// Writes `dir/{data.js, viewer.js, index.html}` (each atomically; the
/// folder is created) and returns the path of `index.html`.
pub fn write_viewer(dir: &Path, title: &str, network: &Value, cut: Option<&Value>) -> Result<PathBuf, ViewerError> {
    // `viewer/` inside a result folder: a real folder, never a link out of it
    match (dir.parent().filter(|p| !p.as_os_str().is_empty()), dir.file_name()) {
        (Some(parent), Some(name)) if parent.is_dir() => {
            crate::io::files::safe_write::real_dir(parent, Path::new(name)).map_err(io_error(dir))?;
        }
        _ => std::fs::create_dir_all(dir).map_err(io_error(dir))?,
    }
    let files = [
        ("data.js", viewer_data_script(title, network, cut)),
        ("viewer.js", VIEWER_JS.to_string()),
        ("index.html", VIEWER_INDEX_HTML.to_string()),
    ];
    for (name, text) in files {
        let path = dir.join(name);
        write_atomic(&path, text.as_bytes()).map_err(io_error(&path))?;
    }
    let index = dir.join("index.html");
    std::fs::canonicalize(&index).map_err(io_error(&index))
}

/// Writes the viewer of the result at `result` (a job's output folder, or a
/// stream's `OUT.ply` / `OUT.vtu`) into `into` (default: `viewer/` in the
/// result's folder); returns the path of `index.html`.
pub fn write_result_viewer(result: &Path, title: &str, into: Option<&Path>) -> Result<PathBuf, ViewerError> {
    let folder = if result.is_dir() { result } else { result.parent().unwrap_or(Path::new(".")) };
    let (network, cut) = folder_network(result)?;
    write_viewer(&into.map_or_else(|| folder.join("viewer"), Path::to_path_buf), title, &network, cut.as_ref())
}

/// The network to show for a result folder (or a stream file) and the
/// cut's `cut.json` when there is one: `network.json`, or for a cut (no
/// network.json) the cut-cells of `cells.obj`, each OBJ group one cell, or a
/// stream's polygons and topology.
pub fn folder_network(result: &Path) -> Result<(Value, Option<Value>), ViewerError> {
    if !result.is_dir() {
        return match stream_file_topology(result) {
            Some(topo) => Ok((stream_to_network(result, &topo)?, None)),
            None => Err(ViewerError::NoResult(result.to_path_buf())),
        };
    }
    let outdir = result;
    // Only the current set counts: an interrupted run is refused, and after
    // `cut` then `ia` into one folder the manifest names the ia files only.
    let listed = crate::io::files::outdir::check_complete(outdir).map_err(|what| invalid(outdir, what))?;
    let current = |name: &str| listed.as_ref().is_none_or(|l| l.iter().any(|n| n == name));
    let cut = match read_if_exists(&outdir.join("cut.json"))? {
        Some(bytes) if current("cut.json") => Some(parse_json(&outdir.join("cut.json"), &bytes)?),
        _ => None,
    };
    let net_path = outdir.join("network.json");
    if current("network.json") {
        if let Some(bytes) = read_if_exists(&net_path)? {
            let value = parse_json(&net_path, &bytes)?;
            check_network(&net_path, &value)?;
            return Ok((value, cut));
        }
    }
    let obj_path = outdir.join("cells.obj");
    if current("cells.obj") {
        if let Some(bytes) = read_if_exists(&obj_path)? {
            let text = String::from_utf8(bytes).map_err(|_| invalid(&obj_path, "not an OBJ text file"))?;
            return Ok((obj_cells_to_network(&obj_path, &text)?, cut));
        }
    }
    match stream_in(outdir) {
        Some((file, topo)) => Ok((stream_to_network(&file, &topo)?, None)),
        None => Err(ViewerError::NoResult(outdir.to_path_buf())),
    }
}

/// The file's bytes, `None` when it does not exist, an error naming it otherwise.
fn read_if_exists(path: &Path) -> Result<Option<Vec<u8>>, ViewerError> {
    match crate::io::files::input::read_input(path) {
        Ok(b) => Ok(Some(b)),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(e) => Err(invalid(path, format!("cannot read: {e}"))),
    }
}

fn parse_json(path: &Path, bytes: &[u8]) -> Result<Value, ViewerError> {
    let text = std::str::from_utf8(bytes)
        .map_err(|e| invalid(path, format!("not a septa network (not UTF-8 text: byte {})", e.valid_up_to())))?;
    serde_json::from_str(text).map_err(|e| ViewerError::Json {
        path: path.to_path_buf(),
        line: e.line(),
        message: e.to_string(),
    })
}

/// The network contract the viewer relies on: `points` rows of 3 finite
/// numbers, `faces` lists of at least 3 indices into `points` (before: a
/// face index -1 or 99999999 produced a viewer that fails in the browser).
fn check_network(path: &Path, v: &Value) -> Result<(), ViewerError> {
    let points =
        v.get("points").and_then(|p| p.as_array()).ok_or_else(|| invalid(path, "missing array field \"points\""))?;
    for (i, p) in points.iter().enumerate() {
        let ok = p.as_array().is_some_and(|c| c.len() == 3 && c.iter().all(|x| x.as_f64().is_some_and(f64::is_finite)));
        if !ok {
            return Err(invalid(path, format!("point {i} is not 3 finite numbers: {p}")));
        }
    }
    let faces =
        v.get("faces").and_then(|f| f.as_array()).ok_or_else(|| invalid(path, "missing array field \"faces\""))?;
    for (i, f) in faces.iter().enumerate() {
        let ids = f.as_array().ok_or_else(|| invalid(path, format!("face {i} is not a list of point indices")))?;
        if ids.len() < 3 {
            return Err(invalid(path, format!("face {i} has {} point indices, at least 3 are needed", ids.len())));
        }
        if let Some(x) = ids.iter().find(|x| x.as_u64().is_none_or(|j| (j as usize) >= points.len())) {
            return Err(invalid(path, format!("face {i} refers to point {x}, but there are {} points", points.len())));
        }
    }
    Ok(())
}

/// `NAME.topology.json` beside a stream file `NAME.ply` / `NAME.vtu`, if both exist.
fn stream_file_topology(file: &Path) -> Option<PathBuf> {
    let ext = file.extension()?.to_string_lossy().to_ascii_lowercase();
    if !(ext == "ply" || ext == "vtu") || !file.is_file() {
        return None;
    }
    let topo = file.with_extension("topology.json");
    topo.is_file().then_some(topo)
}

/// The first stream in `dir` (by name): `NAME.ply` or `NAME.vtu` with its
/// `NAME.topology.json`.
fn stream_in(dir: &Path) -> Option<(PathBuf, PathBuf)> {
    let mut found: Vec<(PathBuf, PathBuf)> = std::fs::read_dir(dir)
        .ok()?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter_map(|p| stream_file_topology(&p).map(|t| (p, t)))
        .collect();
    found.sort();
    found.into_iter().next()
}

/// A streamed network (its file's polygons, its topology file's patches,
/// chains, corners, shells and cells) in the network contract.
fn stream_to_network(file: &Path, topology: &Path) -> Result<Value, ViewerError> {
    let bytes = crate::io::files::input::read_input(topology).map_err(io_error(topology))?;
    let mut value = parse_json(topology, &bytes)?;
    let is_vtu = file.extension().is_some_and(|e| e.eq_ignore_ascii_case("vtu"));
    let stream: StreamPly =
        if is_vtu { read_stream_vtu(file) } else { read_stream_ply(file) }.map_err(ViewerError::Stream)?;
    let obj = value.as_object_mut().ok_or_else(|| invalid(topology, "not a JSON object"))?;
    obj.insert("points".into(), json!(stream.points));
    obj.insert("faces".into(), json!(stream.faces));
    obj.insert("face_label".into(), json!(stream.labels));
    obj.insert("face_patch".into(), json!(stream.patch));
    obj.insert("face_cells".into(), json!(stream.cells));
    obj.remove("piece_patch");
    obj.remove("piece_cells");
    Ok(value)
}

/// Converts an OBJ of cut-cells (one `g`/`o` group per cell) into the
/// network contract: every face bounds its group's cell on the positive side.
fn obj_cells_to_network(path: &Path, text: &str) -> Result<Value, ViewerError> {
    let mut points: Vec<[f64; 3]> = Vec::new();
    let mut faces: Vec<Vec<usize>> = Vec::new();
    let mut face_cell: Vec<i64> = Vec::new();
    let mut cell_names: Vec<String> = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let err = |what: &str| ViewerError::Invalid {
            path: PathBuf::from(format!("{}:{}", path.display(), n + 1)),
            what: what.into(),
        };
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
    let cells: Vec<_> =
        (0..cell_names.len()).map(|c| json!({ "shells": [], "label": [c], "name": cell_names[c] })).collect();
    let patches: Vec<_> = (0..cell_names.len())
        .map(|c| json!({ "label": [c], "faces": face_cell.iter().filter(|&&x| x == c as i64).count() }))
        .collect();
    let face_cells: Vec<[i64; 2]> = face_cell.iter().map(|&c| [c, -1]).collect();
    Ok(json!({
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
