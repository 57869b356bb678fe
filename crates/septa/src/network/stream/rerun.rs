//! Ray shooting's questions (Du et al. Sec. 7.1, `raytrace.rs`) answered
//! for a streamed network, whose polygons are no longer in memory: the
//! block holding the tet a ray looks at is run again (blocks are pure
//! functions of the input, so it gives the same polygons, and its summary
//! the same patch pieces, as when it was streamed) and its pieces are
//! mapped to components and shells through the assembly (`assembly.rs`).
//! A ray looks at two or three tets per network component, so only a few
//! blocks are run again; the last few are kept.

use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use super::assembly::Assembled;
use crate::complex::NONE;
use crate::grid::{BoxGrid, Grid};
use crate::network::block::{BlockOut, Worker};
use crate::network::field::BoundedField;
use crate::network::sparse::run_block_with;
use crate::network::topology::{faces_at_vertices, FaceSide, RayIndex};
use crate::network::{NetworkOptions, VKey};

/// The faces that halves left open at block boundaries became (`halves.rs`).
pub(crate) struct HalfPieces {
    /// (block index, its first slot in `piece`), ascending: blocks with open halves.
    pub blocks: Vec<(usize, u32)>,
    /// Per open half, the piece of its face (`NONE`: no face).
    pub piece: Vec<u32>,
}

/// A block run again, indexed for lookups.
struct Rerun {
    index: usize,
    out: BlockOut,
    /// Its open halves, with their vertices sorted, and the piece of each face.
    open: Vec<(SmallVec<[u32; 8]>, u32)>,
    /// Global piece of each polygon.
    piece: Vec<u32>,
    vmap: FxHashMap<VKey, u32>,
    /// Polygons at block vertex `v`: `polys[start[v]..start[v + 1]]`.
    start: Vec<u32>,
    polys: Vec<u32>,
}

/// [`RayIndex`] by re-running blocks (module doc).
pub(crate) struct RerunIndex<'a> {
    pub grid: &'a BoxGrid,
    pub g: &'a Grid,
    pub functions: &'a dyn BoundedField,
    pub options: &'a NetworkOptions,
    /// (block index, its first piece), ascending: the streamed blocks.
    pub block_pieces: &'a [(usize, u32)],
    pub halves: &'a HalfPieces,
    pub assembled: &'a Assembled,
    pub worker: Worker,
    cache: Vec<Rerun>,
    /// Blocks run again (for the summary).
    pub reruns: usize,
}

/// How many re-run blocks are kept.
const KEEP: usize = 8;

impl<'a> RerunIndex<'a> {
    pub(crate) fn new(
        grid: &'a BoxGrid,
        g: &'a Grid,
        functions: &'a dyn BoundedField,
        options: &'a NetworkOptions,
        block_pieces: &'a [(usize, u32)],
        halves: &'a HalfPieces,
        assembled: &'a Assembled,
    ) -> RerunIndex<'a> {
        RerunIndex {
            grid,
            g,
            functions,
            options,
            block_pieces,
            halves,
            assembled,
            worker: Worker::default(),
            cache: Vec::new(),
            reruns: 0,
        }
    }

    /// The block holding `tet`, run again (`None`: it was never streamed,
    /// so it holds no network, or it fails now, which it did not before).
    fn block_of(&mut self, tet: &[u32; 4]) -> Option<&Rerun> {
        let ijk = tet
            .iter()
            .map(|&v| self.grid.vertex_ijk(v))
            .fold([usize::MAX; 3], |m, x| [m[0].min(x[0]), m[1].min(x[1]), m[2].min(x[2])]);
        self.block_of_cube(ijk)
    }

    /// The blocks holding a cube with grid vertex `v` as a corner (up to 8).
    fn blocks_at_vertex(&self, v: u32) -> SmallVec<[[usize; 3]; 8]> {
        let p = self.grid.vertex_ijk(v);
        let mut cubes: SmallVec<[[usize; 3]; 8]> = SmallVec::new();
        for d in 0..8 {
            let c = [0, 1, 2].map(|a| p[a].wrapping_sub((d >> a) & 1));
            if (0..3).all(|a| c[a] < self.grid.res[a]) {
                cubes.push(c);
            }
        }
        cubes
    }

    /// The block holding cube `ijk`, run again.
    fn block_of_cube(&mut self, ijk: [usize; 3]) -> Option<&Rerun> {
        let size = self.options.block.max(1);
        let n = self.grid.res.map(|r| r.div_ceil(size));
        let b = ijk.map(|c| c / size);
        self.block_by_index((b[0] * n[1] + b[1]) * n[2] + b[2])
    }

    /// A point where the surfaces of sheets `s1` and `s2` (edge-connected
    /// piece sets, `piece_sheet`) of one component touch: a vertex of both,
    /// searched in the blocks holding them that are equal or neighbours (at
    /// most 64 block pairs looked at), for the error that names it.
    pub(crate) fn contact(&mut self, piece_sheet: &[u32], s1: u32, s2: u32) -> Option<[f64; 3]> {
        let total = piece_sheet.len() as u32;
        let mut with: [Vec<usize>; 2] = [Vec::new(), Vec::new()];
        for (i, &(index, first)) in self.block_pieces.iter().enumerate() {
            let end = self.block_pieces.get(i + 1).map_or(total, |x| x.1);
            for (k, s) in [s1, s2].into_iter().enumerate() {
                if (first..end).any(|p| piece_sheet[p as usize] == s) {
                    with[k].push(index);
                }
            }
        }
        let size = self.options.block.max(1);
        let n = self.grid.res.map(|r| r.div_ceil(size));
        let ijk = |i: usize| [i / (n[1] * n[2]), i / n[2] % n[1], i % n[2]];
        let near = |a: usize, b: usize| (0..3).all(|x| ijk(a)[x].abs_diff(ijk(b)[x]) <= 1);
        let pairs: Vec<(usize, usize)> = with[0]
            .iter()
            .flat_map(|&a| with[1].iter().filter(move |&&b| near(a, b)).map(move |&b| (a, b)))
            .take(64)
            .collect();
        for (a, b) in pairs {
            let first: FxHashMap<VKey, [f64; 3]> = self.block_by_index(a)?.sheet_vertices(piece_sheet, s1).collect();
            let hit = self.block_by_index(b)?.sheet_vertices(piece_sheet, s2).find_map(|(k, _)| first.get(&k).copied());
            if hit.is_some() {
                return hit;
            }
        }
        None
    }

    /// Keys of the vertices where sheets (edge-connected piece sets,
    /// `piece_sheet`) touch: a vertex of pieces of two sheets. Only the
    /// blocks holding pieces of sheets marked in `several` (components of
    /// more than one sheet) are run again; a vertex on a block boundary is
    /// compared across blocks through a map of such vertices alone.
    pub(crate) fn contact_keys(&mut self, piece_sheet: &[u32], several: &[bool]) -> Option<Vec<VKey>> {
        let total = piece_sheet.len() as u32;
        let wanted = |p: u32| p != NONE && several[piece_sheet[p as usize] as usize];
        let blocks: Vec<usize> = (0..self.block_pieces.len())
            .filter(|&i| {
                let end = self.block_pieces.get(i + 1).map_or(total, |x| x.1);
                (self.block_pieces[i].1..end).any(wanted)
            })
            .map(|i| self.block_pieces[i].0)
            .collect();
        let size = self.options.block.max(1);
        let grid = self.grid;
        // Whether a key's grid element lies in a plane between blocks.
        let on_boundary = |k: &VKey| {
            let ijk: SmallVec<[[usize; 3]; 4]> =
                k.grid.iter().filter(|&&v| v != u32::MAX).map(|&v| grid.vertex_ijk(v)).collect();
            (0..3).any(|a| ijk.iter().all(|x| x[a] == ijk[0][a]) && ijk[0][a] % size == 0)
        };
        let mut across: FxHashMap<VKey, u32> = FxHashMap::default();
        let mut keys = Vec::new();
        for index in blocks {
            let r = self.block_by_index(index)?;
            let o = &r.out;
            let mut sheet_at = vec![NONE; o.keys.len()];
            let mut touch = vec![false; o.keys.len()];
            let mut see = |v: u32, p: u32| {
                let s = piece_sheet[p as usize];
                let at = &mut sheet_at[v as usize];
                if *at == NONE {
                    *at = s;
                } else if *at != s {
                    touch[v as usize] = true;
                }
            };
            for (poly, &p) in r.piece.iter().enumerate() {
                if wanted(p) {
                    for &v in &o.poly_verts[o.poly_start[poly] as usize..o.poly_start[poly + 1] as usize] {
                        see(v, p);
                    }
                }
            }
            for (verts, p) in &r.open {
                if wanted(*p) {
                    for &v in verts {
                        see(v, *p);
                    }
                }
            }
            for (v, &s) in sheet_at.iter().enumerate() {
                let k = o.keys[v];
                if touch[v] {
                    keys.push(k);
                } else if s != NONE && on_boundary(&k) {
                    let first = *across.entry(k).or_insert(s);
                    if first != s {
                        keys.push(k);
                    }
                }
            }
        }
        keys.sort_unstable();
        keys.dedup();
        Some(keys)
    }

    /// Block `index`, run again.
    fn block_by_index(&mut self, index: usize) -> Option<&Rerun> {
        if let Some(i) = self.cache.iter().position(|r| r.index == index) {
            let r = self.cache.remove(i);
            self.cache.push(r);
            return self.cache.last();
        }
        let at = self.block_pieces.binary_search_by_key(&index, |x| x.0).ok()?;
        let base = self.block_pieces[at].1;
        let mut r = run_block_with(&mut self.worker, self.g, self.grid, self.functions, self.options, index).ok()?;
        self.reruns += 1;
        let prepared = super::prepare::prepare(self.grid, self.options, &mut r, true).ok()?;
        let out = r.out;
        let s = prepared.summary?;
        let piece = s.poly_piece.iter().map(|&p| base + p).collect();
        let first = match self.halves.blocks.binary_search_by_key(&index, |x| x.0) {
            Ok(at) => self.halves.blocks[at].1 as usize,
            Err(_) => 0,
        };
        let open = prepared
            .open
            .iter()
            .enumerate()
            .map(|(j, h)| {
                let mut vs = h.verts.clone();
                vs.sort_unstable();
                (vs, self.halves.piece.get(first + j).copied().unwrap_or(NONE))
            })
            .collect();
        let vmap = out.keys.iter().enumerate().map(|(i, k)| (*k, i as u32)).collect();
        let (start, polys) = faces_at_vertices(out.keys.len(), &out.poly_start, &out.poly_verts);
        if self.cache.len() == KEEP {
            self.cache.remove(0);
        }
        self.cache.push(Rerun { index, out, open, piece, vmap, start, polys });
        self.cache.last()
    }
}

impl Rerun {
    fn polys_at(&self, v: u32) -> &[u32] {
        &self.polys[self.start[v as usize] as usize..self.start[v as usize + 1] as usize]
    }

    /// The vertices (keys, positions) of this block's polygons on sheet `sheet`.
    fn sheet_vertices<'s>(&'s self, piece_sheet: &'s [u32], sheet: u32) -> impl Iterator<Item = (VKey, [f64; 3])> + 's {
        let o = &self.out;
        (0..o.poly_label.len())
            .filter(move |&p| piece_sheet[self.piece[p] as usize] == sheet)
            .flat_map(move |p| o.poly_verts[o.poly_start[p] as usize..o.poly_start[p + 1] as usize].iter())
            .map(move |&v| (o.keys[v as usize], o.points[v as usize]))
    }

    /// The piece of a face of this block at the vertex with key `key`.
    fn piece_at(&self, key: &VKey) -> Option<u32> {
        let v = *self.vmap.get(key)?;
        match self.polys_at(v).first() {
            Some(&p) => Some(self.piece[p as usize]),
            // On faces paired across blocks only.
            None => self.open.iter().find(|(vs, p)| *p != NONE && vs.contains(&v)).map(|x| x.1),
        }
    }
}

impl RayIndex for RerunIndex<'_> {
    fn component(&mut self, tet: &[u32; 4], key: VKey) -> Option<u32> {
        let assembled = self.assembled;
        if let Some(piece) = self.block_of(tet).and_then(|r| r.piece_at(&key)) {
            return Some(assembled.piece_comp[piece as usize]);
        }
        // A network vertex on a grid vertex or edge that this tet's block did
        // not make (its tets there meet the network only at that point) is
        // still a network vertex if a block around its grid element made it,
        // as the in-memory index finds it by key alone.
        let mut cubes: SmallVec<[[usize; 3]; 16]> = SmallVec::new();
        for &w in key.grid.iter().filter(|&&w| w != u32::MAX) {
            cubes.extend(self.blocks_at_vertex(w));
        }
        for c in cubes {
            if let Some(piece) = self.block_of_cube(c).and_then(|r| r.piece_at(&key)) {
                return Some(assembled.piece_comp[piece as usize]);
            }
        }
        None
    }

    fn shell(&mut self, tet: &[u32; 4], keys: &[VKey], side: FaceSide) -> Option<u32> {
        let assembled = self.assembled;
        let r = self.block_of(tet)?;
        let mut ids: SmallVec<[u32; 8]> = SmallVec::new();
        for k in keys {
            ids.push(*r.vmap.get(k)?);
        }
        ids.sort_unstable();
        for &p in r.polys_at(ids[0]) {
            let o = &r.out;
            let mut vs: SmallVec<[u32; 8]> =
                o.poly_verts[o.poly_start[p as usize] as usize..o.poly_start[p as usize + 1] as usize].into();
            vs.sort_unstable();
            if vs == ids {
                let piece = r.piece[p as usize] as usize;
                return Some(assembled.half_shell[2 * piece + side.of(o.poly_label[p as usize])]);
            }
        }
        // A face lying in a tet face on the block's boundary, paired across blocks.
        let &(_, piece) = r.open.iter().find(|(vs, _)| *vs == ids)?;
        (piece != NONE)
            .then(|| assembled.half_shell[2 * piece as usize + side.of(assembled.piece_label[piece as usize])])
    }
}
