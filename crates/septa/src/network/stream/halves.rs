//! Network faces lying in tet faces, for a stream (docs/sparse.md).
//!
//! Where a function vanishes on a whole tet face (IA) or two materials tie
//! on one (MI), the face is found from each of its two tets as a *half*
//! (`block::HalfPoly`), and the in-memory merge (`topology::merge`) pairs
//! the halves by tet face and vertex keys. A stream never holds the whole
//! network, so it pairs them in two steps with the same rules:
//!
//! 1. inside a block ([`pair_in_block`], a pure function of the block's
//!    output, so a block re-run for ray shooting gives the same polygons):
//!    halves whose two tets are in the block become polygons of the block;
//!    a half on the grid's boundary becomes a one-sided polygon (IA) or
//!    nothing (MI), as in the merge;
//! 2. across blocks (the feeder, in block order): a half on a block's
//!    boundary is kept, keyed by its tet face and vertex keys, until the
//!    block across that face brings the other half; the face is then
//!    streamed with the later block, whose copy of the vertices it uses.
//!
//! Pairing rules (those of the merge): IA, the face has label `[f, f]` for
//! the smallest function `f` vanishing on it and is oriented from the half
//! on `f`'s positive side (side 0); MI, two halves of the same material are
//! no face (the shell passes through), otherwise side 0 is the smaller
//! material and the label the sorted pair.

use smallvec::SmallVec;

use crate::complex::{Mode, NONE};
use crate::grid::BoxGrid;
use crate::network::block::{BlockOut, FaceKey, HalfPoly, Label, SRef};
use crate::network::sign_bit;

/// A half left open at a block boundary (step 2 of the module doc).
#[derive(Clone, Debug)]
pub(crate) struct OpenHalf {
    pub face: FaceKey,
    /// Block vertex ids, counter-clockwise seen from inside the half's tet.
    pub verts: SmallVec<[u32; 8]>,
    /// Block component on the half's side.
    pub cell: u32,
    /// IA: the smallest function vanishing on the face.
    pub zero: u16,
    /// The block's t-node standing for the half's side in shell unions.
    pub t: u32,
}

/// A paired face: its label and which half is on side 0.
pub(crate) struct Paired {
    /// Label `[f, f]` (IA) or the sorted material pair (MI).
    pub label: [u16; 2],
    /// Whether the half given second is on side 0.
    pub second_first: bool,
}

/// Pairs two halves of one tet face (module doc), given their region
/// labels; `None` for two halves of one material (MI: no face).
pub(crate) fn pair(mode: Mode, zero: u16, first: &[u64], second: &[u64]) -> Option<Paired> {
    match mode {
        Mode::Ia => {
            let pos = sign_bit(first, zero as usize);
            Some(Paired { label: [zero, zero], second_first: !pos })
        }
        Mode::Mi => {
            let (ma, mb) = (first[0] as u16, second[0] as u16);
            if ma == mb {
                return None;
            }
            Some(Paired { label: [ma.min(mb), ma.max(mb)], second_first: ma > mb })
        }
    }
}

/// Where a tet face lies: on the grid's boundary, on the boundary of the
/// block of cubes `lo..hi` (and not the grid's), or inside the block.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Place {
    Grid,
    Block,
    Inside,
}

fn place(grid: &BoxGrid, lo: [usize; 3], hi: [usize; 3], face: &FaceKey) -> Place {
    let ijk = face.map(|v| grid.vertex_ijk(v));
    let on = |a: usize, x: usize| ijk.iter().all(|p| p[a] == x);
    if (0..3).any(|a| on(a, 0) || on(a, grid.res[a])) {
        Place::Grid
    } else if (0..3).any(|a| on(a, lo[a]) || on(a, hi[a])) {
        Place::Block
    } else {
        Place::Inside
    }
}

/// Step 1 of the module doc on a block of cubes `lo..hi`: the block's
/// halves become polygons (appended after its own), t-nodes or open
/// halves; its shell unions are rewritten to match, so that afterwards
/// `out.halves` is empty. Returns the open halves in the block's order.
pub(crate) fn pair_in_block(
    out: &mut BlockOut,
    mode: Mode,
    grid: &BoxGrid,
    lo: [usize; 3],
    hi: [usize; 3],
) -> Vec<OpenHalf> {
    let halves = std::mem::take(&mut out.halves);
    if halves.is_empty() {
        return Vec::new();
    }
    let mut by_key: rustc_hash::FxHashMap<(FaceKey, SmallVec<[u32; 8]>), u32> = Default::default();
    let mut pairs = Vec::new();
    for (h, half) in halves.iter().enumerate() {
        let mut sorted = half.verts.clone();
        sorted.sort_unstable();
        match by_key.remove(&(half.face, sorted.clone())) {
            Some(o) => pairs.push((o, h as u32)),
            None => {
                by_key.insert((half.face, sorted), h as u32);
            }
        }
    }
    let mut singles: Vec<u32> = by_key.into_values().collect();
    singles.sort_unstable();
    let mut refs: Vec<Option<SRef>> = vec![None; halves.len()];
    let label_of = |h: &HalfPoly| -> Label { out.comp_label[h.cell as usize].clone() };
    let mut polys: Vec<(SmallVec<[u32; 8]>, [u16; 2], [u32; 2])> = Vec::new();
    let first_poly = out.poly_label.len() as u32;
    let mut tnodes = out.tnodes;
    for (a, b) in pairs {
        let (ha, hb) = (&halves[a as usize], &halves[b as usize]);
        match pair(mode, ha.zero, &label_of(ha), &label_of(hb)) {
            Some(p) => {
                let (s0, s1) = if p.second_first { (hb, ha) } else { (ha, hb) };
                let id = first_poly + polys.len() as u32;
                polys.push((s0.verts.clone(), p.label, [s0.cell, s1.cell]));
                let (x, y) = if p.second_first { (b, a) } else { (a, b) };
                refs[x as usize] = Some(SRef::Side(id, 0));
                refs[y as usize] = Some(SRef::Side(id, 1));
            }
            None => {
                let t = next_t(&mut tnodes);
                refs[a as usize] = Some(SRef::T(t));
                refs[b as usize] = Some(SRef::T(t));
            }
        }
    }
    let mut open = Vec::new();
    for h in singles {
        let half = &halves[h as usize];
        let at = place(grid, lo, hi, &half.face);
        if at == Place::Block {
            let t = next_t(&mut tnodes);
            refs[h as usize] = Some(SRef::T(t));
            open.push(OpenHalf { face: half.face, verts: half.verts.clone(), cell: half.cell, zero: half.zero, t });
            continue;
        }
        // On the grid's boundary (or, never on a proper grid, inside the
        // block): one side only, as the merge makes it.
        match mode {
            Mode::Ia => {
                let id = first_poly + polys.len() as u32;
                if sign_bit(&label_of(half), half.zero as usize) {
                    polys.push((half.verts.clone(), [half.zero; 2], [half.cell, NONE]));
                    refs[h as usize] = Some(SRef::Side(id, 0));
                } else {
                    let rev = half.verts.iter().rev().copied().collect();
                    polys.push((rev, [half.zero; 2], [NONE, half.cell]));
                    refs[h as usize] = Some(SRef::Side(id, 1));
                }
            }
            Mode::Mi => refs[h as usize] = Some(SRef::T(next_t(&mut tnodes))),
        }
    }
    out.tnodes = tnodes;
    for (verts, label, cells) in polys {
        out.poly_verts.extend_from_slice(&verts);
        out.poly_start.push(out.poly_verts.len() as u32);
        out.poly_label.push(label);
        out.poly_cells.push(cells);
    }
    let resolve = |r: SRef| match r {
        SRef::Half(h) => refs[h as usize].expect("every half resolved"),
        other => other,
    };
    for u in &mut out.unions {
        *u = (resolve(u.0), resolve(u.1));
    }
    // Wedges at a half are dropped, as the merge drops them (it keeps
    // wedges between two block polygons only).
    out.wedges.retain(|w| matches!((w.1, w.2), (SRef::Side(..), SRef::Side(..))));
    open
}

/// A fresh t-node of the block.
fn next_t(tnodes: &mut u32) -> u32 {
    *tnodes += 1;
    *tnodes - 1
}
