//! Scene files: every kind of bad input gives an error naming the file,
//! line and field; the accepted forms load to the same rules; sampling is
//! deterministic; block tests never skip an active block.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use septa::scene::{block_may_be_active_ia, block_may_be_active_mi, builtin, sample_grid, Mode, RegionRule, Scene};

fn scene_err(text: &str) -> septa::scene::SceneError {
    Scene::from_json(text, "bad.json", None).unwrap_err()
}

const GRID: &str = r#""grid": {"resolution": 8, "bounds": [[-1,-1,-1],[1,1,1]]}"#;

#[test]
fn errors_name_file_line_and_field() {
    // Unknown primitive.
    let e = scene_err(&format!(
        "{{{GRID},\n \"functions\": [\n  {{\"type\": \"sphere\", \"center\": [0,0,0], \"radius\": 1}},\n  {{\"type\": \"blob\"}}]}}"
    ));
    assert_eq!((e.line, e.path.to_string().as_str()), (4, "functions[1].type"));
    assert!(e.message.contains("unknown primitive `blob`"), "{e}");
    assert!(e.to_string().starts_with("bad.json:4:"), "{e}");

    // Missing parameter.
    let e = scene_err(&format!(
        "{{{GRID},\n \"functions\": [\n  {{\"type\": \"torus\", \"center\": [0,0,0],\n   \"axis_vector\": [0,0,1], \"major_radius\": 1}}]}}"
    ));
    assert_eq!((e.line, e.path.to_string().as_str()), (3, "functions[0]"));
    assert!(e.message.contains("missing parameter `minor_radius`"), "{e}");

    // Negative radius.
    let e = scene_err(&format!(
        "{{{GRID},\n \"functions\": [{{\"type\": \"capsule\", \"a\": [0,0,0], \"b\": [1,0,0],\n \"radius\": -0.2}}]}}"
    ));
    assert_eq!((e.line, e.column, e.path.to_string().as_str()), (3, 12, "functions[0].radius"));
    assert!(e.message.contains("negative radius -0.2"), "{e}");

    // Empty grid: zero resolution, and max not above min.
    let e = scene_err(
        "{\"grid\": {\"resolution\": [4, 0, 4],\n \"bounds\": [[0,0,0],[1,1,1]]}, \"functions\": [{\"type\": \"zero\"}]}",
    );
    assert_eq!((e.line, e.path.to_string().as_str()), (1, "grid.resolution"));
    assert!(e.message.contains("empty grid"), "{e}");
    let e = scene_err(
        "{\"grid\": {\"resolution\": 4,\n \"bounds\": [[0,0,0],[1,0,1]]}, \"functions\": [{\"type\": \"zero\"}]}",
    );
    assert_eq!((e.line, e.path.to_string().as_str()), (2, "grid.bounds"));
    assert!(e.message.contains("empty grid"), "{e}");

    // A region rule referring to an unknown function.
    let e = scene_err(&format!(
        "{{{GRID},\n \"functions\": [{{\"name\": \"a\", \"type\": \"zero\"}}],\n \"regions\": [{{\"when\": \"a\", \"region\": 1}},\n   {{\"when\": \"a & bee\", \"region\": 2}}]}}"
    ));
    assert_eq!((e.line, e.path.to_string().as_str()), (4, "regions[1].when"));
    assert!(e.message.contains("unknown function `bee`"), "{e}");

    // A surface of interest naming a region no rule produces.
    let e = scene_err(&format!(
        "{{{GRID}, \"functions\": [{{\"name\": \"a\", \"type\": \"zero\"}}],\n \"solid\": \"a\", \"surfaces\": [[0, 1], [1, 7]]}}"
    ));
    assert_eq!(e.path.to_string(), "surfaces[1][1]");
    assert_eq!(e.line, 2);

    // A grid whose vertices cannot be numbered.
    let e = scene_err("{\"grid\": {\"resolution\": [100000, 100000, 2], \"bounds\": [[0,0,0],[1,1,1]]}, \"functions\": [{\"type\": \"zero\"}]}");
    assert!(e.message.contains("grid too large"), "{e}");

    // Syntax error: serde_json's line and column.
    let e = scene_err("{\"grid\":\n  {\"resolution\" 4}}");
    assert_eq!(e.line, 2);

    // Duplicate names, bad mode, bad split.
    let e = scene_err(&format!(
        "{{{GRID}, \"functions\": [{{\"name\": \"a\", \"type\": \"zero\"}}, {{\"name\": \"a\", \"type\": \"zero\"}}]}}"
    ));
    assert_eq!(e.path.to_string(), "functions[1].name");
    let e = scene_err(&format!("{{{GRID}, \"mode\": \"xx\", \"functions\": [{{\"type\": \"zero\"}}]}}"));
    assert_eq!(e.path.to_string(), "mode");
    let e = scene_err(
        "{\"grid\": {\"resolution\": 4, \"bounds\": [[0,0,0],[1,1,1]], \"split\": 4}, \"functions\": [{\"type\": \"zero\"}]}",
    );
    assert_eq!(e.path.to_string(), "grid.split");

    // Missing file, unknown built-in.
    assert!(Scene::load("/nonexistent/scene.json").unwrap_err().message.contains("cannot read"));
    assert!(Scene::load("builtin:nope").unwrap_err().message.contains("sphere-with-hole"));
}

#[test]
fn region_forms_agree() {
    let funcs = r#""functions": [{"name": "small", "type": "sphere", "center": [0.25,0.15,0.5], "radius": 0.3},
                                {"name": "large", "type": "sphere", "center": [0,0,0], "radius": 0.6}]"#;
    let forms = [
        r#""regions": [{"when": "small", "region": 1}, {"when": "large", "region": 2}, {"region": 0}]"#,
        r#""regions": {"rules": [{"when": {"function": "small"}, "region": 1}, {"when": "1", "region": 2}], "otherwise": 0}"#,
        r#""regions": [{"when": {"union": ["small"]}, "region": 1}, {"when": {"intersection": ["large", {"complement": "small"}]}, "region": 2}]"#,
    ];
    let reference = builtin::sphere_with_hole();
    for f in forms {
        let s = Scene::from_json(&format!("{{{GRID}, {funcs}, {f}}}"), "s.json", None).unwrap();
        for signs in [[false, false], [false, true], [true, false], [true, true]] {
            assert_eq!(s.regions.region_ia(&signs), reference.regions.region_ia(&signs), "{f}");
        }
    }
    // CSG solid and unnamed functions (named by index).
    let s = Scene::from_json(
        &format!(
            "{{{GRID}, \"functions\": [{{\"type\": \"sphere\", \"center\": [0,0,0], \"radius\": 1}}, {{\"type\": \"plane\", \"point\": [0,0,0], \"normal\": [0,0,1]}}], \"solid\": {{\"difference\": [\"0\", \"1\"]}}}}"
        ),
        "s.json",
        None,
    )
    .unwrap();
    assert_eq!(s.names, vec!["0", "1"]);
    assert_eq!(s.regions, RegionRule::solid(septa::scene::Expr::parse("0 - 1", &|n: &str| n.parse().ok()).unwrap()));
    assert_eq!(s.regions.region_ia(&[true, false]), 1);
    assert_eq!(s.regions.region_ia(&[true, true]), 0);
    assert!(s.interest.surface(0, 1));
}

#[test]
fn reference_function_file_as_scene_functions() {
    let dir = std::env::temp_dir().join(format!("septa_scene_funcs_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("funcs.json"),
        r#"[{"type": "sphere", "center": [0,0,0], "radius": 0.5}, {"type": "zero"}]"#,
    )
    .unwrap();
    std::fs::write(dir.join("scene.json"), format!("{{{GRID}, \"mode\": \"mi\", \"functions\": \"funcs.json\"}}"))
        .unwrap();
    let s = Scene::load(dir.join("scene.json").to_str().unwrap()).unwrap();
    assert_eq!(s.mode, Mode::Mi);
    assert_eq!(s.functions.len(), 2);
    assert_eq!(s.regions.region_mi(1), 1);
    // The reference implementation's own config file loads as a scene.
    std::fs::write(
        dir.join("config.json"),
        r#"{"gridResolution": 20, "gridBbox": [[-1,-1,-1],[1,1,1]], "funcFile": "funcs.json",
            "outputDir": "out", "useLookup": true, "useSecondaryLookup": true, "useTopoRayShooting": true}"#,
    )
    .unwrap();
    let c = Scene::load(dir.join("config.json").to_str().unwrap()).unwrap();
    assert_eq!(c.grid, septa::scene::GridSpec::cube(20, -1.0, 1.0));
    assert_eq!(c.functions, s.functions);
    std::fs::write(
        dir.join("bad.json"),
        "{\"gridResolution\": 0, \"gridBbox\": [[0,0,0],[1,1,1]],\n \"funcFile\": \"funcs.json\"}",
    )
    .unwrap();
    let e = Scene::load(dir.join("bad.json").to_str().unwrap()).unwrap_err();
    assert_eq!((e.line, e.path.to_string().as_str()), (1, "gridResolution"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn every_builtin_loads_and_samples_deterministically() {
    assert_eq!(builtin::list().len(), 8);
    for (name, _) in builtin::list() {
        let s = Scene::load(&format!("builtin:{name}")).unwrap();
        let n = s.grid.resolution;
        assert!(n.iter().all(|&r| (20..=48).contains(&r)), "{name}");
        let pts = s.grid.vertices();
        let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let two = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
        let a = one.install(|| sample_grid(&s.functions, &pts));
        let b = two.install(|| sample_grid(&s.functions, &pts));
        assert!(a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()), "{name}");
        // Once per vertex per function, row-major.
        let k = s.functions.len();
        assert_eq!(a.len(), pts.len() * k);
        let i = pts.len() / 3;
        assert_eq!(a[i * k + k - 1].to_bits(), s.functions[k - 1].eval(pts[i]).to_bits());
        // General position: no sampled value is exactly zero.
        assert!(a.iter().all(|v| *v != 0.0), "{name}: a zero sample");
        // Every region of interest occurs at some vertex.
        if let RegionRule::Rules { .. } = s.regions {
            if s.mode == Mode::Ia {
                let seen: std::collections::BTreeSet<i64> = a
                    .chunks(k)
                    .map(|row| s.regions.region_ia(&row.iter().map(|v| *v > 0.0).collect::<Vec<_>>()))
                    .collect();
                for (x, y) in s.interest.surfaces.iter().flatten() {
                    assert!(seen.contains(x) && seen.contains(y), "{name}: region pair ({x},{y}) unseen");
                }
            }
        }
    }
}

/// Skipped blocks really are empty: on random boxes over the built-in
/// scenes, whenever a block test says "inactive", a dense lattice of samples
/// in the box shows no sign change (IA) or a single material (MI).
#[test]
fn inactive_blocks_are_empty() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let mut skipped = 0;
    for (name, _) in builtin::list() {
        let s = builtin::get(name).unwrap();
        for _ in 0..150 {
            let c = [0, 1, 2].map(|_| rng.gen_range(-1.0..1.0));
            let h = rng.gen_range(0.01..0.2);
            let lo = c.map(|x| x - h);
            let hi = c.map(|x| x + h);
            let n = 5;
            let mut pts = vec![];
            for x in 0..=n {
                for y in 0..=n {
                    for z in 0..=n {
                        let t = [x, y, z];
                        pts.push([0, 1, 2].map(|a| {
                            if t[a] == n {
                                hi[a]
                            } else {
                                lo[a] + 2.0 * h * t[a] as f64 / n as f64
                            }
                        }));
                    }
                }
            }
            let k = s.functions.len();
            let v = sample_grid(&s.functions, &pts);
            let rows: Vec<&[f64]> = v.chunks(k).collect();
            match s.mode {
                Mode::Ia => {
                    if !block_may_be_active_ia(&s.functions, lo, hi) {
                        skipped += 1;
                        for j in 0..k {
                            let pos = rows.iter().filter(|r| r[j] > 0.0).count();
                            let neg = rows.iter().filter(|r| r[j] < 0.0).count();
                            assert!(
                                pos == rows.len() || neg == rows.len(),
                                "{name}: function {j} changes sign in a skipped box"
                            );
                        }
                    }
                }
                Mode::Mi => {
                    if !block_may_be_active_mi(&s.functions, lo, hi) {
                        skipped += 1;
                        let arg = |r: &[f64]| (0..k).max_by(|&a, &b| r[a].total_cmp(&r[b])).unwrap();
                        let m0 = arg(rows[0]);
                        assert!(rows.iter().all(|r| arg(r) == m0), "{name}: two materials in a skipped box");
                    }
                }
            }
        }
    }
    // The test must exercise skipping, not pass vacuously.
    assert!(skipped > 300, "only {skipped} boxes skipped");
}

/// The scene-level block test on the real grid: split every built-in grid
/// into blocks of 4^3 cubes; in every skipped block the sampled grid
/// vertices show no sign change (IA) or one material (MI), and some blocks
/// are skipped.
#[test]
fn scene_blocks_on_grid_vertices() {
    for (name, _) in builtin::list() {
        let s = builtin::get(name).unwrap();
        let n = s.grid.resolution;
        let k = s.functions.len();
        let (mut skipped, mut total) = (0, 0);
        for bi in (0..n[0]).step_by(4) {
            for bj in (0..n[1]).step_by(4) {
                for bk in (0..n[2]).step_by(4) {
                    total += 1;
                    let first = [bi, bj, bk];
                    let last = [0, 1, 2].map(|a| (first[a] + 4).min(n[a]));
                    if s.block_may_be_active(first, last) {
                        continue;
                    }
                    skipped += 1;
                    let mut pts = vec![];
                    for i in first[0]..=last[0] {
                        for j in first[1]..=last[1] {
                            for l in first[2]..=last[2] {
                                pts.push(s.grid.vertex([i, j, l]));
                            }
                        }
                    }
                    let v = sample_grid(&s.functions, &pts);
                    let rows: Vec<&[f64]> = v.chunks(k).collect();
                    let label = |r: &[f64]| -> Vec<bool> {
                        match s.mode {
                            Mode::Ia => r.iter().map(|x| *x > 0.0).collect(),
                            Mode::Mi => {
                                let m = (0..k).max_by(|&a, &b| r[a].total_cmp(&r[b])).unwrap();
                                (0..k).map(|j| j == m).collect()
                            }
                        }
                    };
                    let l0 = label(rows[0]);
                    assert!(rows.iter().all(|r| label(r) == l0), "{name}: block {first:?} skipped but not uniform");
                }
            }
        }
        println!("{name}: skipped {skipped} of {total} blocks");
        // Per-function bounds rarely prove one material dominates a coarse
        // block (MI needs f_i - f_j beyond both widths), so only IA must skip.
        if s.mode == Mode::Ia {
            assert!(skipped > 0, "{name}: nothing skipped");
        }
    }
}

#[test]
fn normals_from_gradients() {
    let s = builtin::sphere_with_hole();
    let large = s.function_index("large").unwrap();
    let n = s.normal_ia(large, [0.6, 0.0, 0.0]);
    assert_eq!(n, [-1.0, 0.0, 0.0]); // into the inside (where f grows)
    assert_eq!(Scene::toward_lesser(n, 2, 0), [1.0, 0.0, 0.0]);
    assert_eq!(Scene::toward_lesser(n, 0, 2), n);
    let a = builtin::apollonius_18();
    let n = a.normal_mi(0, 1, [0.0, 0.0, 0.0]);
    let g = [0, 1, 2].map(|i| a.functions[0].gradient([0.0; 3])[i] - a.functions[1].gradient([0.0; 3])[i]);
    let len = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
    for i in 0..3 {
        assert!((n[i] - g[i] / len).abs() < 1e-15);
    }
}

/// The MI difference bounds (gradient enclosures of spheres, lines,
/// cylinders, planes) on boxes straddling or hugging interfaces: a box
/// declared inactive has one material at every sample.
#[test]
fn mi_difference_bounds_never_skip_an_interface() {
    let mut rng = ChaCha8Rng::seed_from_u64(21);
    let fs = vec![
        septa::scene::Primitive::sphere([0.3, 0.1, 0.0], 0.2),
        septa::scene::Primitive::sphere([-0.4, 0.2, 0.1], 0.1),
        septa::scene::Primitive::sphere([0.0, -0.5, 0.3], 0.15),
        septa::scene::Primitive::line([0.1, 0.1, -0.6], [1.0, 0.3, 0.1]),
        septa::scene::Primitive::cylinder([0.5, -0.5, 0.0], [0.0, 0.2, 1.0], 0.05),
        septa::scene::Primitive::plane([0.0, 0.0, 0.9], [0.1, 0.0, -1.0]),
    ];
    let (mut skipped, mut tried) = (0, 0);
    for _ in 0..3000 {
        let c = [0, 1, 2].map(|_| rng.gen_range(-1.0..1.0));
        let h = 10f64.powf(rng.gen_range(-2.5..-0.5));
        let lo = c.map(|x| x - h);
        let hi = c.map(|x| x + h);
        tried += 1;
        if block_may_be_active_mi(&fs, lo, hi) {
            continue;
        }
        skipped += 1;
        let n = 8;
        let mut owner = None;
        for x in 0..=n {
            for y in 0..=n {
                for z in 0..=n {
                    let t = [x, y, z];
                    let p = [0, 1, 2].map(|a| if t[a] == n { hi[a] } else { lo[a] + 2.0 * h * t[a] as f64 / n as f64 });
                    let v: Vec<f64> = fs.iter().map(|f| f.eval(p)).collect();
                    let m = (0..v.len()).max_by(|&a, &b| v[a].total_cmp(&v[b])).unwrap();
                    assert!(v.iter().enumerate().all(|(j, x)| j == m || *x < v[m]), "tie in a skipped box");
                    assert!(owner.is_none_or(|o| o == m), "two materials in a skipped box {lo:?} {hi:?}");
                    owner = Some(m);
                }
            }
        }
    }
    assert!(skipped > tried / 3, "{skipped} of {tried}");
}

#[test]
fn toml_scenes_load_like_json_and_name_lines() {
    // The same scene in both forms: the same functions, grid and rule.
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/fixtures/two-spheres.toml");
    let toml = &std::fs::read_to_string(&path).unwrap();
    let json = r#"{"mode": "ia", "surfaces": [[0, 2]], "grid": {"resolution": 12, "bounds": [[-1,-1,-1],[1,1,1]]},
      "functions": [{"name": "small", "type": "sphere", "center": [0.25,0.15,0.5], "radius": 0.3},
                    {"name": "large", "type": "sphere", "center": [0,0,0], "radius": 0.6}],
      "regions": [{"when": "small", "region": 1}, {"when": "large", "region": 2}, {"region": 0}]}"#;
    let (a, b) = (Scene::from_toml(toml, "s.toml", None).unwrap(), Scene::from_json(json, "s.json", None).unwrap());
    assert_eq!(
        format!("{:?}", (&a.functions, &a.regions, &a.grid)),
        format!("{:?}", (&b.functions, &b.regions, &b.grid))
    );
    let (ra, rb) = (
        septa::regions::region_surfaces(&a, &Default::default()).unwrap(),
        septa::regions::region_surfaces(&b, &Default::default()).unwrap(),
    );
    assert_eq!(ra.faces, rb.faces);
    assert_eq!(ra.surfaces.len(), 1);
    // Errors name the TOML line and the field.
    let bad = toml.replace("radius = 0.6", "radius = -0.6");
    let e = Scene::from_toml(&bad, "bad.toml", None).unwrap_err();
    assert_eq!((e.file.as_str(), e.line, e.path.to_string().as_str()), ("bad.toml", 20, "functions[1].radius"), "{e}");
    let bad = toml.replace("type = \"sphere\"\ncenter = [0, 0, 0]", "type = \"blob\"\ncenter = [0, 0, 0]");
    let e = Scene::from_toml(&bad, "bad.toml", None).unwrap_err();
    assert_eq!((e.line, e.path.to_string().as_str()), (18, "functions[1].type"), "{e}");
    let e = Scene::from_toml("mode = \"ia\"\n[grid\nresolution = 4\n", "bad.toml", None).unwrap_err();
    assert_eq!(e.line, 2, "{e}");
    // A file ending in .toml is read as TOML.
    let c = Scene::load(path.to_str().unwrap()).unwrap();
    assert_eq!(format!("{:?}", c.functions), format!("{:?}", a.functions));
}
