//! Writing a [`Network`]: `network.json` (the full structure), binary PLY
//! (per-face patch, label and colour) and OBJ (a group per patch, chains as
//! polylines). Every file is written to a temporary file in the same folder
//! and renamed, so a reader never sees a half-written file.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use super::atomic::write_atomic_with;
use crate::complex::NONE;
use crate::network::{CellInfo, Mode, Network, Patch};

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

/// The cell label as JSON: IA a list of booleans (function positive), MI `[material]`.
/// A cell label as JSON: IA one boolean per function (`f > 0`), MI `[material]`.
pub(crate) fn label_json(mode: Mode, functions: usize, l: &[u64]) -> String {
    match mode {
        Mode::Ia => {
            let bits: Vec<&str> = (0..functions)
                .map(|f| if l.get(f / 64).is_some_and(|w| w >> (f % 64) & 1 == 1) { "true" } else { "false" })
                .collect();
            format!("[{}]", bits.join(","))
        }
        Mode::Mi => format!("[{}]", l.first().copied().unwrap_or(0)),
    }
}

/// Writes `network.json`; `extra_seconds` are appended to the network's own stage timings.
/// Everything but `"seconds"` (written last) depends only on the input.
pub fn write_json(net: &Network, path: &Path, extra_seconds: &[(&str, f64)]) -> std::io::Result<()> {
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

/// A colour per patch (golden-ratio hue walk).
pub fn patch_colour(p: u32) -> [u8; 3] {
    let h = (p as f64 * 0.618_033_988_749_895).fract() * 6.0;
    let x = 1.0 - (h % 2.0 - 1.0).abs();
    let (r, g, b) = match h as u32 {
        0 => (1.0, x, 0.0),
        1 => (x, 1.0, 0.0),
        2 => (0.0, 1.0, x),
        3 => (0.0, x, 1.0),
        4 => (x, 0.0, 1.0),
        _ => (1.0, 0.0, x),
    };
    let s = |v: f64| (55.0 + 200.0 * v) as u8;
    [s(r), s(g), s(b)]
}

/// Writes a binary little-endian PLY: vertices (double x, y, z) and the
/// network's polygons as fans of triangles, each with `face` (its polygon
/// in network.json), `patch`, `label0`, `label1` and the patch colour.
/// Triangles because mesh tools (trimesh, meshio) read only face lists of
/// one length with extra properties; the polygons are exact in
/// network.json, network.obj and network.vtu. The polygons are convex, so a
/// fan from their first vertex covers each one.
pub fn write_ply(net: &Network, path: &Path) -> std::io::Result<()> {
    let triangles: usize = (0..net.num_faces()).map(|f| net.face(f).len() - 2).sum();
    write_atomic_with(path, |w| {
        write!(
            w,
            "ply\nformat binary_little_endian 1.0\ncomment septa surface network, polygons as triangle fans\n\
             element vertex {}\nproperty double x\nproperty double y\nproperty double z\n\
             element face {}\nproperty list uchar int vertex_indices\nproperty int face\nproperty int patch\n\
             property int label0\nproperty int label1\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n",
            net.points.len(),
            triangles
        )?;
        for p in &net.points {
            for x in p {
                w.write_all(&x.to_le_bytes())?;
            }
        }
        for f in 0..net.num_faces() {
            let vs = net.face(f);
            let p = net.face_patch[f];
            for j in 1..vs.len() - 1 {
                w.write_all(&[3u8])?;
                for v in [vs[0], vs[j], vs[j + 1]] {
                    w.write_all(&(v as i32).to_le_bytes())?;
                }
                w.write_all(&(f as i32).to_le_bytes())?;
                w.write_all(&(p as i32).to_le_bytes())?;
                w.write_all(&(net.face_label[f][0] as i32).to_le_bytes())?;
                w.write_all(&(net.face_label[f][1] as i32).to_le_bytes())?;
                w.write_all(&patch_colour(p))?;
            }
        }
        Ok(())
    })
}

/// Writes an OBJ: a group `patch_<p>` per patch and an `l` polyline per chain.
pub fn write_obj(net: &Network, path: &Path) -> std::io::Result<()> {
    write_atomic_with(path, |w| {
        writeln!(w, "# septa surface network: {} patches, {} chains", net.patches.len(), net.chains.len())?;
        for p in &net.points {
            writeln!(w, "v {} {} {}", p[0], p[1], p[2])?;
        }
        let mut by_patch: Vec<Vec<u32>> = vec![Vec::new(); net.patches.len()];
        for (f, &p) in net.face_patch.iter().enumerate() {
            by_patch[p as usize].push(f as u32);
        }
        for (p, faces) in by_patch.iter().enumerate() {
            writeln!(w, "g patch_{p}")?;
            for &f in faces {
                w.write_all(b"f")?;
                for &v in net.face(f as usize) {
                    write!(w, " {}", v + 1)?;
                }
                w.write_all(b"\n")?;
            }
        }
        for (c, chain) in net.chains.iter().enumerate() {
            writeln!(w, "g chain_{c}")?;
            w.write_all(b"l")?;
            for &v in chain {
                write!(w, " {}", v + 1)?;
            }
            w.write_all(b"\n")?;
        }
        Ok(())
    })
}

/// Writes a VTK XML unstructured grid (`.vtu`, raw appended binary) of the
/// polygons with cell data `patch`, `label` (2 components) and `cells`
/// (the cells on the positive and negative side, -1 outside the grid).
pub fn write_vtu(net: &Network, path: &Path) -> std::io::Result<()> {
    write_atomic_with(path, |w| {
        let nf = net.num_faces();
        let np = net.points.len();
        // Appended arrays, in order, each preceded by its UInt64 byte count.
        let sizes = [
            (np * 3 * 8, "Float64", "Points", 3),
            (net.face_verts.len() * 4, "Int32", "connectivity", 1),
            (nf * 4, "Int32", "offsets", 1),
            (nf, "UInt8", "types", 1),
            (nf * 4, "Int32", "patch", 1),
            (nf * 2 * 4, "Int32", "label", 2),
            (nf * 2 * 4, "Int32", "cells", 2),
        ];
        let mut offsets = Vec::new();
        let mut off = 0usize;
        for (n, ..) in &sizes {
            offsets.push(off);
            off += 8 + n;
        }
        let da = |i: usize| {
            let (_, ty, name, comps) = sizes[i];
            format!("<DataArray type=\"{ty}\" Name=\"{name}\" NumberOfComponents=\"{comps}\" format=\"appended\" offset=\"{}\"/>\n", offsets[i])
        };
        write!(
            w,
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n\
             <UnstructuredGrid>\n<Piece NumberOfPoints=\"{np}\" NumberOfCells=\"{nf}\">\n<Points>\n{}</Points>\n\
             <Cells>\n{}{}{}</Cells>\n<CellData Scalars=\"patch\">\n{}{}{}</CellData>\n</Piece>\n</UnstructuredGrid>\n\
             <AppendedData encoding=\"raw\">\n_",
            da(0), da(1), da(2), da(3), da(4), da(5), da(6)
        )?;
        let head = |w: &mut BufWriter<File>, i: usize| w.write_all(&(sizes[i].0 as u64).to_le_bytes());
        head(w, 0)?;
        for p in &net.points {
            for x in p {
                w.write_all(&x.to_le_bytes())?;
            }
        }
        head(w, 1)?;
        for &v in &net.face_verts {
            w.write_all(&(v as i32).to_le_bytes())?;
        }
        head(w, 2)?;
        for f in 0..nf {
            w.write_all(&(net.face_start[f + 1] as i32).to_le_bytes())?;
        }
        head(w, 3)?;
        w.write_all(&vec![7u8; nf])?; // VTK_POLYGON
        head(w, 4)?;
        for &p in &net.face_patch {
            w.write_all(&(p as i32).to_le_bytes())?;
        }
        head(w, 5)?;
        for l in &net.face_label {
            w.write_all(&(l[0] as i32).to_le_bytes())?;
            w.write_all(&(l[1] as i32).to_le_bytes())?;
        }
        head(w, 6)?;
        for c in &net.face_cells {
            w.write_all(&(id(c[0]) as i32).to_le_bytes())?;
            w.write_all(&(id(c[1]) as i32).to_le_bytes())?;
        }
        w.write_all(b"\n</AppendedData>\n</VTKFile>\n")
    })
}

/// Writes `network.json`, `network.ply`, `network.obj` and `network.vtu` into `dir` (created if needed).
/// The folder is written as one set (`io::outdir`: lock, stale temporaries
/// removed, `manifest.json` last); errors name the folder or file.
pub fn write_all(net: &Network, dir: &Path, extra_seconds: &[(&str, f64)]) -> std::io::Result<()> {
    let mut out = super::OutputDir::create(dir, "network")?;
    out.write_path("network.ply", |p| write_ply(net, p))?;
    out.write_path("network.obj", |p| write_obj(net, p))?;
    out.write_path("network.vtu", |p| write_vtu(net, p))?;
    out.write_path("network.json", |p| write_json(net, p, extra_seconds))?;
    out.finish()
}
