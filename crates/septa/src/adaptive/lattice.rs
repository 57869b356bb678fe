//! A conforming tet mesh on an integer lattice, refined by longest-edge
//! bisection with closure (Rivara's algorithm): a tet is split at the
//! midpoint of its longest edge, and every tet left with a hanging vertex
//! (a midpoint of one of its edges that is a vertex of the mesh) is split
//! in turn until none is left.
//!
//! Coordinates are integers (`i64`), so every midpoint is exact: the start
//! grid's cubes have an edge of `2^SHIFT` units and bisection never needs a
//! half unit before `SHIFT` levels of halving (the refinement stops long
//! before, at `--min-edge`). Lengths are compared exactly (`i128`), ties
//! broken by the edge's end coordinates, so the result does not depend on
//! the order tets are visited in.
//!
//! The start cubes are split into Kuhn's (Freudenthal's) six tets around
//! the cube's main diagonal, which conform across cube faces. Longest-edge
//! bisection of Kuhn tets produces finitely many shapes (Maubach 1995;
//! Arnold, Mukherjee and Pouly 2000, who show it is the newest-vertex
//! scheme with a bounded number of similarity classes), so quality cannot
//! degrade without bound; `AdaptiveGrid::quality` reports the measured
//! worst radius ratio.

use std::collections::HashMap;

/// A lattice point.
pub type IPoint = [i64; 3];

/// Lattice units per start-cube edge: 2^30 leaves 30 halvings of a start
/// cube (a thousand-millionth of it) before a midpoint could need a half
/// unit, and keeps squared lengths far inside `i128`.
pub const SHIFT: u32 = 30;

/// The refinable mesh.
pub struct Lattice {
    /// Vertex coordinates.
    pub verts: Vec<IPoint>,
    index: HashMap<IPoint, u32>,
    /// Tets (positively oriented), dead ones included.
    pub tets: Vec<[u32; 4]>,
    /// Whether a tet is a leaf of the refinement (part of the mesh).
    pub alive: Vec<bool>,
    /// Leaf tets around each vertex.
    around: Vec<Vec<u32>>,
}

/// The six edges of a tet as pairs of corner slots.
pub const EDGES: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];

impl Lattice {
    /// Kuhn's six tets in each of `n[0] x n[1] x n[2]` cubes of edge
    /// `2^SHIFT`, the lattice's origin at the grid's lowest corner.
    pub fn kuhn(n: [usize; 3]) -> Lattice {
        let mut l = Lattice { verts: vec![], index: HashMap::new(), tets: vec![], alive: vec![], around: vec![] };
        let s = 1i64 << SHIFT;
        let perms = [[0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]];
        for i in 0..n[0] as i64 {
            for j in 0..n[1] as i64 {
                for k in 0..n[2] as i64 {
                    let o = [i * s, j * s, k * s];
                    for p in perms {
                        let mut v = o;
                        let mut ids = [0u32; 4];
                        ids[0] = l.vertex(v);
                        for (slot, &axis) in p.iter().enumerate() {
                            v[axis] += s;
                            ids[slot + 1] = l.vertex(v);
                        }
                        l.push(ids);
                    }
                }
            }
        }
        l
    }

    /// The id of the vertex at `p`, created if new.
    fn vertex(&mut self, p: IPoint) -> u32 {
        if let Some(&v) = self.index.get(&p) {
            return v;
        }
        let v = self.verts.len() as u32;
        self.verts.push(p);
        self.index.insert(p, v);
        self.around.push(Vec::new());
        v
    }

    /// Adds a leaf tet, positively oriented.
    fn push(&mut self, mut ids: [u32; 4]) -> u32 {
        if orient(&ids.map(|v| self.verts[v as usize])) < 0 {
            ids.swap(2, 3);
        }
        let t = self.tets.len() as u32;
        self.tets.push(ids);
        self.alive.push(true);
        for v in ids {
            self.around[v as usize].push(t);
        }
        t
    }

    fn kill(&mut self, t: u32) {
        self.alive[t as usize] = false;
        for v in self.tets[t as usize] {
            let a = &mut self.around[v as usize];
            if let Some(i) = a.iter().position(|&x| x == t) {
                a.swap_remove(i);
            }
        }
    }

    /// Number of leaf tets.
    pub fn leaves(&self) -> usize {
        self.alive.iter().filter(|&&a| a).count()
    }

    /// The corner slots of the tet's longest edge: exact lengths, ties
    /// broken by the smaller end coordinates (the same choice whichever tet
    /// holding the edge asks).
    pub fn longest_edge(&self, t: u32) -> (usize, usize) {
        let ids = self.tets[t as usize];
        let key = |(a, b): (usize, usize)| {
            let (p, q) = (self.verts[ids[a] as usize], self.verts[ids[b] as usize]);
            let len: i128 = (0..3).map(|k| ((p[k] - q[k]) as i128).pow(2)).sum();
            let (lo, hi) = if p < q { (p, q) } else { (q, p) };
            (len, std::cmp::Reverse(lo), std::cmp::Reverse(hi))
        };
        EDGES.into_iter().max_by_key(|&e| key(e)).unwrap()
    }

    /// The midpoint of an edge if it is a vertex of the mesh (a hanging
    /// vertex when the edge belongs to a leaf).
    fn midpoint_vertex(&self, a: u32, b: u32) -> Option<u32> {
        let (p, q) = (self.verts[a as usize], self.verts[b as usize]);
        let mut m = [0; 3];
        for k in 0..3 {
            let s = p[k] + q[k];
            if s % 2 != 0 {
                return None;
            }
            m[k] = s / 2;
        }
        self.index.get(&m).copied()
    }

    fn hanging(&self, t: u32) -> bool {
        let ids = self.tets[t as usize];
        EDGES.iter().any(|&(a, b)| self.midpoint_vertex(ids[a], ids[b]).is_some())
    }

    /// Splits leaf `t` at its longest edge; returns the two children and
    /// whether the midpoint is a new vertex (then the other leaves holding
    /// the edge now hang) with the edge's ends.
    fn bisect(&mut self, t: u32) -> ([u32; 2], Option<(u32, u32)>) {
        let (a, b) = self.longest_edge(t);
        let ids = self.tets[t as usize];
        let (p, q) = (ids[a], ids[b]);
        let new = self.midpoint_vertex(p, q).is_none();
        let (vp, vq) = (self.verts[p as usize], self.verts[q as usize]);
        let m = self.vertex([0, 1, 2].map(|k| (vp[k] + vq[k]) / 2));
        self.kill(t);
        // Replacing one end of the split edge by the midpoint keeps the
        // orientation of the parent.
        let mut c0 = ids;
        c0[b] = m;
        let mut c1 = ids;
        c1[a] = m;
        let c = [self.push(c0), self.push(c1)];
        (c, new.then_some((p, q)))
    }

    /// Bisects every tet of `marked` once and then every tet with a hanging
    /// vertex until the mesh conforms. Returns the leaves created.
    pub fn refine(&mut self, marked: &[u32]) -> Vec<u32> {
        let first_new = self.tets.len() as u32;
        let mut queue: Vec<u32> = Vec::new();
        for &t in marked {
            if !self.alive[t as usize] {
                continue;
            }
            self.split_and_queue(t, &mut queue);
        }
        while let Some(t) = queue.pop() {
            if self.alive[t as usize] && self.hanging(t) {
                self.split_and_queue(t, &mut queue);
            }
        }
        (first_new..self.tets.len() as u32).filter(|&t| self.alive[t as usize]).collect()
    }

    fn split_and_queue(&mut self, t: u32, queue: &mut Vec<u32>) {
        let (children, new_edge) = self.bisect(t);
        queue.extend(children);
        if let Some((p, q)) = new_edge {
            // Every leaf holding edge pq now has its midpoint hanging.
            let (ap, aq) = (&self.around[p as usize], &self.around[q as usize]);
            let (small, other) = if ap.len() <= aq.len() { (ap, q) } else { (aq, p) };
            for &s in small {
                if self.tets[s as usize].contains(&other) {
                    queue.push(s);
                }
            }
        }
    }

    /// Whether every leaf conforms (no hanging vertex): for tests.
    #[cfg(test)]
    pub fn conforms(&self) -> bool {
        (0..self.tets.len() as u32).filter(|&t| self.alive[t as usize]).all(|t| !self.hanging(t))
    }
}

/// Six times the signed volume, exactly.
pub fn orient(p: &[IPoint; 4]) -> i128 {
    let d = |i: usize| [0, 1, 2].map(|k| (p[i][k] - p[0][k]) as i128);
    let (a, b, c) = (d(1), d(2), d(3));
    a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])
}
