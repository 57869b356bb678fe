//! Every primitive: analytic gradient against finite differences, bounds
//! enclose dense samples of random boxes (corners included), bounds are
//! useful far from the surface, and closed-form spot values.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use septa::scene::{load_function_list, Primitive, Scene, TriMesh};

/// One of every primitive type, through the JSON reader.
const ALL: &str = include_str!("../common/all_primitives.json");

fn all() -> Vec<Primitive> {
    load_function_list(ALL, "all.json", None).unwrap()
}

fn random_point(rng: &mut ChaCha8Rng, r: f64) -> [f64; 3] {
    [0, 1, 2].map(|_| rng.gen_range(-r..r))
}

#[test]
fn gradients_match_finite_differences() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for (i, f) in all().iter().enumerate() {
        let mut checked = 0;
        for _ in 0..300 {
            let p = random_point(&mut rng, 0.9);
            let g = f.gradient(p);
            let h = 1e-6;
            let mut smooth = true;
            let mut fd = [0.0; 3];
            for a in 0..3 {
                let (mut pp, mut pm) = (p, p);
                pp[a] += h;
                pm[a] -= h;
                let (fp, f0, fm) = (f.eval(pp), f.eval(p), f.eval(pm));
                let (right, left) = ((fp - f0) / h, (f0 - fm) / h);
                // Skip points next to a kink (one-sided slopes disagree).
                if (right - left).abs() > 1e-3 * (1.0 + right.abs()) {
                    smooth = false;
                }
                fd[a] = (fp - fm) / (2.0 * h);
            }
            if !smooth {
                continue;
            }
            checked += 1;
            for a in 0..3 {
                assert!(
                    (g[a] - fd[a]).abs() < 1e-5 * (1.0 + fd[a].abs()),
                    "primitive {i} at {p:?}: gradient {g:?}, finite differences {fd:?}"
                );
            }
        }
        assert!(checked > 200, "primitive {i}: only {checked} smooth points");
    }
}

#[test]
fn bounds_enclose_dense_samples() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for (i, f) in all().iter().enumerate() {
        for _ in 0..60 {
            let c = random_point(&mut rng, 1.0);
            let size = 10f64.powf(rng.gen_range(-3.0..0.0));
            let half = [0, 1, 2].map(|_| size * rng.gen_range(0.2..1.0));
            let lo = [0, 1, 2].map(|a| c[a] - half[a]);
            let hi = [0, 1, 2].map(|a| c[a] + half[a]);
            let (blo, bhi) = f.bounds(lo, hi);
            assert!(blo <= bhi, "primitive {i}: empty bound");
            let n = 6;
            for x in 0..=n {
                for y in 0..=n {
                    for z in 0..=n {
                        let t = [x, y, z];
                        let p = [0, 1, 2].map(|a| lo[a] + (hi[a] - lo[a]) * t[a] as f64 / n as f64);
                        let p = [0, 1, 2].map(|a| if t[a] == n { hi[a] } else { p[a] });
                        let v = f.eval(p);
                        assert!(
                            blo <= v && v <= bhi,
                            "primitive {i}: {v} at {p:?} outside [{blo}, {bhi}] for box {lo:?} {hi:?}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn bounds_exclude_zero_far_from_the_surface() {
    // Every primitive except those with a zero set near every point
    // (constant, line-like distances are negative: their bounds must say so).
    let f = all();
    let far_lo = [3.0, 3.0, 3.0];
    let far_hi = [3.1, 3.1, 3.1];
    for (i, p) in f.iter().enumerate() {
        let (lo, hi) = p.bounds(far_lo, far_hi);
        let v = p.eval([3.05; 3]);
        assert!(lo <= v && v <= hi);
        assert!(hi - lo < 2.0, "primitive {i}: bound [{lo}, {hi}] too loose");
    }
    // A small box straddling the sphere's surface must contain zero, one
    // inside must be positive.
    let s = Primitive::sphere([0.0; 3], 0.5);
    let (lo, hi) = s.bounds([0.49, -0.01, -0.01], [0.51, 0.01, 0.01]);
    assert!(lo < 0.0 && hi > 0.0);
    let (lo, _) = s.bounds([-0.1; 3], [0.1; 3]);
    assert!(lo > 0.3);
}

#[test]
fn closed_form_values() {
    let b = Primitive::cuboid([0.0; 3], [0.5, 0.5, 0.5]);
    assert_eq!(b.eval([0.0; 3]), 0.5);
    assert_eq!(b.eval([1.0, 0.0, 0.0]), -0.5);
    assert!((b.eval([1.0, 1.0, 0.0]) + 0.5f64.sqrt()).abs() < 1e-15);
    let c = Primitive::capped_cylinder([0.0, 0.0, -1.0], [0.0, 0.0, 1.0], 0.5);
    assert_eq!(c.eval([0.0; 3]), 0.5);
    assert_eq!(c.eval([0.0, 0.0, 1.5]), -0.5);
    assert!((c.eval([1.0, 0.0, 2.0]) + 0.5f64.hypot(1.0)).abs() < 1e-15);
    let t = Primitive::torus([0.0; 3], [0.0, 0.0, 1.0], 0.5, 0.1);
    assert!((t.eval([0.5, 0.0, 0.0]) - 0.1).abs() < 1e-15);
    let l = Primitive::line([0.0; 3], [0.0, 0.0, 1.0]);
    assert_eq!(l.eval([0.3, 0.4, 7.0]), -0.5);
    // A rigid motion of a sphere is the moved sphere.
    let r = septa::scene::rotation([1.0, 2.0, 3.0], 0.7);
    let moved = Primitive::transform(r, [0.2, -0.1, 0.3], Primitive::sphere([0.1, 0.0, 0.0], 0.4)).unwrap();
    let c = [0, 1, 2].map(|i| r[i][0] * 0.1 + [0.2, -0.1, 0.3][i]);
    let direct = Primitive::sphere(c, 0.4);
    for p in [[0.0; 3], [0.5, 0.2, -0.3], [-0.7, 0.1, 0.9]] {
        assert!((moved.eval(p) - direct.eval(p)).abs() < 1e-14);
    }
}

fn parse_obj(text: &str) -> TriMesh {
    let m = septa::io::parse_obj(std::path::Path::new("mem.obj"), text.as_bytes()).unwrap();
    TriMesh::new(m.vertices, m.triangles).unwrap()
}

#[test]
fn mesh_distance_equals_box_distance() {
    // The 12-triangle surface of a cube: its signed distance is the box's.
    let obj = "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n\
               v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n\
               f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    let mesh = parse_obj(obj);
    assert_eq!(mesh.triangles().len(), 12);
    assert!((mesh.winding_number([0.1, 0.2, 0.0]) - 1.0).abs() < 1e-12);
    assert!(mesh.winding_number([1.1, 0.2, 0.0]).abs() < 1e-12);
    let m = Primitive::Mesh(std::sync::Arc::new(mesh));
    let b = Primitive::cuboid([0.0; 3], [0.5; 3]);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for _ in 0..500 {
        let p = random_point(&mut rng, 1.0);
        assert!((m.eval(p) - b.eval(p)).abs() < 1e-12, "at {p:?}");
    }
    assert!(TriMesh::new(vec![[0.0; 3]], vec![[0, 0, 1]]).is_none());
    assert!(TriMesh::new(vec![[0.0; 3]], vec![]).is_none());
}

#[test]
fn mesh_from_obj_file_in_a_scene() {
    let dir = std::env::temp_dir().join(format!("septa_scene_mesh_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("tet.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n")
        .unwrap();
    let text = r#"{"grid": {"resolution": 4, "bounds": [[-1,-1,-1],[1,1,1]]},
        "functions": [{"name": "tet", "type": "mesh", "path": "tet.obj"}]}"#;
    let s = Scene::from_json(text, "s.json", Some(&dir)).unwrap();
    assert!(s.functions[0].eval([0.1, 0.1, 0.1]) > 0.0);
    assert!(s.functions[0].eval([1.0, 1.0, 1.0]) < 0.0);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn stl_binary_and_ascii_match_obj() {
    let obj = "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n\
               v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n\
               f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    let mesh = parse_obj(obj);
    let mut bin = vec![0u8; 80];
    bin.extend((mesh.triangles().len() as u32).to_le_bytes());
    let mut ascii = String::from("solid cube\n");
    for t in mesh.triangles() {
        bin.extend([0u8; 12]);
        ascii.push_str("facet normal 0 0 0\nouter loop\n");
        for &v in t {
            let p = mesh.vertices()[v as usize];
            for c in p {
                bin.extend((c as f32).to_le_bytes());
            }
            ascii.push_str(&format!("vertex {} {} {}\n", p[0], p[1], p[2]));
        }
        bin.extend([0u8; 2]);
        ascii.push_str("endloop\nendfacet\n");
    }
    ascii.push_str("endsolid cube\n");
    let b = Primitive::cuboid([0.0; 3], [0.5; 3]);
    let dir = std::env::temp_dir().join(format!("septa_scene_stl_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("cube_bin.stl"), &bin).unwrap();
    std::fs::write(dir.join("cube_ascii.stl"), &ascii).unwrap();
    std::fs::write(dir.join("cube.obj"), obj).unwrap();
    for f in ["cube_bin.stl", "cube_ascii.stl", "cube.obj"] {
        let m = septa::scene::read_tri_mesh(&dir.join(f)).unwrap();
        assert_eq!(m.triangles().len(), 12);
        let m = Primitive::Mesh(std::sync::Arc::new(m));
        for p in [[0.1, 0.2, -0.3], [0.9, -0.7, 0.2], [0.0, 0.0, 0.45]] {
            assert!((m.eval(p) - b.eval(p)).abs() < 1e-12, "{f} at {p:?}");
        }
    }
    // Through a scene file, by extension.
    std::fs::write(dir.join("cube.stl"), &bin).unwrap();
    let text = r#"{"grid": {"resolution": 4, "bounds": [[-1,-1,-1],[1,1,1]]},
        "functions": [{"type": "mesh", "path": "cube.stl"}]}"#;
    let s = Scene::from_json(text, "s.json", Some(&dir)).unwrap();
    assert_eq!(s.functions[0].eval([0.0; 3]), 0.5);
    std::fs::write(dir.join("bad.stl"), b"solid x\nvertex 1 2\nendsolid\n").unwrap();
    let text = text.replace("cube.stl", "bad.stl");
    let e = Scene::from_json(&text, "s.json", Some(&dir)).unwrap_err();
    assert!(e.message.contains("bad.stl") && e.path.to_string() == "functions[0].path", "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A closed latitude-longitude sphere mesh (outward, counter-clockwise).
fn uv_sphere(r: f64, n: usize) -> septa::scene::TriMesh {
    let mut v = vec![[0.0, 0.0, r], [0.0, 0.0, -r]];
    for i in 1..n {
        let th = std::f64::consts::PI * i as f64 / n as f64;
        for j in 0..2 * n {
            let ph = std::f64::consts::PI * j as f64 / n as f64 + 0.1 * i as f64;
            v.push([r * th.sin() * ph.cos(), r * th.sin() * ph.sin(), r * th.cos()]);
        }
    }
    let id = |i: usize, j: usize| (2 + (i - 1) * 2 * n + j % (2 * n)) as u32;
    let mut t = vec![];
    for j in 0..2 * n {
        t.push([0, id(1, j), id(1, j + 1)]);
        t.push([1, id(n - 1, j + 1), id(n - 1, j)]);
        for i in 1..n - 1 {
            t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    septa::scene::TriMesh::new(v, t).unwrap()
}

#[test]
fn mesh_hierarchy_matches_exhaustive_search() {
    let m = uv_sphere(0.6, 40);
    assert_eq!(m.triangles().len(), 2 * 2 * 40 * 39);
    let mut rng = ChaCha8Rng::seed_from_u64(13);
    let mut near = 0;
    let prim = Primitive::Mesh(std::sync::Arc::new(m.clone()));
    for i in 0..2000 {
        // Half the points within 1% of the surface.
        let dir = normalize3(random_point(&mut rng, 1.0));
        let rad = if i % 2 == 0 { 0.6 * rng.gen_range(0.99..1.01) } else { rng.gen_range(0.0..1.5) };
        let p = dir.map(|x| x * rad);
        let f = prim.eval(p);
        assert_eq!(f.abs(), m.closest_exhaustive(p).0, "distance at {p:?}");
        let exact = m.winding_number_exact(p);
        let fast = m.winding_number(p);
        assert_eq!(exact > 0.5, fast > 0.5, "inside test at {p:?}: {exact} vs {fast}");
        assert!((exact - fast).abs() < 0.05, "{exact} vs {fast}");
        assert_eq!(f > 0.0, exact > 0.5);
        if (rad - 0.6).abs() < 0.006 {
            near += 1;
        }
    }
    assert!(near > 900);
}

fn normalize3(v: [f64; 3]) -> [f64; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|x| x / n)
}
