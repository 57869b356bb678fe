//! The reference implementation's primitive format loads unchanged and
//! samples to the reference data's values bit for bit: every case in
//! `shared/data/isn/` is re-sampled from its own `spec_json` at the grid
//! vertices built by `GridSpec` (also compared bit for bit with the stored
//! `vertices`).
//!
//! The npz reader here is a private test helper (zip central directory,
//! deflate via miniz_oxide, the `.npy` header by hand).

use std::collections::HashMap;
use std::path::PathBuf;

use septa::scene::{load_function_list, sample_grid, GridSpec};

fn data_dir() -> PathBuf {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let mut candidates = vec![];
    if let Ok(d) = std::env::var("SEPTA_SHARED") {
        candidates.push(PathBuf::from(d).join("data/isn"));
    }
    // The repo root's sibling `shared/` (CI and the main checkout), then
    // the machine-wide copy used by worktrees.
    candidates.push(manifest.join("../../../shared/data/isn"));
    candidates.push(PathBuf::from("/work/shared/data/isn"));
    candidates
        .into_iter()
        .find(|p| p.join("expected.json").exists())
        .expect("reference data shared/data/isn not found (set SEPTA_SHARED)")
}

struct Npy {
    shape: Vec<usize>,
    descr: String,
    data: Vec<u8>,
}

fn u16le(b: &[u8], i: usize) -> usize {
    u16::from_le_bytes([b[i], b[i + 1]]) as usize
}

fn u32le(b: &[u8], i: usize) -> usize {
    u32::from_le_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]]) as usize
}

fn read_npz(path: &PathBuf) -> HashMap<String, Npy> {
    let z = std::fs::read(path).unwrap();
    let eocd = (0..=z.len() - 22).rev().find(|&i| z[i..i + 4] == [0x50, 0x4b, 0x05, 0x06]).expect("zip end record");
    let n = u16le(&z, eocd + 10);
    let mut at = u32le(&z, eocd + 16);
    let mut out = HashMap::new();
    for _ in 0..n {
        assert_eq!(z[at..at + 4], [0x50, 0x4b, 0x01, 0x02]);
        let method = u16le(&z, at + 10);
        let csize = u32le(&z, at + 20);
        let name_len = u16le(&z, at + 28);
        let extra = u16le(&z, at + 30);
        let comment = u16le(&z, at + 32);
        let local = u32le(&z, at + 42);
        let name = String::from_utf8(z[at + 46..at + 46 + name_len].to_vec()).unwrap();
        at += 46 + name_len + extra + comment;
        let start = local + 30 + u16le(&z, local + 26) + u16le(&z, local + 28);
        let raw = &z[start..start + csize];
        let bytes = match method {
            0 => raw.to_vec(),
            8 => miniz_oxide::inflate::decompress_to_vec(raw).unwrap(),
            m => panic!("zip method {m}"),
        };
        out.insert(name.trim_end_matches(".npy").to_string(), parse_npy(&bytes));
    }
    out
}

fn parse_npy(b: &[u8]) -> Npy {
    assert_eq!(&b[..6], b"\x93NUMPY");
    let (hlen, hstart) = if b[6] == 1 { (u16le(b, 8), 10) } else { (u32le(b, 8), 12) };
    let header = std::str::from_utf8(&b[hstart..hstart + hlen]).unwrap();
    let field = |k: &str| {
        let i = header.find(k).unwrap() + k.len();
        header[i..].trim_start_matches([':', ' ']).to_string()
    };
    let descr = field("'descr'");
    let descr = descr[1..].split('\'').next().unwrap().to_string();
    assert!(field("'fortran_order'").starts_with("False"));
    let shape_s = field("'shape'");
    let shape_s = &shape_s[1..shape_s.find(')').unwrap()];
    let shape = shape_s.split(',').filter(|s| !s.trim().is_empty()).map(|s| s.trim().parse().unwrap()).collect();
    Npy { shape, descr, data: b[hstart + hlen..].to_vec() }
}

impl Npy {
    fn f64s(&self) -> Vec<f64> {
        assert_eq!(self.descr, "<f8");
        self.data.chunks_exact(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect()
    }
    fn i64s(&self) -> Vec<i64> {
        assert_eq!(self.descr, "<i8");
        self.data.chunks_exact(8).map(|c| i64::from_le_bytes(c.try_into().unwrap())).collect()
    }
    /// A numpy unicode scalar (`<U...`, UTF-32 little endian).
    fn text(&self) -> String {
        assert!(self.descr.starts_with("<U"));
        self.data
            .chunks_exact(4)
            .map(|c| u32::from_le_bytes(c.try_into().unwrap()))
            .take_while(|&c| c != 0)
            .map(|c| char::from_u32(c).unwrap())
            .collect()
    }
}

#[test]
fn reference_cases_resample_bit_for_bit() {
    let dir = data_dir();
    let mut cases: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "npz"))
        .collect();
    cases.sort();
    assert!(cases.len() >= 9, "expected the 9 reference cases");
    for case in cases {
        let npz = read_npz(&case);
        let spec = npz["spec_json"].text();
        let functions = load_function_list(&spec, "spec_json", None).unwrap();
        let r = npz["grid_res"].i64s()[0] as usize;
        let bbox = npz["bbox"].f64s();
        let grid = GridSpec {
            resolution: [r; 3],
            bounds: [[bbox[0], bbox[1], bbox[2]], [bbox[3], bbox[4], bbox[5]]],
            split: 5,
        };
        let verts = grid.vertices();
        let stored_v = npz["vertices"].f64s();
        assert_eq!(npz["vertices"].shape, vec![verts.len(), 3]);
        let flat: Vec<f64> = verts.iter().flatten().copied().collect();
        assert!(flat.iter().zip(&stored_v).all(|(a, b)| a.to_bits() == b.to_bits()), "{case:?}: grid vertices differ");
        let values = sample_grid(&functions, &verts);
        let stored = npz["values"].f64s();
        assert_eq!(npz["values"].shape, vec![verts.len(), functions.len()]);
        let differing = values.iter().zip(&stored).filter(|(a, b)| a.to_bits() != b.to_bits()).count();
        assert_eq!(differing, 0, "{case:?}: {differing} values differ");
    }
}

#[test]
fn reference_function_file_variants() {
    // `{"input": [...]}` (the reference's BSH compatibility), every
    // reference type, `squared`, and a negative radius (unsigned sphere).
    let text = r#"{"input": [
        {"type": "sphere", "center": [0,0,0], "radius": 0.5, "squared": true},
        {"type": "sphere", "center": [0,0,0], "radius": -0.5},
        {"type": "plane", "point": [0,0,0], "normal": [0,0,2]},
        {"type": "line", "point": [0,0,0], "unit_vector": [0,0,1]},
        {"type": "cylinder", "axis_point1": [0,0,0], "axis_point2": [0,0,3], "radius": 0.2},
        {"type": "cylinder", "axis_point": [0,0,0], "axis_vector": [0,0,1], "radius": 0.2, "squared": true},
        {"type": "torus", "center": [0,0,0], "axis_vector": [0,0,1], "major_radius": 0.2, "minor_radius": 0.1},
        {"type": "circle", "center": [0,0,0], "axis_vector": [0,0,1], "radius": 0.2},
        {"type": "cone", "apex": [0,0,0], "axis_vector": [0,0,1], "apex_angle": 0.5},
        {"type": "zero"}]}"#;
    let f = load_function_list(text, "funcs.json", None).unwrap();
    let p = [0.3, 0.4, 1.0];
    let v: Vec<f64> = f.iter().map(|f| f.eval(p)).collect();
    let d = (0.09f64 + 0.16 + 1.0).sqrt();
    let expect = [
        0.25 - (0.09 + 0.16 + 1.0),
        -(0.5 - d).abs(),
        1.0,
        -0.5,
        0.2 - 0.5,
        0.04 - 0.25,
        0.1 - ((0.5f64 - 0.2).powi(2) + 1.0).sqrt(),
        -((0.5f64 - 0.2).powi(2) + 1.0).sqrt(),
        1.0 - 0.5f64.cos() * d,
        0.0,
    ];
    for (i, (a, b)) in v.iter().zip(expect).enumerate() {
        assert!((a - b).abs() < 1e-14, "function {i}: {a} vs {b}");
    }
}
