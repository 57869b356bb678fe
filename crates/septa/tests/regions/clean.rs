//! Clean-up of small and thin triangles (Bloomenthal 4.5.3.1) never changes
//! the combinatorics: on every built-in scene and several closeness
//! factors, each surface keeps its region pair, Euler characteristic and
//! boundary loops; each curve its regions, closedness and ends, its
//! vertices a subsequence of the original; every surface stays
//! consistently oriented; no triangle is degenerate; the smallest angle
//! never gets worse; and it does collapse and flip edges (the shortest edge
//! grows).

use std::collections::{BTreeMap, HashMap};

use septa::regions::{clean, region_surfaces, RegionOptions, RegionSurfaces};
use septa::scene::Scene;

fn topology(r: &RegionSurfaces) -> Vec<(i64, i64, i64, usize)> {
    let mut s: Vec<_> =
        r.surfaces.iter().map(|s| (s.regions[0] as i64, s.regions[1] as i64, s.euler, s.boundary_loops)).collect();
    s.sort();
    s
}

fn shortest_edge(r: &RegionSurfaces) -> f64 {
    let p = &r.network.points;
    let mut best = f64::INFINITY;
    for i in 0..r.faces.len() {
        let f = &r.loops[r.loop_start[i] as usize..r.loop_start[i + 1] as usize];
        for k in 0..f.len() {
            let (a, b) = (p[f[k] as usize], p[f[(k + 1) % f.len()] as usize]);
            best = best.min(((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt());
        }
    }
    best
}

fn is_subsequence(small: &[u32], big: &[u32]) -> bool {
    let mut it = big.iter();
    small.iter().all(|x| it.any(|y| y == x))
}

#[test]
fn clean_up_keeps_the_combinatorics() {
    let (mut collapsed, mut flipped) = (0, 0);
    for (name, _) in septa::scene::builtin::list() {
        let scene = Scene::load(&format!("builtin:{name}")).unwrap();
        let r = region_surfaces(&scene, &RegionOptions::default()).unwrap();
        let res = scene.grid.resolution;
        let h = (0..3)
            .map(|a| (scene.grid.bounds[1][a] - scene.grid.bounds[0][a]) / res[a] as f64)
            .fold(f64::MAX, f64::min);
        for factor in [0.05, 0.2, 0.5] {
            let what = format!("{name} close {factor}");
            let (c, stats) = clean(&r, factor * h);
            collapsed += stats.collapsed;
            flipped += stats.flipped;
            assert_eq!(topology(&c), topology(&r), "{what}: surfaces");
            assert_eq!(c.curves.len(), r.curves.len(), "{what}");
            for (a, b) in c.curves.iter().zip(&r.curves) {
                assert_eq!((&a.regions, a.closed), (&b.regions, b.closed), "{what}");
                if !b.closed {
                    assert!(is_subsequence(&a.vertices, &b.vertices), "{what}: curve order");
                    assert_eq!((a.vertices[0], a.vertices.last()), (b.vertices[0], b.vertices.last()), "{what}: ends");
                } else {
                    // A loop may lose its first vertex: compare cyclically.
                    let (ring, orig) = (&a.vertices[..a.vertices.len() - 1], &b.vertices[..b.vertices.len() - 1]);
                    assert_eq!(a.vertices.first(), a.vertices.last(), "{what}: a loop stays closed");
                    let twice: Vec<u32> = orig.iter().chain(orig).copied().collect();
                    assert!(is_subsequence(ring, &twice), "{what}: loop order");
                    assert!(ring.len() >= 3, "{what}: a loop keeps three vertices");
                }
            }
            // Orientation: in a surface no directed edge is used twice.
            let mut directed: HashMap<(u32, u32, u32), u32> = HashMap::new();
            for i in 0..c.faces.len() {
                let f = &c.loops[c.loop_start[i] as usize..c.loop_start[i + 1] as usize];
                assert_eq!(f.len(), 3);
                assert!(f[0] != f[1] && f[1] != f[2] && f[0] != f[2], "{what}: degenerate triangle");
                for k in 0..3 {
                    *directed.entry((c.face_surface[i], f[k], f[(k + 1) % 3])).or_default() += 1;
                }
            }
            assert!(directed.values().all(|&n| n == 1), "{what}: orientation");
            assert_eq!(stats.triangles_after, c.faces.len());
            assert!(stats.min_angle[1] >= stats.min_angle[0], "{what}: smallest angle {:?}", stats.min_angle);
            if stats.collapsed > 0 {
                assert!(shortest_edge(&c) > shortest_edge(&r), "{what}: the shortest edge grows");
            }
        }
    }
    assert!(collapsed > 100, "the clean-up collapses edges ({collapsed})");
    assert!(flipped > 10, "the clean-up flips edges under thin triangles ({flipped})");
}

#[test]
fn clean_up_keeps_the_enclosed_volume_close() {
    // Box minus cylinder: collapsing short edges onto network vertices
    // moves the boundary by at most the closeness, so the enclosed volume
    // changes by far less than the surface area times that.
    let scene = Scene::load("builtin:box-minus-cylinder").unwrap();
    let r = region_surfaces(&scene, &RegionOptions::default()).unwrap();
    let regions: BTreeMap<i64, ()> = r.cell_region.iter().map(|&g| (g as i64, ())).collect();
    let h = (scene.grid.bounds[1][0] - scene.grid.bounds[0][0]) / scene.grid.resolution[0] as f64;
    let (c, stats) = clean(&r, 0.3 * h);
    assert!(stats.collapsed > 0);
    for (&g, _) in &regions {
        let (a, b) = (r.enclosed_volume(g as _), c.enclosed_volume(g as _));
        assert!((a - b).abs() <= 0.02 * a.abs().max(1e-9), "region {g}: {a} vs {b}");
    }
}
