//! A block's state while its tets are processed: the output arrays growing
//! tet by tet, the block's vertex maps, and the regions (cells of the tets'
//! complexes) joined across tet faces by their contacts; compressed to the
//! block's components when the block is done (`finish`). Below every
//! per-tet path (`worker`, `simple`, `program`, `keys`, the fast paths),
//! which all write into it.

use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use super::types::{copy_label, BlockOut, FaceKey, Label, OpenT};
use crate::network::VKey;
use crate::uf::UnionFind;

/// The lengths of a block's growing output arrays. The next block of a
/// worker (a neighbour, with about as much surface) reserves them and half
/// again up front, so its arrays do not grow by doubling and copying (a
/// tenth of the block stage's instructions went to reallocations on 18
/// spheres); the spare room is given back when the block is finished, and
/// the heap's free pages after the merge (`crate::heap`).
#[derive(Clone, Copy, Default)]
pub(super) struct Lengths {
    keys: usize,
    poly_start: usize,
    poly_verts: usize,
    unions: usize,
    wedges: usize,
    nodes: usize,
}

impl Lengths {
    pub(super) fn of(st: &State) -> Lengths {
        Lengths {
            keys: st.out.keys.len(),
            poly_start: st.out.poly_start.len(),
            poly_verts: st.out.poly_verts.len(),
            unions: st.out.unions.len(),
            wedges: st.out.wedges.len(),
            nodes: st.node_label.len(),
        }
    }

    pub(super) fn reserve(&self, st: &mut State) {
        let o = &mut st.out;
        let room = |n: usize| n + n / 2;
        o.keys.reserve(room(self.keys));
        o.shared.reserve(room(self.keys));
        o.points.reserve(room(self.keys));
        o.poly_start.reserve(room(self.poly_start));
        o.poly_verts.reserve(room(self.poly_verts));
        o.poly_label.reserve(room(self.poly_start));
        o.poly_cells.reserve(room(self.poly_start));
        o.unions.reserve(room(self.unions));
        o.wedges.reserve(room(self.wedges));
        st.uf.reserve(room(self.nodes));
        st.node_label.reserve(room(self.nodes));
        st.node_volume.reserve(room(self.nodes));
    }
}

/// Block-local maps, dropped with the block.
#[derive(Default)]
pub(crate) struct State {
    pub out: BlockOut,
    pub(crate) vmap: FxHashMap<VKey, u32>,
    /// Edge vertices by packed key (`keys::packed`).
    pub(crate) emap: FxHashMap<u64, u32>,
    pub(super) contacts: FxHashMap<(FaceKey, Label), u32>,
    pub(super) tmap: FxHashMap<(FaceKey, Label, u32, u32), u32>,
    pub uf: UnionFind,
    pub node_label: Vec<Label>,
    pub node_volume: Vec<f64>,
    /// Whether regions are joined across tet faces (cell grouping).
    pub grouping: bool,
    /// The cube range of a box block (`None`: a range of mesh tets).
    pub block_box: Option<([usize; 3], [usize; 3])>,
}

pub(crate) const FACE_OF: [[usize; 3]; 4] = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]];

/// The sorted grid vertices of face `i` (opposite corner `i`) of `tet`.
pub(super) fn face_key(tet: &[u32; 4], i: usize) -> FaceKey {
    let mut f = FACE_OF[i].map(|j| tet[j]);
    f.sort_unstable();
    f
}

/// Records that region `node` touches tet face `face` with `label`
/// (cell grouping joins the two regions at a face).
pub(super) fn contact(st: &mut State, face: FaceKey, label: &Label, node: u32) {
    use std::collections::hash_map::Entry;
    if !st.grouping {
        return;
    }
    match st.contacts.entry((face, copy_label(label))) {
        Entry::Occupied(o) => {
            let other = o.remove();
            st.uf.union(other, node)
        }
        Entry::Vacant(v) => {
            v.insert(node);
        }
    }
}

/// Compresses block regions to components and exports the open contacts.
pub(super) fn finish(mut st: State) -> BlockOut {
    let (comp, count) = st.uf.components();
    let mut out = st.out;
    // Not `vec![SmallVec::new(); count]`: that clones the empty label
    // `count` times through `SmallVec`'s `extend`.
    out.comp_label = std::iter::repeat_with(SmallVec::new).take(count).collect();
    out.comp_volume = vec![0.0; count];
    for (n, label) in st.node_label.into_iter().enumerate() {
        let c = comp[n] as usize;
        out.comp_volume[c] += st.node_volume[n];
        if out.comp_label[c].is_empty() {
            out.comp_label[c] = label;
        }
    }
    for cells in &mut out.poly_cells {
        *cells = cells.map(|x| comp[x as usize]);
    }
    for h in &mut out.halves {
        h.cell = comp[h.cell as usize];
    }
    let mut contacts: Vec<(FaceKey, Label, u32)> =
        st.contacts.into_iter().map(|((f, l), n)| (f, l, comp[n as usize])).collect();
    contacts.sort_unstable();
    out.contacts = contacts;
    let mut open: Vec<(OpenT, u32)> = st
        .tmap
        .into_iter()
        .map(|((f, l, a, b), t)| {
            let (ka, kb) = (out.keys[a as usize], out.keys[b as usize]);
            ((f, l, ka.min(kb), ka.max(kb)), t)
        })
        .collect();
    open.sort_unstable();
    out.open_t = open;
    if out.poly_start.is_empty() {
        out.poly_start.push(0);
    }
    // The room reserved from the previous block (`Lengths`) that this one
    // did not use: shrinking keeps the chunk in place (no copy).
    out.keys.shrink_to_fit();
    out.shared.shrink_to_fit();
    out.points.shrink_to_fit();
    out.poly_start.shrink_to_fit();
    out.poly_verts.shrink_to_fit();
    out.poly_label.shrink_to_fit();
    out.poly_cells.shrink_to_fit();
    out.unions.shrink_to_fit();
    out.wedges.shrink_to_fit();
    out
}
