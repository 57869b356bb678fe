//! Cut-vertex candidates (face triples) and their merging: two triples that
//! name the same point are found equal by exact sorting along a line they
//! share (TopoCut Sec. 3.1, "equivalent" points) and united here.

use crate::cut::base::geom::Def;
use crate::uf::UnionFind;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// A small multiplicative hasher for integer keys (the default SipHash is
/// needlessly slow for the millions of look-ups of triples).
#[derive(Default, Clone, Copy)]
pub struct FxHasher(u64);

impl Hasher for FxHasher {
    #[inline]
    fn finish(&self) -> u64 {
        self.0
    }
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(b as u64);
        }
    }
    #[inline]
    fn write_u32(&mut self, i: u32) {
        self.write_u64(i as u64);
    }
    #[inline]
    fn write_u8(&mut self, i: u8) {
        self.write_u64(i as u64);
    }
    #[inline]
    fn write_usize(&mut self, i: usize) {
        self.write_u64(i as u64);
    }
    #[inline]
    fn write_u64(&mut self, i: u64) {
        self.0 = (self.0.rotate_left(5) ^ i).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

/// Hash map with [`FxHasher`].
pub type FxMap<K, V> = HashMap<K, V, BuildHasherDefault<FxHasher>>;

/// All candidate triples with a union-find over "same point".
#[derive(Default)]
pub struct Nodes {
    /// Definition of each node.
    pub defs: Vec<Def>,
    /// The nodes of cut-vertex triples, by triple.
    index: FxMap<Def, u32>,
    /// The node of input vertex `v` (`u32::MAX`: none yet): most corners
    /// of the pieces of a large mesh are input vertices, looked up here
    /// without hashing.
    of_vertex: Vec<u32>,
    same: UnionFind,
}

impl Nodes {
    /// The node of a triple, created on first use.
    pub fn get(&mut self, d: Def) -> u32 {
        let i = self.defs.len() as u32;
        if let Def::V(v) = d {
            let v = v as usize;
            if v >= self.of_vertex.len() {
                self.of_vertex.resize(v + 1, u32::MAX);
            }
            if self.of_vertex[v] != u32::MAX {
                return self.of_vertex[v];
            }
            self.of_vertex[v] = i;
        } else {
            if let Some(&j) = self.index.get(&d) {
                return j;
            }
            self.index.insert(d, i);
        }
        self.defs.push(d);
        self.same.push();
        i
    }

    /// Representative of a node.
    pub fn find(&mut self, i: u32) -> u32 {
        self.same.find(i)
    }

    /// Records that two triples are the same point. The smaller definition
    /// becomes the representative, so the result does not depend on the
    /// order of merges.
    pub fn union(&mut self, a: u32, b: u32) {
        let defs = &self.defs;
        self.same.union_by(a, b, |ra, rb| defs[ra as usize] <= defs[rb as usize]);
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.defs.len()
    }
}
