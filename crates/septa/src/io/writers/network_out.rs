//! Writing a [`Network`]: `network.json` (the full structure), binary PLY
//! (per-face patch, label and colour) and OBJ (a group per patch, chains as
//! polylines). Every file is written to a temporary file in the same folder
//! and renamed, so a reader never sees a half-written file.

use std::io::Write;
use std::path::Path;

use crate::complex::Mode;
use crate::complex::NONE;
use crate::io::files::atomic::write_atomic_with;
use crate::io::writers::result::{Annotations, Format, ResultView};
use crate::network::{CellInfo, Network, Patch};

pub(crate) fn list<W: Write + ?Sized, T: std::fmt::Display>(
    w: &mut W,
    xs: impl IntoIterator<Item = T>,
) -> std::io::Result<()> {
    w.write_all(b"[")?;
    for (i, x) in xs.into_iter().enumerate() {
        if i > 0 {
            w.write_all(b",")?;
        }
        write!(w, "{x}")?;
    }
    w.write_all(b"]")
}

fn id(x: u32) -> i64 {
    if x == NONE {
        -1
    } else {
        x as i64
    }
}

/// A cell label as JSON: IA one boolean per function (`f > 0`), MI `[material]`.
pub(crate) fn label_json(mode: Mode, functions: usize, l: &[u64]) -> String {
    match mode {
        Mode::Ia => {
            let bits: Vec<&str> =
                (0..functions).map(|f| if crate::network::sign_bit(l, f) { "true" } else { "false" }).collect();
            format!("[{}]", bits.join(","))
        }
        Mode::Mi => format!("[{}]", l.first().copied().unwrap_or(0)),
    }
}

/// Writes `network.json`; `extra_seconds` are appended to the network's own
/// stage timings; `notes` adds `names` and `measures` when there are any.
/// Everything but `"seconds"` (written last) depends only on the input.
pub fn write_network_json(
    net: &Network,
    notes: &Annotations,
    path: &Path,
    extra_seconds: &[(&str, f64)],
) -> std::io::Result<()> {
    write_atomic_with(path, |w| {
        let mode = match net.mode {
            Mode::Ia => "ia",
            Mode::Mi => "mi",
        };
        write!(w, "{{\"mode\":\"{mode}\",\"functions\":{},\n\"points\":[", net.functions)?;
        for (i, p) in net.points.iter().enumerate() {
            if i > 0 {
                w.write_all(b",")?;
            }
            write!(w, "[{},{},{}]", p[0], p[1], p[2])?;
        }
        w.write_all(b"],\n\"faces\":[")?;
        for f in 0..net.num_faces() {
            if f > 0 {
                w.write_all(b",")?;
            }
            list(w, net.face(f).iter())?;
        }
        w.write_all(b"],\n\"face_label\":[")?;
        for (f, l) in net.face_label.iter().enumerate() {
            if f > 0 {
                w.write_all(b",")?;
            }
            write!(w, "[{},{}]", l[0], l[1])?;
        }
        w.write_all(b"],\n\"face_patch\":")?;
        list(w, net.face_patch.iter())?;
        w.write_all(b",\n\"face_cells\":[")?;
        for (f, c) in net.face_cells.iter().enumerate() {
            if f > 0 {
                w.write_all(b",")?;
            }
            write!(w, "[{},{}]", id(c[0]), id(c[1]))?;
        }
        w.write_all(b"],\n")?;
        write_topology(
            w,
            &TopologyJson {
                mode: net.mode,
                functions: net.functions,
                patches: &net.patches,
                chains: &net.chains,
                chain_patches: &net.chain_patches,
                corners: &net.corners,
                shells: &net.shells,
                cells: &net.cells,
            },
        )?;
        write_notes(w, notes)?;
        if let Some(e) = &net.embedding {
            w.write_all(b",\n\"embedding\":")?;
            serde_json::to_writer(&mut *w, e)?;
        }
        let seconds: Vec<(&str, f64)> = net.seconds.iter().chain(extra_seconds.iter()).copied().collect();
        write_counts_seconds(w, &net.counts(), &seconds)
    })
}

/// The topology part of `network.json`, shared with a stream's
/// `topology.json` (`summary_out.rs`).
pub(crate) struct TopologyJson<'a> {
    pub mode: Mode,
    pub functions: usize,
    pub patches: &'a [Patch],
    pub chains: &'a [Vec<u32>],
    pub chain_patches: &'a [Vec<u32>],
    pub corners: &'a [u32],
    pub shells: &'a [Vec<u32>],
    pub cells: &'a [CellInfo],
}

/// Writes `"patches":[..],\n"chains":[..],\n"chain_patches":[..],\n"corners":[..],\n"shells":[..],\n"cells":[..]`.
pub(crate) fn write_topology<W: Write + ?Sized>(w: &mut W, t: &TopologyJson) -> std::io::Result<()> {
    w.write_all(b"\"patches\":[")?;
    for (i, p) in t.patches.iter().enumerate() {
        if i > 0 {
            w.write_all(b",")?;
        }
        write!(w, "{{\"label\":[{},{}],\"faces\":{}}}", p.label[0], p.label[1], p.faces)?;
    }
    for (name, xs) in [("chains", t.chains), ("chain_patches", t.chain_patches)] {
        write!(w, "],\n\"{name}\":[")?;
        lists(w, xs)?;
    }
    w.write_all(b"],\n\"corners\":")?;
    list(w, t.corners.iter())?;
    w.write_all(b",\n\"shells\":[")?;
    lists(w, t.shells)?;
    w.write_all(b"],\n\"cells\":[")?;
    for (i, c) in t.cells.iter().enumerate() {
        if i > 0 {
            w.write_all(b",")?;
        }
        w.write_all(b"{\"shells\":")?;
        list(w, c.shells.iter())?;
        write!(w, ",\"label\":{}}}", label_json(t.mode, t.functions, &c.label))?;
    }
    w.write_all(b"]")
}

/// `,\n"names":{..}` and `,\n"measures":{..}` when there are any (NaN, a
/// cell without a volume, as `null`).
pub(crate) fn write_notes<W: Write + ?Sized>(w: &mut W, notes: &Annotations) -> std::io::Result<()> {
    if !notes.names.is_empty() {
        write!(w, ",\n\"names\":{}", notes.names.to_json())?;
    }
    if !notes.measures.is_empty() {
        write!(w, ",\n\"measures\":{}", notes.measures.to_json())?;
    }
    Ok(())
}

/// Comma-separated JSON lists.
fn lists<W: Write + ?Sized>(w: &mut W, xs: &[Vec<u32>]) -> std::io::Result<()> {
    for (i, c) in xs.iter().enumerate() {
        if i > 0 {
            w.write_all(b",")?;
        }
        list(w, c.iter())?;
    }
    Ok(())
}

/// Writes `,\n"counts":{..},\n"seconds":{..}}\n`, closing the document.
pub(crate) fn write_counts_seconds<W: Write + ?Sized>(
    w: &mut W,
    counts: &[(&str, usize)],
    seconds: &[(&str, f64)],
) -> std::io::Result<()> {
    w.write_all(b",\n\"counts\":{")?;
    for (i, (k, v)) in counts.iter().enumerate() {
        if i > 0 {
            w.write_all(b",")?;
        }
        write!(w, "\"{k}\":{v}")?;
    }
    w.write_all(b"},\n\"seconds\":{")?;
    for (i, (k, v)) in seconds.iter().enumerate() {
        if i > 0 {
            w.write_all(b",")?;
        }
        write!(w, "\"{k}\":{v}")?;
    }
    w.write_all(b"}}\n")
}

/// Writes `network.ply`: the polygons as triangle fans with `face`, `patch`,
/// `labels_0`, `labels_1`, `cells_0`, `cells_1` and the patch colour
/// (`result_mesh.rs`).
pub fn write_network_ply(net: &Network, path: &Path) -> std::io::Result<()> {
    crate::io::writers::result_mesh::write_ply(
        &ResultView::of_network(net),
        path,
        crate::io::writers::result_mesh::PlyLayout::Full,
    )
}

/// Writes an OBJ: a group per patch, an `l` polyline per chain, the corners as `p`.
pub fn write_network_obj(net: &Network, path: &Path) -> std::io::Result<()> {
    crate::io::writers::result_mesh::write_obj(&ResultView::of_network(net), path)
}

/// Writes a VTK XML unstructured grid (`.vtu`) of the polygons with cell
/// data `patch`, `labels` (2 components) and `cells` (2 components).
pub fn write_network_vtu(net: &Network, path: &Path) -> std::io::Result<()> {
    crate::io::writers::result_vtk::write_vtu(&ResultView::of_network(net), path)
}

/// The JSON of a network's counts, stage seconds and cell method, for
/// `network.npz`'s `meta`.
pub fn network_meta(net: &Network, extra_seconds: &[(&str, f64)]) -> serde_json::Value {
    let mut counts: serde_json::Map<String, serde_json::Value> =
        net.counts().into_iter().map(|(k, v)| (k.to_string(), v.into())).collect();
    counts.insert("components".into(), net.components.into());
    counts.insert("active_tets".into(), net.active_tets.into());
    let seconds: serde_json::Map<String, serde_json::Value> =
        net.seconds.iter().chain(extra_seconds.iter()).map(|(k, v)| (k.to_string(), (*v).into())).collect();
    let mut meta = serde_json::json!({"counts": counts, "seconds": seconds, "cells_method": net.cells_method.as_str()});
    if let Some(e) = &net.embedding {
        meta["embedding"] = serde_json::json!(e);
    }
    meta
}

/// Writes `network.json`, `network.npz`, `network.ply`, `network.obj` and
/// `network.vtu` into `dir` (created if needed): [`Format::DEFAULT`].
pub fn write_network(
    net: &Network,
    notes: &Annotations,
    dir: &Path,
    extra_seconds: &[(&str, f64)],
) -> std::io::Result<()> {
    write_network_formats(net, notes, dir, Format::DEFAULT, extra_seconds)
}

/// Writes `network.<ext>` for each of `formats` (with `notes`: names and
/// measures) into `dir` (created if needed) as one set (`io::outdir`: lock, stale temporaries removed,
/// `manifest.json` last); `network.json` after the others. Errors name the
/// folder or file.
pub fn write_network_formats(
    net: &Network,
    notes: &Annotations,
    dir: &Path,
    formats: &[Format],
    extra_seconds: &[(&str, f64)],
) -> std::io::Result<()> {
    write_network_formats_with(net, notes, dir, formats, extra_seconds, &[])
}

/// A file written beside a result, in the same folder transaction: its
/// name and its bytes (the adaptive grid's `grid.vtu` and `adaptive.json`).
pub type ExtraFile<'a> = (&'a str, &'a [u8]);

/// Every format but JSON of a result view into an open output folder,
/// with the extra files: shared by networks, region results and `septa
/// remesh` (a result read back, remeshed and written again).
pub fn write_view_formats(
    view: &ResultView<'_>,
    out: &mut crate::io::OutputDir,
    formats: &[Format],
    meta: &serde_json::Value,
    extra_files: &[ExtraFile<'_>],
) -> std::io::Result<()> {
    for (name, bytes) in extra_files {
        out.write_path(name, |p| std::fs::write(p, bytes))?;
    }
    for &f in formats.iter().filter(|&&f| f != Format::Json) {
        if let Some(solid) = f.solid() {
            crate::io::writers::solids_out::write_solids_into(view, out, solid)?;
            continue;
        }
        if f == Format::Vtm {
            // The multiblock and its pieces network/<block>.vtu, all staged.
            crate::io::writers::result_vtk::write_vtm_into(view, out, "network")?;
            continue;
        }
        out.write_path(&format!("network.{}", f.name()), |p| {
            crate::io::writers::result_file::write_file(view, p, f, meta)
        })?;
    }
    Ok(())
}

/// [`write_network_formats`] with extra files staged and committed with
/// the result (all or nothing, like the formats themselves).
pub fn write_network_formats_with(
    net: &Network,
    notes: &Annotations,
    dir: &Path,
    formats: &[Format],
    extra_seconds: &[(&str, f64)],
    extra_files: &[ExtraFile<'_>],
) -> std::io::Result<()> {
    let mut out = crate::io::OutputDir::create(dir, "network")?;
    let view = ResultView::of_annotated(net, notes);
    let meta = network_meta(net, extra_seconds);
    write_view_formats(&view, &mut out, formats, &meta, extra_files)?;
    if formats.contains(&Format::Json) {
        out.write_path("network.json", |p| write_network_json(net, notes, p, extra_seconds))?;
    }
    out.finish()
}
