//! Bloomenthal's examples and the CSG check: the topology of each surface
//! and curve of interest, as stated in `scene/builtin.rs`.

use septa::regions::{region_surfaces, RegionOptions, RegionSurfaces};
use septa::scene::Scene;

fn run(name: &str) -> RegionSurfaces {
    let scene = Scene::load(&format!("builtin:{name}")).unwrap();
    let r = region_surfaces(&scene, &RegionOptions::default()).unwrap();
    let mut s: Vec<_> = r.surfaces.iter().map(|s| (s.regions, s.euler, s.boundary_loops, s.faces)).collect();
    s.sort();
    let c: Vec<_> = r.curves.iter().map(|c| (c.regions.clone(), c.closed, c.vertices.len())).collect();
    eprintln!("{name}: surfaces {s:?}\n  curves {c:?}");
    r
}

/// (regions, euler, boundary loops) of every surface, sorted.
fn topology(r: &RegionSurfaces) -> Vec<([i64; 2], i64, usize)> {
    let mut s: Vec<_> = r.surfaces.iter().map(|s| (s.regions.map(|x| x as i64), s.euler, s.boundary_loops)).collect();
    s.sort();
    s
}

/// (regions, closed) of every curve, sorted.
fn curves(r: &RegionSurfaces) -> Vec<(Vec<i64>, bool)> {
    let mut c: Vec<_> = r.curves.iter().map(|c| (c.regions.clone(), c.closed)).collect();
    c.sort();
    c
}

#[test]
fn sphere_with_hole_is_a_disk() {
    let r = run("sphere-with-hole");
    assert_eq!(topology(&r), vec![([0, 2], 1, 1)]);
    assert_eq!(curves(&r), vec![(vec![0, 1, 2], true)]);
}

#[test]
fn sphere_plane_hole() {
    let r = run("sphere-plane-hole");
    assert_eq!(topology(&r), vec![([0, 2], 1, 1), ([0, 3], 1, 1), ([2, 3], 0, 2)]);
    assert_eq!(
        curves(&r),
        vec![
            (vec![0, 1, 2], false),
            (vec![0, 1, 3], false),
            (vec![0, 2, 3], false),
            (vec![1, 2, 3], false),
            (vec![2, 3, 4], true)
        ]
    );
    // The four arcs all end at the same two corners (hole, sphere and plane meet there).
    let mut ends: Vec<[u32; 2]> = r
        .curves
        .iter()
        .filter(|c| !c.closed)
        .map(|c| {
            let (a, b) = (c.vertices[0], *c.vertices.last().unwrap());
            [a.min(b), a.max(b)]
        })
        .collect();
    ends.dedup();
    assert_eq!(ends.len(), 1, "arcs end at {ends:?}");
}

#[test]
fn polygons_are_counter_clockwise_from_the_lesser_region() {
    // Within a surface every interior edge is traversed once in each
    // direction: the orientation is consistent; and the normal of the
    // sphere-with-hole's polygons points to region 0 (outside the sphere).
    let r = run("sphere-with-hole");
    let mut directed = std::collections::HashSet::new();
    for i in 0..r.faces.len() {
        let p = &r.loops[r.loop_start[i] as usize..r.loop_start[i + 1] as usize];
        for k in 0..p.len() {
            assert!(directed.insert((p[k], p[(k + 1) % p.len()])), "edge traversed twice in one direction");
        }
        // Newell normal vs outward direction from the sphere centre (the origin).
        let pts: Vec<[f64; 3]> = p.iter().map(|&v| r.network.points[v as usize]).collect();
        let mut n = [0.0; 3];
        let mut c = [0.0; 3];
        for k in 0..pts.len() {
            let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
            n[0] += (a[1] - b[1]) * (a[2] + b[2]);
            n[1] += (a[2] - b[2]) * (a[0] + b[0]);
            n[2] += (a[0] - b[0]) * (a[1] + b[1]);
            for j in 0..3 {
                c[j] += a[j] / pts.len() as f64;
            }
        }
        assert!(n[0] * c[0] + n[1] * c[1] + n[2] * c[2] > 0.0, "polygon {i} faces into the sphere");
    }
}

#[test]
fn normals_point_into_the_lesser_region() {
    let scene = Scene::load("builtin:sphere-with-hole").unwrap();
    let r = region_surfaces(&scene, &RegionOptions { normals: true, ..Default::default() }).unwrap();
    assert!(!r.normals.is_empty());
    for &(v, pair, n) in &r.normals {
        assert_eq!(pair, [0, 2]);
        let p = r.network.points[v as usize];
        assert!(n[0] * p[0] + n[1] * p[1] + n[2] * p[2] > 0.0);
    }
    // Written out: one row per copy, and every polygon corner names the copy of its own vertex.
    let doc = septa::io::regions_document(&r);
    assert_eq!(doc["normals"]["vertex"].as_array().unwrap().len(), r.normals.len());
    let copies = septa::io::regions_face_normals(&r);
    for (i, c) in copies.iter().enumerate() {
        let poly = &r.loops[r.loop_start[i] as usize..r.loop_start[i + 1] as usize];
        assert!(poly.iter().zip(c).all(|(&v, &k)| r.normals[k as usize].0 == v));
    }
    let plain = region_surfaces(&scene, &RegionOptions::default()).unwrap();
    assert!(septa::io::regions_document(&plain).get("normals").is_none());
}

#[test]
fn saucer_square() {
    let r = run("saucer-square");
    assert_eq!(topology(&r), vec![([1, 2], 1, 1), ([1, 3], 1, 1), ([2, 3], 0, 2)]);
    assert_eq!(curves(&r), vec![(vec![0, 2, 3], true), (vec![1, 2, 3], true)]);
}

#[test]
fn patch_blend() {
    let r = run("patch-blend");
    assert_eq!(topology(&r), vec![([1, 2], 1, 1), ([1, 3], 1, 1), ([2, 3], 0, 2)]);
}

/// (open, closed) feature curves, each between regions 0 and 1 on two
/// functions, and the corners where the open ones end.
fn features(r: &RegionSurfaces) -> (usize, usize, usize) {
    use septa::regions::CurveKind;
    assert!(r.curves.iter().all(|c| c.kind == CurveKind::Feature && c.regions == [0, 1] && c.functions.len() == 2));
    let open = r.curves.iter().filter(|c| !c.closed).count();
    let corners = septa::io::ResultView::of_regions(r).corners.len();
    (open, r.curves.len() - open, corners)
}

#[test]
fn box_minus_cylinder_is_a_torus() {
    let r = run("box-minus-cylinder");
    assert_eq!(topology(&r), vec![([0, 1], 0, 0)]);
    // Its sharp edges: the 12 box edges between the 8 box corners, and the
    // 2 circles where the cylinder meets top and bottom.
    assert_eq!(features(&r), (12, 2, 8));
    let names = |c: &septa::regions::Curve| c.functions.clone();
    // A box edge lies on two of the six half-spaces; a circle on the hole (6) and zlo (4) or zhi (5).
    let mut circles: Vec<Vec<u32>> = r.curves.iter().filter(|c| c.closed).map(names).collect();
    circles.sort();
    assert_eq!(circles, vec![vec![4, 6], vec![5, 6]]);
    // Each box edge is straight and 1 long.
    for c in r.curves.iter().filter(|c| !c.closed) {
        assert!((c.length - 1.0).abs() < 1e-12, "box edge of length {}", c.length);
    }
}

#[test]
fn cad_part_has_genus_3() {
    let r = run("cad-part");
    assert_eq!(topology(&r), vec![([0, 1], -4, 0)]);
    // The plate's pentagonal prism: 15 edges between 10 corners; closed:
    // the boss where it leaves the plate and at its top, the bore at the
    // boss top and the plate bottom, each hole at the plate's top and bottom.
    assert_eq!(features(&r), (15, 8, 10));
}

#[test]
fn features_follow_the_scene() {
    // `"features": false` drops them; an explicit empty `curves` list keeps them.
    let mut scene = Scene::load("builtin:box-minus-cylinder").unwrap();
    scene.interest.features = false;
    assert!(region_surfaces(&scene, &RegionOptions::default()).unwrap().curves.is_empty());
    let text = septa::scene::scene_text(&Scene::load("builtin:box-minus-cylinder").unwrap()).unwrap();
    let doc: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert!(doc.get("features").is_none() && doc.get("curves").is_none());
    let mut doc2 = doc.clone();
    doc2["features"] = serde_json::json!(false);
    let s = Scene::from_json(&doc2.to_string(), "<test>", None).unwrap();
    assert!(!s.interest.features);
    doc2["features"] = serde_json::json!("yes");
    let e = Scene::from_json(&doc2.to_string(), "<test>", None).unwrap_err().to_string();
    assert!(e.contains("features"), "{e}");
}

#[test]
fn two_boxes_in_a_label_volume() {
    // Background 0, box 1 and box 2 side by side: three disks meeting on one loop.
    let n = 12;
    let mut labels = vec![0i64; n * n * n];
    for i in 3..9 {
        for j in 3..7 {
            for k in 3..7 {
                labels[(i * n + j) * n + k] = if i < 6 { 1 } else { 2 };
            }
        }
    }
    for sigma in [0.0, 0.7] {
        let r = septa::regions::label_surfaces(&labels, [n, n, n], sigma).unwrap();
        assert_eq!(topology(&r), vec![([0, 1], 1, 1), ([0, 2], 1, 1), ([1, 2], 1, 1)], "sigma {sigma}");
        assert_eq!(curves(&r), vec![(vec![0, 1, 2], true)], "sigma {sigma}");
    }
    let bad = septa::regions::label_surfaces(&labels, [n, n, n + 1], 0.0);
    assert!(bad.is_err());
}

#[test]
fn box_minus_cylinder_volume_converges() {
    let exact = septa::scene::builtin::box_minus_cylinder_volume();
    let mut errors = Vec::new();
    for n in [11, 21, 41] {
        let mut scene = Scene::load("builtin:box-minus-cylinder").unwrap();
        let [lo, hi] = scene.grid.bounds;
        scene.grid = septa::scene::GridSpec { resolution: [n; 3], bounds: [lo, hi], split: 5 };
        let r = region_surfaces(&scene, &RegionOptions::default()).unwrap();
        assert_eq!(topology(&r), vec![([0, 1], 0, 0)], "resolution {n}");
        errors.push((r.enclosed_volume(1) - exact).abs() / exact);
    }
    eprintln!("relative volume errors {errors:?}");
    assert!(errors[1] < errors[0] && errors[2] < errors[1] && errors[2] < 5e-3, "{errors:?}");
}

/// `network.json` (what the viewer and `septa.load` read) says per polygon
/// what every other format says: `face_cells` index its `cells` (the
/// regions, ascending), `face_label` are the regions of the two sides,
/// lesser (the positive side) first; never the network's internal cells.
#[test]
fn region_json_ids_are_the_result_models() {
    for name in ["cad-part", "sphere-plane-hole"] {
        let r = run(name);
        let doc = septa::io::regions_document(&r);
        let view = septa::io::ResultView::of_regions(&r);
        let cells = doc["cells"].as_array().unwrap();
        let region: Vec<i64> = cells.iter().map(|c| c["label"][0].as_i64().unwrap()).collect();
        assert!(region.windows(2).all(|w| w[0] < w[1]), "{name}: regions ascending");
        let face_cells = doc["face_cells"].as_array().unwrap();
        let face_label = doc["face_label"].as_array().unwrap();
        assert_eq!(face_cells.len(), r.faces.len());
        assert_eq!(face_label.len(), r.faces.len());
        for (i, &f) in r.faces.iter().enumerate() {
            let ids: Vec<i64> = face_cells[i].as_array().unwrap().iter().map(|x| x.as_i64().unwrap()).collect();
            let labels: Vec<i64> = face_label[i].as_array().unwrap().iter().map(|x| x.as_i64().unwrap()).collect();
            assert_eq!(ids, view.cells[i].map(i64::from).to_vec(), "{name} face {i}");
            assert_eq!(labels, view.labels[i].map(i64::from).to_vec(), "{name} face {i}");
            // the ids name the regions of the polygon's two network cells
            let [cp, cn] = r.network.face_cells[f as usize];
            let (a, b) = (r.cell_region[cp as usize], r.cell_region[cn as usize]);
            assert_eq!([region[ids[0] as usize], region[ids[1] as usize]], [a.min(b), a.max(b)], "{name} face {i}");
        }
    }
}
