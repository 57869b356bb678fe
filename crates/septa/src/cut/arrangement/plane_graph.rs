//! Cut-faces inside cut-planes (TopoCut Sec. 4): the half-edge structure
//! `H(p)` of plane `p` built from its intersection lines with the other
//! planes, the boundary curves `p ^ dOmega` (pieces of `(T,P)` lines and mesh
//! edges lying in `p`), exact edge-cycle ordering around each vertex, and
//! the loops of `next`. A loop is a cut-face when the region on its left
//! is inside the domain: known at once from any boundary edge of the loop
//! (App. C's side tests), and carried across plane-plane edges by
//! union-find otherwise.

use crate::cut::arrangement::nodes::FxMap;
use crate::cut::base::geom::{cross3, dot3, neg3, sub3, v3, Ctx, LineDir, V3};
use crate::uf::UnionFind;
use septa_exact::{filtered_sign_bounded, Bounded, Exact, Interval, Ring, Sign};

/// An edge of a plane graph or a face: end points (compact ids), the line
/// it lies on, and whether `a -> b` runs along `+dir`.
#[derive(Clone, Copy, Debug)]
pub struct GEdge {
    /// First end.
    pub a: u32,
    /// Second end.
    pub b: u32,
    /// Supporting line.
    pub dir: LineDir,
    /// `a -> b` is along `+dir`.
    pub fwd: bool,
}

/// What lies on the left of a half-edge in a plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// Inside the domain.
    Inside,
    /// Outside.
    Outside,
    /// On a mesh triangle lying in the plane.
    Surface,
}

/// A cut-face on a plane: one loop of compact vertex ids, counter-clockwise
/// about the plane normal for an outer boundary (clockwise for a hole),
/// with the line of each edge `i -> i+1`.
#[derive(Clone, Debug)]
pub struct PlaneLoop {
    /// The plane.
    pub plane: u32,
    /// Corners.
    pub verts: Vec<u32>,
    /// Line of edge `i -> i+1` and whether it runs along `+dir`.
    pub dirs: Vec<(LineDir, bool)>,
    /// Index (in the plane's list) of the outer loop of the cut-face this
    /// loop bounds: itself for an outer boundary, the enclosing loop for a hole.
    pub outer: u32,
    /// The loop has an edge on a plane-plane line only (not on the mesh):
    /// then it is an outer boundary, since no plane-plane line reaches into
    /// a hole of an inside face (it would have to cross the face).
    pub has_line_edge: bool,
}

/// Boundary information for edges (compact end points, sorted).
pub struct Boundary {
    /// Edges strictly inside triangle `t` (on a `(T,P)` line).
    pub gamma: FxMap<(u32, u32), u32>,
    /// Edges on mesh edge `e`.
    pub mesh: FxMap<(u32, u32), u32>,
}

pub(crate) fn dir_vec<R: Ring>(c: &Ctx, d: LineDir, fwd: bool) -> V3<R> {
    let v = c.line_dir::<R>(d);
    if fwd {
        v
    } else {
        neg3(&v)
    }
}

/// Counter-clockwise order of directions in the plane with normal `n`.
pub(crate) struct Ccw {
    pub(crate) i: usize,
    pub(crate) j: usize,
    pub(crate) flip: bool,
}

impl Ccw {
    pub(crate) fn new(n: &[f64; 3]) -> Ccw {
        let k = (0..3).max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs())).unwrap();
        Ccw { i: (k + 1) % 3, j: (k + 2) % 3, flip: n[k] < 0.0 }
    }

    fn half(&self, c: &Ctx, d: (LineDir, bool), iv: &V3<Interval>) -> u8 {
        let comp = |k: usize| match iv[k].sign() {
            Some(s) => s,
            None => filtered_sign_bounded(
                || dir_vec::<Bounded>(c, d.0, d.1)[k],
                || dir_vec::<Interval>(c, d.0, d.1)[k],
                || dir_vec::<Exact>(c, d.0, d.1)[k].clone(),
            ),
        };
        let y = comp(self.j);
        if y == Sign::Positive || (y == Sign::Zero && comp(self.i) == Sign::Positive) {
            0
        } else {
            1
        }
    }

    pub(crate) fn cross(&self, c: &Ctx, a: (LineDir, bool), b: (LineDir, bool)) -> Sign {
        let (i, j) = (self.i, self.j);
        fn f<R: Ring>(c: &Ctx, a: (LineDir, bool), b: (LineDir, bool), i: usize, j: usize) -> R {
            let x = dir_vec::<R>(c, a.0, a.1);
            let y = dir_vec::<R>(c, b.0, b.1);
            x[i].mul(&y[j]).sub(&x[j].mul(&y[i]))
        }
        filtered_sign_bounded(
            || f::<Bounded>(c, a, b, i, j),
            || f::<Interval>(c, a, b, i, j),
            || f::<Exact>(c, a, b, i, j),
        )
    }

    /// Sorts directions counter-clockwise about the plane normal (stable:
    /// directions that compare equal keep their order).
    fn sort(&self, c: &Ctx, items: &mut [(u32, (LineDir, bool))]) {
        // A vertex of a plane's graph has a handful of half-edges (four where
        // two lines cross): their keys stay on the stack and an insertion
        // sort orders them, where vectors per vertex and a merge sort were
        // most of this function's time on the small cuts.
        const SMALL: usize = 12;
        if items.len() <= SMALL {
            let mut iv = [[Interval::point(0.0); 3]; SMALL];
            let mut halves = [0u8; SMALL];
            for (k, x) in items.iter().enumerate() {
                iv[k] = dir_vec::<Interval>(c, x.1 .0, x.1 .1);
                halves[k] = self.half(c, x.1, &iv[k]);
            }
            let mut idx: [u8; SMALL] = std::array::from_fn(|k| k as u8);
            let idx = &mut idx[..items.len()];
            for a in 1..idx.len() {
                let mut b = a;
                while b > 0 && self.cmp(c, items, &iv, &halves, idx[b] as usize, idx[b - 1] as usize).is_lt() {
                    idx.swap(b, b - 1);
                    b -= 1;
                }
            }
            let sorted: [(u32, (LineDir, bool)); SMALL] =
                std::array::from_fn(|k| items[idx.get(k).map_or(0, |&i| i as usize)]);
            items.copy_from_slice(&sorted[..items.len()]);
        } else {
            // interval directions computed once per item; exact only on doubt
            let iv: Vec<V3<Interval>> = items.iter().map(|x| dir_vec::<Interval>(c, x.1 .0, x.1 .1)).collect();
            let halves: Vec<u8> = items.iter().zip(&iv).map(|(x, v)| self.half(c, x.1, v)).collect();
            let mut idx: Vec<usize> = (0..items.len()).collect();
            idx.sort_by(|&x, &y| self.cmp(c, items, &iv, &halves, x, y));
            let sorted: Vec<_> = idx.iter().map(|&k| items[k]).collect();
            items.copy_from_slice(&sorted);
        }
        if self.flip {
            items.reverse();
        }
    }

    /// The counter-clockwise order of directions `x` and `y` of `items` (by
    /// half-plane, then by the exact sign of their cross product; interval
    /// copies `iv` first); `Equal` for parallel ones.
    fn cmp(
        &self,
        c: &Ctx,
        items: &[(u32, (LineDir, bool))],
        iv: &[V3<Interval>],
        halves: &[u8],
        x: usize,
        y: usize,
    ) -> std::cmp::Ordering {
        let (hx, hy) = (halves[x], halves[y]);
        if hx != hy {
            return hx.cmp(&hy);
        }
        let (i, j) = (self.i, self.j);
        let cr = iv[x][i].mul(&iv[y][j]).sub(&iv[x][j].mul(&iv[y][i]));
        let s = match cr.sign() {
            Some(s) => s,
            None => self.cross(c, items[x].1, items[y].1),
        };
        match s {
            Sign::Positive => std::cmp::Ordering::Less,
            Sign::Negative => std::cmp::Ordering::Greater,
            Sign::Zero => std::cmp::Ordering::Equal,
        }
    }
}

/// Side status of the left of half-edge `h` in plane `p` for an edge inside
/// triangle `t`: below the triangle is inside.
fn gamma_status(c: &Ctx, p: u32, t: u32, h: (LineDir, bool)) -> Status {
    // On the line t ^ p itself the side is known: with h = n_p x n_t,
    // n_t . (n_p x h) = (n_p . n_t)^2 - |n_p|^2 |n_t|^2 < 0 (inside).
    if h.0 == LineDir::TriPlane(t, p) {
        return if h.1 { Status::Inside } else { Status::Outside };
    }
    fn f<R: Ring>(c: &Ctx, p: u32, t: u32, h: (LineDir, bool)) -> R {
        let w = cross3(&c.pn::<R>(p), &dir_vec::<R>(c, h.0, h.1));
        dot3(&c.tn::<R>(t), &w)
    }
    match filtered_sign_bounded(|| f::<Bounded>(c, p, t, h), || f::<Interval>(c, p, t, h), || f::<Exact>(c, p, t, h)) {
        Sign::Negative => Status::Inside,
        Sign::Positive => Status::Outside,
        Sign::Zero => Status::Surface,
    }
}

/// Side status of the left of half-edge `h` in plane `p` for an edge on mesh
/// edge `e`: the direction `w = n_p x h` against the wedge of the two
/// triangles at `e` (TopoCut Sec. 4.1, face-cycle test of tuple types); at a
/// non-manifold edge against each of its wedges, which are disjoint (App. C,
/// eq. 18: inside one of them is inside).
pub(crate) fn mesh_status(c: &Ctx, p: u32, e: u32, h: (LineDir, bool)) -> Status {
    let Some(ws) = c.wedges.get(&e) else {
        return wedge_status(c, p, e, c.edge_tris[e as usize], h);
    };
    let mut status = Status::Outside;
    for &w in ws {
        match wedge_status(c, p, e, w, h) {
            Status::Inside => return Status::Inside,
            Status::Surface => status = Status::Surface,
            Status::Outside => {}
        }
    }
    status
}

/// [`mesh_status`] for the wedge between `t1` (running `u -> v`) and `t2`.
fn wedge_status(c: &Ctx, p: u32, e: u32, [t1, t2]: [u32; 2], h: (LineDir, bool)) -> Status {
    let [u, v] = c.edges[e as usize];
    let apex = *c.tris[t2 as usize].iter().find(|&&x| x != u && x != v).unwrap();
    fn side<R: Ring>(c: &Ctx, p: u32, t: u32, h: (LineDir, bool)) -> R {
        let w = cross3(&c.pn::<R>(p), &dir_vec::<R>(c, h.0, h.1));
        dot3(&c.tn::<R>(t), &w)
    }
    fn conv<R: Ring>(c: &Ctx, t1: u32, u: u32, apex: u32) -> R {
        dot3(&c.tn::<R>(t1), &sub3(&v3(&c.verts[apex as usize]), &v3(&c.verts[u as usize])))
    }
    let s1 = filtered_sign_bounded(
        || side::<Bounded>(c, p, t1, h),
        || side::<Interval>(c, p, t1, h),
        || side::<Exact>(c, p, t1, h),
    );
    let s2 = filtered_sign_bounded(
        || side::<Bounded>(c, p, t2, h),
        || side::<Interval>(c, p, t2, h),
        || side::<Exact>(c, p, t2, h),
    );
    let cv = filtered_sign_bounded(
        || conv::<Bounded>(c, t1, u, apex),
        || conv::<Interval>(c, t1, u, apex),
        || conv::<Exact>(c, t1, u, apex),
    );
    use Sign::*;
    match cv {
        Negative => {
            if s1 == Negative && s2 == Negative {
                Status::Inside
            } else if (s1 == Zero && s2 == Negative) || (s2 == Zero && s1 == Negative) {
                Status::Surface
            } else {
                Status::Outside
            }
        }
        Positive => {
            if s1 == Positive && s2 == Positive {
                Status::Outside
            } else if (s1 == Zero && s2 == Positive) || (s2 == Zero && s1 == Positive) {
                Status::Surface
            } else {
                Status::Inside
            }
        }
        Zero => match s1 {
            Negative => Status::Inside,
            Zero => Status::Surface,
            Positive => Status::Outside,
        },
    }
}

/// Builds `H(p)` from its edges and returns the inside loops (cut-faces).
pub fn plane_faces(c: &Ctx, p: u32, edges: &[GEdge], bnd: &Boundary, unclassified: &mut u64) -> Vec<PlaneLoop> {
    // dedup edges by end points
    let mut seen: FxMap<(u32, u32), ()> = FxMap::default();
    let mut es: Vec<GEdge> = Vec::with_capacity(edges.len());
    for e in edges {
        if e.a == e.b {
            continue;
        }
        let k = (e.a.min(e.b), e.a.max(e.b));
        if seen.insert(k, ()).is_none() {
            es.push(*e);
        }
    }
    // half-edges 2k: a->b, 2k+1: b->a
    let nh = es.len() * 2;
    let tail = |h: usize| if h % 2 == 0 { es[h / 2].a } else { es[h / 2].b };
    let hdir = |h: usize| -> (LineDir, bool) {
        let e = &es[h / 2];
        (e.dir, if h % 2 == 0 { e.fwd } else { !e.fwd })
    };
    // the half-edges grouped by tail (in order of half-edge within a
    // tail, as they were pushed before), each group then sorted into its
    // tail's cyclic order: one array of rings, `(start, len)` per ring
    let mut by_tail: Vec<(u32, u32)> = (0..nh as u32).map(|h| (tail(h as usize), h)).collect();
    by_tail.sort_unstable();
    let mut ring_hs: Vec<(u32, (LineDir, bool))> = by_tail.iter().map(|&(_, h)| (h, hdir(h as usize))).collect();
    let ccw = Ccw::new(&[c.planes[p as usize][0], c.planes[p as usize][1], c.planes[p as usize][2]]);
    // position of each half-edge in its tail's cyclic order: its ring's
    // start and length, its index in `ring_hs`
    let mut pos = vec![(0u32, 0u32, 0u32); nh];
    let mut s = 0;
    while s < nh {
        let mut e = s + 1;
        while e < nh && by_tail[e].0 == by_tail[s].0 {
            e += 1;
        }
        let list = &mut ring_hs[s..e];
        if list.len() > 1 {
            ccw.sort(c, list);
        }
        for (i, x) in list.iter().enumerate() {
            pos[x.0 as usize] = (s as u32, (e - s) as u32, (s + i) as u32);
        }
        s = e;
    }
    // next(h) = the half-edge clockwise after twin(h) at the head of h
    let next = |h: usize| -> usize {
        let (start, len, at) = pos[h ^ 1];
        let j = if at == start { start + len - 1 } else { at - 1 };
        ring_hs[j as usize].0 as usize
    };
    let mut loop_of = vec![u32::MAX; nh];
    let mut loops: Vec<Vec<usize>> = Vec::new();
    for h0 in 0..nh {
        if loop_of[h0] != u32::MAX {
            continue;
        }
        let l = loops.len() as u32;
        let mut cyc = Vec::new();
        let mut h = h0;
        while loop_of[h] == u32::MAX {
            loop_of[h] = l;
            cyc.push(h);
            h = next(h);
        }
        loops.push(cyc);
    }
    // status of loops
    let mut status: Vec<Option<Status>> = vec![None; loops.len()];
    let mut line_edge = vec![false; loops.len()];
    let mut joined = UnionFind::new(loops.len());
    for h in 0..nh {
        let e = &es[h / 2];
        let k = (e.a.min(e.b), e.a.max(e.b));
        let l = loop_of[h] as usize;
        // a loop's status is that of its first boundary half-edge: the
        // others' are not computed
        if let Some(&t) = bnd.gamma.get(&k) {
            if status[l].is_none() {
                status[l] = Some(gamma_status(c, p, t, hdir(h)));
            }
        } else if let Some(&me) = bnd.mesh.get(&k) {
            if status[l].is_none() {
                status[l] = Some(mesh_status(c, p, me, hdir(h)));
            }
        } else {
            line_edge[l] = true;
            if h % 2 == 0 {
                joined.union(loop_of[h], loop_of[h ^ 1]);
            }
        }
    }
    let mut comp_status: Vec<Option<Status>> = vec![None; loops.len()];
    for l in 0..loops.len() {
        if let Some(s) = status[l] {
            let r = joined.find(l as u32) as usize;
            if comp_status[r].is_none() {
                comp_status[r] = Some(s);
            }
        }
    }
    if std::env::var("SEPTA_DEBUG").is_ok() {
        eprintln!("plane {p}: {} edges, {} loops, status {:?}", es.len(), loops.len(), status);
        for e in &es {
            eprintln!("  edge {} {} {:?} fwd {}", e.a, e.b, e.dir, e.fwd);
        }
        for cyc in &loops {
            eprintln!("  loop {:?}", cyc.iter().map(|&h| tail(h)).collect::<Vec<_>>());
        }
    }
    let mut faces = Vec::new();
    for (l, cyc) in loops.iter().enumerate() {
        let s = match status[l] {
            Some(s) => s,
            None => {
                let r = joined.find(l as u32) as usize;
                match comp_status[r] {
                    Some(s) => s,
                    None => {
                        *unclassified += 1;
                        Status::Outside
                    }
                }
            }
        };
        if s != Status::Inside {
            continue;
        }
        faces.push(PlaneLoop {
            plane: p,
            verts: cyc.iter().map(|&h| tail(h)).collect(),
            dirs: cyc.iter().map(|&h| hdir(h)).collect(),
            outer: 0,
            has_line_edge: line_edge[l],
        });
    }
    faces
}

#[cfg(test)]
#[path = "plane_graph_tests.rs"]
mod tests;
