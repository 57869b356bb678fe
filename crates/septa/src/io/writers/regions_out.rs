//! Writers for region surfaces: `network.json` in the schema every Septa
//! job writes (the viewer reads it) and `surfaces.obj` (a group per
//! surface, `l` polylines for curves). Files are written atomically.
//!
//! With normals (Bloomenthal 4.5.3.2: one vertex copy per region pair, each
//! with the gradient normal pointing into the lesser region), `network.json`
//! gets `"normals": {"vertex": [..], "regions": [[a, b], ..], "normal":
//! [[x, y, z], ..]}` (one row per copy) and `"face_normals"` (per polygon,
//! the copy of each of its vertices), and `surfaces.obj` writes the copies
//! as `vn` lines referenced by `f v//vn`: a vertex shared by two surfaces
//! keeps one position and gets one normal per surface.

use std::fmt::Write as _;
use std::path::Path;

use serde_json::{json, Value};

use crate::io::writers::result::{Format, ResultView};
use crate::regions::RegionSurfaces;

/// The JSON summary: counts, surfaces and curves (what `--json` prints).
pub fn regions_summary(r: &RegionSurfaces) -> Value {
    let net = &r.network;
    let mut counts = serde_json::Map::new();
    for (name, n) in net.counts() {
        counts.insert(name.to_string(), json!(n));
    }
    json!({
        "mode": "regions",
        "network": counts,
        "vertices": distinct_vertices(r),
        "faces": r.faces.len(),
        "regions": r.region_ids().iter().enumerate().map(|(i, &g)| {
            let mut o = json!({"region": g, "volume": finite(r.measures.cell_volume.get(i))});
            if let Some(n) = r.names.region(g) {
                o["name"] = json!(n);
            }
            o
        }).collect::<Vec<_>>(),
        "surfaces": r.surfaces.iter().enumerate().map(|(i, s)| json!({"regions": s.regions, "faces": s.faces,
            "euler": s.euler, "boundary_loops": s.boundary_loops, "area": finite(r.measures.patch_area.get(i))}))
            .collect::<Vec<_>>(),
        "curves": r.curves.iter().map(|c| json!({"kind": c.kind.as_str(), "regions": c.regions, "functions": c.functions,
            "function_names": c.functions.iter().map(|&f| r.names.function(f as usize)).collect::<Vec<_>>(),
            "closed": c.closed, "length": c.length, "vertices": c.vertices.len()})).collect::<Vec<_>>(),
        "names": r.names.to_json(),
        "seconds": r.seconds.iter().map(|(k, v)| (k.to_string(), json!(v))).collect::<serde_json::Map<_, _>>(),
        "embedding": r.embedding,
        "clean": r.clean.map(|c| json!({"triangles_before": c.triangles_before, "triangles_after": c.triangles_after,
            "collapsed": c.collapsed, "refused": c.refused, "flipped": c.flipped,
            "min_angle_degrees": {"before": c.min_angle[0], "after": c.min_angle[1]}})),
    })
}

/// A measure as JSON: `null` when unknown or not finite.
fn finite(x: Option<&f64>) -> Value {
    match x {
        Some(&v) if v.is_finite() => json!(v),
        _ => Value::Null,
    }
}

/// Number of distinct network vertices of the kept polygons (a mark per
/// network vertex: no set of 700,000 entries built for one count).
fn distinct_vertices(r: &RegionSurfaces) -> usize {
    let mut used = vec![false; r.network.points.len()];
    r.loops.iter().filter(|&&v| !std::mem::replace(&mut used[v as usize], true)).count()
}

/// Per polygon of `r`, the normal copy (row of `r.normals`) of each of its
/// vertices: the copy of (vertex, the polygon's region pair). Empty without normals.
pub fn regions_face_normals(r: &RegionSurfaces) -> Vec<Vec<u32>> {
    if r.normals.is_empty() {
        return Vec::new();
    }
    let net = &r.network;
    // `r.normals` is sorted by (vertex, pair): binary search.
    let copy = |v: u32, pair: [crate::scene::RegionId; 2]| -> u32 {
        r.normals.binary_search_by(|(w, q, _)| (*w, *q).cmp(&(v, pair))).map(|i| i as u32).unwrap_or(u32::MAX)
    };
    (0..r.faces.len())
        .map(|i| {
            let [cp, cn] = net.face_cells[r.faces[i] as usize];
            let (a, b) = (r.cell_region[cp as usize], r.cell_region[cn as usize]);
            let pair = [a.min(b), a.max(b)];
            r.loops[r.loop_start[i] as usize..r.loop_start[i + 1] as usize].iter().map(|&v| copy(v, pair)).collect()
        })
        .collect()
}

/// The `network.json` document of region surfaces (the schema every job
/// writes). Per polygon `face_label` and `face_cells` come from the one
/// result model ([`ResultView::of_regions`]), as in every other format:
/// `face_cells` index `cells` (the regions, ascending), never the
/// underlying network's internal cells.
pub fn regions_document(r: &RegionSurfaces) -> Value {
    let view = ResultView::of_regions(r);
    let polys: Vec<&[u32]> = (0..view.num_faces()).map(|f| view.face(f)).collect();
    let mut doc = json!({
        "mode": "regions",
        "points": view.points,
        "faces": polys,
        "face_label": view.labels,
        "face_patch": view.patch,
        "face_cells": view.cells,
        "patches": r.surfaces.iter().map(|s| json!({"label": s.regions, "faces": s.faces, "euler": s.euler, "boundary_loops": s.boundary_loops})).collect::<Vec<_>>(),
        "chains": view.chains,
        "chain_regions": r.curves.iter().map(|c| &c.regions).collect::<Vec<_>>(),
        "chain_kind": r.curves.iter().map(|c| c.kind.as_str()).collect::<Vec<_>>(),
        "corners": view.corners,
        "shells": view.shells,
        "cells": view.cell_labels.iter().map(|l| json!({"shells": [], "label": l})).collect::<Vec<_>>(),
        "counts": regions_summary(r),
        "seconds": r.seconds.iter().map(|(k, v)| (k.to_string(), json!(v))).collect::<serde_json::Map<_, _>>(),
    });
    if !r.names.is_empty() {
        doc["names"] = r.names.to_json();
    }
    if !r.measures.is_empty() {
        doc["measures"] = r.measures.to_json();
    }
    if !r.normals.is_empty() {
        doc["normals"] = json!({
            "vertex": r.normals.iter().map(|n| n.0).collect::<Vec<_>>(),
            "regions": r.normals.iter().map(|n| n.1).collect::<Vec<_>>(),
            "normal": r.normals.iter().map(|n| n.2).collect::<Vec<_>>(),
        });
        doc["face_normals"] = json!(regions_face_normals(r));
    }
    doc
}

/// Writes `network.json`, `network.npz`, `network.ply`, `network.obj`,
/// `network.vtu` ([`Format::DEFAULT`]) and `surfaces.obj` into `dir`.
pub fn write_regions(r: &RegionSurfaces, dir: &Path) -> std::io::Result<()> {
    write_regions_formats(r, dir, Format::DEFAULT)
}

/// Writes `network.<ext>` for each of `formats` (the result vocabulary of
/// `result.rs`: patches are the surfaces, chains the curves) and, with
/// JSON, `surfaces.obj` (a group per surface named by its regions, normals
/// as `vn`) into `dir` (created if needed), as one set (`io::outdir`: lock,
/// stale temporaries removed, `manifest.json` last).
pub fn write_regions_formats(r: &RegionSurfaces, dir: &Path, formats: &[Format]) -> std::io::Result<()> {
    write_regions_formats_with(r, dir, formats, &[])
}

/// [`write_regions_formats`] with extra files committed with the result
/// (`ExtraFile`: the adaptive grid's `grid.vtu`, `adaptive.json`).
pub fn write_regions_formats_with(
    r: &RegionSurfaces,
    dir: &Path,
    formats: &[Format],
    extra_files: &[super::network_out::ExtraFile<'_>],
) -> std::io::Result<()> {
    let mut out = crate::io::OutputDir::create(dir, "regions")?;
    let meta = json!({"counts": regions_summary(r),
        "seconds": r.seconds.iter().map(|(k, v)| (k.to_string(), json!(v))).collect::<serde_json::Map<_, _>>()});
    let view = ResultView::of_regions(r);
    super::network_out::write_view_formats(&view, &mut out, formats, &meta, extra_files)?;
    if !formats.contains(&Format::Json) {
        return out.finish();
    }
    let net = &r.network;
    let polys: Vec<&[u32]> =
        (0..r.faces.len()).map(|i| &r.loops[r.loop_start[i] as usize..r.loop_start[i + 1] as usize]).collect();
    out.write("network.json", regions_document(r).to_string().as_bytes())?;
    let mut obj = String::from("# Septa region surfaces: a group per surface, curves as polylines\n");
    for p in &net.points {
        writeln!(obj, "v {} {} {}", p[0], p[1], p[2]).unwrap();
    }
    for (_, _, n) in &r.normals {
        writeln!(obj, "vn {} {} {}", n[0], n[1], n[2]).unwrap();
    }
    let copies = regions_face_normals(r);
    for (s, surf) in r.surfaces.iter().enumerate() {
        writeln!(obj, "g surface_{s}_regions_{}_{}", surf.regions[0], surf.regions[1]).unwrap();
        for (i, poly) in polys.iter().enumerate() {
            if r.face_surface[i] as usize == s {
                let ids: Vec<String> = match copies.get(i) {
                    Some(c) => poly.iter().zip(c).map(|(v, n)| format!("{}//{}", v + 1, n + 1)).collect(),
                    None => poly.iter().map(|v| (v + 1).to_string()).collect(),
                };
                writeln!(obj, "f {}", ids.join(" ")).unwrap();
            }
        }
    }
    for (i, c) in r.curves.iter().enumerate() {
        let regions: Vec<String> = c.regions.iter().map(|x| x.to_string()).collect();
        writeln!(obj, "g curve_{i}_regions_{}", regions.join("_")).unwrap();
        let ids: Vec<String> = c.vertices.iter().map(|v| (v + 1).to_string()).collect();
        writeln!(obj, "l {}", ids.join(" ")).unwrap();
    }
    out.write("surfaces.obj", obj.as_bytes())?;
    out.finish()
}
