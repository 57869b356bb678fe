//! Built-in scenes through the exact network: the topology each scene
//! promises (`builtin::expected`) holds for the surfaces and curves of
//! interest, computed here from the network's polygons, their cells and the
//! scene's region rule; and `apollonius-18` on its default grid has the
//! reference implementation's counts for `mi18_R20`.
//!
//! Surfaces of interest: polygons whose two cells lie in different regions
//! forming a pair of interest, grouped by pair; Euler characteristic
//! V - E + F of the group, boundary loops = components of the edges used
//! by one polygon of the group. Curves of interest: network edges around
//! which the cells' regions include a triple of interest.

use std::collections::{BTreeMap, HashMap, HashSet};

use septa::complex::Mode as NetMode;
use septa::grid::{BoxGrid, Grid, Split};
use septa::network::{compute, Network, NetworkOptions};
use septa::scene::{builtin, Mode, RegionId, Scene};

fn network(s: &Scene) -> (Network, Grid) {
    let split = if s.grid.split == 6 { Split::Six } else { Split::Five };
    let grid = Grid::Box(BoxGrid::new(s.grid.resolution, s.grid.bounds, split).unwrap());
    let (_, values) = s.sample();
    let mode = match s.mode {
        Mode::Ia => NetMode::Ia,
        Mode::Mi => NetMode::Mi,
    };
    let net = compute(&grid, &values, s.functions.len(), &NetworkOptions::new(mode)).unwrap();
    (net, grid)
}

fn cell_region(s: &Scene, net: &Network, cell: u32) -> Option<RegionId> {
    let c = net.cells.get(cell as usize)?;
    Some(match s.mode {
        Mode::Ia => {
            let signs: Vec<bool> = (0..s.functions.len()).map(|f| c.label[f / 64] >> (f % 64) & 1 == 1).collect();
            s.regions.region_ia(&signs)
        }
        Mode::Mi => s.regions.region_mi(c.label[0] as usize),
    })
}

/// Components and degree-1 vertices of a graph given by its edges.
fn graph(edges: &[[u32; 2]]) -> (usize, usize) {
    let mut adj: HashMap<u32, Vec<u32>> = HashMap::new();
    for [a, b] in edges {
        adj.entry(*a).or_default().push(*b);
        adj.entry(*b).or_default().push(*a);
    }
    let ends = adj.values().filter(|n| n.len() == 1).count();
    let (mut seen, mut comps) = (HashSet::new(), 0);
    for s in adj.keys() {
        if seen.insert(*s) {
            comps += 1;
            let mut stack = vec![*s];
            while let Some(x) = stack.pop() {
                for y in &adj[&x] {
                    if seen.insert(*y) {
                        stack.push(*y);
                    }
                }
            }
        }
    }
    (comps, ends)
}

struct Measured {
    /// pair -> (components, euler, boundary loops)
    surfaces: BTreeMap<[RegionId; 2], (usize, i64, usize)>,
    /// triple -> (components, end points)
    curves: BTreeMap<[RegionId; 3], (usize, usize)>,
}

fn measure(s: &Scene, net: &Network) -> Measured {
    let mut by_pair: BTreeMap<[RegionId; 2], Vec<usize>> = BTreeMap::new();
    let mut edge_regions: HashMap<[u32; 2], HashSet<RegionId>> = HashMap::new();
    for f in 0..net.num_faces() {
        let [a, b] = net.face_cells[f].map(|c| cell_region(s, net, c));
        let vs = net.face(f);
        for i in 0..vs.len() {
            let (u, v) = (vs[i], vs[(i + 1) % vs.len()]);
            let e = edge_regions.entry([u.min(v), u.max(v)]).or_default();
            e.extend(a);
            e.extend(b);
        }
        if let (Some(a), Some(b)) = (a, b) {
            if s.interest.surface(a, b) {
                by_pair.entry([a.min(b), a.max(b)]).or_default().push(f);
            }
        }
    }
    let mut surfaces = BTreeMap::new();
    for (pair, faces) in by_pair {
        let mut verts = HashSet::new();
        let mut edges: HashMap<[u32; 2], Vec<usize>> = HashMap::new();
        for &f in &faces {
            let vs = net.face(f);
            for i in 0..vs.len() {
                let (u, v) = (vs[i], vs[(i + 1) % vs.len()]);
                verts.insert(u);
                edges.entry([u.min(v), u.max(v)]).or_default().push(f);
            }
        }
        let euler = verts.len() as i64 - edges.len() as i64 + faces.len() as i64;
        // Components of polygons through shared edges.
        let mut adj: Vec<[u32; 2]> = vec![];
        for fs in edges.values() {
            for w in fs.windows(2) {
                adj.push([w[0] as u32, w[1] as u32]);
            }
        }
        for &f in &faces {
            adj.push([f as u32, f as u32]);
        }
        let comps = graph(&adj).0;
        let boundary: Vec<[u32; 2]> = edges.iter().filter(|(_, f)| f.len() == 1).map(|(e, _)| *e).collect();
        surfaces.insert(pair, (comps, euler, graph(&boundary).0));
    }
    let mut curves = BTreeMap::new();
    for t in s.interest.curves.iter().flatten() {
        let edges: Vec<[u32; 2]> =
            edge_regions.iter().filter(|(_, r)| t.iter().all(|x| r.contains(x))).map(|(e, _)| *e).collect();
        curves.insert(*t, graph(&edges));
    }
    Measured { surfaces, curves }
}

fn check(name: &str) {
    let s = builtin::get(name).unwrap();
    let (net, _) = network(&s);
    let m = measure(&s, &net);
    let (surfs, curves) = builtin::expected(name).unwrap();
    let mut wrong = vec![];
    for e in &surfs {
        let got = m.surfaces.get(&e.regions).copied().unwrap_or((0, 0, 0));
        eprintln!("{name} surface {:?}: (components, euler, loops) = {got:?}", e.regions);
        if got != (e.components, e.euler, e.boundary_loops) {
            wrong.push(format!("surface {:?}: got {got:?}, promised {e:?}", e.regions));
        }
    }
    assert_eq!(m.surfaces.len(), surfs.len(), "{name}: surfaces {:?}", m.surfaces);
    for e in &curves {
        let (comps, ends) = m.curves[&e.regions];
        eprintln!("{name} curve {:?}: components {comps}, end points {ends}", e.regions);
        let closed = ends == 0;
        if comps != e.components || closed != e.closed {
            wrong.push(format!("curve {:?}: {comps} components, {ends} ends; promised {e:?}", e.regions));
        }
    }
    assert!(wrong.is_empty(), "{name}: {wrong:?}");
}

#[test]
fn saucer_square_topology() {
    check("saucer-square");
}

#[test]
fn sphere_with_hole_topology() {
    check("sphere-with-hole");
}

#[test]
fn sphere_plane_hole_topology() {
    check("sphere-plane-hole");
}

#[test]
fn patch_blend_topology() {
    check("patch-blend");
}

#[test]
fn cad_part_topology() {
    check("cad-part");
}

#[test]
fn box_minus_cylinder_topology() {
    check("box-minus-cylinder");
    // Its sharp edges are chains: 12 box edges and 2 circles, 8 corners
    // (chains of the whole arrangement that lie on the solid's boundary).
    let s = builtin::box_minus_cylinder();
    let (net, grid) = network(&s);
    let on_boundary = |v: u32| {
        let p = net.points[v as usize];
        p.iter().all(|x| x.abs() <= 0.5 + 1e-9)
    };
    let _ = grid;
    let boundary_chains = net
        .chains
        .iter()
        .filter(|c| c.iter().all(|&v| on_boundary(v)))
        .filter(|c| {
            // A chain of the solid's surface has cells of both regions around it.
            let mid = c[c.len() / 2];
            let mut regions = HashSet::new();
            for f in 0..net.num_faces() {
                if net.face(f).contains(&mid) {
                    for cell in net.face_cells[f] {
                        regions.extend(cell_region(&s, &net, cell));
                    }
                }
            }
            regions.len() == 2
        })
        .count();
    assert_eq!(boundary_chains, 14);
}

#[test]
fn apollonius_18_equals_the_reference() {
    // Default grid = mi18_R20's grid; the reference's counts (expected.json).
    let s = builtin::apollonius_18();
    let (net, _) = network(&s);
    let c: BTreeMap<_, _> = net.counts().into_iter().collect();
    assert_eq!(
        (c["patches"], c["chains"], c["corners"], c["cells"], c["components"], c["faces"], c["vertices"]),
        (70, 91, 68, 18, 1, 13224, 8805)
    );
}

#[test]
fn box_minus_cylinder_volume_converges() {
    let exact = builtin::box_minus_cylinder_volume();
    let mut errors = vec![];
    for n in [11, 21, 41] {
        let mut s = builtin::box_minus_cylinder();
        s.grid.resolution = [n; 3];
        let grid = Grid::Box(BoxGrid::new(s.grid.resolution, s.grid.bounds, Split::Five).unwrap());
        let (_, values) = s.sample();
        let mut opts = NetworkOptions::new(NetMode::Ia);
        opts.volumes = true;
        let net = compute(&grid, &values, s.functions.len(), &opts).unwrap();
        let vol: f64 = (0..net.cells.len() as u32)
            .filter(|&c| cell_region(&s, &net, c) == Some(1))
            .map(|c| net.cells[c as usize].volume)
            .sum();
        eprintln!("box minus cylinder, {n}^3: volume {vol}, error {}", vol - exact);
        errors.push((vol - exact).abs());
    }
    assert!(errors[0] > errors[1] && errors[1] > errors[2], "{errors:?}");
    assert!(errors[2] < 2e-3, "{errors:?}");
}

#[test]
fn voronoi_lines_5_has_one_cell_per_line() {
    let s = builtin::voronoi_lines_5();
    let (net, _) = network(&s);
    let c: BTreeMap<_, _> = net.counts().into_iter().collect();
    eprintln!("voronoi-lines-5: {c:?}");
    assert_eq!(c["cells"], 5);
    let mut materials: Vec<u64> = net.cells.iter().map(|c| c.label[0]).collect();
    materials.sort();
    assert_eq!(materials, vec![0, 1, 2, 3, 4]);
    assert_eq!(c["components"], 1);
    // Recorded from the exact run (regression values).
    assert_eq!((c["patches"], c["chains"], c["corners"]), (16, 17, 19));
    // Their source: not one run but the diagram of the lines. Other
    // samplings of the same distance functions (a finer grid, the 6-tet
    // split: other sample points, other tets) resolve the same Voronoi
    // diagram, so they must give the same combinatorics.
    for (n, split) in [(33, 6), (45, 5), (45, 6)] {
        let mut t = builtin::voronoi_lines_5();
        t.grid.resolution = [n; 3];
        t.grid.split = split;
        let (other, _) = network(&t);
        let o: BTreeMap<_, _> = other.counts().into_iter().collect();
        eprintln!("voronoi-lines-5 at {n}^3, {split} tets per cube: {o:?}");
        for k in ["patches", "chains", "corners", "cells", "components"] {
            assert_eq!(o[k], c[k], "{k} at {n}^3 with {split} tets per cube");
        }
    }
}

/// Polygons of the surfaces of interest oriented counter-clockwise seen
/// from the lesser region (Bloomenthal 4.5.2.4) with [`must_flip`]: the
/// network gives each polygon counter-clockwise from its positive side
/// (cell `face_cells[f][0]`). Checks: every edge inside a surface is
/// traversed in opposite directions by its two polygons (consistent
/// orientation), and on the sphere with a hole the normals point out, into
/// region 0, the lesser one.
#[test]
fn surfaces_are_oriented_from_the_lesser_region() {
    use septa::scene::must_flip;
    for name in ["sphere-with-hole", "saucer-square", "sphere-plane-hole", "cad-part"] {
        let s = builtin::get(name).unwrap();
        let (net, _) = network(&s);
        let mut directed: HashMap<([RegionId; 2], [u32; 2]), i32> = HashMap::new();
        let mut volume = 0.0;
        for f in 0..net.num_faces() {
            let [Some(pos), Some(neg)] = net.face_cells[f].map(|c| cell_region(&s, &net, c)) else { continue };
            if !s.interest.surface(pos, neg) {
                continue;
            }
            let mut vs = net.face(f).to_vec();
            if must_flip(pos, neg) {
                vs.reverse();
            }
            let pair = [pos.min(neg), pos.max(neg)];
            for i in 0..vs.len() {
                let (u, v) = (vs[i], vs[(i + 1) % vs.len()]);
                *directed.entry((pair, [u, v])).or_default() += 1;
            }
            // Signed volume contribution (fan from the first vertex).
            let p: Vec<[f64; 3]> = vs.iter().map(|&v| net.points[v as usize]).collect();
            for i in 1..p.len() - 1 {
                let (a, b, c) = (p[0], p[i], p[i + 1]);
                volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                    + a[2] * (b[0] * c[1] - b[1] * c[0]))
                    / 6.0;
            }
        }
        for ((pair, [u, v]), n) in &directed {
            assert_eq!(*n, 1, "{name} {pair:?}: edge {u}-{v} traversed {n} times the same way");
        }
        if name == "sphere-with-hole" {
            // Normals into region 0 (outside): positive enclosed volume, a
            // little less than the large sphere's (the hole is open).
            let sphere = 4.0 / 3.0 * std::f64::consts::PI * 0.6f64.powi(3);
            assert!(volume > 0.5 * sphere && volume < sphere, "{volume}");
        }
    }
}
