//! Union-find with path halving and union by index (the smaller root wins,
//! so the result does not depend on the order of unions).

/// A disjoint-set forest over `0..n`.
#[derive(Clone, Debug, Default)]
pub struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    /// `n` singletons.
    pub fn new(n: usize) -> UnionFind {
        UnionFind { parent: (0..n as u32).collect() }
    }

    /// Adds a singleton and returns its id.
    pub fn push(&mut self) -> u32 {
        let id = self.parent.len() as u32;
        self.parent.push(id);
        id
    }

    /// Reserves room for `n` more elements.
    pub fn reserve(&mut self, n: usize) {
        self.parent.reserve(n);
    }

    /// Frees the room reserved beyond the elements.
    pub fn shrink_to_fit(&mut self) {
        self.parent.shrink_to_fit();
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.parent.len()
    }

    /// Root of `x`'s set (the smallest element of the set).
    pub fn find(&mut self, mut x: u32) -> u32 {
        while self.parent[x as usize] != x {
            let p = self.parent[x as usize];
            self.parent[x as usize] = self.parent[p as usize];
            x = p;
        }
        x
    }

    /// Joins the sets of `a` and `b`; of the two roots, the one for which
    /// `keep_first(ra, rb)` holds stays the root (callers order roots by
    /// something other than their index, e.g. the cut's point definitions,
    /// so that the representative does not depend on the order of unions).
    pub fn union_by(&mut self, a: u32, b: u32, keep_first: impl FnOnce(u32, u32) -> bool) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra == rb {
            return;
        }
        if keep_first(ra, rb) {
            self.parent[rb as usize] = ra;
        } else {
            self.parent[ra as usize] = rb;
        }
    }

    /// Joins the sets of `a` and `b`.
    pub fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra < rb {
            self.parent[rb as usize] = ra;
        } else if rb < ra {
            self.parent[ra as usize] = rb;
        }
    }

    /// [`UnionFind::components`] in the union-find's own array (no second
    /// array of `n` ids at a stage's peak of memory). When every parent
    /// precedes its child, which [`UnionFind::union`] and path halving keep,
    /// a single pass in increasing order finds each element's component at
    /// its parent, already numbered; after [`UnionFind::union_by`] it may
    /// not hold, and the general pass runs.
    pub fn into_components(mut self) -> (Vec<u32>, usize) {
        if self.parent.iter().enumerate().any(|(x, &p)| p as usize > x) {
            return self.components();
        }
        let mut count = 0;
        for x in 0..self.parent.len() {
            let p = self.parent[x] as usize;
            self.parent[x] = if p == x {
                count += 1;
                count - 1
            } else {
                self.parent[p]
            };
        }
        (self.parent, count as usize)
    }

    /// Dense component ids `0..count`, numbered by smallest element, and the count.
    pub fn components(&mut self) -> (Vec<u32>, usize) {
        let n = self.parent.len();
        let mut id = vec![u32::MAX; n];
        let mut count = 0;
        for x in 0..n as u32 {
            let r = self.find(x);
            if id[r as usize] == u32::MAX {
                id[r as usize] = count;
                count += 1;
            }
            id[x as usize] = id[r as usize];
        }
        (id, count as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::UnionFind;

    #[test]
    fn components_in_place_equal_the_general_pass() {
        let mut state = 12345u64;
        for n in [0usize, 1, 2, 7, 100, 1000] {
            let mut uf = UnionFind::new(n);
            for _ in 0..n / 2 {
                state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                let (a, b) = ((state >> 33) as usize % n.max(1), (state >> 13) as usize % n.max(1));
                uf.union(a as u32, b as u32);
            }
            let mut copy = UnionFind { parent: uf.parent.clone() };
            assert_eq!(uf.into_components(), copy.components(), "{n}");
        }
        // Roots chosen against the index order: the general pass runs.
        let mut uf = UnionFind::new(4);
        uf.union_by(0, 3, |_, _| false);
        uf.union_by(1, 2, |_, _| false);
        let mut copy = UnionFind { parent: uf.parent.clone() };
        assert_eq!(uf.into_components(), copy.components());
    }
}
