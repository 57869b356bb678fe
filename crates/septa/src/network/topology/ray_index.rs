//! What ray shooting (`raytrace.rs`, Du et al. Sec. 7.1) asks of a
//! network, and the answer for a merged network in memory: which component
//! a vertex is in ([`RayIndex::component`]) and which shell a face side
//! belongs to ([`RayIndex::shell`]). A stream answers the same questions by
//! re-running blocks (`stream/rerun.rs`).

use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use crate::complex::NONE;
use crate::network::VKey;

/// What ray shooting asks of the network: which component a vertex is in,
/// and which shell a face side belongs to. Both questions name the tet
/// being looked at, so an index may answer from that tet's block alone
/// (the in-memory network, or a block re-run on demand: `rerun.rs`).
pub(crate) trait RayIndex {
    /// The connected component of the network vertex with key `key` (a
    /// vertex of the complex of `tet`), or `None` if it is no network vertex.
    fn component(&mut self, tet: &[u32; 4], key: VKey) -> Option<u32>;

    /// The shell of side `side` (0 positive, 1 negative) of the network
    /// face of `tet` whose vertices have the keys `keys`.
    fn shell(&mut self, tet: &[u32; 4], keys: &[VKey], side: FaceSide) -> Option<u32>;
}

/// Which side of a network face a cell of a tet lies on.
#[derive(Clone, Copy, Debug)]
pub(crate) enum FaceSide {
    /// Side 0 (positive) or 1, read from the tet's own face.
    Of(usize),
    /// A face lying in a tet face (its halves paired in the merge): IA, the
    /// cell is on the vanishing function's positive side (side 0) or not.
    Positive(bool),
    /// MI, the cell's material; side 0 is the face's smaller material.
    Material(u16),
}

impl FaceSide {
    /// The side, given the face's two labels (`[f, f]` in IA, the sorted
    /// material pair in MI), as the merge orients faces in tet faces.
    pub(crate) fn of(self, label: [u16; 2]) -> usize {
        match self {
            FaceSide::Of(s) => s,
            FaceSide::Positive(p) => usize::from(!p),
            FaceSide::Material(m) => usize::from(m != label[0]),
        }
    }
}

/// The in-memory network as ray shooting sees it.
pub(crate) struct RayInput<'a> {
    pub keys: &'a [VKey],
    pub face_start: &'a [u32],
    pub face_verts: &'a [u32],
    pub face_patch: &'a [u32],
    pub face_label: &'a [[u16; 2]],
    pub shell_of_hp: &'a [u32],
    /// Connected component of each vertex.
    pub vertex_comp: &'a [u32],
    pub num_comps: usize,
}

impl RayInput<'_> {
    /// Per component, where its ray starts (see [`ray_start`]), or `None`
    /// if a component touches no grid edge or vertex (cannot happen on a
    /// proper network).
    pub(crate) fn starts(&self) -> Option<Vec<(u32, u32)>> {
        let mut best: Vec<(u32, u32)> = vec![(u32::MAX, u32::MAX); self.num_comps];
        for (v, k) in self.keys.iter().enumerate() {
            if let Some(s) = ray_start(k) {
                let c = self.vertex_comp[v] as usize;
                best[c] = best[c].min(s);
            }
        }
        best.iter().all(|b| b.0 != u32::MAX).then_some(best)
    }
}

/// The ordering vector's first two entries for a network vertex on the grid's
/// edges: `(v, u)` for an edge-point on grid edge `v < u`, `(w, 0)` for a
/// vertex at grid vertex `w` (before every edge-point of edges from `w`,
/// as `u > w >= 0`); `None` for vertices inside grid faces or tets.
pub(crate) fn ray_start(k: &VKey) -> Option<(u32, u32)> {
    if k.grid[1] == u32::MAX {
        Some((k.grid[0], 0))
    } else if k.grid[2] == u32::MAX {
        Some((k.grid[0], k.grid[1]))
    } else {
        None
    }
}

/// [`RayIndex`] over the merged network. Rays ask for a shell about once per
/// network component, so the faces at a vertex are first found by a scan
/// of the face loops; past [`SCANS`] questions a vertex-to-face index is
/// built (on one component, the index cost more than the whole ray stage).
pub(crate) struct MergedIndex<'a> {
    inp: &'a RayInput<'a>,
    vmap: KeyIndex<'a>,
    /// Faces at vertex `v`: `vf[start[v]..start[v + 1]]`, once built.
    index: Option<(Vec<u32>, Vec<u32>)>,
    scans: usize,
}

/// Shell questions answered by scanning before the index is built.
const SCANS: usize = 16;

impl<'a> MergedIndex<'a> {
    pub(crate) fn new(inp: &'a RayInput<'a>) -> MergedIndex<'a> {
        MergedIndex { inp, vmap: KeyIndex::new(inp.keys), index: None, scans: 0 }
    }

    /// The faces at vertex `v`, ascending (the same list either way).
    fn faces_at(&mut self, v: u32) -> SmallVec<[u32; 16]> {
        let inp = self.inp;
        if self.index.is_none() && self.scans == SCANS {
            self.index = Some(faces_at_vertices(inp.keys.len(), inp.face_start, inp.face_verts));
        }
        match &self.index {
            Some((start, vf)) => vf[start[v as usize] as usize..start[v as usize + 1] as usize].into(),
            None => {
                self.scans += 1;
                // The face holding loop position `j`: the last one starting at or before it.
                let face_of = |j: usize| inp.face_start.partition_point(|&s| s as usize <= j) as u32 - 1;
                let mut out: SmallVec<[u32; 16]> = SmallVec::new();
                for (j, _) in inp.face_verts.iter().enumerate().filter(|&(_, &u)| u == v) {
                    let f = face_of(j);
                    if out.last() != Some(&f) {
                        out.push(f);
                    }
                }
                out
            }
        }
    }
}

/// The faces at each of `nv` vertices, as `(start, faces)`: face ids at `v`
/// are `faces[start[v]..start[v + 1]]` (polygon `f` is
/// `face_verts[face_start[f]..face_start[f + 1]]`).
pub(crate) fn faces_at_vertices(nv: usize, face_start: &[u32], face_verts: &[u32]) -> (Vec<u32>, Vec<u32>) {
    let mut start = vec![0u32; nv + 1];
    for &v in face_verts {
        start[v as usize + 1] += 1;
    }
    for v in 0..nv {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut faces = vec![0u32; face_verts.len()];
    for f in 0..face_start.len().saturating_sub(1) {
        for j in face_start[f]..face_start[f + 1] {
            let v = face_verts[j as usize] as usize;
            faces[fill[v] as usize] = f as u32;
            fill[v] += 1;
        }
    }
    (start, faces)
}

impl RayIndex for MergedIndex<'_> {
    fn component(&mut self, _tet: &[u32; 4], key: VKey) -> Option<u32> {
        self.vmap.get(key).map(|id| self.inp.vertex_comp[id as usize])
    }

    fn shell(&mut self, _tet: &[u32; 4], keys: &[VKey], side: FaceSide) -> Option<u32> {
        let mut ids: SmallVec<[u32; 8]> = SmallVec::new();
        for &k in keys {
            ids.push(self.vmap.get(k)?);
        }
        ids.sort_unstable();
        let inp = self.inp;
        for gf in self.faces_at(ids[0]) {
            let mut vs: SmallVec<[u32; 8]> =
                inp.face_verts[inp.face_start[gf as usize] as usize..inp.face_start[gf as usize + 1] as usize].into();
            vs.sort_unstable();
            if vs == ids {
                let side = side.of(inp.face_label[gf as usize]);
                let s = inp.shell_of_hp[2 * inp.face_patch[gf as usize] as usize + side];
                return (s != NONE).then_some(s);
            }
        }
        None
    }
}

/// Global vertex id by key. Rays look up only a few keys, so when the keys
/// are in canonical order (sorted by grid element, as after
/// `canon::canonicalize_merged`) a binary search beats hashing every vertex;
/// otherwise a hash map is built.
enum KeyIndex<'a> {
    Sorted(&'a [VKey]),
    Hashed(FxHashMap<VKey, u32>),
}

impl<'a> KeyIndex<'a> {
    fn new(keys: &'a [VKey]) -> KeyIndex<'a> {
        if keys.windows(2).all(|w| w[0].grid <= w[1].grid) {
            KeyIndex::Sorted(keys)
        } else {
            KeyIndex::Hashed(keys.iter().enumerate().map(|(i, k)| (*k, i as u32)).collect())
        }
    }

    fn get(&self, key: VKey) -> Option<u32> {
        match self {
            KeyIndex::Sorted(keys) => {
                let lo = keys.partition_point(|k| k.grid < key.grid);
                keys[lo..].iter().take_while(|k| k.grid == key.grid).position(|k| *k == key).map(|i| (lo + i) as u32)
            }
            KeyIndex::Hashed(map) => map.get(&key).copied(),
        }
    }
}
