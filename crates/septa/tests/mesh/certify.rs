//! Certification of the written doubles (`septa::mesh::certify_*`): after
//! it, the exact check finds no coincident points, no degenerate triangle
//! and no crossing pair on every built-in scene, grid networks, label
//! volumes (placed by a rotation too), and on inputs damaged on purpose;
//! and it changes no count: every polygon keeps its vertex cycle (a
//! rotation of its loop at most), surfaces and curves their topology.

use crate::common;
use septa::complex::Mode;
use septa::grid::{BoxGrid, Grid, Split};
use septa::mesh::{certify_network, certify_regions, check_network, check_regions, place_labels};
use septa::network::{compute, Network, NetworkOptions};
use septa::regions::{label_surfaces, region_surfaces, RegionSurfaces};
use septa::scene::Scene;

/// The loop as a cycle: rotated to start at its smallest vertex.
fn cycle(l: &[u32]) -> Vec<u32> {
    let m = (0..l.len()).min_by_key(|&i| l[i]).unwrap();
    (0..l.len()).map(|i| l[(m + i) % l.len()]).collect()
}

fn same_polygons(start: &[u32], a: &[u32], b: &[u32]) {
    for f in 0..start.len() - 1 {
        let r = start[f] as usize..start[f + 1] as usize;
        assert_eq!(cycle(&a[r.clone()]), cycle(&b[r]), "polygon {f} changed");
    }
}

fn moved_little(a: &[[f64; 3]], b: &[[f64; 3]], h: f64) {
    for (p, q) in a.iter().zip(b) {
        let d = (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt();
        assert!(d <= h, "a vertex moved by {d} (more than {h})");
    }
}

fn certified_regions(name: &str) -> (RegionSurfaces, RegionSurfaces) {
    let scene = Scene::load(name).unwrap();
    let raw = region_surfaces(&scene, &Default::default()).unwrap();
    let mut r = raw.clone();
    let grid = scene.grid.box_grid().unwrap();
    let e = certify_regions(&mut r, Some(&grid), Some(grid.bounds));
    assert_eq!(e.after.violations(), 0, "{name}: {:?}", e.after);
    assert_eq!(e.after.triangles, e.before.triangles);
    assert_eq!(check_regions(&r, Some(grid.bounds)), e.after, "{name}: the report is the check of what is kept");
    // the cells the kept surfaces close: all but the one around the others
    assert!(e.after.cells_positive + 1 >= e.after.cells_checked, "{name}: {:?}", e.after);
    same_polygons(&r.loop_start, &raw.loops, &r.loops);
    let h = (0..3).map(|k| (grid.bounds[1][k] - grid.bounds[0][k]) / grid.res[k] as f64).fold(f64::INFINITY, f64::min);
    moved_little(&raw.network.points, &r.network.points, h / 8.0);
    let topo =
        |r: &RegionSurfaces| -> Vec<_> { r.surfaces.iter().map(|s| (s.regions, s.euler, s.boundary_loops)).collect() };
    assert_eq!(topo(&raw), topo(&r));
    (raw, r)
}

#[test]
fn builtin_scenes_are_certified() {
    for (name, _) in septa::scene::builtin::list() {
        certified_regions(&format!("builtin:{name}"));
    }
}

#[test]
fn cad_part_is_repaired() {
    // as computed, its doubles have two vertices at one point, degenerate
    // triangles and crossing pairs (a test that would pass without repairs
    // would prove nothing)
    let (raw, r) = certified_regions("builtin:cad-part");
    let e = r.embedding.as_ref().unwrap();
    assert!(check_regions(&raw, None).violations() > 0);
    assert!(e.before.violations() > 0 && e.nudged + e.rotated > 0, "{e:?}");
}

fn box_network(functions: &[septa::scene::Primitive], n: usize, mode: Mode) -> (Network, BoxGrid) {
    let grid = BoxGrid::new([n; 3], [[-1.0; 3], [1.0; 3]], Split::Five).unwrap();
    let g = Grid::Box(grid.clone());
    let values = septa::scene::sample_grid(functions, &g.vertices());
    (compute(&g, &values, functions.len(), &NetworkOptions::new(mode)).unwrap(), grid)
}

#[test]
fn grid_networks_are_certified() {
    for (spec, mode, n) in [("ia18", Mode::Ia, 24), ("ia18", Mode::Mi, 20)] {
        let (raw, grid) = box_network(&common::spec(spec), n, mode);
        let mut net = raw.clone();
        let e = certify_network(&mut net, Some(&grid));
        assert_eq!(e.after.violations(), 0, "{spec} {mode:?}: {:?}", e.after);
        assert_eq!(net.counts(), raw.counts());
        same_polygons(&net.face_start, &raw.face_verts, &net.face_verts);
        assert_eq!(check_network(&net, Some(grid.bounds)), e.after);
        // every cell but the one around the others is proven positive
        assert!(e.after.cells_positive + 1 >= e.after.cells_checked && e.after.cells_checked > 1, "{:?}", e.after);
    }
}

#[test]
fn damage_is_found_and_repaired() {
    // two vertices put at one point, and a vertex pushed through the
    // surface: the check sees both, certification repairs both
    let (mut net, grid) = box_network(&common::spec("ia18"), 16, Mode::Ia);
    let f = (0..net.num_faces()).find(|&f| net.face(f).len() >= 4).unwrap();
    let (a, b) = (net.face(f)[0], net.face(f)[2]);
    net.points[a as usize] = net.points[b as usize];
    let c = net.face(f + 1)[1];
    let p = net.points[c as usize];
    net.points[c as usize] = [p[0] + 0.2, p[1] - 0.15, p[2] + 0.1];
    let damaged = check_network(&net, Some(grid.bounds));
    assert!(damaged.coincident_points >= 1 && damaged.degenerate_triangles >= 1, "{damaged:?}");
    assert!(damaged.intersecting_pairs >= 1, "{damaged:?}");
    // without the grid: putting the vertices back on their grid edges
    // (the snap) would undo the damage by itself
    let e = certify_network(&mut net, None);
    assert_eq!(e.after.violations(), 0, "{:?}", e.after);
    assert!(e.nudged >= 1, "{e:?}");
}

#[test]
fn label_volumes_are_certified_in_world_space() {
    // four labels meeting along curves and at points, placed by a rotation
    // with a shear and by a mirror
    let n = 14;
    let mut v = vec![0i64; n * n * n];
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let (x, y, z) = (i as f64 - 6.3, j as f64 - 6.8, k as f64 - 7.1);
                v[(i * n + j) * n + k] =
                    if x * x + y * y + z * z < 20.0 { 1 + (x > 0.0) as i64 + 2 * (y > 0.4 * x) as i64 } else { 0 };
            }
        }
    }
    let (c, s) = (0.6f64, 0.8f64);
    for affine in [
        [[0.5, 0.0, 0.0, 1.0], [0.0, 0.7, 0.0, -2.0], [0.0, 0.0, 0.3, 0.1]],
        [[c, -s, 0.1, 1.0], [s, c, 0.0, 0.0], [0.0, 0.2, 1.1, 3.0]],
        [[-1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]],
    ] {
        let raw = label_surfaces(&v, [n; 3], 0.0).unwrap();
        let mut r = raw.clone();
        let e = place_labels(&mut r, [n; 3], &affine, true).unwrap().unwrap();
        assert_eq!(e.after.violations(), 0, "{affine:?}: {:?}", e.after);
        assert!(e.after.triangles > 0);
        assert_eq!(r.surfaces.len(), raw.surfaces.len());
        if affine[0][1] == 0.0 && affine[1][0] == 0.0 {
            // a box closes the regions: all but the one around the others proven
            assert!(e.after.cells_checked == 5 && e.after.cells_positive >= 4, "{:?}", e.after);
        }
    }
}
