//! Intersection lines and the linear order of cut-vertices on them
//! (TopoCut Sec. 3.1): mesh edges `(T,T)` and plane pairs `(P,P)`. Equal
//! points on a line are merged; the ordered, merged sequence gives the
//! cut-edges on that line. (Lines `(T,P)` inside a triangle are ordered by
//! the clipping in [`crate::cut::arrangement::clip`].)

use crate::cut::arrangement::nodes::{FxMap, Nodes};
use crate::cut::base::geom::{dot3, Ctx, Def, LineDir, V3};
use septa_exact::{Bounded, Interval, Ring, Sign};
use std::cmp::Ordering;

/// Homogeneous coordinates `(H, W)` of three-plane points, kept across the
/// three plane-pair lines each lies on: as [`Bounded`] doubles, and as
/// intervals once a comparison needed them.
#[derive(Default)]
pub struct HomCache {
    bounded: FxMap<u32, (V3<Bounded>, Bounded)>,
    interval: FxMap<u32, (V3<Interval>, Interval)>,
}

impl HomCache {
    fn hom<R: Ring>(c: &Ctx, map: &mut FxMap<u32, (V3<R>, R)>, n: u32, d: Def) -> (V3<R>, R) {
        if let Def::PPP(..) = d {
            map.entry(n).or_insert_with(|| c.hom::<R>(d)).clone()
        } else {
            c.hom::<R>(d)
        }
    }
}

/// Sorts nodes along a line direction, merges equal points, and returns one
/// node per distinct point in increasing order. `cache` keeps the
/// coordinates of `PPP` nodes between calls.
pub fn sort_line(c: &Ctx, nodes: &mut Nodes, pts: &mut Vec<u32>, dir: LineDir, cache: &mut HomCache) -> Vec<u32> {
    pts.sort_unstable();
    pts.dedup();
    let defs = &nodes.defs;
    // floating-point pre-sort keys (paper Sec. 6.3, "line sorting speedup"),
    // decided exactly whenever they cannot tell. First tier: the line
    // parameters `H.d / W` as doubles with proven error bounds (a few
    // multiplications each, where the tight intervals below cost dozens);
    // the sign of a difference of two decides their order.
    let params: Vec<Option<Bounded>> = {
        let dv = c.line_dir::<Bounded>(dir);
        pts.iter()
            .map(|&n| {
                let (h, w) = HomCache::hom(c, &mut cache.bounded, n, defs[n as usize]);
                dot3(&h, &dv).div(&w)
            })
            .collect()
    };
    // Second tier, for the pairs the first leaves open (nearly or exactly
    // equal points, `W` near zero): the same comparison in tight intervals,
    // which also see the exact zeros of coincident points; formed on first
    // use. Third: the exact order.
    type Key = (Interval, Interval, Option<Interval>);
    let intervals: std::cell::RefCell<(Vec<Option<Key>>, &mut FxMap<u32, (V3<Interval>, Interval)>)> =
        std::cell::RefCell::new((vec![None; pts.len()], &mut cache.interval));
    let dv_iv = c.line_dir::<Interval>(dir);
    // `(H.d, W)` and the enclosure of their quotient
    let key = |i: usize| -> Key {
        let mut iv = intervals.borrow_mut();
        if let Some(k) = iv.0[i] {
            return k;
        }
        let (h, w) = HomCache::hom(c, iv.1, pts[i], defs[pts[i] as usize]);
        let hd = dot3(&h, &dv_iv);
        let k = (hd, w, hd.div(&w));
        iv.0[i] = Some(k);
        k
    };
    let mut idx: Vec<usize> = (0..pts.len()).collect();
    let memo: std::cell::RefCell<FxMap<(usize, usize), Sign>> = Default::default();
    let cmp = |&i: &usize, &j: &usize| -> Ordering {
        if i == j {
            return Ordering::Equal;
        }
        let first = match (params[i], params[j]) {
            (Some(a), Some(b)) => b.sub(&a).sign(),
            _ => None,
        };
        let s = match first {
            Some(s) => s,
            None => {
                let ((ha, wa, pa), (hb, wb, pb)) = (key(i), key(j));
                // disjoint enclosures of the parameters, then the sign of
                // their difference's numerator
                let disjoint = match (pa, pb) {
                    (Some(a), Some(b)) if a.hi < b.lo => Some(Sign::Positive),
                    (Some(a), Some(b)) if a.lo > b.hi => Some(Sign::Negative),
                    _ => None,
                };
                let numerator = || hb.mul(&wa).sub(&ha.mul(&wb)).mul(&wa).mul(&wb).sign();
                match disjoint.or_else(numerator) {
                    Some(s) => s,
                    None => {
                        // exact results memoised: a pair of equal points is
                        // met again when merging
                        let key = (i.min(j), i.max(j));
                        let cached = memo.borrow().get(&key).copied();
                        let s = match cached {
                            Some(s) => s,
                            None => {
                                let s = c.order(defs[pts[key.0] as usize], defs[pts[key.1] as usize], dir);
                                memo.borrow_mut().insert(key, s);
                                s
                            }
                        };
                        if i < j {
                            s
                        } else {
                            s.flip()
                        }
                    }
                }
            }
        };
        match s {
            Sign::Positive => Ordering::Less,
            Sign::Negative => Ordering::Greater,
            Sign::Zero => Ordering::Equal,
        }
    };
    idx.sort_by(cmp);
    let mut out: Vec<u32> = Vec::with_capacity(idx.len());
    let mut last: Option<usize> = None;
    let mut merges: Vec<(u32, u32)> = Vec::new();
    for &i in &idx {
        if let Some(l) = last {
            if cmp(&l, &i) == Ordering::Equal {
                merges.push((pts[l], pts[i]));
                continue;
            }
        }
        out.push(pts[i]);
        last = Some(i);
    }
    for (a, b) in merges {
        nodes.union(a, b);
    }
    out
}

/// Point lists of plane-pair lines, keyed by `(p, q)` with `p < q`.
pub type LinePoints = FxMap<(u32, u32), Vec<u32>>;

/// Registers a point on every plane-pair line through it.
pub fn register(lines: &mut LinePoints, crosses: &[bool], np: usize, node: u32, planes: &[u32]) {
    for (i, &a) in planes.iter().enumerate() {
        for &b in &planes[i + 1..] {
            let (p, q) = (a.min(b), a.max(b));
            if p != q && crosses[p as usize * np + q as usize] {
                lines.entry((p, q)).or_default().push(node);
            }
        }
    }
}

/// Mesh edges cut by planes: for each edge, the ordered distinct points
/// from `u` to `v`; registers every point that lies on two planes.
pub fn mesh_edges(c: &Ctx, nodes: &mut Nodes, lines: &mut LinePoints, crosses: &[bool]) -> Vec<Vec<u32>> {
    let np = c.planes.len();
    let mut chains = Vec::with_capacity(c.edges.len());
    let mut pts = Vec::new();
    let mut cache = HomCache::default();
    for (e, &[u, v]) in c.edges.iter().enumerate() {
        let e = e as u32;
        pts.clear();
        let mut inside: Vec<u32> = Vec::new();
        for p in 0..np as u32 {
            let (su, sv) = (c.pv_sign(p, u), c.pv_sign(p, v));
            if su * sv < 0 {
                pts.push(nodes.get(Def::EP(e, p)));
            } else if su == 0 && sv == 0 {
                inside.push(p);
            }
        }
        let mut chain = vec![nodes.get(Def::V(u))];
        if !pts.is_empty() {
            let sorted = sort_line(c, nodes, &mut pts, LineDir::Mesh(e), &mut cache);
            for &n in &sorted {
                // all planes crossing here, plus those containing the edge
                let r = nodes.find(n);
                let mut z: Vec<u32> = Vec::new();
                for &m in pts.iter() {
                    if nodes.find(m) == r {
                        if let Def::EP(_, p) = nodes.defs[m as usize] {
                            z.push(p);
                        }
                    }
                }
                z.extend(inside.iter().copied());
                if z.len() >= 2 {
                    register(lines, crosses, np, n, &z);
                }
            }
            chain.extend(sorted);
        }
        chain.push(nodes.get(Def::V(v)));
        chains.push(chain);
    }
    for v in 0..c.verts.len() as u32 {
        let z: Vec<u32> = (0..np as u32).filter(|&p| c.pv_sign(p, v) == 0).collect();
        if z.len() >= 2 {
            let n = nodes.get(Def::V(v));
            register(lines, crosses, np, n, &z);
        }
    }
    chains
}

/// Plane-pair lines: adds the three-plane points and sorts every line.
/// Returns, per line, the ordered distinct points.
pub fn plane_lines(
    c: &Ctx,
    nodes: &mut Nodes,
    lines: &mut LinePoints,
    crosses: &[bool],
) -> Vec<((u32, u32), Vec<u32>)> {
    let np = c.planes.len() as u32;
    let mut out = Vec::new();
    let mut cache = HomCache::default();
    for p in 0..np {
        for q in p + 1..np {
            if !crosses[(p * np + q) as usize] {
                continue;
            }
            // A line that meets no point of the mesh misses the bounded
            // domain entirely: every point where it meets the surface was
            // registered (vertex, edge crossing or triangle interior).
            let Some(mut pts) = lines.remove(&(p, q)) else {
                continue;
            };
            for r in 0..np {
                if r != p && r != q && c.det3(p, q, r) != Sign::Zero {
                    let mut k = [p, q, r];
                    k.sort_unstable();
                    pts.push(nodes.get(Def::PPP(k[0], k[1], k[2])));
                }
            }
            if pts.is_empty() {
                continue;
            }
            let sorted = sort_line(c, nodes, &mut pts, LineDir::PlanePlane(p, q), &mut cache);
            out.push(((p, q), sorted));
        }
    }
    out
}

#[cfg(test)]
#[path = "lines_tests.rs"]
mod tests;
