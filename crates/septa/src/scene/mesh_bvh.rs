//! Bounding volume hierarchy over a triangle mesh: exact closest point by
//! branch and bound, and the fast winding number (Barill et al. 2018):
//! a cluster far from the query point (farther than `BETA` times its
//! radius) contributes its dipole term `N . (c - q) / (4 pi |c - q|^3)`
//! (N: its area vector, c: its area centroid), near clusters are summed
//! exactly. Only the sign of `w - 1/2` is used, and far-field errors are a
//! small fraction of 1/2 for a closed mesh.

use super::vec3::*;

/// Far-field threshold: clusters farther than this many radii use their
/// dipole.
const BETA: f64 = 2.5;
/// Triangles per leaf.
const LEAF: usize = 8;

#[derive(Clone, Debug)]
struct Node {
    lo: V3,
    hi: V3,
    /// Range in `Bvh::tris` (leaves only: `count > 0`).
    first: usize,
    count: usize,
    children: [usize; 2],
    /// Sum of the triangles' area vectors (half the cross products).
    area: V3,
    /// Area-weighted centroid.
    center: V3,
    /// Largest distance from `center` to a vertex of the cluster.
    radius: f64,
}

/// The hierarchy (indices into the mesh's triangles).
#[derive(Clone, Debug)]
pub(crate) struct Bvh {
    nodes: Vec<Node>,
    tris: Vec<usize>,
}

/// Closest point to `p` on triangle `a b c` (Voronoi regions of the
/// triangle's vertices, edges and face, in barycentric form).
pub(crate) fn closest_on_triangle(p: V3, a: V3, b: V3, c: V3) -> V3 {
    let ab = sub(b, a);
    let ac = sub(c, a);
    let ap = sub(p, a);
    let d1 = dot(ab, ap);
    let d2 = dot(ac, ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = sub(p, b);
    let d3 = dot(ab, bp);
    let d4 = dot(ac, bp);
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return add(a, scale(ab, d1 / (d1 - d3)));
    }
    let cp = sub(p, c);
    let d5 = dot(ab, cp);
    let d6 = dot(ac, cp);
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return add(a, scale(ac, d2 / (d2 - d6)));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return add(b, scale(sub(c, b), w));
    }
    let denom = 1.0 / (va + vb + vc);
    add(a, add(scale(ab, vb * denom), scale(ac, vc * denom)))
}

/// Signed solid angle of triangle `a b c` seen from `p` (Van Oosterom and
/// Strackee), positive when `p` is behind its counter-clockwise side.
pub(crate) fn solid_angle(p: V3, a: V3, b: V3, c: V3) -> f64 {
    let (a, b, c) = (sub(a, p), sub(b, p), sub(c, p));
    let (la, lb, lc) = (norm(a), norm(b), norm(c));
    let num = dot(a, cross(b, c));
    let den = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
    2.0 * num.atan2(den)
}

fn box_dist2(p: V3, lo: V3, hi: V3) -> f64 {
    (0..3)
        .map(|a| {
            let d = (lo[a] - p[a]).max(p[a] - hi[a]).max(0.0);
            d * d
        })
        .sum()
}

impl Bvh {
    /// Build over `tris` of `v` (median split on the longest centroid axis).
    pub fn build(v: &[V3], t: &[[u32; 3]]) -> Bvh {
        let mut bvh = Bvh { nodes: Vec::with_capacity(2 * t.len() / LEAF + 1), tris: (0..t.len()).collect() };
        let cent: Vec<V3> = t
            .iter()
            .map(|x| scale(add(add(v[x[0] as usize], v[x[1] as usize]), v[x[2] as usize]), 1.0 / 3.0))
            .collect();
        bvh.node(v, t, &cent, 0, t.len());
        bvh
    }

    fn node(&mut self, v: &[V3], t: &[[u32; 3]], cent: &[V3], first: usize, end: usize) -> usize {
        let id = self.nodes.len();
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        let (mut area, mut moment, mut total) = ([0.0; 3], [0.0; 3], 0.0);
        for &k in &self.tris[first..end] {
            let [a, b, c] = t[k].map(|i| v[i as usize]);
            for p in [a, b, c] {
                for x in 0..3 {
                    lo[x] = lo[x].min(p[x]);
                    hi[x] = hi[x].max(p[x]);
                }
            }
            let n = scale(cross(sub(b, a), sub(c, a)), 0.5);
            let w = norm(n);
            area = add(area, n);
            moment = add(moment, scale(cent[k], w));
            total += w;
        }
        let center = if total > 0.0 { scale(moment, 1.0 / total) } else { scale(add(lo, hi), 0.5) };
        let mut radius = 0.0f64;
        for &k in &self.tris[first..end] {
            for i in t[k] {
                radius = radius.max(norm(sub(v[i as usize], center)));
            }
        }
        self.nodes.push(Node { lo, hi, first, count: end - first, children: [0, 0], area, center, radius });
        if end - first > LEAF {
            let axis = (0..3).max_by(|&x, &y| (hi[x] - lo[x]).total_cmp(&(hi[y] - lo[y]))).unwrap_or(0);
            let mid = (first + end) / 2;
            self.tris[first..end].select_nth_unstable_by(mid - first, |&x, &y| cent[x][axis].total_cmp(&cent[y][axis]));
            let l = self.node(v, t, cent, first, mid);
            let r = self.node(v, t, cent, mid, end);
            self.nodes[id].children = [l, r];
            self.nodes[id].count = 0;
        }
        id
    }

    /// Exact closest point: distance and point.
    pub fn closest(&self, v: &[V3], t: &[[u32; 3]], p: V3) -> (f64, V3) {
        let mut best = (f64::INFINITY, p);
        let mut stack = vec![0usize];
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n];
            if box_dist2(p, node.lo, node.hi) >= best.0 * best.0 {
                continue;
            }
            if node.count > 0 {
                for &k in &self.tris[node.first..node.first + node.count] {
                    let [a, b, c] = t[k].map(|i| v[i as usize]);
                    let q = closest_on_triangle(p, a, b, c);
                    let d = norm(sub(p, q));
                    if d < best.0 {
                        best = (d, q);
                    }
                }
            } else {
                // Visit the nearer child first (pushed last).
                let [l, r] = node.children;
                let dl = box_dist2(p, self.nodes[l].lo, self.nodes[l].hi);
                let dr = box_dist2(p, self.nodes[r].lo, self.nodes[r].hi);
                if dl < dr {
                    stack.extend([r, l]);
                } else {
                    stack.extend([l, r]);
                }
            }
        }
        best
    }

    /// Fast winding number at `p`.
    pub fn winding(&self, v: &[V3], t: &[[u32; 3]], p: V3) -> f64 {
        let mut total = 0.0;
        let mut stack = vec![0usize];
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n];
            let d = sub(node.center, p);
            let dist = norm(d);
            if dist > BETA * node.radius {
                total += dot(node.area, d) / (dist * dist * dist);
            } else if node.count > 0 {
                for &k in &self.tris[node.first..node.first + node.count] {
                    let [a, b, c] = t[k].map(|i| v[i as usize]);
                    total += solid_angle(p, a, b, c);
                }
            } else {
                stack.extend(node.children);
            }
        }
        total / (4.0 * std::f64::consts::PI)
    }
}
