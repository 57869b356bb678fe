//! The constraints every patch shares: the edges where the patches meet
//! (chains, and a patch's border on the grid's box), split into *traces*
//! between fixed vertices, and the vertices that never move.
//!
//! An edge is a constraint when it is not inside one patch: not held by
//! exactly two triangles of one patch, or on a chain. A vertex is *fixed*
//! when it is a corner, a chain's end, on other than two constraint edges,
//! between two constraint edges of different kinds (other chains, other
//! patches around them, or other sides of the grid's box), where patches touch at a point, or where the
//! triangles around it do not form one fan per patch side (a patch pinched
//! there). A trace is a path of constraint edges between fixed vertices; a
//! closed one without any gets its first vertex fixed. Chains are rebuilt
//! after remeshing by walking their traces (CGAL's protected constraints
//! and Boltcheva et al.'s feature graph play this part; here the graph is
//! the exact network's).

use rustc_hash::FxHashMap;

use super::soup::{dot, ekey, sub, Kind, Soup, V};

/// Polygons to remesh and the network's curves.
pub(crate) struct Source<'a> {
    pub points: &'a [V],
    pub start: &'a [u32],
    pub verts: &'a [u32],
    /// Per polygon its patch.
    pub patch: &'a [u32],
    /// Chains as vertex paths (a closed chain repeats its first vertex).
    pub chains: &'a [Vec<u32>],
    pub corners: &'a [u32],
    /// The grid's box: a patch's border on it turns where it goes from one
    /// side of the box to another (a fixed vertex there).
    pub bounds: Option<[[f64; 3]; 2]>,
}

/// The sides of the box both ends of the edge `ab` are exactly on (bit
/// `2k + s`: side `s` of axis `k`).
fn box_sides(x: &[V], a: u32, b: u32, bounds: Option<[[f64; 3]; 2]>) -> u8 {
    let Some(bb) = bounds else { return 0 };
    let (p, q) = (x[a as usize], x[b as usize]);
    let mut m = 0;
    for k in 0..3 {
        for (s, side) in bb.iter().enumerate() {
            if p[k] == side[k] && q[k] == side[k] {
                m |= 1 << (2 * k + s);
            }
        }
    }
    m
}

/// A piece of a chain: from `start` along the edges of `trace`, first
/// towards `hint`.
#[derive(Clone, Debug)]
pub(super) struct Piece {
    pub start: u32,
    pub trace: u32,
    pub hint: V,
}

/// The soup with its constraints, and each chain as its pieces.
pub(super) struct Built {
    pub soup: Soup,
    pub chains: Vec<Vec<Piece>>,
    pub traces: usize,
    /// The original triangles (the fans) with their patches, and the
    /// constraint edges with their traces.
    pub tris: Vec<[u32; 3]>,
    pub tri_patch: Vec<u32>,
    pub segs: Vec<[u32; 2]>,
    pub seg_trace: Vec<u32>,
    /// Per trace, the patches around it and the sides of the box it is on.
    pub trace_class: Vec<(Vec<u32>, u8)>,
}

/// Fans the polygons and finds the constraints (module doc).
pub(super) fn build(src: &Source) -> Built {
    let mut tris = Vec::new();
    let mut tri_patch = Vec::new();
    for f in 0..src.start.len() - 1 {
        let l = &src.verts[src.start[f] as usize..src.start[f + 1] as usize];
        for k in 1..l.len().saturating_sub(1) {
            tris.push([l[0], l[k], l[k + 1]]);
            tri_patch.push(src.patch[f]);
        }
    }
    let mut soup = Soup::new(src.points.to_vec(), tris.clone(), tri_patch.clone());
    let n = soup.x.len();
    // the triangles at each edge
    let mut uses: FxHashMap<(u32, u32), Vec<u32>> = FxHashMap::default();
    for (t, tri) in tris.iter().enumerate() {
        for k in 0..3 {
            uses.entry(ekey(tri[k], tri[(k + 1) % 3])).or_default().push(t as u32);
        }
    }
    let mut chain_of: FxHashMap<(u32, u32), u32> = FxHashMap::default();
    for (c, path) in src.chains.iter().enumerate() {
        for w in path.windows(2) {
            chain_of.insert(ekey(w[0], w[1]), c as u32);
        }
    }
    // a constraint edge's kind: its chain, the patches around it and the
    // sides of the box it is on
    let mut class: FxHashMap<(u32, u32), (u32, Vec<u32>, u8)> = FxHashMap::default();
    for (e, ts) in &uses {
        let mut ps: Vec<u32> = ts.iter().map(|&t| tri_patch[t as usize]).collect();
        ps.sort_unstable();
        let inside = ts.len() == 2 && ps[0] == ps[1] && !chain_of.contains_key(e) && opposite(&tris, ts, *e);
        if !inside {
            let sides = box_sides(src.points, e.0, e.1, src.bounds);
            class.insert(*e, (chain_of.get(e).copied().unwrap_or(u32::MAX), ps, sides));
        }
    }
    let mut fedges: Vec<Vec<u32>> = vec![Vec::new(); n];
    for &(a, b) in class.keys() {
        fedges[a as usize].push(b);
        fedges[b as usize].push(a);
    }
    let mut used = vec![false; n];
    for t in &tris {
        for &v in t {
            used[v as usize] = true;
        }
    }
    let mut fixed = vec![false; n];
    for &c in src.corners {
        fixed[c as usize] = true;
    }
    for path in src.chains {
        if let (Some(&a), Some(&b)) = (path.first(), path.last()) {
            fixed[a as usize] = true;
            fixed[b as usize] = true;
        }
    }
    for v in 0..n {
        if !used[v] || fixed[v] {
            continue;
        }
        let fe = &fedges[v];
        let v32 = v as u32;
        let patches = {
            let mut p: Vec<u32> = soup.vt[v].iter().map(|&t| tri_patch[t as usize]).collect();
            p.sort_unstable();
            p.dedup();
            p
        };
        fixed[v] = match fe.len() {
            0 => patches.len() != 1 || fans(&soup, v32, &class) != (1, true),
            2 => {
                let (a, b) = (&class[&ekey(v32, fe[0])], &class[&ekey(v32, fe[1])]);
                let (nf, closed) = fans(&soup, v32, &class);
                a != b || closed || nf != a.1.len()
            }
            _ => true,
        };
    }
    // traces: from each fixed vertex along each constraint edge
    let mut trace_of: FxHashMap<(u32, u32), u32> = FxHashMap::default();
    let mut traces = 0u32;
    let mut trace_class: Vec<(Vec<u32>, u8)> = Vec::new();
    let mut walk = |s: u32, first: u32, fixed: &[bool], trace_of: &mut FxHashMap<(u32, u32), u32>| {
        let id = traces;
        traces += 1;
        let c = &class[&ekey(s, first)];
        trace_class.push((c.1.clone(), c.2));
        let (mut prev, mut v) = (s, first);
        trace_of.insert(ekey(s, first), id);
        while !fixed[v as usize] {
            let next = *fedges[v as usize].iter().find(|&&w| w != prev).unwrap();
            trace_of.insert(ekey(v, next), id);
            (prev, v) = (v, next);
        }
    };
    for s in 0..n as u32 {
        if fixed[s as usize] {
            for &w in &fedges[s as usize] {
                if !trace_of.contains_key(&ekey(s, w)) {
                    walk(s, w, &fixed, &mut trace_of);
                }
            }
        }
    }
    // closed loops of curve vertices: the smallest vertex fixed
    let mut order: Vec<(u32, u32)> = class.keys().copied().collect();
    order.sort_unstable();
    for (a, b) in order {
        if !trace_of.contains_key(&(a, b)) {
            fixed[a as usize] = true;
            for &w in &fedges[a as usize].clone() {
                if !trace_of.contains_key(&ekey(a, w)) {
                    walk(a, w, &fixed, &mut trace_of);
                }
            }
        }
    }
    for v in 0..n {
        soup.kind[v] = if fixed[v] || !used[v] {
            Kind::Fixed
        } else if let Some(&w) = fedges[v].first() {
            Kind::Curve(trace_of[&ekey(v as u32, w)])
        } else {
            Kind::Free(tri_patch[soup.vt[v][0] as usize])
        };
    }
    let mut segs = Vec::with_capacity(trace_of.len());
    let mut seg_trace = Vec::with_capacity(trace_of.len());
    let mut sorted: Vec<(&(u32, u32), &u32)> = trace_of.iter().collect();
    sorted.sort_unstable();
    for (&(a, b), &t) in sorted {
        segs.push([a, b]);
        seg_trace.push(t);
    }
    soup.feat = trace_of.clone();
    // chains as pieces between fixed vertices
    let chains = src
        .chains
        .iter()
        .map(|path| {
            let mut pieces = Vec::new();
            for (i, w) in path.windows(2).enumerate() {
                if i == 0 || fixed[w[0] as usize] {
                    let trace = trace_of.get(&ekey(w[0], w[1])).copied().unwrap_or(u32::MAX);
                    pieces.push(Piece {
                        start: w[0],
                        trace,
                        hint: sub(src.points[w[1] as usize], src.points[w[0] as usize]),
                    });
                }
            }
            pieces
        })
        .collect();
    Built { soup, chains, traces: traces as usize, tris, tri_patch, segs, seg_trace, trace_class }
}

/// Whether the two triangles `ts` use the edge `e` in opposite directions
/// (one patch's orientation continues across it).
fn opposite(tris: &[[u32; 3]], ts: &[u32], e: (u32, u32)) -> bool {
    let dir = |t: u32| {
        let tri = tris[t as usize];
        (0..3).any(|k| tri[k] == e.0 && tri[(k + 1) % 3] == e.1)
    };
    dir(ts[0]) != dir(ts[1])
}

/// The fans of triangles around `v` joined across its non-constraint
/// edges: how many, and whether there is one and it closes.
fn fans(s: &Soup, v: u32, class: &FxHashMap<(u32, u32), (u32, Vec<u32>, u8)>) -> (usize, bool) {
    let ts: Vec<u32> = s.vt[v as usize].to_vec();
    let mut comp: Vec<usize> = (0..ts.len()).collect();
    fn find(c: &mut [usize], i: usize) -> usize {
        let mut r = i;
        while c[r] != r {
            r = c[r];
        }
        c[i] = r;
        r
    }
    let mut inner_edges = 0;
    let mut by_edge: FxHashMap<u32, Vec<usize>> = FxHashMap::default();
    for (i, &t) in ts.iter().enumerate() {
        for &w in &s.tris[t as usize] {
            if w != v {
                by_edge.entry(w).or_default().push(i);
            }
        }
    }
    for (w, is) in &by_edge {
        if class.contains_key(&ekey(v, *w)) || is.len() != 2 {
            continue;
        }
        inner_edges += 1;
        let (a, b) = (find(&mut comp, is[0]), find(&mut comp, is[1]));
        comp[a] = b;
    }
    let mut roots: Vec<usize> = (0..ts.len()).map(|i| find(&mut comp, i)).collect();
    roots.sort_unstable();
    roots.dedup();
    // one closed fan: as many inner edges as triangles
    (roots.len(), roots.len() == 1 && inner_edges == ts.len())
}

/// The chains as vertex paths of the remeshed soup: each piece walked from
/// its start along its trace to the next fixed vertex.
pub(super) fn rebuild_chains(s: &Soup, chains: &[Vec<Piece>]) -> Vec<Vec<u32>> {
    chains
        .iter()
        .map(|pieces| {
            let mut path: Vec<u32> = Vec::new();
            for p in pieces {
                if path.last() != Some(&p.start) {
                    path.push(p.start);
                }
                let on = |a: u32, w: u32| s.feat.get(&ekey(a, w)) == Some(&p.trace);
                let x0 = s.x[p.start as usize];
                let first = s.neighbours(p.start).into_iter().filter(|&w| on(p.start, w)).max_by(|&a, &b| {
                    let da = dot(sub(s.x[a as usize], x0), p.hint);
                    let db = dot(sub(s.x[b as usize], x0), p.hint);
                    da.total_cmp(&db)
                });
                let Some(mut v) = first else { continue };
                let mut prev = p.start;
                path.push(v);
                while !matches!(s.kind[v as usize], Kind::Fixed) {
                    let Some(next) = s.neighbours(v).into_iter().find(|&w| w != prev && on(v, w)) else { break };
                    (prev, v) = (v, next);
                    path.push(v);
                }
            }
            path
        })
        .collect()
}
