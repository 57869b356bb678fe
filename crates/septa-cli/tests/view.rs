//! `septa view` on the hand-made fixture (tests/fixtures/two-planes, written
//! by scripts/make_fixture.py) and on bad input.
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("septa-view-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn septa(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_septa")).args(args).output().unwrap()
}

#[test]
fn view_writes_self_contained_folder() {
    let dir = scratch("fixture");
    std::fs::copy(root().join("tests/fixtures/two-planes/network.json"), dir.join("network.json")).unwrap();
    let out = septa(&["view", dir.to_str().unwrap(), "--no-open"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v = dir.join("viewer");
    // The bundle written is the committed, built one (byte for byte).
    let dist = root().join("viewer/dist");
    for f in ["index.html", "viewer.js"] {
        assert_eq!(std::fs::read(v.join(f)).unwrap(), std::fs::read(dist.join(f)).unwrap(), "{f}");
    }
    let data = std::fs::read_to_string(v.join("data.js")).unwrap();
    let json = data.strip_prefix("window.__SEPTA_DATA = ").unwrap().trim_end().trim_end_matches(';');
    let value: serde_json::Value = serde_json::from_str(json).unwrap();
    assert_eq!(value["network"]["patches"].as_array().unwrap().len(), 4);
    assert_eq!(value["network"]["cells"].as_array().unwrap().len(), 4);
    // Nothing is loaded from the network at view time.
    let html = std::fs::read_to_string(v.join("index.html")).unwrap();
    assert!(!html.contains("http://") && !html.contains("https://"));
    assert!(!std::fs::read_dir(&v).unwrap().any(|e| e.unwrap().path().extension().is_some_and(|x| x == "tmp-septa")));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn view_reads_cut_cells_obj() {
    let dir = scratch("cut");
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\ng cell0\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    std::fs::write(dir.join("cells.obj"), obj).unwrap();
    let out = septa(&["view", dir.to_str().unwrap(), "--no-open"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let data = std::fs::read_to_string(dir.join("viewer/data.js")).unwrap();
    assert!(data.contains("\"mode\":\"cut\""));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn view_rejects_folder_without_results() {
    let dir = scratch("empty");
    let out = septa(&["view", dir.to_str().unwrap(), "--no-open"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("network.json"), "{err}");
    std::fs::write(dir.join("network.json"), "{\"points\": [1,\n").unwrap();
    let out = septa(&["view", dir.to_str().unwrap(), "--no-open"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("network.json:2") && err.contains("invalid JSON"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn demo_prints_table() {
    let dir = scratch("demo");
    let out = septa(&["demo", "--out", dir.join("d").to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("vertices") && text.contains("cells") && text.contains("septa view"), "{text}");
    assert!(dir.join("d").is_dir());
    // The streamed job: the reference's topology of 18 spheres (1944 patches,
    // 1908 chains, 636 corners, 672 shells and cells), files but no viewer.
    let row = text.lines().find(|l| l.starts_with("stream-ia18")).unwrap_or_else(|| panic!("{text}"));
    let cols: Vec<&str> = row.split_whitespace().collect();
    assert_eq!(&cols[3..8], &["1944", "1908", "636", "672", "672"], "{row}");
    let s = dir.join("d").join("stream-ia18");
    assert!(s.join("stream.ply").is_file() && s.join("stream.topology.json").is_file());
    assert!(!s.join("viewer").exists());
    // `septa view` on that folder writes its viewer (the stream's polygons
    // with the topology file's patches).
    let out = septa(&["view", s.to_str().unwrap(), "--no-open"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let data = std::fs::read_to_string(s.join("viewer/data.js")).unwrap();
    assert!(data.contains("\"face_patch\""), "no per-face patches in the stream's viewer");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn view_reads_a_stream_folder() {
    // A streamed network (`--stream`): polygons in NAME.ply, topology in
    // NAME.topology.json; the viewer shows both, with the stream's counts.
    let dir = scratch("stream");
    let ply = dir.join("stream.ply");
    let out = septa(&["ia", "builtin:sphere-with-hole", "--stream", ply.to_str().unwrap(), "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let out = septa(&["view", dir.to_str().unwrap(), "--no-open"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let data = std::fs::read_to_string(dir.join("viewer/data.js")).unwrap();
    let json = data.strip_prefix("window.__SEPTA_DATA = ").unwrap().trim_end().trim_end_matches(';');
    let net = &serde_json::from_str::<serde_json::Value>(json).unwrap()["network"];
    let faces = net["faces"].as_array().unwrap();
    let n = |v: &serde_json::Value| v.as_array().unwrap().len();
    assert_eq!(faces.len(), n(&net["face_patch"]));
    assert_eq!(faces.len(), n(&net["face_cells"]));
    assert_eq!(faces.len() as u64, summary["faces"].as_u64().unwrap());
    let topo = &summary["counts"];
    assert_eq!(n(&net["patches"]) as u64, topo["patches"].as_u64().unwrap(), "{summary}");
    assert_eq!(n(&net["cells"]) as u64, topo["cells"].as_u64().unwrap());
    // Every face names its patch: as many faces per patch as the topology says.
    let mut per_patch = vec![0u64; n(&net["patches"])];
    for p in net["face_patch"].as_array().unwrap() {
        per_patch[p.as_u64().expect("a patch id, not -1") as usize] += 1;
    }
    let expected: Vec<u64> = net["patches"].as_array().unwrap().iter().map(|p| p["faces"].as_u64().unwrap()).collect();
    assert_eq!(per_patch, expected);
    // A PLY that is not a stream's is refused with its name.
    std::fs::write(&ply, b"ply\nformat ascii 1.0\nend_header\n").unwrap();
    let out = septa(&["view", dir.to_str().unwrap(), "--no-open"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("stream.ply"), "{}", String::from_utf8_lossy(&out.stderr));
}

/// The network of a viewer's data.js.
fn viewer_network(viewer: &Path) -> serde_json::Value {
    let data = std::fs::read_to_string(viewer.join("data.js")).unwrap();
    let json = data.strip_prefix("window.__SEPTA_DATA = ").unwrap().trim_end().trim_end_matches(';');
    serde_json::from_str::<serde_json::Value>(json).unwrap()["network"].clone()
}

#[test]
fn view_reads_a_vtu_stream_and_a_stream_file() {
    // `--stream OUT.vtu` used to give a folder `septa view` refused. The .vtu
    // holds the same polygons, labels, patches and cells as the PLY stream.
    let (pdir, vdir) = (scratch("stream-ply"), scratch("stream-vtu"));
    for (dir, name) in [(&pdir, "s.ply"), (&vdir, "s.vtu")] {
        let out = septa(&["ia", "builtin:sphere-with-hole", "--stream", dir.join(name).to_str().unwrap(), "-q"]);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    }
    let out = septa(&["view", vdir.to_str().unwrap(), "--no-open"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let out = septa(&["view", pdir.join("s.ply").to_str().unwrap(), "--no-open"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let (mut from_vtu, mut from_ply) = (viewer_network(&vdir.join("viewer")), viewer_network(&pdir.join("viewer")));
    let faces = from_vtu["faces"].as_array().unwrap().len();
    assert!(faces > 100, "{faces} faces");
    for net in [&mut from_vtu, &mut from_ply] {
        net.as_object_mut().unwrap().remove("seconds");
    }
    assert_eq!(from_vtu, from_ply);
    // The file named directly: the viewer goes beside it.
    let out = septa(&["view", vdir.join("s.vtu").to_str().unwrap(), "--no-open"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    // A truncated .vtu is refused with its name, not a panic.
    let bytes = std::fs::read(vdir.join("s.vtu")).unwrap();
    std::fs::write(vdir.join("s.vtu"), &bytes[..bytes.len() / 2]).unwrap();
    let out = septa(&["view", vdir.to_str().unwrap(), "--no-open"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("s.vtu"), "{}", String::from_utf8_lossy(&out.stderr));
}
