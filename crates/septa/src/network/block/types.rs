//! What a block hands to the merge: polygons with global keys, region
//! components and the contacts, unions and wedges that join them across
//! blocks (Du et al. Sec. 7; merged by `topology::merge`).

use smallvec::SmallVec;

use crate::network::VKey;

/// A 3D region label: IA sign bits over all functions (bit `f` set iff
/// `f > 0`), MI the material in word 0.
pub(crate) type Label = SmallVec<[u64; 2]>;

/// A copy of `l`: `Label::clone` goes element by element through
/// `SmallVec`'s `extend` (a measurable share of a block's work); the words
/// are plain data and copy as a slice.
#[inline]
pub(crate) fn copy_label(l: &[u64]) -> Label {
    Label::from_slice(l)
}

/// Sorted grid vertices of a tet face.
pub(crate) type FaceKey = [u32; 3];

/// A side of a network face, for shell assembly.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SRef {
    /// Side `1` (negative) or `0` (positive) of a block polygon.
    Side(u32, u8),
    /// The side of a half-polygon (a network face on a tet face) facing its tet.
    Half(u32),
    /// A piece of a transparent tet face at one edge (a wedge passing through).
    T(u32),
}

/// A network face lying on a tet face (a function vanishing on the whole
/// face, or two materials tied on it), seen from one of its two tets.
#[derive(Clone, Debug)]
pub(crate) struct HalfPoly {
    pub face: FaceKey,
    /// Block vertex ids, counter-clockwise seen from inside the tet.
    pub verts: SmallVec<[u32; 8]>,
    /// Block region (after compression: block component).
    pub cell: u32,
    /// IA: the (smallest) function vanishing on the face.
    pub zero: u16,
}

/// Key of a transparent tet-face piece at an edge, across blocks.
pub(crate) type OpenT = (FaceKey, Label, VKey, VKey);

/// What a block hands to the merge.
#[derive(Debug, Default)]
pub(crate) struct BlockOut {
    pub keys: Vec<VKey>,
    /// Per key: whether its grid element may be shared with another block
    /// (lies on the block's boundary); the others need no global lookup.
    pub shared: Vec<bool>,
    pub points: Vec<[f64; 3]>,
    pub poly_start: Vec<u32>,
    pub poly_verts: Vec<u32>,
    pub poly_label: Vec<[u16; 2]>,
    pub poly_cells: Vec<[u32; 2]>,
    pub halves: Vec<HalfPoly>,
    pub comp_label: Vec<Label>,
    pub comp_volume: Vec<f64>,
    pub contacts: Vec<(FaceKey, Label, u32)>,
    pub unions: Vec<(SRef, SRef)>,
    /// Wedges at chain edges inside tets: (edge, face side, face side).
    pub wedges: Vec<([u32; 2], SRef, SRef)>,
    pub tnodes: u32,
    pub open_t: Vec<(OpenT, u32)>,
    pub active_tets: usize,
    pub tets: usize,
}
