//! An independent, approximate cross-check of the topology each built-in
//! scene's comment promises, without the exact network: label voxel
//! centres of a fine grid by region and measure the **cuberille** surface
//! between each region pair of interest (faces between voxels of the two
//! regions): components, Euler characteristic, boundary loops; and for
//! each triple of interest the voxel edges whose four voxels show all
//! three regions: components and end points.
//!
//! Voxel surfaces can have non-manifold spots, so this is a probe, not
//! the exact test (the network tests assert the exact topology); it runs
//! with `cargo run --release -p septa --example scene_topology_probe`.

use std::collections::{HashMap, HashSet};

use septa::scene::{builtin, Mode, Scene};

type P = (i32, i32, i32);

struct Probe {
    n: i32,
    labels: Vec<i64>,
}

impl Probe {
    fn new(s: &Scene, n: i32) -> Probe {
        let [lo, hi] = s.grid.bounds;
        let mut pts = Vec::with_capacity((n * n * n) as usize);
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    let t = [i, j, k];
                    pts.push([0, 1, 2].map(|a| lo[a] + (hi[a] - lo[a]) * (t[a] as f64 + 0.5) / n as f64));
                }
            }
        }
        let kf = s.functions.len();
        let v = septa::scene::sample_grid(&s.functions, &pts);
        let labels = v
            .chunks(kf)
            .map(|row| match s.mode {
                Mode::Ia => s.regions.region_ia(&row.iter().map(|x| *x > 0.0).collect::<Vec<_>>()),
                Mode::Mi => {
                    let m = (0..kf).max_by(|&a, &b| row[a].total_cmp(&row[b])).unwrap();
                    s.regions.region_mi(m)
                }
            })
            .collect();
        Probe { n, labels }
    }

    fn at(&self, p: P) -> Option<i64> {
        let n = self.n;
        if p.0 < 0 || p.1 < 0 || p.2 < 0 || p.0 >= n || p.1 >= n || p.2 >= n {
            None
        } else {
            Some(self.labels[((p.0 * n + p.1) * n + p.2) as usize])
        }
    }

    /// (components, euler, boundary loops) of the cuberille surface between
    /// regions a and b. Lattice points are voxel corners (doubled coords).
    fn surface(&self, a: i64, b: i64) -> (usize, i64, usize) {
        let mut faces: Vec<[P; 4]> = vec![];
        for i in 0..self.n {
            for j in 0..self.n {
                for k in 0..self.n {
                    let l = self.at((i, j, k));
                    for ax in 0..3 {
                        let q = [(i + 1, j, k), (i, j + 1, k), (i, j, k + 1)][ax];
                        let m = self.at(q);
                        let pair = (l.unwrap(), m);
                        if m.is_none() || !((pair.0 == a && pair.1 == Some(b)) || (pair.0 == b && pair.1 == Some(a))) {
                            continue;
                        }
                        // Face at the shared side: corner coordinates.
                        let c = |d1: i32, d2: i32| -> P {
                            let mut p = [i + 1, j + 1, k + 1];
                            let o = [(1, 2), (0, 2), (0, 1)][ax];
                            let mut v = [i, j, k];
                            v[ax] = p[ax];
                            v[o.0] += d1;
                            v[o.1] += d2;
                            p = v;
                            (p[0], p[1], p[2])
                        };
                        faces.push([c(0, 0), c(1, 0), c(1, 1), c(0, 1)]);
                    }
                }
            }
        }
        let mut verts = HashSet::new();
        let mut edges: HashMap<(P, P), Vec<usize>> = HashMap::new();
        for (fi, f) in faces.iter().enumerate() {
            for e in 0..4 {
                verts.insert(f[e]);
                let (u, v) = (f[e], f[(e + 1) % 4]);
                edges.entry((u.min(v), u.max(v))).or_default().push(fi);
            }
        }
        let euler = verts.len() as i64 - edges.len() as i64 + faces.len() as i64;
        // Components of faces through shared edges.
        let mut parent: Vec<usize> = (0..faces.len()).collect();
        fn find(p: &mut [usize], x: usize) -> usize {
            let mut x = x;
            while p[x] != x {
                p[x] = p[p[x]];
                x = p[x];
            }
            x
        }
        for fs in edges.values() {
            for w in fs.windows(2) {
                let (x, y) = (find(&mut parent, w[0]), find(&mut parent, w[1]));
                parent[x] = y;
            }
        }
        let comps = (0..faces.len()).filter(|&x| find(&mut parent, x) == x).count();
        // Boundary loops: components of edges used by one face.
        let bedges: Vec<(P, P)> = edges.iter().filter(|(_, f)| f.len() == 1).map(|(e, _)| *e).collect();
        (comps, euler, components(&bedges).0)
    }

    /// (components, end points) of the voxel curve where a, b, c meet.
    fn curve(&self, t: [i64; 3]) -> (usize, usize) {
        let mut edges = vec![];
        for i in 0..=self.n {
            for j in 0..=self.n {
                for k in 0..=self.n {
                    for ax in 0..3 {
                        // Lattice edge from corner (i,j,k) along ax; its 4 voxels.
                        let o = [(1, 2), (0, 2), (0, 1)][ax];
                        let mut around = vec![];
                        for (d1, d2) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                            let mut v = [i, j, k];
                            v[o.0] -= d1;
                            v[o.1] -= d2;
                            if let Some(l) = self.at((v[0], v[1], v[2])) {
                                around.push(l);
                            }
                        }
                        if t.iter().all(|r| around.contains(r)) {
                            let mut w = [i, j, k];
                            w[ax] += 1;
                            edges.push(((i, j, k), (w[0], w[1], w[2])));
                        }
                    }
                }
            }
        }
        components(&edges)
    }
}

/// (components, degree-1 vertices) of a graph given by edges.
fn components(edges: &[(P, P)]) -> (usize, usize) {
    let mut adj: HashMap<P, Vec<P>> = HashMap::new();
    for (u, v) in edges {
        adj.entry(*u).or_default().push(*v);
        adj.entry(*v).or_default().push(*u);
    }
    let ends = adj.values().filter(|n| n.len() == 1).count();
    let mut seen = HashSet::new();
    let mut comps = 0;
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

fn main() {
    let names =
        ["saucer-square", "sphere-with-hole", "sphere-plane-hole", "patch-blend", "cad-part", "box-minus-cylinder"];
    let mut bad = vec![];
    for name in names {
        let (surfs, curves) = builtin::expected(name).unwrap();
        let s = builtin::get(name).unwrap();
        let probe = Probe::new(&s, 160);
        for e in surfs {
            let (pair, c, e, l) = (e.regions, e.components, e.euler, e.boundary_loops);
            let got = probe.surface(pair[0], pair[1]);
            println!("{name} surface {pair:?}: components, euler, loops = {got:?} (expected {:?})", (c, e, l));
            if got != (c, e, l) {
                bad.push(format!("{name} {pair:?}"));
            }
        }
        for e in curves {
            let (t, c) = (e.regions, e.components);
            let got = probe.curve(t);
            // Voxel curves grow spurs, so only components are compared.
            println!("{name} curve {t:?}: components, ends = {got:?} (expected {c}, closed {})", e.closed);
            if got.0 != c {
                bad.push(format!("{name} {t:?}"));
            }
        }
    }
    assert!(bad.is_empty(), "{bad:?}");
}
