//! Do two tets of a mesh overlap? Decided exactly, for every pair whose
//! bounding boxes overlap.
//!
//! A background grid must cover each point at most once (Du et al. 2022,
//! Sec. 3: the grid is a tetrahedral *decomposition* of the domain); an extra
//! tet laid over others used to be accepted and produced cells twice.
//!
//! Two tets `A` and `B` (closed, non-degenerate) have disjoint interiors iff
//! the origin is not interior to the Minkowski difference `A - B`, i.e. iff
//! some facet plane of `A - B` weakly separates them. Every facet of `A - B`
//! has the normal of a face of `A`, of a face of `B`, or of the cross product
//! of an edge of `A` and an edge of `B` (the separating-axis theorem, with
//! touching allowed). Each candidate is tested with exact signs of 3x3
//! determinants (septa-exact): no tolerance decides whether two tets overlap.
//!
//! Broad phase: a bounding-volume hierarchy over the tets' boxes; pairs whose
//! boxes only touch (or share a face, already checked to lie on opposite sides
//! by the manifold test) need no exact test.

use septa_exact::{det_sign_diff, Sign};

use super::mesh::orientation;

/// Tets per leaf of the hierarchy.
const LEAF: usize = 8;

/// An axis-aligned box, `lo <= hi`.
#[derive(Clone, Copy, Debug)]
struct Aabb {
    lo: [f64; 3],
    hi: [f64; 3],
}

impl Aabb {
    const EMPTY: Aabb = Aabb { lo: [f64::INFINITY; 3], hi: [f64::NEG_INFINITY; 3] };

    fn of(points: &[[f64; 3]; 4]) -> Aabb {
        let mut b = Aabb::EMPTY;
        for p in points {
            b.add(p, p);
        }
        b
    }

    fn add(&mut self, lo: &[f64; 3], hi: &[f64; 3]) {
        for a in 0..3 {
            self.lo[a] = self.lo[a].min(lo[a]);
            self.hi[a] = self.hi[a].max(hi[a]);
        }
    }

    /// The open boxes intersect (boxes that only touch do not: the tets
    /// inside them then have disjoint interiors). Comparisons of input
    /// coordinates, so exact.
    fn overlaps(&self, o: &Aabb) -> bool {
        (0..3).all(|a| self.lo[a] < o.hi[a] && o.lo[a] < self.hi[a])
    }
}

/// A node of the hierarchy: leaves hold `order[start..end]`.
struct Node {
    b: Aabb,
    start: u32,
    end: u32,
    /// Index of the first child (the second follows it), or 0 for a leaf.
    child: u32,
}

struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
}

fn corners(vertices: &[[f64; 3]], tet: &[u32; 4]) -> [[f64; 3]; 4] {
    tet.map(|v| vertices[v as usize])
}

impl Bvh {
    fn build(vertices: &[[f64; 3]], tets: &[[u32; 4]]) -> Bvh {
        // Centroids only steer the split; any value would keep the result exact.
        let centre: Vec<[f32; 3]> = tets
            .iter()
            .map(|t| {
                let p = corners(vertices, t);
                std::array::from_fn(|a| ((p[0][a] + p[1][a] + p[2][a] + p[3][a]) * 0.25) as f32)
            })
            .collect();
        let mut bvh =
            Bvh { nodes: Vec::with_capacity(2 * tets.len() / LEAF + 1), order: (0..tets.len() as u32).collect() };
        bvh.split(vertices, tets, &centre, 0, tets.len());
        bvh
    }

    /// Appends the node for `order[start..end]` and its subtree; returns its index.
    fn split(
        &mut self,
        vertices: &[[f64; 3]],
        tets: &[[u32; 4]],
        centre: &[[f32; 3]],
        start: usize,
        end: usize,
    ) -> u32 {
        let mut b = Aabb::EMPTY;
        for &t in &self.order[start..end] {
            for p in corners(vertices, &tets[t as usize]) {
                b.add(&p, &p);
            }
        }
        let id = self.nodes.len() as u32;
        self.nodes.push(Node { b, start: start as u32, end: end as u32, child: 0 });
        if end - start <= LEAF {
            return id;
        }
        let axis = (0..3).max_by(|&x, &y| (b.hi[x] - b.lo[x]).total_cmp(&(b.hi[y] - b.lo[y]))).unwrap_or(0);
        let mid = start + (end - start) / 2;
        self.order[start..end].select_nth_unstable_by(mid - start, |&x, &y| {
            centre[x as usize][axis].total_cmp(&centre[y as usize][axis])
        });
        // Children are pushed in order, so the left child is `id + 1`; the
        // right one's index is stored after the left subtree is complete.
        let left = self.split(vertices, tets, centre, start, mid);
        let right = self.split(vertices, tets, centre, mid, end);
        debug_assert_eq!(left, id + 1);
        self.nodes[id as usize].child = right;
        id
    }

    /// The smallest overlapping pair among tets of node `x` and of node `y`
    /// (`x == y`: pairs within it), by a simultaneous descent of both
    /// subtrees: each pair of overlapping nodes is visited once. The upper
    /// levels run in parallel.
    fn pairs(&self, m: &Mesh, x: u32, y: u32, depth: u32) -> Option<(usize, usize)> {
        let (nx, ny) = (&self.nodes[x as usize], &self.nodes[y as usize]);
        if x != y && !nx.b.overlaps(&ny.b) {
            return None;
        }
        let (leaf_x, leaf_y) = (nx.child == 0, ny.child == 0);
        if leaf_x && leaf_y {
            return self.leaf_pairs(m, nx, ny, x == y);
        }
        let both = |a: (u32, u32), b: (u32, u32)| -> Option<(usize, usize)> {
            let (ra, rb) = if depth < 12 {
                rayon::join(|| self.pairs(m, a.0, a.1, depth + 1), || self.pairs(m, b.0, b.1, depth + 1))
            } else {
                (self.pairs(m, a.0, a.1, depth + 1), self.pairs(m, b.0, b.1, depth + 1))
            };
            ra.into_iter().chain(rb).min()
        };
        if x == y {
            let (l, r) = (x + 1, nx.child);
            let same = both((l, l), (r, r));
            let cross = self.pairs(m, l, r, depth + 1);
            return same.into_iter().chain(cross).min();
        }
        // Descend into the node with more tets (a leaf is never split).
        let split_x = !leaf_x && (leaf_y || nx.end - nx.start >= ny.end - ny.start);
        if split_x {
            both((x + 1, y), (nx.child, y))
        } else {
            both((x, y + 1), (x, ny.child))
        }
    }

    fn leaf_pairs(&self, m: &Mesh, nx: &Node, ny: &Node, same: bool) -> Option<(usize, usize)> {
        let tx = &self.order[nx.start as usize..nx.end as usize];
        let ty = &self.order[ny.start as usize..ny.end as usize];
        let boxes = |ts: &[u32]| -> [Aabb; LEAF] {
            let mut out = [Aabb::EMPTY; LEAF];
            for (o, &t) in out.iter_mut().zip(ts) {
                *o = Aabb::of(&corners(m.vertices, &m.tets[t as usize]));
            }
            out
        };
        let bx = boxes(tx);
        let by = if same { bx } else { boxes(ty) };
        let mut best: Option<(usize, usize)> = None;
        for (p, &i) in tx.iter().enumerate() {
            let from = if same { p + 1 } else { 0 };
            for (q, &j) in ty.iter().enumerate().skip(from) {
                let pair = (i.min(j) as usize, i.max(j) as usize);
                if !bx[p].overlaps(&by[q])
                    || best.is_some_and(|b| b <= pair)
                    || shares_face(&m.tets[i as usize], &m.tets[j as usize])
                {
                    continue;
                }
                // The exact test is symmetric in its two tets.
                let (a, b) = (corners(m.vertices, &m.tets[i as usize]), corners(m.vertices, &m.tets[j as usize]));
                if interiors_overlap(&a, &b) {
                    best = Some(pair);
                }
            }
        }
        best
    }
}

/// The tets and their corner positions.
struct Mesh<'a> {
    vertices: &'a [[f64; 3]],
    tets: &'a [[u32; 4]],
}

/// The smallest pair `(i, j)`, `i < j`, of tets whose interiors intersect,
/// if any. Tets must be positively oriented and non-degenerate, and tets
/// sharing a face must already be known to lie on opposite sides of it.
pub(crate) fn find_overlap(vertices: &[[f64; 3]], tets: &[[u32; 4]]) -> Option<(usize, usize)> {
    if tets.len() < 2 {
        return None;
    }
    let bvh = Bvh::build(vertices, tets);
    bvh.pairs(&Mesh { vertices, tets }, 0, 0, 0)
}

fn shares_face(a: &[u32; 4], b: &[u32; 4]) -> bool {
    a.iter().filter(|v| b.contains(v)).count() >= 3
}

/// Whether two positively oriented, non-degenerate tets have a common
/// interior point (exact).
pub(crate) fn interiors_overlap(a: &[[f64; 3]; 4], b: &[[f64; 3]; 4]) -> bool {
    !(face_separates(a, b) || face_separates(b, a) || edge_pair_separates(a, b))
}

/// Some face plane of `a` has all of `b` on its outer side or on it.
fn face_separates(a: &[[f64; 3]; 4], b: &[[f64; 3]; 4]) -> bool {
    (0..4).any(|k| {
        // Replacing corner k by q gives the orientation of q against the
        // face opposite k: positive on a's side (a is positively oriented).
        b.iter().all(|q| {
            let mut t = *a;
            t[k] = *q;
            orientation(&t) != Sign::Positive
        })
    })
}

const EDGES: [[usize; 4]; 6] = [[0, 1, 2, 3], [0, 2, 1, 3], [0, 3, 1, 2], [1, 2, 0, 3], [1, 3, 0, 2], [2, 3, 0, 1]];

/// Some plane spanned by an edge of `a` and the direction of an edge of `b`
/// supports `a` along that edge and `b` along its edge, with `b` on the far
/// side (a facet of `A - B` whose plane weakly separates them).
fn edge_pair_separates(a: &[[f64; 3]; 4], b: &[[f64; 3]; 4]) -> bool {
    for [i, j, k, l] in EDGES {
        for [m, n, o, p] in EDGES {
            // s(x, base) = sign of (x - base) . n with n = (a_j - a_i) x (b_n - b_m).
            let s = |x: [f64; 3], base: [f64; 3]| det_sign_diff(&[a[j], b[n], x], &[a[i], b[m], base]);
            let sa = [s(a[k], a[i]), s(a[l], a[i])];
            if sa == [Sign::Zero; 2] {
                // Parallel edges: n = 0 (a non-degenerate a is not flat).
                continue;
            }
            let sb = [s(b[o], b[m]), s(b[p], b[m])];
            let gap = s(b[m], a[i]);
            let weakly = |below: Sign| {
                let above = -below;
                sa.iter().all(|&x| x != above) && sb.iter().all(|&x| x != below) && gap != below
            };
            if weakly(Sign::Negative) || weakly(Sign::Positive) {
                return true;
            }
        }
    }
    false
}

#[cfg(test)]
#[path = "overlap_tests.rs"]
mod tests;
