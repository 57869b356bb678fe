//! `septa ia|mi|regions` evaluate analytic functions sparsely by default:
//! the JSON summary reports the blocks, `--dense` opts out with identical
//! output files, `--sparse` is accepted as a no-op, and input that sparse
//! evaluation cannot take (sampled values) still runs, densely.
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("septa-sparse-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn septa(args: &[&str]) -> serde_json::Value {
    let out = Command::new(env!("CARGO_BIN_EXE_septa")).args(args).output().unwrap();
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

/// network.json without its trailing "seconds" object.
fn network_json(dir: &Path) -> Vec<u8> {
    let bytes = std::fs::read(dir.join("network.json")).unwrap();
    let cut = bytes.windows(11).rposition(|w| w == b"\"seconds\":{").expect("seconds written last");
    bytes[..cut].to_vec()
}

#[test]
fn ia_and_mi_are_sparse_by_default_and_equal_dense() {
    for (mode, spec) in [("ia", "nested8"), ("mi", "mi18")] {
        let spec = root().join(format!("data/specs/{spec}.json"));
        let spec = spec.to_str().unwrap();
        let (a, b, c) =
            (scratch(&format!("{mode}-default")), scratch(&format!("{mode}-dense")), scratch(&format!("{mode}-alias")));
        let base = [mode, spec, "--grid", "24", "--block", "4", "--json", "-o"];
        let sparse = septa(&[&base[..], &[a.to_str().unwrap()]].concat());
        let dense = septa(&[&base[..], &[b.to_str().unwrap(), "--dense"]].concat());
        let alias = septa(&[&base[..], &[c.to_str().unwrap(), "--sparse"]].concat());
        let blocks = &sparse["blocks"];
        assert_eq!(blocks["total"], 216, "{mode}: {sparse}");
        let n = |k: &str| blocks[k].as_u64().unwrap();
        assert_eq!(n("skipped") + n("sampled"), 216);
        assert!(n("active") <= n("sampled") && n("skipped") > 0, "{mode}: {blocks}");
        assert!(dense.get("blocks").is_none(), "{mode}: --dense reports no blocks");
        assert_eq!(alias["blocks"], sparse["blocks"]);
        for k in ["active_tets", "patches", "chains", "cells", "faces", "vertices"] {
            assert_eq!(sparse[k], dense[k], "{mode}: {k}");
        }
        assert_eq!(network_json(&a), network_json(&b), "{mode}: network.json");
        assert_eq!(network_json(&a), network_json(&c), "{mode}: network.json");
    }
}

#[test]
fn regions_sparse_by_default_and_npz_stays_dense() {
    // Written into a scratch folder: regions writes its files like every command.
    let dir = std::env::temp_dir().join(format!("septa-sparse-regions-{}", std::process::id()));
    let out = dir.to_str().unwrap();
    let r = septa(&["regions", "builtin:sphere-with-hole", "--json", "-o", out]);
    let d = septa(&["regions", "builtin:sphere-with-hole", "--json", "--dense", "-o", out]);
    let _ = std::fs::remove_dir_all(&dir);
    assert!(r["blocks"]["skipped"].as_u64().unwrap() > 0, "{r}");
    assert!(d.get("blocks").is_none());
    assert_eq!(r["network"], d["network"]);
    assert_eq!(r["curves"].as_array().unwrap().len(), d["curves"].as_array().unwrap().len());
    // Sampled values (the reference's ia4_R20.npz): the dense path, no
    // blocks, even with --sparse.
    let shared = std::env::var("SEPTA_SHARED").map(PathBuf::from).unwrap_or_else(|_| root().join("../shared"));
    let npz = [shared.join("data/isn/ia4_R20.npz"), PathBuf::from("/work/shared/data/isn/ia4_R20.npz")]
        .into_iter()
        .find(|p| p.exists())
        .expect("reference data shared/data not found: set SEPTA_SHARED to the shared/ folder");
    let out = scratch("npz");
    let s = septa(&["ia", npz.to_str().unwrap(), "--json", "--sparse", "-o", out.to_str().unwrap()]);
    assert!(s.get("blocks").is_none(), "{s}");
    assert_eq!(s["cells"], 16, "{s}");
}

#[test]
fn stream_writes_topology_unless_polygons_only() {
    let spec = root().join("data/specs/ia18.json");
    let spec = spec.to_str().unwrap();
    let dir = scratch("stream");
    let (a, b) = (dir.join("a.ply"), dir.join("b.ply"));
    let full = septa(&["ia", spec, "--grid", "20", "--block", "8", "--json", "-o", dir.join("mem").to_str().unwrap()]);
    let s = septa(&["ia", spec, "--grid", "20", "--block", "8", "--json", "--stream", a.to_str().unwrap()]);
    // The topology streamed equals the in-memory run's counts, and its JSON is beside the PLY.
    for k in ["vertices", "faces", "edges", "patches", "chains", "corners", "shells", "cells", "components"] {
        assert_eq!(s["counts"][k], full[k], "{k}");
    }
    let topo: serde_json::Value = serde_json::from_slice(&std::fs::read(dir.join("a.topology.json")).unwrap()).unwrap();
    assert_eq!(topo["counts"], s["counts"]);
    assert_eq!(topo["cells"].as_array().unwrap().len(), full["cells"].as_u64().unwrap() as usize);
    let p = septa(&[
        "ia",
        spec,
        "--grid",
        "20",
        "--block",
        "8",
        "--json",
        "--stream",
        b.to_str().unwrap(),
        "--polygons-only",
    ]);
    assert!(p.get("counts").is_none() && !dir.join("b.topology.json").exists());
    assert_eq!((p["faces"].clone(), p["vertices"].clone()), (s["faces"].clone(), s["vertices"].clone()));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn stream_takes_faces_lying_in_tet_faces() {
    // Three coordinate planes (grid planes at 16^3, on block boundaries for
    // blocks of 4) and a sphere through grid vertices: streamed with the
    // in-memory run's topology, in .ply and .vtu alike.
    let dir = scratch("stream-degenerate");
    let f = dir.join("axes.json");
    std::fs::write(
        &f,
        r#"[{"type": "plane", "point": [0, 0, 0], "normal": [1, 0, 0]},
            {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]},
            {"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]},
            {"type": "sphere", "center": [0, 0, 0], "radius": 0.5}]"#,
    )
    .unwrap();
    let f = f.to_str().unwrap();
    let mem = septa(&["ia", f, "--grid", "16", "--block", "4", "--json", "-o", dir.join("mem").to_str().unwrap()]);
    assert_eq!(
        (&mem["patches"], &mem["chains"], &mem["corners"], &mem["cells"]),
        (&32.into(), &24.into(), &13.into(), &16.into())
    );
    // Into a folder that does not exist yet: made, as -o folders are.
    for out in ["new/s.ply", "s.vtu"] {
        let s =
            septa(&["ia", f, "--grid", "16", "--block", "4", "--json", "--stream", dir.join(out).to_str().unwrap()]);
        for k in ["vertices", "faces", "edges", "patches", "chains", "corners", "shells", "cells", "components"] {
            assert_eq!(s["counts"][k], mem[k], "{out}: {k}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn scenes_in_json_and_toml_give_the_same_network_sparse_and_dense() {
    let dir = scratch("toml");
    let json = r#"{"mode": "ia", "grid": {"resolution": 14, "bounds": [[-1,-1,-1],[1,1,1]]},
      "functions": [{"name": "a", "type": "sphere", "center": [0.25,0.15,0.5], "radius": 0.3},
                    {"name": "b", "type": "sphere", "center": [0,0,0], "radius": 0.6}]}"#;
    let toml = "mode = \"ia\"\n[grid]\nresolution = 14\nbounds = [[-1, -1, -1], [1, 1, 1]]\n\
        [[functions]]\nname = \"a\"\ntype = \"sphere\"\ncenter = [0.25, 0.15, 0.5]\nradius = 0.3\n\
        [[functions]]\nname = \"b\"\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 0.6\n";
    std::fs::write(dir.join("s.json"), json).unwrap();
    std::fs::write(dir.join("s.toml"), toml).unwrap();
    let mut outs = Vec::new();
    for file in ["s.json", "s.toml"] {
        for dense in [false, true] {
            let out = dir.join(format!("{file}-{dense}"));
            let f = dir.join(file);
            let mut args = vec!["ia", f.to_str().unwrap(), "--json", "-o", out.to_str().unwrap()];
            if dense {
                args.push("--dense");
            }
            let s = septa(&args);
            assert!(s["faces"].as_u64().unwrap() > 0, "{file} dense {dense}");
            outs.push(network_json(&out));
        }
    }
    assert!(outs.windows(2).all(|w| w[0] == w[1]), "JSON/TOML, sparse/dense: the same network.json");
    let _ = std::fs::remove_dir_all(&dir);
}
