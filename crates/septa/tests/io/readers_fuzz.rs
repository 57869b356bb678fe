//! Readers on the arrays users have (which used to fail: Fortran order, big-endian,
//! bool and float `.npy`) and fuzzed with arbitrary bytes and mutated valid
//! files (bounded: a fixed number of proptest cases per reader, no timing):
//! each returns a value or an error, never panics, and a header claiming
//! more items than the file holds is refused before allocating.
use std::path::Path;

use proptest::prelude::*;
use septa::io::{parse_npy, NpyArray};

/// A `.npy` version 1 file.
pub(crate) fn npy(descr: &str, fortran: bool, shape: &[usize], data: &[u8]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(|s| s.to_string()).collect();
    let shape = if dims.len() == 1 { format!("({},)", dims[0]) } else { format!("({})", dims.join(", ")) };
    let mut h = format!(
        "{{'descr': '{descr}', 'fortran_order': {}, 'shape': {shape}, }}",
        if fortran { "True" } else { "False" }
    );
    while (10 + h.len() + 1) % 64 != 0 {
        h.push(' ');
    }
    h.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(h.len() as u16).to_le_bytes());
    out.extend_from_slice(h.as_bytes());
    out.extend_from_slice(data);
    out
}

const SHAPE: [usize; 3] = [2, 3, 4];

/// Value of C-order element `(i, j, k)`: distinct per element, so any
/// misplaced element shows.
fn val(i: usize, j: usize, k: usize) -> i64 {
    (100 * i + 10 * j + k) as i64 - 7
}

fn c_order() -> Vec<i64> {
    let mut v = Vec::new();
    for i in 0..SHAPE[0] {
        for j in 0..SHAPE[1] {
            for k in 0..SHAPE[2] {
                v.push(val(i, j, k));
            }
        }
    }
    v
}

fn f_order() -> Vec<i64> {
    let mut v = Vec::new();
    for k in 0..SHAPE[2] {
        for j in 0..SHAPE[1] {
            for i in 0..SHAPE[0] {
                v.push(val(i, j, k));
            }
        }
    }
    v
}

#[test]
fn npy_orders_byte_orders_and_dtypes() {
    let want = NpyArray::I64(SHAPE.to_vec(), c_order());
    let le = |v: &[i64]| v.iter().flat_map(|x| (*x as i32).to_le_bytes()).collect::<Vec<u8>>();
    let be = |v: &[i64]| v.iter().flat_map(|x| (*x as i32).to_be_bytes()).collect::<Vec<u8>>();
    assert_eq!(parse_npy(&npy("<i4", false, &SHAPE, &le(&c_order()))).unwrap(), want);
    assert_eq!(parse_npy(&npy("<i4", true, &SHAPE, &le(&f_order()))).unwrap(), want, "Fortran order");
    assert_eq!(parse_npy(&npy(">i4", false, &SHAPE, &be(&c_order()))).unwrap(), want, "big-endian");
    assert_eq!(parse_npy(&npy(">i4", true, &SHAPE, &be(&f_order()))).unwrap(), want, "big-endian Fortran");
    let f8: Vec<u8> = f_order().iter().flat_map(|x| (*x as f64).to_be_bytes()).collect();
    let NpyArray::F64(s, d) = parse_npy(&npy(">f8", true, &SHAPE, &f8)).unwrap() else { panic!("not floats") };
    assert_eq!((s, d), (SHAPE.to_vec(), c_order().iter().map(|&x| x as f64).collect::<Vec<f64>>()));
    let bools: Vec<u8> = c_order().iter().map(|x| (x % 2 != 0) as u8).collect();
    let NpyArray::I64(_, d) = parse_npy(&npy("|b1", false, &SHAPE, &bools)).unwrap() else { panic!("not ints") };
    assert_eq!(d, bools.iter().map(|&b| b as i64).collect::<Vec<_>>());
    let u8s: Vec<u8> = (0..24).collect();
    assert_eq!(parse_npy(&npy("|u1", false, &[24], &u8s)).unwrap(), NpyArray::I64(vec![24], (0..24).collect()));
}

#[test]
fn npy_bad_headers_are_errors() {
    // A header claiming 2^40 items over 16 bytes: refused before allocating.
    let e = parse_npy(&npy("<f8", false, &[1 << 40], &[0; 16])).unwrap_err();
    assert!(e.contains("truncated"), "{e}");
    assert!(parse_npy(&npy("<f8", false, &[usize::MAX, 3], &[])).is_err());
    assert!(parse_npy(&npy("<c16", false, &[1], &[0; 16])).is_err());
    assert!(parse_npy(b"\x93NUMPY\x01\x00\xff\xff{").is_err());
    assert!(parse_npy(b"PK\x03\x04").is_err());
}

const OFF: &str = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
const OBJ: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
const PLY: &str = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
const MSH: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n$Elements\n1\n1 4 0 1 2 3 4\n$EndElements\n";
const PLANES: &str = "2 4\n1 0 0 -0.5\n0 1 0 -0.25\n";
const FUNCS: &str =
    r#"[{"type":"sphere","center":[0,0,0],"radius":0.5},{"type":"plane","point":[0,0,0],"normal":[0,0,1]}]"#;
const SCENE: &str = r#"{"grid":{"resolution":4,"bounds":[[-1,-1,-1],[1,1,1]]},"functions":[{"name":"a","type":"sphere","center":[0,0,0],"radius":0.5}],"regions":"a"}"#;

/// Every reader on the same bytes: values or errors, never a panic.
fn all_readers(b: &[u8]) {
    let p = Path::new("fuzz");
    let _ = parse_npy(b);
    let _ = septa::io::parse_off(p, b);
    let _ = septa::io::parse_obj(p, b);
    let _ = septa::io::parse_ply(p, b);
    let _ = septa::io::parse_stl(p, b);
    if let Ok(t) = std::str::from_utf8(b) {
        let _ = septa::io::parse_planes(p, t);
        let _ = septa::io::parse_msh(t, "fuzz");
        let _ = septa::scene::load_function_list(t, "fuzz", None);
        let _ = septa::scene::Scene::from_json(t, "fuzz", None);
    }
}

/// A valid file with a few bytes replaced, inserted or removed.
fn mutated() -> impl Strategy<Value = Vec<u8>> {
    let npy_ok =
        npy("<i4", true, &SHAPE, &f_order().iter().flat_map(|x| (*x as i32).to_le_bytes()).collect::<Vec<_>>());
    let seeds: Vec<Vec<u8>> =
        vec![npy_ok, OFF.into(), OBJ.into(), PLY.into(), MSH.into(), PLANES.into(), FUNCS.into(), SCENE.into()];
    (0..seeds.len(), prop::collection::vec((any::<usize>(), any::<u8>(), 0u8..3), 1..6)).prop_map(move |(s, edits)| {
        let mut b = seeds[s].clone();
        for (at, byte, op) in edits {
            let i = at % (b.len() + 1);
            match op {
                0 if i < b.len() => b[i] = byte,
                1 => b.insert(i, byte),
                _ if i < b.len() => {
                    b.remove(i);
                }
                _ => {}
            }
        }
        b
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn readers_never_panic_on_bytes(b in prop::collection::vec(any::<u8>(), 0..300)) {
        all_readers(&b);
    }

    #[test]
    fn readers_never_panic_on_mutated_files(b in mutated()) {
        all_readers(&b);
    }

    #[test]
    fn tet_mesh_validation_never_panics(
        v in prop::collection::vec(prop::array::uniform3(prop_oneof![Just(0.0), Just(1.0), Just(-1.0), Just(f64::NAN), Just(1e-300)]), 0..8),
        t in prop::collection::vec(prop::array::uniform4(-2i64..10), 0..6),
    ) {
        let _ = septa::grid::TetMesh::new(v, &t);
    }
}
