//! Curves of interest: network edges around which the three regions of a
//! triple of interest meet, joined into polylines (feature curves are
//! `features.rs`).

use rustc_hash::FxHashMap;

use crate::network::Network;
use crate::scene::{Interest, RegionId};

/// What made a curve.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum CurveKind {
    /// Three regions of a triple of interest meet along it (Bloomenthal 4.2).
    Junction,
    /// A kept surface between two regions changes the function it lies on
    /// (a sharp edge of a CSG solid; `features.rs`).
    Feature,
}

impl CurveKind {
    /// `"junction"` or `"feature"` (the name in every output).
    pub fn as_str(self) -> &'static str {
        match self {
            CurveKind::Junction => "junction",
            CurveKind::Feature => "feature",
        }
    }
}

/// A curve of interest: where three regions meet, or a feature curve.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// Junction or feature.
    pub kind: CurveKind,
    /// The regions, ascending: the triple of a junction, the pair on
    /// either side of a feature.
    pub regions: Vec<RegionId>,
    /// A feature's functions (ascending): those whose zero sets (IA) or
    /// material pairs (MI) hold the polygons meeting along it; empty for a
    /// junction.
    pub functions: Vec<u32>,
    /// Network vertices in order (a closed curve repeats its first vertex).
    pub vertices: Vec<u32>,
    /// Whether the curve is a loop.
    pub closed: bool,
    /// Length of the polyline (floating point).
    pub length: f64,
}

pub(crate) use crate::measure::path_length;

pub(crate) fn extract(net: &Network, region: &[RegionId], interest: &Interest) -> Vec<Curve> {
    if interest.curves.as_ref().is_some_and(|l| l.is_empty()) {
        return Vec::new();
    }
    // A triple needs three regions around an edge: edges with fewer are
    // not looked at.
    extract_with(net, region, 3, &|around: &[RegionId]| interest.curve(around))
}

/// [`extract`] with the triple of each edge chosen by `pick` from the sorted
/// distinct regions around it (`None`: no curve of interest there).
/// `pick` must answer `None` for sets of fewer than `min_regions` regions:
/// edges that cannot have that many are not looked at (0: every edge).
pub(crate) fn extract_with(
    net: &Network,
    region: &[RegionId],
    min_regions: usize,
    pick: &dyn Fn(&[RegionId]) -> Option<[RegionId; 3]>,
) -> Vec<Curve> {
    // The regions around an edge are among those around either end vertex
    // (every polygon at the edge holds both ends). Up to `min_regions`
    // distinct regions per vertex, in one linear pass, rule out the edges
    // inside surfaces (nearly all of them) before anything is sorted.
    let wanted = min_regions.min(3);
    let mut seen: Vec<([RegionId; 3], u8)> = vec![([0; 3], 0); if wanted > 1 { net.points.len() } else { 0 }];
    if wanted > 1 {
        for f in 0..net.num_faces() {
            for c in net.face_cells[f] {
                if c == u32::MAX {
                    continue;
                }
                let r = region[c as usize];
                for &v in net.face(f) {
                    let (set, n) = &mut seen[v as usize];
                    if (*n as usize) < wanted && !set[..*n as usize].contains(&r) {
                        set[*n as usize] = r;
                        *n += 1;
                    }
                }
            }
        }
    }
    let may_be_curve = |v: u32| wanted <= 1 || seen[v as usize].1 as usize >= wanted;
    // Regions around each candidate edge, from the cells of its polygons:
    // one (edge, region) entry per polygon side, sorted and deduplicated,
    // so each edge's regions are a sorted run (no map of small vectors).
    let mut around: Vec<((u32, u32), RegionId)> = Vec::new();
    for f in 0..net.num_faces() {
        let p = net.face(f);
        let cells = net.face_cells[f];
        for k in 0..p.len() {
            let (a, b) = (p[k], p[if k + 1 == p.len() { 0 } else { k + 1 }]);
            if !(may_be_curve(a) && may_be_curve(b)) {
                continue;
            }
            for c in cells {
                if c != u32::MAX {
                    around.push(((a.min(b), a.max(b)), region[c as usize]));
                }
            }
        }
    }
    around.sort_unstable();
    around.dedup();
    let mut curve_edges: FxHashMap<[RegionId; 3], Vec<(u32, u32)>> = FxHashMap::default();
    // Few distinct region sets occur: ask `pick` once per set.
    let mut picked: FxHashMap<Vec<RegionId>, Option<[RegionId; 3]>> = FxHashMap::default();
    let mut set: Vec<RegionId> = Vec::new();
    let mut i = 0;
    while i < around.len() {
        let e = around[i].0;
        set.clear();
        while i < around.len() && around[i].0 == e {
            set.push(around[i].1);
            i += 1;
        }
        let t = match picked.get(&set) {
            Some(&t) => t,
            None => {
                let t = pick(&set);
                picked.insert(set.clone(), t);
                t
            }
        };
        if let Some(t) = t {
            curve_edges.entry(t).or_default().push(e);
        }
    }
    let mut triples: Vec<[RegionId; 3]> = curve_edges.keys().copied().collect();
    triples.sort();
    let mut out = Vec::new();
    for t in triples {
        for (vertices, closed) in polylines(&curve_edges[&t]) {
            let length = path_length(&net.points, &vertices);
            out.push(Curve {
                kind: CurveKind::Junction,
                regions: t.to_vec(),
                functions: Vec::new(),
                vertices,
                closed,
                length,
            });
        }
    }
    out
}

/// Splits an edge set into maximal paths between vertices of degree != 2,
/// and loops; deterministic for a sorted input.
pub(crate) fn polylines(edges: &[(u32, u32)]) -> Vec<(Vec<u32>, bool)> {
    let mut adj: FxHashMap<u32, Vec<(u32, usize)>> = FxHashMap::default();
    for (i, &(a, b)) in edges.iter().enumerate() {
        adj.entry(a).or_default().push((b, i));
        adj.entry(b).or_default().push((a, i));
    }
    let mut used = vec![false; edges.len()];
    let mut out = Vec::new();
    let walk = |start: u32, first: usize, used: &mut Vec<bool>| {
        let mut path = vec![start];
        let (mut cur, mut e) = (start, first);
        loop {
            used[e] = true;
            let (a, b) = edges[e];
            let next = if a == cur { b } else { a };
            path.push(next);
            cur = next;
            if adj[&cur].len() != 2 {
                break;
            }
            match adj[&cur].iter().find(|&&(_, j)| !used[j]) {
                Some(&(_, j)) => e = j,
                None => break,
            }
        }
        let closed = path.len() > 2 && path[0] == *path.last().unwrap();
        (path, closed)
    };
    let mut ends: Vec<u32> = adj.iter().filter(|(_, n)| n.len() != 2).map(|(&v, _)| v).collect();
    ends.sort_unstable();
    for v in ends {
        for &(_, e) in adj[&v].clone().iter() {
            if !used[e] {
                out.push(walk(v, e, &mut used));
            }
        }
    }
    for e in 0..edges.len() {
        if !used[e] {
            out.push(walk(edges[e].0, e, &mut used));
        }
    }
    out
}
