//! Every case of the shared data folder's `isn/`: counts equal to the reference
//! implementation's (expected.json), on the built-in box grid, and the box
//! grid's tets equal to the input's; and from the analytic functions the
//! values were sampled from (`spec_json`), sparse and streamed with topology.

use crate::common;

use std::path::{Path, PathBuf};

use septa::complex::Mode;
use septa::grid::{BoxGrid, Grid, Split, TetMesh};
use septa::io::{read_grid_input, read_npz, NpyArray};
use septa::network::{
    compute, compute_sparse, stream_topology, NetworkError, NetworkOptions, StreamBlock, StreamError, StreamSink,
};
use septa::scene::load_function_list;

fn data_dir() -> Option<PathBuf> {
    Some(common::shared_data().join("isn"))
}

fn box_grid(path: &Path) -> (Grid, Vec<f64>, usize, septa::io::GridInput) {
    let input = read_grid_input(path).unwrap();
    let r = input.grid_res.expect("grid_res");
    let bbox = input.bbox.expect("bbox");
    let g = BoxGrid::new([r; 3], bbox, Split::Five).unwrap();
    (Grid::Box(g), input.values.clone(), input.k, input)
}

#[test]
fn box_grid_equals_input_tets() {
    let Some(dir) = data_dir() else { return };
    for name in ["shifted4_ia_eps1e-7_R2_s0", "ia4_R20"] {
        let (grid, _, _, input) = box_grid(&dir.join(format!("{name}.npz")));
        assert_eq!(grid.num_tets(), input.tets.len());
        assert_eq!(grid.num_vertices(), input.vertices.len());
        for (t, tet) in input.tets.iter().enumerate() {
            assert_eq!(grid.tet(t).map(|v| v as i64), *tet, "{name} tet {t}");
        }
        for (v, p) in input.vertices.iter().enumerate() {
            let q = grid.vertex(v as u32);
            for a in 0..3 {
                assert!((p[a] - q[a]).abs() <= 1e-12 * (1.0 + p[a].abs()), "{name} vertex {v}");
            }
        }
    }
}

fn check_case(dir: &Path, name: &str, expected: &serde_json::Value, mesh: bool, raytrace: bool) {
    let (grid, values, k, input) = box_grid(&dir.join(format!("{name}.npz")));
    let grid = if mesh { Grid::Mesh(TetMesh::new(input.vertices.clone(), &input.tets).unwrap()) } else { grid };
    let mode = match expected["mode"].as_str().unwrap() {
        "ia" => Mode::Ia,
        _ => Mode::Mi,
    };
    let mut opts = NetworkOptions::new(mode);
    opts.block = 8;
    opts.raytrace = raytrace;
    let net = compute(&grid, &values, k, &opts).unwrap();
    eprintln!("{name} ({}): {:?}", net.cells_method, net.counts());
    let mut wrong = Vec::new();
    for (key, got) in net.counts() {
        let want = expected[key].as_u64().unwrap() as usize;
        if want != got {
            wrong.push(format!("{key}: got {got}, reference {want}"));
        }
    }
    assert!(wrong.is_empty(), "{name}: {wrong:?}");
}

#[test]
fn counts_equal_reference() {
    let Some(dir) = data_dir() else { return };
    let expected: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("expected.json")).unwrap()).unwrap();
    let mut failures = Vec::new();
    for (name, exp) in expected.as_object().unwrap() {
        // Ray shooting (or its fallback), cell grouping, and the input's tets as a mesh.
        for (mesh, raytrace) in [(false, true), (false, false), (true, true)] {
            let r = std::panic::catch_unwind(|| check_case(&dir, name, exp, mesh, raytrace));
            if let Err(e) = r {
                failures.push(e.downcast_ref::<String>().cloned().unwrap_or_else(|| name.clone()));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

struct Faces(usize);

impl StreamSink for Faces {
    fn block(&mut self, b: &StreamBlock) -> std::io::Result<()> {
        self.0 += b.num_polygons();
        Ok(())
    }
}

#[test]
fn sampled_values_analytic_functions_and_the_stream_agree_with_the_reference() {
    // The same cases from their analytic functions: the sparse path (one
    // evaluator for every format) and the stream with topology give the
    // reference's counts, as the sampled values do.
    let Some(dir) = data_dir() else { return };
    let expected: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("expected.json")).unwrap()).unwrap();
    for (name, exp) in expected.as_object().unwrap() {
        let path = dir.join(format!("{name}.npz"));
        let Some(NpyArray::Str(text)) = read_npz(&path).unwrap().remove("spec_json") else {
            panic!("{name}: no spec_json")
        };
        let f = load_function_list(&text, name, None).unwrap();
        let (grid, values, k, _) = box_grid(&path);
        let Grid::Box(g) = &grid else { unreachable!() };
        let mode = if exp["mode"] == "ia" { Mode::Ia } else { Mode::Mi };
        let mut o = NetworkOptions::new(mode);
        o.block = 4;
        let dense = compute(&grid, &values, k, &o).unwrap();
        let (sparse, _) = compute_sparse(g, &f, &o).unwrap();
        assert_eq!(sparse.counts(), dense.counts(), "{name}: sparse from the functions");
        let mut sink = Faces(0);
        match stream_topology(g, &f, &o, 2, &mut sink) {
            Ok((_, summary)) => {
                assert_eq!(summary.counts(), dense.counts(), "{name}: streamed");
                assert_eq!(sink.0, dense.num_faces(), "{name}: streamed faces");
            }
            // Cell grouping in memory (a crack next to sheets touching at points): refused clearly.
            Err(e) => {
                assert_ne!(sparse.cells_method, "raytrace", "{name}: the stream refused: {e}");
                let typed = matches!(&e, StreamError::Network(NetworkError::SheetsTouchAtPoints { labels, .. }) if labels.len() >= 2);
                assert!(typed && e.to_string().contains("touch only at points"), "{name}: {e}");
            }
        }
        for (key, got) in dense.counts() {
            assert_eq!(exp[key].as_u64().unwrap() as usize, got, "{name}: {key}");
        }
    }
}
