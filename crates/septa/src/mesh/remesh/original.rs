//! The unremeshed result as the surface a remeshed vertex stays on (sampled
//! input): the closest point on its patch's original triangles, or on its
//! constraint curve's original edges. Triangles and edges are found through
//! a uniform grid searched ring by ring until no unvisited cell can hold a
//! closer point. Floating point: this places vertices; whether the result
//! is an embedding is decided by the exact check afterwards.

use rustc_hash::FxHashMap;

use super::soup::{add, dot, scale, sub, V};

/// The original triangles (with patches) and constraint edges (with traces).
pub(super) struct Original {
    x: Vec<V>,
    tris: Vec<[u32; 3]>,
    patch: Vec<u32>,
    segs: Vec<[u32; 2]>,
    trace: Vec<u32>,
    size: f64,
    tri_cells: FxHashMap<[i64; 3], Vec<u32>>,
    seg_cells: FxHashMap<[i64; 3], Vec<u32>>,
    /// Per patch its triangles and per trace its edges (the search's last resort).
    by_patch: FxHashMap<u32, Vec<u32>>,
    by_trace: FxHashMap<u32, Vec<u32>>,
}

/// Which elements a query may land on.
#[derive(Clone, Copy)]
pub(super) enum On {
    Patch(u32),
    Trace(u32),
    /// Any triangle (the Hausdorff distance).
    Any,
}

/// The closest point to `p` on the segment `ab`.
pub(super) fn on_segment(p: V, a: V, b: V) -> V {
    let d = sub(b, a);
    let l = dot(d, d);
    let t = if l > 0.0 { (dot(sub(p, a), d) / l).clamp(0.0, 1.0) } else { 0.0 };
    if t == 0.0 {
        a
    } else if t == 1.0 {
        b
    } else {
        add(a, scale(d, t))
    }
}

/// The closest point to `p` on the triangle `abc` (Voronoi regions of its
/// corners, edges and face; a degenerate triangle by its edges).
pub(super) fn on_triangle(p: V, a: V, b: V, c: V) -> V {
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = sub(p, b);
    let (d3, d4) = (dot(ab, bp), dot(ac, bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return on_segment(p, a, b);
    }
    let cp = sub(p, c);
    let (d5, d6) = (dot(ab, cp), dot(ac, cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return on_segment(p, a, c);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return on_segment(p, b, c);
    }
    let s = va + vb + vc;
    if !(s > 0.0) || !s.is_finite() {
        // degenerate: the best of the edges
        let cands = [on_segment(p, a, b), on_segment(p, b, c), on_segment(p, a, c)];
        return *cands.iter().min_by(|u, w| d2_(p, **u).total_cmp(&d2_(p, **w))).unwrap();
    }
    let (v, w) = (vb / s, vc / s);
    // corners that share a coordinate keep it exactly (a patch in a plane
    // of the box stays in it)
    let mut q = add(a, add(scale(ab, v), scale(ac, w)));
    for k in 0..3 {
        if a[k] == b[k] && a[k] == c[k] {
            q[k] = a[k];
        }
    }
    q
}

fn d2_(p: V, q: V) -> f64 {
    let d = sub(p, q);
    dot(d, d)
}

fn cell(p: V, size: f64) -> [i64; 3] {
    p.map(|c| (c / size).floor() as i64)
}

fn file(cells: &mut FxHashMap<[i64; 3], Vec<u32>>, size: f64, lo: V, hi: V, id: u32) {
    let (a, b) = (cell(lo, size), cell(hi, size));
    for i in a[0]..=b[0] {
        for j in a[1]..=b[1] {
            for k in a[2]..=b[2] {
                cells.entry([i, j, k]).or_default().push(id);
            }
        }
    }
}

fn bounds(pts: &[V]) -> (V, V) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in pts {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

impl Original {
    pub fn new(x: &[V], tris: &[[u32; 3]], patch: &[u32], segs: &[[u32; 2]], trace: &[u32], size: f64) -> Original {
        let mut o = Original {
            x: x.to_vec(),
            tris: tris.to_vec(),
            patch: patch.to_vec(),
            segs: segs.to_vec(),
            trace: trace.to_vec(),
            size,
            tri_cells: FxHashMap::default(),
            seg_cells: FxHashMap::default(),
            by_patch: FxHashMap::default(),
            by_trace: FxHashMap::default(),
        };
        for (t, tri) in tris.iter().enumerate() {
            let (lo, hi) = bounds(&tri.map(|v| x[v as usize]));
            file(&mut o.tri_cells, size, lo, hi, t as u32);
            o.by_patch.entry(patch[t]).or_default().push(t as u32);
        }
        for (s, seg) in segs.iter().enumerate() {
            let (lo, hi) = bounds(&seg.map(|v| x[v as usize]));
            file(&mut o.seg_cells, size, lo, hi, s as u32);
            o.by_trace.entry(trace[s]).or_default().push(s as u32);
        }
        o
    }

    fn point(&self, id: u32, on: On, p: V) -> Option<V> {
        match on {
            On::Trace(t) => (self.trace[id as usize] == t).then(|| {
                let [a, b] = self.segs[id as usize].map(|v| self.x[v as usize]);
                on_segment(p, a, b)
            }),
            On::Patch(q) if self.patch[id as usize] != q => None,
            _ => {
                let [a, b, c] = self.tris[id as usize].map(|v| self.x[v as usize]);
                Some(on_triangle(p, a, b, c))
            }
        }
    }

    /// The closest point to `p` on what `on` names (`p` itself if nothing).
    pub fn closest(&self, p: V, on: On) -> V {
        let cells = if matches!(on, On::Trace(_)) { &self.seg_cells } else { &self.tri_cells };
        let c = cell(p, self.size);
        let (mut best, mut best_d) = (p, f64::INFINITY);
        let consider = |list: &Vec<u32>, best: &mut V, best_d: &mut f64| {
            for &id in list {
                if let Some(q) = self.point(id, on, p) {
                    let d = d2_(p, q);
                    if d < *best_d {
                        (*best, *best_d) = (q, d);
                    }
                }
            }
        };
        for r in 0i64..24 {
            for i in -r..=r {
                for j in -r..=r {
                    for k in -r..=r {
                        if i.abs().max(j.abs()).max(k.abs()) != r {
                            continue;
                        }
                        if let Some(list) = cells.get(&[c[0] + i, c[1] + j, c[2] + k]) {
                            consider(list, &mut best, &mut best_d);
                        }
                    }
                }
            }
            // every unvisited cell is at least r cells away
            if best_d.sqrt() <= r as f64 * self.size {
                return best;
            }
        }
        // far from everything: every candidate
        let all: Vec<u32> = match on {
            On::Patch(q) => self.by_patch.get(&q).cloned().unwrap_or_default(),
            On::Trace(t) => self.by_trace.get(&t).cloned().unwrap_or_default(),
            On::Any => (0..self.tris.len() as u32).collect(),
        };
        consider(&all, &mut best, &mut best_d);
        best
    }
}
