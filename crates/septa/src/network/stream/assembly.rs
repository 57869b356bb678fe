//! Topology assembled from block summaries (docs/sparse.md; Du et al. Sec. 7):
//! patches, chains, corners, components, shells and cells of a network whose
//! polygons are never held together (they stream to disk, `stream.rs`).
//!
//! Blocks come in index order (x slabs outermost). Each brings its
//! [`BlockSummary`]; the assembly keeps, for the whole run, only numbers
//! per patch piece (a few per active block) and the network's chain edges
//! (a curve's worth); for about two slabs it keeps the open edges and open
//! tet-face pieces of the blocks' boundaries, closing each once no later
//! block can reach it (its grid element lies left of the current slab):
//!
//! - patches: pieces joined across closed open edges met by exactly two
//!   polygons (as `topology.rs` joins faces across edges of two faces);
//! - chains: edges met by three or more polygons, ordered into curves
//!   between corners by `topology::chains`;
//! - components: pieces joined at a vertex, inside a block or across blocks
//!   through a shared vertex key; edge-connected pieces (for ray shooting's
//!   precondition) likewise through any edge;
//! - shells: half-pieces joined by the blocks' wedge unions and across block
//!   faces by their open tet-face pieces, then every half-piece of a patch side;
//! - cells: ray shooting (Sec. 7.1, `raytrace.rs`), asking a block re-run on
//!   demand (`rerun.rs`) which component a hit vertex is in and which shell
//!   a hit face side belongs to.
//!
//! Numbering is deterministic (block order): patches by their first piece,
//! shells by their smallest half-patch, cells by their smallest shell (as
//! `canon.rs` numbers cells), vertices as streamed (`numbering.rs`).

use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use super::numbering::max_x;
use super::summary::{BlockSummary, ShellNode};
use super::summary_result::NetworkSummary;
use crate::complex::Mode;
use crate::complex::NONE;
use crate::grid::BoxGrid;
use crate::network::block::{BlockOut, Label, OpenT};
use crate::network::dense::label_free_cells;
use crate::network::topology::{cell_cycle, chains, min_rotation, wedge_cycle};
use crate::network::topology::{edge_on_grid_boundary, ray_start};
use crate::network::{CellInfo, NetworkError, Patch, VKey};
use crate::uf::UnionFind;

/// An edge of the block boundary not yet closed.
struct OpenEdge {
    /// Polygons around it so far.
    faces: u32,
    /// Pieces of its polygons.
    pieces: SmallVec<[u32; 4]>,
    /// It is closed once the current slab starts right of this x index.
    retire: u32,
    /// It lies on the grid's boundary (else one polygon means a crack).
    on_boundary: bool,
}

/// The assembly state (module doc).
pub(crate) struct Assembler {
    mode: Mode,
    functions: usize,
    plane: u64,
    grid: BoxGrid,
    /// Some block had an edge of one polygon off the grid boundary, or an
    /// open edge closed with one polygon there (a crack).
    cracked: bool,
    slab: usize,
    // Per piece.
    piece_label: Vec<[u16; 2]>,
    piece_faces: Vec<u32>,
    piece_side_label: Vec<[Label; 2]>,
    piece_start: Vec<(u32, u32)>,
    /// Shell node of the piece's positive side (the negative one follows).
    piece_node: Vec<u32>,
    patch_uf: UnionFind,
    sheet_uf: UnionFind,
    comp_uf: UnionFind,
    shell_uf: UnionFind,
    open_edges: FxHashMap<[u32; 2], OpenEdge>,
    open_t: FxHashMap<OpenT, u32>,
    chain_edges: Vec<[u32; 2]>,
    /// The pieces around each chain edge (streamed vertex ids).
    chain_pieces: FxHashMap<[u32; 2], SmallVec<[u32; 4]>>,
    /// Wedges (edge, side `2 f + s`, side) with streamed face ids, and the piece of each face in one.
    wedges: Vec<([u32; 2], u32, u32)>,
    wedge_piece: FxHashMap<u32, u32>,
    edges: usize,
    faces: u64,
    active_tets: usize,
    /// (block index, its first piece), ascending.
    pub(crate) block_pieces: Vec<(usize, u32)>,
    /// Blocks with open halves (`halves.rs`): (block index, its first slot in `half_piece`), ascending.
    pub(crate) block_halves: Vec<(usize, u32)>,
    /// Per open half, the piece of the face it became (`NONE`: none, or not yet).
    pub(crate) half_piece: Vec<u32>,
    /// Most open edges and tet-face pieces held at once.
    pub(crate) peak_open: usize,
}

impl Assembler {
    pub(crate) fn new(mode: Mode, functions: usize, plane: u64, grid: BoxGrid) -> Assembler {
        Assembler {
            mode,
            functions,
            plane,
            grid,
            cracked: false,
            slab: 0,
            piece_label: Vec::new(),
            piece_faces: Vec::new(),
            piece_side_label: Vec::new(),
            piece_start: Vec::new(),
            piece_node: Vec::new(),
            patch_uf: UnionFind::default(),
            sheet_uf: UnionFind::default(),
            comp_uf: UnionFind::default(),
            shell_uf: UnionFind::default(),
            open_edges: FxHashMap::default(),
            open_t: FxHashMap::default(),
            chain_edges: Vec::new(),
            chain_pieces: FxHashMap::default(),
            wedges: Vec::new(),
            wedge_piece: FxHashMap::default(),
            edges: 0,
            faces: 0,
            active_tets: 0,
            block_pieces: Vec::new(),
            block_halves: Vec::new(),
            half_piece: Vec::new(),
            peak_open: 0,
        }
    }

    /// Pieces so far (the next block's first piece).
    pub(crate) fn pieces(&self) -> u32 {
        self.piece_label.len() as u32
    }

    /// Joins the components of two (global) pieces: a shared vertex seen again.
    pub(crate) fn same_vertex(&mut self, a: u32, b: u32) {
        self.comp_uf.union(a, b);
    }

    /// Adds block `index` (cubes from x index `lo_x`), its output, summary
    /// and the streamed ids of its vertices (`numbering.rs`). The caller has
    /// already reported repeated shared vertices through [`Assembler::same_vertex`]
    /// with pieces numbered from [`Assembler::pieces`].
    pub(crate) fn add(
        &mut self,
        index: usize,
        lo_x: usize,
        out: &BlockOut,
        s: &BlockSummary,
        ids: &[u32],
    ) -> Result<BlockNodes, NetworkError> {
        if lo_x > self.slab {
            self.slab = lo_x;
            self.close(lo_x);
        }
        let base = self.pieces();
        let n = s.piece_label.len() as u32;
        self.block_pieces.push((index, base));
        self.active_tets += out.active_tets;
        let face_base = self.faces;
        self.faces += out.poly_label.len() as u64;
        if self.faces >= (1 << 31) {
            return Err(NetworkError::TooManyPolygons);
        }
        // Pieces and their nodes: 2 half-pieces each, then the block's extra classes.
        let node_base = self.shell_uf.len() as u32;
        for c in 0..n as usize {
            self.piece_label.push(s.piece_label[c]);
            self.piece_faces.push(s.piece_faces[c]);
            self.piece_side_label.push(s.piece_side_label[c].clone());
            self.piece_start.push(s.piece_start[c]);
            self.piece_node.push(node_base + 2 * c as u32);
            self.patch_uf.push();
            self.sheet_uf.push();
            self.comp_uf.push();
            self.shell_uf.push();
            self.shell_uf.push();
        }
        for _ in 0..s.extras {
            self.shell_uf.push();
        }
        for &(a, b) in &s.sheet_pairs {
            self.sheet_uf.union(base + a, base + b);
        }
        for &(a, b) in &s.vertex_pairs {
            self.comp_uf.union(base + a, base + b);
        }
        for &(a, b) in &s.shell_pairs {
            self.shell_uf.union(node_base + a, node_base + b);
        }
        let node = |x: ShellNode| match x {
            ShellNode::Half(h) => node_base + h,
            ShellNode::Extra(e) => node_base + 2 * n + e,
        };
        for (key, x) in &s.open_t {
            let x = node(*x);
            match self.open_t.remove(key) {
                Some(o) => self.shell_uf.union(o, x),
                None => {
                    self.open_t.insert(key.clone(), x);
                }
            }
        }
        self.edges += s.inner_edges;
        self.cracked |= s.cracked;
        let gid = |v: u32| ids[v as usize];
        for ([a, b], around) in &s.chain_edges {
            let (x, y) = (gid(*a), gid(*b));
            self.chain_edges.push([x.min(y), x.max(y)]);
            self.chain_pieces.insert([x.min(y), x.max(y)], around.iter().map(|&p| base + p).collect());
        }
        for ([a, b], around) in &s.open_edges {
            let (x, y) = (gid(*a), gid(*b));
            let key = [x.min(y), x.max(y)];
            let e = self.open_edges.entry(key).or_insert_with(|| OpenEdge {
                faces: 0,
                pieces: SmallVec::new(),
                retire: max_x(self.plane, &out.keys[*a as usize]).min(max_x(self.plane, &out.keys[*b as usize])) as u32,
                on_boundary: edge_on_grid_boundary(&self.grid, &out.keys[*a as usize], &out.keys[*b as usize]),
            });
            if e.faces == 0 {
                self.edges += 1;
            }
            for &p in around {
                e.pieces.push(base + p);
                e.faces += 1;
                // Any edge joins its polygons' sheets.
                self.sheet_uf.union(e.pieces[0], base + p);
            }
        }
        for &([a, b], x, y) in &s.wedges {
            let (u, v) = (gid(a), gid(b));
            let side = |z: u32| 2 * face_base as u32 + z;
            self.wedges.push(([u.min(v), u.max(v)], side(x), side(y)));
            for z in [x, y] {
                self.wedge_piece.insert(face_base as u32 + z / 2, base + s.poly_piece[z as usize / 2]);
            }
        }
        self.peak_open = self.peak_open.max(self.open_edges.len() + self.open_t.len());
        Ok(BlockNodes { node_base, pieces: n })
    }

    /// Adds a network face in a tet face on a block boundary, paired across
    /// two blocks (`halves.rs`) and streamed with the later one, as a piece
    /// of its own: `ids` and `keys` are its vertices (streamed ids and keys)
    /// counter-clockwise seen from side 0, `side_label` the region labels on
    /// its two sides and `nodes` the shell nodes of the halves on side 0 and 1.
    /// Returns the piece.
    pub(crate) fn add_face_across(
        &mut self,
        ids: &[u32],
        keys: &[VKey],
        label: [u16; 2],
        side_label: [Label; 2],
        nodes: [u32; 2],
    ) -> Result<u32, NetworkError> {
        let piece = self.pieces();
        self.faces += 1;
        if self.faces >= (1 << 31) {
            return Err(NetworkError::TooManyPolygons);
        }
        let node = self.shell_uf.len() as u32;
        self.piece_label.push(label);
        self.piece_faces.push(1);
        self.piece_side_label.push(side_label);
        self.piece_start.push(keys.iter().filter_map(ray_start).min().unwrap_or((u32::MAX, u32::MAX)));
        self.piece_node.push(node);
        self.patch_uf.push();
        self.sheet_uf.push();
        self.comp_uf.push();
        self.shell_uf.push();
        self.shell_uf.push();
        self.shell_uf.union(node, nodes[0]);
        self.shell_uf.union(node + 1, nodes[1]);
        // Every edge of a face in a block's boundary has both ends there: open.
        for j in 0..ids.len() {
            let k = (j + 1) % ids.len();
            let (x, y) = (ids[j], ids[k]);
            let retire = max_x(self.plane, &keys[j]).min(max_x(self.plane, &keys[k])) as u32;
            let on_boundary = edge_on_grid_boundary(&self.grid, &keys[j], &keys[k]);
            let e = self.open_edges.entry([x.min(y), x.max(y)]).or_insert_with(|| OpenEdge {
                faces: 0,
                pieces: SmallVec::new(),
                retire,
                on_boundary,
            });
            if e.faces == 0 {
                self.edges += 1;
            }
            e.pieces.push(piece);
            e.faces += 1;
            self.sheet_uf.union(e.pieces[0], piece);
        }
        self.peak_open = self.peak_open.max(self.open_edges.len() + self.open_t.len());
        Ok(piece)
    }

    /// Joins the shells of two nodes: two halves of one material meeting
    /// across a block boundary (MI; the shell passes through, `halves.rs`).
    pub(crate) fn same_shell(&mut self, a: u32, b: u32) {
        self.shell_uf.union(a, b);
    }

    /// Closes the open edges and tet-face pieces no block from x index `slab` on can reach.
    fn close(&mut self, slab: usize) {
        let Assembler { open_edges, patch_uf, chain_edges, chain_pieces, open_t, plane, cracked, .. } = self;
        open_edges.retain(|key, e| {
            if (e.retire as usize) >= slab {
                return true;
            }
            match e.faces {
                2 => patch_uf.union(e.pieces[0], e.pieces[1]),
                1 => *cracked |= !e.on_boundary,
                _ => {
                    chain_edges.push(*key);
                    chain_pieces.insert(*key, std::mem::take(&mut e.pieces));
                }
            }
            false
        });
        let plane = *plane;
        // An unpaired tet-face piece left of the slab lies on the grid boundary.
        open_t.retain(|k, _| k.0.iter().map(|&v| (v as u64 / plane) as usize).max().unwrap_or(0) >= slab);
    }

    /// The topology, with cells by ray shooting through `index` (built by
    /// the caller from the assembly's pieces, components and shells: see
    /// [`Assembled`]). `row0` holds the values at grid vertex 0 (the label
    /// of a cell bounded by no face).
    pub(crate) fn finish(
        mut self,
        vertices: usize,
        rays: impl FnOnce(&Assembled, &[u32], &[bool]) -> Option<(Vec<u32>, usize)>,
        contact: impl FnOnce(&Assembled, &[u32], u32, u32) -> Option<[f64; 3]>,
        row0: &[f64],
    ) -> Result<NetworkSummary, NetworkError> {
        self.close(usize::MAX);
        let np = self.piece_label.len();
        let (piece_patch, npatch) = self.patch_uf.components();
        let mut patches: Vec<Patch> = (0..npatch).map(|_| Patch { label: [u16::MAX; 2], faces: 0 }).collect();
        let mut patch_piece = vec![NONE; npatch];
        for c in 0..np {
            let p = piece_patch[c] as usize;
            patches[p].label = patches[p].label.min(self.piece_label[c]);
            patches[p].faces += self.piece_faces[c] as usize;
            if patch_piece[p] == NONE {
                patch_piece[p] = c as u32;
            }
        }
        // Every half-piece of a patch side is on one shell.
        for c in 0..np {
            let first = patch_piece[piece_patch[c] as usize] as usize;
            for s in 0..2 {
                self.shell_uf.union(self.piece_node[first] + s, self.piece_node[c] + s);
            }
        }
        let mut shell_of_root: FxHashMap<u32, u32> = FxHashMap::default();
        let mut shells: Vec<Vec<u32>> = Vec::new();
        let mut shell_of_hp = vec![NONE; 2 * npatch];
        for hp in 0..2 * npatch {
            let r = self.shell_uf.find(self.piece_node[patch_piece[hp / 2] as usize] + (hp % 2) as u32);
            let s = *shell_of_root.entry(r).or_insert_with(|| {
                shells.push(Vec::new());
                shells.len() as u32 - 1
            });
            shells[s as usize].push(hp as u32);
            shell_of_hp[hp] = s;
        }
        let (piece_comp, ncomp) = self.comp_uf.components();
        let (piece_sheet, sheets) = self.sheet_uf.components();
        let mut starts = vec![(u32::MAX, u32::MAX); ncomp];
        for c in 0..np {
            let k = piece_comp[c] as usize;
            starts[k] = starts[k].min(self.piece_start[c]);
        }
        let half_shell: Vec<u32> = (0..2 * np).map(|h| shell_of_hp[2 * piece_patch[h / 2] as usize + h % 2]).collect();
        let piece_label = std::mem::take(&mut self.piece_label);
        let a = Assembled { piece_label, piece_comp, half_shell, starts, num_shells: shells.len() };
        // Sheets of one component touching only at points (tangent spheres)
        // have their shells linked there first: `several` marks the sheets
        // of such components (empty when every component is one sheet).
        let mut several = Vec::new();
        if sheets != ncomp && self.cracked {
            // Behind a crack sheets may only seem to touch at points.
            return Err(touching_at_points(&a, &piece_sheet, self.mode, self.cracked, contact));
        }
        if sheets != ncomp {
            let (mut first, mut multi) = (vec![NONE; ncomp], vec![false; ncomp]);
            for (&c, &s) in a.piece_comp.iter().zip(&piece_sheet) {
                let f = &mut first[c as usize];
                if *f == NONE {
                    *f = s;
                }
                multi[c as usize] |= *f != s;
            }
            several = vec![false; sheets];
            for (&c, &s) in a.piece_comp.iter().zip(&piece_sheet) {
                several[s as usize] |= multi[c as usize];
            }
        }
        let cells_of = if a.starts.iter().all(|s| s.0 != u32::MAX) { rays(&a, &piece_sheet, &several) } else { None };
        let Some((shell_cell, ncells)) = cells_of else {
            if sheets != ncomp {
                return Err(touching_at_points(&a, &piece_sheet, self.mode, self.cracked, contact));
            }
            return Err(NetworkError::RayAlongNetwork);
        };
        // Cells numbered by their smallest shell (the shell-less outer cell last).
        let mut first_shell = vec![u32::MAX; ncells];
        for (s, &c) in shell_cell.iter().enumerate() {
            first_shell[c as usize] = first_shell[c as usize].min(s as u32);
        }
        let mut order: Vec<u32> = (0..ncells as u32).collect();
        order.sort_by_key(|&c| first_shell[c as usize]);
        let mut renum = vec![0u32; ncells];
        for (i, &c) in order.iter().enumerate() {
            renum[c as usize] = i as u32;
        }
        let mut cells: Vec<CellInfo> =
            (0..ncells).map(|_| CellInfo { shells: Vec::new(), label: Default::default(), volume: 0.0 }).collect();
        for (s, &c) in shell_cell.iter().enumerate() {
            cells[renum[c as usize] as usize].shells.push(s as u32);
        }
        let mut piece_cells = vec![[NONE; 2]; np];
        for c in 0..np {
            for s in 0..2 {
                let cell = renum[shell_cell[a.half_shell[2 * c + s] as usize] as usize];
                piece_cells[c][s] = cell;
                if cells[cell as usize].label.is_empty() {
                    cells[cell as usize].label = self.piece_side_label[c][s].clone();
                }
            }
        }
        label_free_cells(&mut cells, self.mode, row0);
        let (chains, corners) = compact_chains(&mut self.chain_edges);
        self.wedges.sort_unstable();
        let chain_patches = self.chain_patches(&chains, &piece_patch, &piece_cells);
        Ok(NetworkSummary {
            mode: self.mode,
            functions: self.functions,
            vertices,
            faces: self.faces as usize,
            edges: self.edges,
            patches,
            chains,
            chain_patches,
            corners,
            shells,
            cells,
            components: ncomp,
            active_tets: self.active_tets,
            piece_patch,
            piece_cells,
        })
    }

    /// Cyclic patch orders of the chains from the per-tet wedges, else
    /// (chains on tet faces and tet edges) from the cells between the
    /// pieces around a chain edge, as the in-memory network finds them.
    fn chain_patches(&self, chains: &[Vec<u32>], piece_patch: &[u32], piece_cells: &[[u32; 2]]) -> Vec<Vec<u32>> {
        let mut by_edge: FxHashMap<[u32; 2], Vec<(u32, u32)>> = FxHashMap::default();
        // Sorted by the caller, so each edge's walk starts the same way every run.
        for &(e, x, y) in &self.wedges {
            by_edge.entry(e).or_default().push((x, y));
        }
        let patch_of = |side: u32| piece_patch[self.wedge_piece[&(side / 2)] as usize];
        let edge = |c: &[u32], k: usize| [c[k].min(c[k + 1]), c[k].max(c[k + 1])];
        chains
            .iter()
            .map(|c| {
                let n = c.len().saturating_sub(1);
                let cyc = (0..n)
                    .find_map(|k| by_edge.get(&edge(c, k)).and_then(|p| wedge_cycle(p, &patch_of)))
                    .or_else(|| {
                        (0..n).find_map(|k| {
                            let pieces = self.chain_pieces.get(&edge(c, k))?;
                            cell_cycle(pieces, piece_cells, piece_patch)
                        })
                    })
                    .unwrap_or_default();
                min_rotation(&cyc)
            })
            .collect()
    }
}

/// Where a block's shell nodes start in the assembly (see [`BlockNodes::node`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct BlockNodes {
    node_base: u32,
    pieces: u32,
}

impl BlockNodes {
    /// The assembly's shell node for a block's [`ShellNode`].
    pub(crate) fn node(&self, x: ShellNode) -> u32 {
        match x {
            ShellNode::Half(h) => self.node_base + h,
            ShellNode::Extra(e) => self.node_base + 2 * self.pieces + e,
        }
    }
}

/// What ray shooting needs from the assembly.
pub(crate) struct Assembled {
    /// Label of each piece (IA `[f, f]`, MI `[a, b]`).
    pub piece_label: Vec<[u16; 2]>,
    /// Network component of each piece.
    pub piece_comp: Vec<u32>,
    /// Shell of each half-piece `2 * piece + side`.
    pub half_shell: Vec<u32>,
    /// Per component, the smallest grid edge carrying one of its vertices.
    pub starts: Vec<(u32, u32)>,
    /// Number of shells.
    pub num_shells: usize,
}

/// The error for a component whose sheets touch only at points where the
/// shells cannot be linked (a crack nearby, `topology::edge_on_grid_boundary`, or a
/// local picture that cannot be read): names the functions (IA) or materials (MI) that touch.
fn touching_at_points(
    a: &Assembled,
    piece_sheet: &[u32],
    mode: Mode,
    cracked: bool,
    contact: impl FnOnce(&Assembled, &[u32], u32, u32) -> Option<[f64; 3]>,
) -> NetworkError {
    // The first component holding two sheets, and the labels of its pieces.
    let mut first_sheet: FxHashMap<u32, u32> = FxHashMap::default();
    let mut two = None;
    for (&c, &s) in a.piece_comp.iter().zip(piece_sheet) {
        let first = *first_sheet.entry(c).or_insert(s);
        if first != s {
            two = Some((c, first, s));
            break;
        }
    }
    let mut labels: Vec<u16> = Vec::new();
    let mut at = None;
    if let Some((c, s1, s2)) = two {
        for (p, &pc) in a.piece_comp.iter().enumerate() {
            if pc == c {
                labels.extend(a.piece_label[p]);
            }
        }
        at = contact(a, piece_sheet, s1, s2);
    }
    labels.sort_unstable();
    labels.dedup();
    NetworkError::SheetsTouchAtPoints { mode, labels, at, cracked }
}

/// Chains and corners from chain edges on streamed vertex ids: the ids are
/// compacted to the chain vertices first (`topology::chains` indexes by vertex).
fn compact_chains(edges: &mut [[u32; 2]]) -> (Vec<Vec<u32>>, Vec<u32>) {
    edges.sort_unstable();
    let mut verts: Vec<u32> = edges.iter().flatten().copied().collect();
    verts.sort_unstable();
    verts.dedup();
    let local = |v: u32| verts.binary_search(&v).expect("a chain vertex") as u32;
    let compact: Vec<[u32; 2]> = edges.iter().map(|&[a, b]| [local(a), local(b)]).collect();
    let (chains, corners) = chains(verts.len(), &compact);
    let back = |v: &u32| verts[*v as usize];
    (chains.iter().map(|c| c.iter().map(back).collect()).collect(), corners.iter().map(back).collect())
}
