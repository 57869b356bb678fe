//! Bloomenthal's examples and the CSG check: the topology of each surface
//! and curve of interest, as stated in `scene/builtin.rs`.

use septa::regions::{region_surfaces, RegionOptions, RegionSurfaces};
use septa::scene::Scene;

fn run(name: &str) -> RegionSurfaces {
    let scene = Scene::load(&format!("builtin:{name}")).unwrap();
    let r = region_surfaces(&scene, &RegionOptions::default()).unwrap();
    let mut s: Vec<_> = r.surfaces.iter().map(|s| (s.regions, s.euler, s.boundary_loops, s.faces)).collect();
    s.sort();
    let c: Vec<_> = r.curves.iter().map(|c| (c.regions, c.closed, c.vertices.len())).collect();
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
fn curves(r: &RegionSurfaces) -> Vec<([i64; 3], bool)> {
    let mut c: Vec<_> = r.curves.iter().map(|c| (c.regions.map(|x| x as i64), c.closed)).collect();
    c.sort();
    c
}

#[test]
fn sphere_with_hole_is_a_disk() {
    let r = run("sphere-with-hole");
    assert_eq!(topology(&r), vec![([0, 2], 1, 1)]);
    assert_eq!(curves(&r), vec![([0, 1, 2], true)]);
}

#[test]
fn sphere_plane_hole() {
    let r = run("sphere-plane-hole");
    assert_eq!(topology(&r), vec![([0, 2], 1, 1), ([0, 3], 1, 1), ([2, 3], 0, 2)]);
    assert_eq!(
        curves(&r),
        vec![([0, 1, 2], false), ([0, 1, 3], false), ([0, 2, 3], false), ([1, 2, 3], false), ([2, 3, 4], true)]
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
    assert_eq!(curves(&r), vec![([0, 2, 3], true), ([1, 2, 3], true)]);
}

#[test]
fn patch_blend() {
    let r = run("patch-blend");
    assert_eq!(topology(&r), vec![([1, 2], 1, 1), ([1, 3], 1, 1), ([2, 3], 0, 2)]);
}

#[test]
fn box_minus_cylinder_is_a_torus() {
    let r = run("box-minus-cylinder");
    assert_eq!(topology(&r), vec![([0, 1], 0, 0)]);
}

#[test]
fn cad_part_has_genus_3() {
    let r = run("cad-part");
    assert_eq!(topology(&r), vec![([0, 1], -4, 0)]);
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
        assert_eq!(curves(&r), vec![([0, 1, 2], true)], "sigma {sigma}");
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
