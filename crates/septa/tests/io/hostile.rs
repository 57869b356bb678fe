//! Hostile inputs to the readers, structure-aware (docs/guide.md on bad input): PLY headers,
//! polyhedral `.vtu` face streams, NRRD headers, `.npz` member headers and
//! region-rule text generated with the counts, indices and nesting that
//! crashed or hung the readers (a count of 1.8e19, a point index `nan`,
//! sizes whose product wraps, a million `!`). Every case returns a value or
//! an error, never a panic, a hang or an allocation of the declared size.
//! Also the messages of failed writes and the inline viewer's escaping.
use std::io::Write;
use std::path::{Path, PathBuf};

use proptest::prelude::*;

use super::readers_fuzz::npy;

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("septa-hostile-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Counts a header may declare: small, honest, and the hostile ones.
fn count() -> impl Strategy<Value = String> {
    prop_oneof![
        (0u64..6).prop_map(|n| n.to_string()),
        Just("100000000000".to_string()),
        Just("18000000000000000000".to_string()),
        Just("18446744073709551615".to_string()),
        Just("-1".to_string()),
        Just("1e11".to_string()),
    ]
}

fn ply() -> impl Strategy<Value = Vec<u8>> {
    let prop = prop_oneof![
        Just("property float x\n"),
        Just("property float y\n"),
        Just("property float z\n"),
        Just("property double w\n"),
        Just("property list uchar int vertex_indices\n"),
        Just("property list uint int vertex_indices\n"),
    ];
    let elem = (prop_oneof![Just("vertex"), Just("face"), Just("junk")], count(), prop::collection::vec(prop, 0..4));
    (
        prop_oneof![Just("ascii"), Just("binary_little_endian"), Just("binary_big_endian")],
        prop::collection::vec(elem, 0..4),
        prop::collection::vec(any::<u8>(), 0..64),
    )
        .prop_map(|(format, elems, body)| {
            let mut s = format!("ply\nformat {format} 1.0\n");
            for (name, n, props) in elems {
                s += &format!("element {name} {n}\n");
                props.iter().for_each(|p| s += p);
            }
            s += "end_header\n";
            let mut b = s.into_bytes();
            b.extend(body);
            b
        })
}

/// A number of a `.vtu` faces stream: ids, counts and the values that were
/// read as point 0 or overflowed a capacity.
fn vtu_number() -> impl Strategy<Value = String> {
    prop_oneof![
        (0u32..6).prop_map(|n| n.to_string()),
        Just("nan".to_string()),
        Just("0.7".to_string()),
        Just("-1".to_string()),
        Just("1e19".to_string()),
        Just("1e12".to_string()),
        Just("inf".to_string()),
    ]
}

fn vtu(faces: &[String], offsets: &[String]) -> String {
    format!(
        r#"<VTKFile type="UnstructuredGrid"><UnstructuredGrid><Piece>
<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 0 1 0 0 0 1</DataArray></Points>
<DataArray type="UInt8" Name="types" format="ascii">42</DataArray>
<DataArray type="Int64" Name="face_connectivity" format="ascii">{}</DataArray>
<DataArray type="Int64" Name="face_offsets" format="ascii">{}</DataArray>
<DataArray type="Int64" Name="polyhedron_to_faces" format="ascii">{}</DataArray>
<DataArray type="Int64" Name="polyhedron_offsets" format="ascii">{}</DataArray>
</Piece></UnstructuredGrid></VTKFile>"#,
        faces.join(" "),
        offsets.join(" "),
        offsets.join(" "),
        offsets.first().cloned().unwrap_or_default()
    )
}

fn vtu_legacy(faces: &[String]) -> String {
    format!(
        r#"<VTKFile type="UnstructuredGrid"><UnstructuredGrid><Piece>
<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 0 1 0 0 0 1</DataArray></Points>
<DataArray type="UInt8" Name="types" format="ascii">42</DataArray>
<DataArray type="Int64" Name="faces" format="ascii">{}</DataArray>
</Piece></UnstructuredGrid></VTKFile>"#,
        faces.join(" ")
    )
}

fn nrrd() -> impl Strategy<Value = Vec<u8>> {
    let size = prop_oneof![
        (1u64..4).prop_map(|n| n.to_string()),
        Just("2305843009213693953".to_string()),
        Just("4294967296".to_string()),
        Just("0".to_string()),
    ];
    (
        prop::array::uniform3(size),
        prop_oneof![Just("raw"), Just("gzip"), Just("ascii")],
        prop_oneof![Just("int8"), Just("uint16"), Just("double")],
        prop::collection::vec(any::<u8>(), 0..40),
    )
        .prop_map(|(s, enc, ty, body)| {
            let mut b =
                format!("NRRD0004\ntype: {ty}\ndimension: 3\nsizes: {} {} {}\nencoding: {enc}\n\n", s[0], s[1], s[2])
                    .into_bytes();
            b.extend(body);
            b
        })
}

fn shape() -> impl Strategy<Value = Vec<usize>> {
    prop_oneof![
        Just(vec![4, 3]),
        Just(vec![1, 4]),
        Just(vec![4]),
        Just(vec![100_000_000_000, 3]),
        Just(vec![1 << 62, 4]),
        Just(vec![]),
    ]
}

fn rule() -> impl Strategy<Value = String> {
    let tok = prop_oneof![Just("!"), Just("("), Just(")"), Just("a"), Just("b"), Just(" & "), Just(" | "), Just(" - ")];
    prop_oneof![
        prop::collection::vec(tok, 0..60).prop_map(|t| t.concat()),
        (0usize..3, 200usize..400).prop_map(|(k, n)| match k {
            0 => format!("{}a", "!".repeat(n)),
            1 => format!("{}a{}", "(".repeat(n), ")".repeat(n)),
            _ => format!("a{}", " - b".repeat(n)),
        }),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn ply_headers_never_hang_or_overallocate(b in ply()) {
        let _ = septa::io::parse_ply(Path::new("fuzz.ply"), &b);
    }

    #[test]
    fn vtu_face_streams_are_read_strictly(
        faces in prop::collection::vec(vtu_number(), 0..24),
        offsets in prop::collection::vec(vtu_number(), 0..4),
        legacy in any::<bool>(),
        case in 0u32..1_000_000,
    ) {
        let d = scratch("vtu");
        let p = d.join(format!("{case}.vtu"));
        std::fs::write(&p, if legacy { vtu_legacy(&faces) } else { vtu(&faces, &offsets) }).unwrap();
        if let Ok((points, cells)) = septa::io::read_polyhedra(&p) {
            // every index read is a point of the file
            prop_assert!(cells.iter().flatten().flatten().all(|&i| (i as usize) < points.len()));
        }
        // one triangle of three drawn ids: read exactly when all three are
        // whole numbers naming one of the 4 points (`nan`, `0.7` were point 0)
        let tri = &faces[..faces.len().min(3)];
        let mut stream = vec!["1".to_string(), tri.len().to_string()];
        stream.extend(tri.iter().cloned());
        std::fs::write(&p, vtu_legacy(&stream)).unwrap();
        let ids_ok = tri.iter().all(|t| t.parse::<u32>().is_ok_and(|i| i < 4));
        prop_assert_eq!(septa::io::read_polyhedra(&p).is_ok(), ids_ok, "{:?}", tri);
        let _ = std::fs::remove_file(&p);
    }

    #[test]
    fn nrrd_headers_never_panic(b in nrrd(), case in 0u32..1_000_000) {
        let d = scratch("nrrd");
        let p = d.join(format!("{case}.nrrd"));
        std::fs::write(&p, &b).unwrap();
        let _ = septa::io::read_label_volume(&p);
        let _ = std::fs::remove_file(&p);
    }

    #[test]
    fn npz_member_headers_bound_what_is_read(shapes in prop::array::uniform3(shape()), case in 0u32..1_000_000) {
        let d = scratch("npz");
        let p = d.join(format!("{case}.npz"));
        let mut z = zip::ZipWriter::new(std::fs::File::create(&p).unwrap());
        for ((name, descr), s) in [("vertices", "<f8"), ("tets", "<i8"), ("values", "<f8")].iter().zip(&shapes) {
            z.start_file(format!("{name}.npy"), zip::write::SimpleFileOptions::default()).unwrap();
            z.write_all(&npy(descr, false, s, &[0u8; 96])).unwrap();
        }
        z.finish().unwrap();
        let _ = septa::io::read_grid_input(&p);
        let _ = std::fs::remove_file(&p);
    }

    #[test]
    fn region_rules_parse_or_refuse(text in rule()) {
        let names = ["a", "b"];
        if let Ok(e) = septa::scene::Expr::parse(&text, &|n: &str| names.iter().position(|x| *x == n)) {
            // the tree is walked without trouble
            let _ = e.eval(&|i| i == 0);
        }
    }
}

#[test]
fn deep_and_long_rules_are_refused_with_the_limit() {
    let resolve = |n: &str| (n == "a").then_some(0);
    let e = septa::scene::Expr::parse(&format!("{}a", "!".repeat(1_000_000)), &resolve).unwrap_err();
    assert!(e.contains("longer than the limit"), "{e}");
    let e = septa::scene::Expr::parse(&format!("{}a{}", "(".repeat(20_000), ")".repeat(20_000)), &resolve).unwrap_err();
    assert!(e.contains("nested deeper than 256"), "{e}");
    // 256 levels are read, and `a - a - a` is `a - (a | a)`
    let ok = format!("{}a{}", "(".repeat(256), ")".repeat(256));
    assert!(septa::scene::Expr::parse(&ok, &resolve).is_ok());
    let chain = septa::scene::Expr::parse(&format!("a{}", " - a".repeat(10_000)), &resolve).unwrap();
    assert!(!chain.eval(&|_| true) && !chain.eval(&|_| false));
}

/// A full disk keeps the system's words and names the final file, not the
/// staged or temporary name (was: the staged name, "No space left" lost).
#[test]
fn failed_writes_name_the_final_file() {
    let d = scratch("enospc");
    let e = septa::io::write_atomic_with(&d.join("cells.vtu"), |_| Err(std::io::Error::from_raw_os_error(28)))
        .unwrap_err()
        .to_string();
    assert!(e.contains("No space left on device") && e.contains("cells.vtu") && !e.contains(".tmp"), "{e}");
    let mut out = septa::io::OutputDir::create(&d.join("o"), "cut").unwrap();
    let e = out.write_with("cells.vtu", |_| Err(std::io::Error::from_raw_os_error(28))).unwrap_err().to_string();
    assert!(e.contains("No space left on device") && e.contains("o/cells.vtu") && !e.contains("staged"), "{e}");
    let e = out
        .write_path("cut.json", |p| Err(std::io::Error::other(format!("writing {}: disk full", p.display()))))
        .unwrap_err()
        .to_string();
    assert!(e.contains("o/cut.json") && !e.contains("staged"), "{e}");
    drop(out);
    let _ = std::fs::remove_dir_all(&d);
}

/// The inline page ends each script where it should: `</SCRIPT>` in any
/// letter case inside the data cannot close the data script (was: only
/// lowercase `</script` was escaped).
#[test]
fn inline_viewer_escapes_script_ends_in_any_case() {
    let net =
        serde_json::json!({"points": [], "faces": [], "note": "</SCRIPT><script>alert(1)</script></ScRiPt ><!--"});
    let plain = serde_json::json!({"points": [], "faces": []});
    let ends = |v: &serde_json::Value| {
        septa::io::viewer_inline_page("t", v, None).to_ascii_lowercase().matches("</script").count()
    };
    assert_eq!(ends(&net), ends(&plain));
    let page = septa::io::viewer_inline_page("t", &net, None);
    assert!(page.contains("alert(1)") && !page.contains("<!--\""), "the text is kept, escaped");
}

/// A string member (`<U3`: three characters of four bytes each) is read
/// whole: the bound on what is inflated counts its bytes, not its characters.
#[test]
fn npz_string_members_are_read_whole() {
    let d = scratch("npz-str");
    let p = d.join("s.npz");
    let mut z = zip::ZipWriter::new(std::fs::File::create(&p).unwrap());
    let utf32: Vec<u8> = "abc".chars().flat_map(|c| (c as u32).to_le_bytes()).collect();
    z.start_file("spec_json.npy", zip::write::SimpleFileOptions::default()).unwrap();
    z.write_all(&npy("<U3", false, &[], &utf32)).unwrap();
    z.start_file("bbox.npy", zip::write::SimpleFileOptions::default()).unwrap();
    z.write_all(&npy("<f8", false, &[2], &[1.0f64, 2.0].iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<_>>()))
        .unwrap();
    z.finish().unwrap();
    let a = septa::io::read_npz(&p).unwrap();
    assert_eq!(a["spec_json"], septa::io::NpyArray::Str("abc".into()));
    assert_eq!(a["bbox"], septa::io::NpyArray::F64(vec![2], vec![1.0, 2.0]));
    let _ = std::fs::remove_dir_all(&d);
}

/// CSG trees of the adaptive-grid paper's format: a chain of nodes deeper
/// than the limit, or nodes shared so often that the expression would
/// double at each level, are errors naming the limit; so is a node key the
/// format does not have.
#[test]
fn csg_trees_deep_or_exploding_are_refused() {
    let tree =
        |n: usize, node: &dyn Fn(usize) -> String| format!("[{}]", (1..=n).map(node).collect::<Vec<_>>().join(","));
    let chain = tree(5000, &|k| {
        let next = if k == 5000 { "-1".to_string() } else { (k + 1).to_string() };
        format!(r#"{{"type":"Negation","elements":[{next},0]}}"#)
    });
    let e = septa::scene::load_csg_tree(&chain, "t.json", 1, false).unwrap_err().to_string();
    assert!(e.contains("deeper than 1024"), "{e}");
    let doubling = tree(60, &|k| {
        let next = if k == 60 { "-1".to_string() } else { (k + 1).to_string() };
        format!(r#"{{"type":"Union","elements":[{next},{next}]}}"#)
    });
    let e = septa::scene::load_csg_tree(&doubling, "t.json", 1, false).unwrap_err().to_string();
    assert!(e.contains("expands to more than"), "{e}");
    // 1000 levels and a few shared nodes are read
    let ok = tree(1000, &|k| {
        let next = if k == 1000 { "-1".to_string() } else { (k + 1).to_string() };
        format!(r#"{{"type":"Negation","elements":[{next},0]}}"#)
    });
    assert!(septa::scene::load_csg_tree(&ok, "t.json", 1, false).unwrap().eval(&|_| true));
    let e = septa::scene::load_csg_tree(r#"[{"type":"Union","elements":[-1,-1],"elemnts":[]}]"#, "t.json", 1, false)
        .unwrap_err()
        .to_string();
    assert!(e.contains("`elemnts`") && e.starts_with("t.json:1:"), "{e}");
}

/// The keys main's scene reader accepts stay accepted (the adaptive-grid
/// paper's `flat` sphere, its grid with `bbox_min`/`bbox_max`, an `rbf`'s
/// display fields), and a key next to them that nothing reads is refused.
#[test]
fn strict_scenes_keep_the_accepted_keys() {
    let scene = |grid: &str, f: &str| format!(r#"{{"grid": {grid}, "functions": [{f}]}}"#);
    let anchor = r#"{"resolution": [2], "bbox_min": [-1,-1,-1], "bbox_max": [1,1,1]}"#;
    let flat = r#"{"type":"sphere","center":[0,0,0],"radius":0.8,"squared":true,"flat":true,"name":"s"}"#;
    septa::scene::Scene::from_json(&scene(anchor, flat), "s.json", None).unwrap();
    let inline_rbf = r#"{"type":"rbf","centers":[[0,0,0]],"coefficients":[1,0,0,0],"polynomial":[-0.5,0,0,0],"color":[1,0,0,1],"samples":"x.xyz"}"#;
    septa::scene::Scene::from_json(&scene(anchor, inline_rbf), "s.json", None).unwrap();
    let bad_grid = r#"{"resolution": [2], "bbox_min": [-1,-1,-1], "bbox_max": [1,1,1], "bbox_mid": 0}"#;
    let e = septa::scene::Scene::from_json(&scene(bad_grid, flat), "s.json", None).unwrap_err().to_string();
    assert!(e.contains("`bbox_mid`"), "{e}");
    let typo = r#"{"type":"sphere","center":[0,0,0],"radiuss":0.8,"radius":0.5}"#;
    let e = septa::scene::Scene::from_json(&scene(anchor, typo), "s.json", None).unwrap_err().to_string();
    assert!(e.contains("`radiuss`"), "{e}");
}
