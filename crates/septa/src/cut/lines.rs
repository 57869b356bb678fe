//! Intersection lines and the linear order of cut-vertices on them
//! (TopoCut Sec. 3.1): mesh edges `(T,T)` and plane pairs `(P,P)`. Equal
//! points on a line are merged; the ordered, merged sequence gives the
//! cut-edges on that line. (Lines `(T,P)` inside a triangle are ordered by
//! the clipping in [`super::clip`].)

use super::geom::{dot3, Ctx, Def, LineDir, V3};
use super::nodes::{FxMap, Nodes};
use septa_exact::{Interval, Ring, Sign};
use std::cmp::Ordering;

/// Interval homogeneous coordinates `(H, W)` of three-plane points, kept
/// across the three plane-pair lines each lies on.
pub type HomCache = FxMap<u32, (V3<Interval>, Interval)>;

/// Sorts nodes along a line direction, merges equal points, and returns one
/// node per distinct point in increasing order. `cache` keeps the interval
/// coordinates of `PPP` nodes between calls.
pub fn sort_line(c: &Ctx, nodes: &mut Nodes, pts: &mut Vec<u32>, dir: LineDir, cache: &mut HomCache) -> Vec<u32> {
    pts.sort_unstable();
    pts.dedup();
    // floating-point pre-sort keys (paper Sec. 6.3, "line sorting speedup"),
    // decided exactly whenever the intervals overlap
    let dv = c.line_dir::<Interval>(dir);
    let keys: Vec<(Interval, Interval)> = pts
        .iter()
        .map(|&n| {
            let d = nodes.defs[n as usize];
            let (h, w) = if let Def::PPP(..) = d {
                cache.entry(n).or_insert_with(|| c.hom::<Interval>(d)).clone()
            } else {
                c.hom::<Interval>(d)
            };
            (dot3(&h, &dv), w)
        })
        .collect();
    // First tier: enclosures of the exact line parameters `H.d / W`; two
    // disjoint ones order their points (the comparison below is the sign
    // of the same difference), overlapping ones go on to the products.
    let params: Vec<Option<Interval>> = keys.iter().map(|(h, w)| h.div(w)).collect();
    let mut idx: Vec<usize> = (0..pts.len()).collect();
    let defs = &nodes.defs;
    let memo: std::cell::RefCell<FxMap<(usize, usize), Sign>> = Default::default();
    let cmp = |&i: &usize, &j: &usize| -> Ordering {
        if i == j {
            return Ordering::Equal;
        }
        if let (Some(a), Some(b)) = (params[i], params[j]) {
            if a.hi < b.lo {
                return Ordering::Less;
            }
            if a.lo > b.hi {
                return Ordering::Greater;
            }
        }
        let (ha, wa) = keys[i];
        let (hb, wb) = keys[j];
        let x = hb.mul(&wa).sub(&ha.mul(&wb)).mul(&wa).mul(&wb);
        let s = match x.sign() {
            Some(s) => s,
            None => {
                // exact results memoised: a pair of equal points is met again
                // when merging
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
