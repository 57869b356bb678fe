//! `septa ia|mi|regions --adaptive`: the certified adaptive grid from the
//! command line, with grid.vtu and adaptive.json beside the result.
use std::process::Command;

fn septa(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_septa")).args(args).output().unwrap()
}

/// A fresh folder under the system's temporary folder.
fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("septa-adaptive-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn json(path: &std::path::Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn tiny_sphere_found_certified_and_grid_written() {
    let dir = scratch("tiny");
    let scene = dir.join("tiny.json");
    std::fs::write(&scene, r#"[{"type":"sphere","center":[0.1,0.2,0.3],"radius":0.01}]"#).unwrap();
    let out = dir.join("out");
    let s = scene.to_str().unwrap();
    let o = out.to_str().unwrap();
    // At --grid 8 a uniform grid misses the sphere entirely.
    let r = septa(&["ia", s, "--grid", "8", "--bounds", "-1", "-1", "-1", "1", "1", "1", "-o", o, "--json"]);
    assert!(r.status.success());
    let v: serde_json::Value = serde_json::from_slice(&r.stdout).unwrap();
    assert_eq!(v["patches"], 0);
    let r =
        septa(&["ia", s, "--grid", "8", "--bounds", "-1", "-1", "-1", "1", "1", "1", "--adaptive", "-o", o, "--json"]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let v: serde_json::Value = serde_json::from_slice(&r.stdout).unwrap();
    assert_eq!((v["patches"].as_u64(), v["cells"].as_u64()), (Some(1), Some(2)));
    assert_eq!(v["adaptive"]["certified"], true);
    let a = json(&out.join("adaptive.json"));
    assert_eq!(a["leaves"]["min-edge"], 0);
    assert_eq!(a["leaves"]["budget"], 0);
    let tets = a["tets"].as_u64().unwrap();
    assert_eq!(v["tets"].as_u64(), Some(tets));
    // grid.vtu: an appended-raw VTK file naming every tet's stop reason.
    let vtu = std::fs::read(out.join("grid.vtu")).unwrap();
    let head = String::from_utf8_lossy(&vtu[..1500.min(vtu.len())]).to_string();
    assert!(head.contains(&format!("NumberOfCells=\"{tets}\"")) && head.contains("Name=\"stop\""), "{head}");
    // Listed in the folder's manifest.
    let m = std::fs::read_to_string(out.join("manifest.json")).unwrap();
    assert!(m.contains("grid.vtu") && m.contains("adaptive.json"));
}

#[test]
fn budget_and_min_edge_are_reported_never_silent() {
    let dir = scratch("budget");
    let scene = dir.join("tiny.json");
    std::fs::write(&scene, r#"[{"type":"sphere","center":[0.1,0.2,0.3],"radius":0.01}]"#).unwrap();
    let o = dir.join("out");
    let r = septa(&[
        "ia",
        scene.to_str().unwrap(),
        "--grid",
        "8",
        "--bounds",
        "-1",
        "-1",
        "-1",
        "1",
        "1",
        "1",
        "--adaptive",
        "--max-tets",
        "2000",
        "-o",
        o.to_str().unwrap(),
    ]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let text = String::from_utf8_lossy(&r.stdout);
    assert!(text.contains("NOT certified"), "{text}");
    let a = json(&o.join("adaptive.json"));
    assert_eq!(a["certified"], false);
    assert!(a["leaves"]["budget"].as_u64().unwrap() > 0);
    assert!(!a["uncertified_places"].as_array().unwrap().is_empty());
}

#[test]
fn bad_settings_refused_with_the_flag_named() {
    let dir = scratch("bad");
    let scene = dir.join("s.json");
    std::fs::write(&scene, r#"[{"type":"sphere","center":[0,0,0],"radius":0.5}]"#).unwrap();
    let o = dir.join("out");
    for (flag, value) in [("--tolerance", "-1"), ("--min-edge", "0"), ("--max-tets", "10")] {
        let arg = format!("{flag}={value}");
        let r = septa(&["ia", scene.to_str().unwrap(), "--grid", "8", "--adaptive", &arg, "-o", o.to_str().unwrap()]);
        assert!(!r.status.success());
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(err.contains(flag), "{flag}: {err}");
        assert!(!o.join("network.json").exists());
    }
}

#[test]
fn regions_adaptive_runs_on_a_scene() {
    let dir = scratch("regions");
    let o = dir.join("out");
    let r = septa(&[
        "regions",
        "builtin:cad-part",
        "--adaptive",
        "--tolerance",
        "0.05",
        "--max-tets",
        "400000",
        "-o",
        o.to_str().unwrap(),
        "--json",
    ]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let v: serde_json::Value = serde_json::from_slice(&r.stdout).unwrap();
    assert!(v["adaptive"]["tets"].as_u64().unwrap() > 0);
    assert!(o.join("grid.vtu").exists());
}
