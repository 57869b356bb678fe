//! The triangle soup the remeshing edits: every patch's triangles in one
//! list, each vertex with the triangles around it, so that an edge on a
//! chain is split or shortened once for all the patches around it.

use rustc_hash::FxHashMap;
use smallvec::SmallVec;

pub(super) type V = [f64; 3];

pub(super) fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub(super) fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub(super) fn scale(a: V, s: f64) -> V {
    [a[0] * s, a[1] * s, a[2] * s]
}
pub(super) fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub(super) fn cross(a: V, b: V) -> V {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
pub(super) fn norm(a: V) -> f64 {
    dot(a, a).sqrt()
}
pub(super) fn dist(a: V, b: V) -> f64 {
    norm(sub(a, b))
}
pub(super) fn unit(a: V) -> V {
    let n = norm(a);
    if n > 0.0 && n.is_finite() {
        scale(a, 1.0 / n)
    } else {
        [0.0; 3]
    }
}

/// What a vertex may do.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// A corner of the network, a chain's end, or a point where patches or
    /// curves meet otherwise: never moves, never goes.
    Fixed,
    /// Inside the constraint curve (`trace`) between two fixed vertices:
    /// slides along it, or goes into a neighbour on it.
    Curve(u32),
    /// Inside a patch: moves on it, goes into any neighbour.
    Free(u32),
}

/// The triangles of all patches, edited in place.
pub(super) struct Soup {
    pub x: Vec<V>,
    pub kind: Vec<Kind>,
    /// Per vertex, the original vertex whose identity (grid key) it takes.
    pub origin: Vec<u32>,
    pub tris: Vec<[u32; 3]>,
    pub patch: Vec<u32>,
    pub alive: Vec<bool>,
    /// Per vertex, the live triangles holding it.
    pub vt: Vec<SmallVec<[u32; 8]>>,
    /// Constraint edges `(min, max)` and their trace.
    pub feat: FxHashMap<(u32, u32), u32>,
}

pub(super) fn ekey(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

impl Soup {
    pub fn new(x: Vec<V>, tris: Vec<[u32; 3]>, patch: Vec<u32>) -> Soup {
        let n = x.len();
        let mut vt: Vec<SmallVec<[u32; 8]>> = vec![SmallVec::new(); n];
        for (t, tri) in tris.iter().enumerate() {
            for &v in tri {
                vt[v as usize].push(t as u32);
            }
        }
        let alive = vec![true; tris.len()];
        Soup {
            x,
            kind: vec![Kind::Fixed; n],
            origin: (0..n as u32).collect(),
            tris,
            patch,
            alive,
            vt,
            feat: FxHashMap::default(),
        }
    }

    pub fn add_vertex(&mut self, p: V, kind: Kind, origin: u32) -> u32 {
        self.x.push(p);
        self.kind.push(kind);
        self.origin.push(origin);
        self.vt.push(SmallVec::new());
        (self.x.len() - 1) as u32
    }

    pub fn add_tri(&mut self, tri: [u32; 3], patch: u32) -> u32 {
        let t = self.tris.len() as u32;
        self.tris.push(tri);
        self.patch.push(patch);
        self.alive.push(true);
        for &v in &tri {
            self.vt[v as usize].push(t);
        }
        t
    }

    pub fn kill_tri(&mut self, t: u32) {
        for &v in &self.tris[t as usize] {
            self.vt[v as usize].retain(|s| *s != t);
        }
        self.alive[t as usize] = false;
    }

    pub fn set_tri(&mut self, t: u32, tri: [u32; 3]) {
        for &v in &self.tris[t as usize] {
            self.vt[v as usize].retain(|s| *s != t);
        }
        self.tris[t as usize] = tri;
        for &v in &tri {
            self.vt[v as usize].push(t);
        }
    }

    /// The live triangles holding the edge `ab`.
    pub fn edge_tris(&self, a: u32, b: u32) -> SmallVec<[u32; 4]> {
        self.vt[a as usize].iter().copied().filter(|&t| self.tris[t as usize].contains(&b)).collect()
    }

    /// The vertices joined to `v` by an edge, ascending.
    pub fn neighbours(&self, v: u32) -> SmallVec<[u32; 16]> {
        let mut out: SmallVec<[u32; 16]> = SmallVec::new();
        for &t in &self.vt[v as usize] {
            out.extend(self.tris[t as usize].iter().copied().filter(|&w| w != v));
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Every live edge once, `(min, max)`.
    pub fn edges(&self) -> Vec<(u32, u32)> {
        let mut e: Vec<(u32, u32)> = Vec::with_capacity(self.tris.len() * 3 / 2);
        for (t, tri) in self.tris.iter().enumerate() {
            if self.alive[t] {
                for k in 0..3 {
                    e.push(ekey(tri[k], tri[(k + 1) % 3]));
                }
            }
        }
        e.sort_unstable();
        e.dedup();
        e
    }

    /// The (unnormalised) normal of `tri` at the positions `x`.
    pub fn normal_of(x: &[V], tri: &[u32; 3]) -> V {
        let [a, b, c] = tri.map(|v| x[v as usize]);
        cross(sub(b, a), sub(c, a))
    }

    /// The unit normal of `patch` around the vertices `vs`: the sum of the
    /// unnormalised normals of its triangles there (weighted by area, so a
    /// sliver, whose own normal means little, counts little).
    pub fn patch_normal(&self, vs: &[u32], patch: u32) -> V {
        let mut n = [0.0; 3];
        let mut seen: SmallVec<[u32; 32]> = SmallVec::new();
        for &v in vs {
            for &t in &self.vt[v as usize] {
                if self.patch[t as usize] == patch && !seen.contains(&t) {
                    seen.push(t);
                    n = add(n, Soup::normal_of(&self.x, &self.tris[t as usize]));
                }
            }
        }
        unit(n)
    }

    /// Whether the triangles around `vs`, with the positions `at` gives,
    /// all keep facing their patch's normal there (within 60 degrees) and
    /// none is degenerate.
    pub fn faces_ok(&self, vs: &[u32], skip: impl Fn(&[u32; 3]) -> bool, at: impl Fn(u32) -> V) -> bool {
        let mut normals: SmallVec<[(u32, V); 4]> = SmallVec::new();
        for &v in vs {
            for &t in &self.vt[v as usize] {
                let tri = self.tris[t as usize];
                if skip(&tri) {
                    continue;
                }
                let p = self.patch[t as usize];
                let r = match normals.iter().find(|(q, _)| *q == p) {
                    Some(&(_, r)) => r,
                    None => {
                        let r = self.patch_normal(vs, p);
                        normals.push((p, r));
                        r
                    }
                };
                let q = tri.map(&at);
                let new = cross(sub(q[1], q[0]), sub(q[2], q[0]));
                if norm(new) == 0.0 || dot(unit(new), r) < 0.5 {
                    return false;
                }
            }
        }
        true
    }

    /// The apex of triangle `t` opposite the edge `ab`.
    pub fn apex(&self, t: u32, a: u32, b: u32) -> u32 {
        *self.tris[t as usize].iter().find(|&&w| w != a && w != b).unwrap()
    }

    pub fn len(&self, a: u32, b: u32) -> f64 {
        dist(self.x[a as usize], self.x[b as usize])
    }

    /// The trace neighbours of a curve vertex (its two constraint edges).
    pub fn curve_neighbours(&self, v: u32) -> SmallVec<[u32; 2]> {
        self.neighbours(v).into_iter().filter(|&w| self.feat.contains_key(&ekey(v, w))).collect()
    }
}

/// Smallest angle of a triangle, in degrees (0 when degenerate).
pub(super) fn min_angle(p: [V; 3]) -> f64 {
    let mut best = 180.0f64;
    for k in 0..3 {
        let (u, v) = (sub(p[(k + 1) % 3], p[k]), sub(p[(k + 2) % 3], p[k]));
        let c = dot(u, v) / (norm(u) * norm(v));
        best = best.min(if c.is_finite() { c.clamp(-1.0, 1.0).acos().to_degrees() } else { 0.0 });
    }
    best
}
