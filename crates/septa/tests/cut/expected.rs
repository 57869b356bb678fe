//! Cut-cell counts against the TopoCut reference (`topocut/expected.json` in the shared data folder)
//! plus the output checks (faces bound 1-2 cells, volumes, no empty cell).
//! Small meshes by default; all meshes with `SEPTA_FULL=1`; one case with
//! `SEPTA_CASE=name`.

use crate::common;

use septa::cut::{cut_mesh, CutOptions};
use septa::io::{read_mesh, read_planes};
use std::path::Path;

fn data() -> String {
    common::shared_data().display().to_string()
}
const SMALL: &[&str] = &["cube", "staircase", "knight", "plate_genus9", "bunny", "fertility"];

#[test]
fn counts_match_reference() {
    let text = std::fs::read_to_string(format!("{}/topocut/expected.json", data())).unwrap();
    let exp: serde_json::Value = serde_json::from_str(&text).unwrap();
    let full = std::env::var("SEPTA_FULL").is_ok();
    let only = std::env::var("SEPTA_CASE").ok();
    let mut failures = Vec::new();
    let mut ran = 0;
    for (name, case) in exp.as_object().unwrap() {
        let mesh_name = case["mesh"].as_str().unwrap();
        let stem = mesh_name.trim_end_matches(".obj");
        if let Some(o) = &only {
            if o != name {
                continue;
            }
        } else if !full && !SMALL.contains(&stem) {
            continue;
        }
        let mesh = read_mesh(Path::new(&format!("{}/meshes/{mesh_name}", data()))).unwrap();
        let planes =
            read_planes(Path::new(&format!("{}/topocut/{}", data(), case["planes"].as_str().unwrap()))).unwrap();
        let t = std::time::Instant::now();
        let out = cut_mesh(&mesh.vertices, &mesh.triangles, &planes, &CutOptions::default()).unwrap();
        let secs = t.elapsed().as_secs_f64();
        ran += 1;
        let c = out.counts;
        let want = |k: &str| case[k].as_u64().unwrap() as usize;
        let got = [c.cut_vertices, c.cut_edges, c.cut_faces, c.cut_cells];
        let exp4 = [want("cut_vertices"), want("cut_edges"), want("cut_faces"), want("cut_cells")];
        let check = out.validate();
        eprintln!(
            "{name:20} got {got:?} want {exp4:?} {} {:.3}s fallbacks {} check {:?}",
            if got == exp4 { "OK" } else { "MISMATCH" },
            secs,
            out.stats.exact_fallbacks,
            check
                .as_ref()
                .map(|v| (v.euler, v.euler_by_cell, v.domain_euler, v.non_ball_cells, v.volume_relative_error))
                .map_err(|e| e.to_string())
        );
        let euler_ok = check.as_ref().map(|v| v.euler_by_cell == v.domain_euler).unwrap_or(false);
        if got != exp4 || !euler_ok {
            failures.push(name.clone());
        }
    }
    assert!(ran > 0 || only.is_some());
    assert!(failures.is_empty(), "failing cases: {failures:?}");
}
