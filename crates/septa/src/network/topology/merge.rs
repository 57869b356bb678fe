//! Merging block outputs into one network: global vertex ids by key, regions
//! joined across block faces, network faces on tet faces paired up.
//! Blocks are merged in block order, so numbering is deterministic.

use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use crate::complex::{Mode, NONE};
use crate::network::block::{BlockOut, FaceKey, Label, OpenT, SRef};
use crate::network::VKey;
use crate::uf::UnionFind;

/// Region labels stored flat, a fixed number of words each (one for MI
/// and for IA up to 64 functions): a `Vec<Label>` costs 24 bytes a region,
/// and there are two or more regions per active tet.
#[derive(Default)]
pub(crate) struct Labels {
    words: usize,
    data: Vec<u64>,
}

impl Labels {
    /// Number of labels.
    pub(crate) fn len(&self) -> usize {
        if self.words == 0 {
            0
        } else {
            self.data.len() / self.words
        }
    }

    /// Label `r`.
    pub(crate) fn get(&self, r: u32) -> &[u64] {
        &self.data[r as usize * self.words..(r as usize + 1) * self.words]
    }

    /// Appends a label (zero-padded to the common width, which grows if needed).
    pub(crate) fn push(&mut self, l: &[u64]) {
        let w = l.len().max(1);
        if w > self.words {
            let n = self.len();
            let old = std::mem::take(&mut self.data);
            self.data = Vec::with_capacity((n + 1) * w);
            for r in 0..n {
                self.data.extend_from_slice(&old[r * self.words..(r + 1) * self.words]);
                self.data.resize((r + 1) * w, 0);
            }
            self.words = w;
        }
        let at = self.data.len();
        self.data.extend_from_slice(l);
        self.data.resize(at + self.words, 0);
    }
}

/// Everything the topology stage needs.
#[derive(Default)]
pub(crate) struct Merged {
    pub keys: Vec<VKey>,
    pub points: Vec<[f64; 3]>,
    pub face_start: Vec<u32>,
    pub face_verts: Vec<u32>,
    pub face_label: Vec<[u16; 2]>,
    /// Region nodes (before grouping) on each side.
    pub face_nodes: Vec<[u32; 2]>,
    pub region_uf: UnionFind,
    pub region_label: Labels,
    /// Per region (shorter when the rest are 0: volumes not asked for).
    pub region_volume: Vec<f64>,
    /// Shell union-find over `2 * face + side` then extra nodes.
    pub shell_pairs: Vec<(u32, u32)>,
    pub shell_nodes: usize,
    /// Wedges at chain edges: (edge, side `2f+s`, side `2g+t`) facing one cell.
    pub wedges: Vec<([u32; 2], u32, u32)>,
    pub active_tets: usize,
    /// The region groups were dropped before the topology stage (a caller
    /// that never groups cells); `region_label` stays.
    pub regions_dropped: bool,
}

impl Merged {
    /// Frees the region union-find for a topology stage that will take its
    /// cells from ray shooting or not at all (the sparse path falls back to
    /// the dense one rather than group cells): the topology stage then
    /// reports grouping without computing it.
    pub(crate) fn drop_region_groups(&mut self) {
        self.region_uf = UnionFind::default();
        self.regions_dropped = true;
    }

    /// Gives back what the merge's growing arrays hold beyond their
    /// lengths (up to half of each, from doubling) before the topology
    /// stage allocates its own: the run's peak of memory is there.
    fn shrink_to_fit(&mut self) {
        self.keys.shrink_to_fit();
        self.points.shrink_to_fit();
        self.face_start.shrink_to_fit();
        self.face_verts.shrink_to_fit();
        self.face_label.shrink_to_fit();
        self.face_nodes.shrink_to_fit();
        self.region_uf.shrink_to_fit();
        self.region_label.data.shrink_to_fit();
        self.region_volume.shrink_to_fit();
        self.shell_pairs.shrink_to_fit();
        self.wedges.shrink_to_fit();
    }
}

/// Merges blocks one at a time, in block order, so a caller can drop each
/// block's output as soon as it is merged (peak memory: the merged network
/// plus the blocks in flight, not every block at once).
pub(crate) struct Merger {
    mode: Mode,
    m: Merged,
    vmap: FxHashMap<VKey, u32>,
    contacts: FxHashMap<(FaceKey, Label), u32>,
    open_t: FxHashMap<OpenT, u32>,
    /// (face key, global verts, region, zero) of half-polygons.
    halves: Vec<(FaceKey, SmallVec<[u32; 8]>, u32, u16)>,
    /// Raw shell unions, in "pre" ids: Side -> 2*face+side, Half -> halves,
    /// T -> t-nodes; resolved after the halves are paired.
    pre_unions: Vec<(Pre, Pre)>,
    t_total: u32,
    t_pairs: Vec<(u32, u32)>,
}

/// Merges `blocks` in their order.
pub(crate) fn merge(mode: Mode, blocks: Vec<BlockOut>) -> Merged {
    let mut g = Merger::new(mode);
    g.reserve(&blocks);
    for b in blocks {
        g.add(b);
    }
    g.finish()
}

impl Merger {
    pub(crate) fn new(mode: Mode) -> Merger {
        Merger {
            mode,
            m: Merged { face_start: vec![0], ..Default::default() },
            vmap: FxHashMap::default(),
            contacts: FxHashMap::default(),
            open_t: FxHashMap::default(),
            halves: Vec::new(),
            pre_unions: Vec::new(),
            t_total: 0,
            t_pairs: Vec::new(),
        }
    }

    /// Reserves room for `blocks`: growing by doubling copies every element
    /// and touches fresh pages again (a measurable share of the run).
    pub(crate) fn reserve(&mut self, blocks: &[BlockOut]) {
        let m = &mut self.m;
        let sum = |f: &dyn Fn(&BlockOut) -> usize| blocks.iter().map(f).sum::<usize>();
        let polys = sum(&|b| b.poly_label.len());
        m.face_start.reserve(polys);
        m.face_label.reserve(polys);
        m.face_nodes.reserve(polys);
        m.face_verts.reserve(sum(&|b| b.poly_verts.len()));
        let verts = sum(&|b| b.keys.len());
        m.keys.reserve(verts);
        m.points.reserve(verts);
        let regions = sum(&|b| b.comp_label.len());
        m.region_uf.reserve(regions);
        self.pre_unions.reserve(sum(&|b| b.unions.len()));
        m.wedges.reserve(sum(&|b| b.wedges.len()));
    }

    /// Merges the next block (blocks must come in block order for a
    /// deterministic numbering).
    pub(crate) fn add(&mut self, b: BlockOut) {
        let Merger { m, vmap, contacts, open_t, halves, pre_unions, t_total, t_pairs, .. } = self;
        let region_base = m.region_label.len() as u32;
        let face_base = m.face_label.len() as u32;
        let half_base = halves.len() as u32;
        let t_base = *t_total;
        *t_total += b.tnodes;
        m.active_tets += b.active_tets;
        // Vertices: global ids only for polygon vertices (lazily).
        let mut remap = vec![NONE; b.keys.len()];
        let mut gid = |v: u32, m: &mut Merged| -> u32 {
            if remap[v as usize] == NONE {
                let key = b.keys[v as usize];
                let next = m.keys.len() as u32;
                // A vertex inside its block is unique: no global lookup.
                let id = if b.shared[v as usize] { *vmap.entry(key).or_insert(next) } else { next };
                if id == next {
                    m.keys.push(key);
                    m.points.push(b.points[v as usize]);
                }
                remap[v as usize] = id;
            }
            remap[v as usize]
        };
        for p in 0..b.poly_label.len() {
            for j in b.poly_start[p]..b.poly_start[p + 1] {
                let id = gid(b.poly_verts[j as usize], &mut *m);
                m.face_verts.push(id);
            }
            m.face_start.push(m.face_verts.len() as u32);
            m.face_label.push(b.poly_label[p]);
            m.face_nodes.push(b.poly_cells[p].map(|c| c + region_base));
        }
        for h in &b.halves {
            let verts: SmallVec<[u32; 8]> = h.verts.iter().map(|&v| gid(v, &mut *m)).collect();
            halves.push((h.face, verts, h.cell + region_base, h.zero));
        }
        for _ in 0..b.comp_label.len() {
            m.region_uf.push();
        }
        for l in &b.comp_label {
            m.region_label.push(l);
        }
        // Volumes are all zero unless asked for: keep none then (the
        // vector stays shorter than the regions and reads as 0 beyond).
        if b.comp_volume.iter().any(|&v| v != 0.0) {
            m.region_volume.resize(region_base as usize, 0.0);
            m.region_volume.extend(b.comp_volume);
        }
        for (f, l, c) in b.contacts {
            let node = c + region_base;
            match contacts.remove(&(f, l.clone())) {
                Some(o) => m.region_uf.union(o, node),
                None => {
                    contacts.insert((f, l), node);
                }
            }
        }
        for (key, t) in b.open_t {
            let t = t + t_base;
            match open_t.remove(&key) {
                Some(o) => t_pairs.push((o, t)),
                None => {
                    open_t.insert(key, t);
                }
            }
        }
        let conv = |r: SRef| match r {
            SRef::Side(p, s) => Pre::Side(2 * (p + face_base) + s as u32),
            SRef::Half(h) => Pre::Half(h + half_base),
            SRef::T(t) => Pre::T(t + t_base),
        };
        pre_unions.extend(b.unions.into_iter().map(|(a, c)| (conv(a), conv(c))));
        for (e, r1, r2) in b.wedges {
            if let (Pre::Side(x), Pre::Side(y)) = (conv(r1), conv(r2)) {
                let (a, c) = (gid(e[0], &mut *m), gid(e[1], &mut *m));
                m.wedges.push(([a.min(c), a.max(c)], x, y));
            }
        }
    }

    /// Pairs half-polygons, resolves shell nodes and returns the merged network.
    pub(crate) fn finish(self) -> Merged {
        let Merger { mode, mut m, halves, pre_unions, t_total, t_pairs, .. } = self;
        // Pair the halves of network faces lying on tet faces.
        let mut half_side: Vec<Option<u32>> = vec![None; halves.len()];
        let mut extra_pairs = Vec::new(); // half-half unions (MI: same material both sides)
        let mut by_key: FxHashMap<(FaceKey, SmallVec<[u32; 8]>), u32> = FxHashMap::default();
        let mut pairs = Vec::new();
        for (h, (face, verts, _, _)) in halves.iter().enumerate() {
            let mut sorted = verts.clone();
            sorted.sort_unstable();
            match by_key.remove(&(*face, sorted.clone())) {
                Some(o) => pairs.push((o, h as u32)),
                None => {
                    by_key.insert((*face, sorted), h as u32);
                }
            }
        }
        let mut singles: Vec<u32> = by_key.into_values().collect();
        singles.sort_unstable();
        let new_face = |m: &mut Merged, verts: &[u32], label: [u16; 2], nodes: [u32; 2]| -> u32 {
            m.face_verts.extend_from_slice(verts);
            m.face_start.push(m.face_verts.len() as u32);
            m.face_label.push(label);
            m.face_nodes.push(nodes);
            m.face_label.len() as u32 - 1
        };
        for (a, b) in pairs {
            let (ha, hb) = (&halves[a as usize], &halves[b as usize]);
            match mode {
                Mode::Ia => {
                    let f = ha.3;
                    let pos_a = crate::network::sign_bit(m.region_label.get(ha.2), f as usize);
                    let (first, second) = if pos_a { (a, b) } else { (b, a) };
                    let (h1, h2) = (&halves[first as usize], &halves[second as usize]);
                    let id = new_face(&mut m, &h1.1, [f, f], [h1.2, h2.2]);
                    half_side[first as usize] = Some(2 * id);
                    half_side[second as usize] = Some(2 * id + 1);
                }
                Mode::Mi => {
                    let ma = m.region_label.get(ha.2)[0] as u16;
                    let mb = m.region_label.get(hb.2)[0] as u16;
                    if ma == mb {
                        extra_pairs.push((a, b));
                        continue;
                    }
                    let (first, second) = if ma < mb { (a, b) } else { (b, a) };
                    let (h1, h2) = (&halves[first as usize], &halves[second as usize]);
                    let id = new_face(&mut m, &h1.1, [ma.min(mb), ma.max(mb)], [h1.2, h2.2]);
                    half_side[first as usize] = Some(2 * id);
                    half_side[second as usize] = Some(2 * id + 1);
                }
            }
        }
        if mode == Mode::Ia {
            // A function vanishing on a grid boundary face: one side only.
            for h in singles {
                let (_, verts, node, f) = &halves[h as usize];
                let pos = crate::network::sign_bit(m.region_label.get(*node), *f as usize);
                if pos {
                    let id = new_face(&mut m, verts, [*f, *f], [*node, NONE]);
                    half_side[h as usize] = Some(2 * id);
                } else {
                    let rev: Vec<u32> = verts.iter().rev().copied().collect();
                    let id = new_face(&mut m, &rev, [*f, *f], [NONE, *node]);
                    half_side[h as usize] = Some(2 * id + 1);
                }
            }
        }
        // Resolve shell nodes: sides first, then t-nodes, then unpaired halves.
        let sides = 2 * m.face_label.len() as u32;
        let half_extra_base = sides + t_total;
        let resolve = |p: Pre| -> u32 {
            match p {
                Pre::Side(s) => s,
                Pre::T(t) => sides + t,
                Pre::Half(h) => half_side[h as usize].unwrap_or(half_extra_base + h),
            }
        };
        m.shell_pairs = pre_unions.into_iter().map(|(a, b)| (resolve(a), resolve(b))).collect();
        m.shell_pairs.extend(t_pairs.into_iter().map(|(a, b)| (sides + a, sides + b)));
        for (a, b) in extra_pairs {
            m.shell_pairs.push((resolve(Pre::Half(a)), resolve(Pre::Half(b))));
            let (ra, rb) = (halves[a as usize].2, halves[b as usize].2);
            m.region_uf.union(ra, rb);
        }
        m.shell_nodes = (half_extra_base as usize) + halves.len();
        m.shrink_to_fit();
        m
    }
}

#[derive(Clone, Copy)]
enum Pre {
    Side(u32),
    Half(u32),
    T(u32),
}
