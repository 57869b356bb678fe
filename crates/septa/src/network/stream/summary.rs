//! A block's summary: what the topology stage (Du et al. Sec. 7) needs to
//! know about a block, without its polygons (docs/sparse.md: "topology assembled
//! from block summaries without loading every block's polygons at once").
//!
//! Inside a block, polygons are joined into *patch pieces* across every edge
//! whose whole star lies in the block and is met by exactly two polygons
//! (a patch is a union of pieces). An edge is open (its star may reach
//! other blocks) only when both its ends lie on the block's boundary; such
//! edges are handed on with the pieces around them and closed by the
//! assembly (`assembly.rs`) once no later block can reach them. Everything
//! else the summary keeps is per piece (label, face count, the region labels
//! on its two sides, where its ray may start) or lies on the block boundary
//! (open edges, shared vertices, open tet-face pieces of shells): it grows
//! with the block's surface and its number of pieces, not with its polygons.
//!
//! The summary is a pure function of the block's output, so a block re-run
//! later (ray shooting, `rerun.rs`) numbers its pieces the same way.

use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use super::halves::OpenHalf;
use crate::complex::NONE;
use crate::grid::BoxGrid;
use crate::network::block::{BlockOut, Label, OpenT, SRef};
use crate::network::topology::{edge_on_grid_boundary, ray_start};
use crate::uf::UnionFind;

/// A node of the shell union-find a block hands on for an open tet-face piece.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ShellNode {
    /// Half-piece `2 * piece + side` (block-local piece).
    Half(u32),
    /// A block-local class of transparent tet-face pieces meeting no polygon side in the block.
    Extra(u32),
}

/// What the assembly needs from one block (module doc); piece, polygon and
/// vertex ids are block-local.
#[derive(Debug, Default)]
pub(crate) struct BlockSummary {
    /// Patch piece of each polygon.
    pub poly_piece: Vec<u32>,
    /// Per piece: its label (IA `[f, f]`, MI `[a, b]`).
    pub piece_label: Vec<[u16; 2]>,
    /// Per piece: its number of polygons.
    pub piece_faces: Vec<u32>,
    /// Per piece: the region label on its positive and negative side.
    pub piece_side_label: Vec<[Label; 2]>,
    /// Per piece: the smallest grid edge `(v, u)` carrying one of its
    /// vertices (where a ray may start, `raytrace.rs`); `(MAX, MAX)` if none.
    pub piece_start: Vec<(u32, u32)>,
    /// Edges with both ends on the block's boundary, `[a, b]` with `a < b`,
    /// and the piece of each polygon around them.
    pub open_edges: Vec<([u32; 2], SmallVec<[u32; 4]>)>,
    /// Number of edges that are not open.
    pub inner_edges: usize,
    /// An edge of one polygon off the block's and the grid's boundary (a
    /// crack: `topology::edge_on_grid_boundary`).
    pub cracked: bool,
    /// Chain edges (three or more polygons) that are not open, with the
    /// piece of each polygon around them (for the cyclic patch order where
    /// no wedge gives it: chains on tet faces and tet edges).
    pub chain_edges: Vec<([u32; 2], SmallVec<[u32; 4]>)>,
    /// Pieces joined along a chain edge inside the block (edge-connected).
    pub sheet_pairs: Vec<(u32, u32)>,
    /// Pieces joined at a vertex inside the block (network components).
    pub vertex_pairs: Vec<(u32, u32)>,
    /// Per vertex: the piece of its first polygon (`NONE`: on no polygon).
    pub vertex_piece: Vec<u32>,
    /// Half-pieces `2 * piece + side` bounding one shell (Sec. 7), as joined inside the block.
    pub shell_pairs: Vec<(u32, u32)>,
    /// Transparent tet-face pieces left open at the block boundary, with their shell node.
    pub open_t: Vec<(OpenT, ShellNode)>,
    /// The shell node of each open half (`halves.rs`), in the block's order.
    pub open_half_node: Vec<ShellNode>,
    /// Number of [`ShellNode::Extra`] classes.
    pub extras: u32,
    /// Wedges at chain edges inside tets: (edge, side `2 p + s`, side `2 q + t`) of block polygons.
    pub wedges: Vec<([u32; 2], u32, u32)>,
}

/// The summary of a block's output (module doc), after its halves were
/// paired inside the block (`halves::pair_in_block`, which returned `open`).
pub(crate) fn summarize(grid: &BoxGrid, out: &BlockOut, open: &[OpenHalf]) -> BlockSummary {
    assert!(out.halves.is_empty(), "halves are paired before a block is summarised");
    let np = out.poly_label.len();
    let poly = |p: usize| &out.poly_verts[out.poly_start[p] as usize..out.poly_start[p + 1] as usize];
    // Polygon sides as (a, b, polygon), a < b, sorted: a run is one edge.
    let sides = sorted_sides(out.keys.len(), np, &poly);
    let mut s = BlockSummary::default();
    let mut uf = UnionFind::new(np);
    let mut runs: Vec<(usize, usize)> = Vec::new(); // open or chain edges, resolved after pieces
    let mut i = 0;
    while i < sides.len() {
        let (a, b) = (sides[i].0, sides[i].1);
        let mut j = i + 1;
        while j < sides.len() && sides[j].0 == a && sides[j].1 == b {
            j += 1;
        }
        let open = out.shared[a as usize] && out.shared[b as usize];
        if open {
            runs.push((i, j));
        } else {
            s.inner_edges += 1;
            match j - i {
                1 => s.cracked |= !edge_on_grid_boundary(grid, &out.keys[a as usize], &out.keys[b as usize]),
                2 => uf.union(sides[i].2, sides[i + 1].2),
                _ => {
                    runs.push((i, j));
                }
            }
        }
        i = j;
    }
    let (poly_piece, pieces) = uf.components();
    let mut sheet = UnionFind::new(pieces);
    for &(i, j) in &runs {
        let (a, b) = (sides[i].0, sides[i].1);
        let around: SmallVec<[u32; 4]> = sides[i..j].iter().map(|x| poly_piece[x.2 as usize]).collect();
        if out.shared[a as usize] && out.shared[b as usize] {
            s.open_edges.push(([a, b], around));
        } else {
            for &x in &around[1..] {
                sheet.union(around[0], x);
            }
            s.chain_edges.push(([a, b], around));
        }
    }
    drop(sides);
    s.sheet_pairs = pairs_to_roots(&mut sheet);
    // Per piece: label, faces, side labels, ray start; per vertex: first piece.
    s.piece_label = vec![[0, 0]; pieces];
    s.piece_faces = vec![0; pieces];
    s.piece_side_label = vec![[Label::new(), Label::new()]; pieces];
    s.piece_start = vec![(u32::MAX, u32::MAX); pieces];
    s.vertex_piece = vec![NONE; out.keys.len()];
    let mut at_vertex = UnionFind::new(pieces);
    for p in 0..np {
        let c = poly_piece[p] as usize;
        s.piece_faces[c] += 1;
        // The smallest face label (as `topology::build` labels patches).
        s.piece_label[c] =
            if s.piece_faces[c] == 1 { out.poly_label[p] } else { s.piece_label[c].min(out.poly_label[p]) };
        if s.piece_faces[c] == 1 {
            // A one-sided face on the grid boundary has no region outside.
            s.piece_side_label[c] =
                out.poly_cells[p].map(|r| if r == NONE { Label::new() } else { out.comp_label[r as usize].clone() });
        }
        for &v in poly(p) {
            let k = &out.keys[v as usize];
            if let Some(start) = ray_start(k) {
                s.piece_start[c] = s.piece_start[c].min(start);
            }
            match s.vertex_piece[v as usize] {
                NONE => s.vertex_piece[v as usize] = c as u32,
                o => at_vertex.union(o, c as u32),
            }
        }
    }
    s.vertex_pairs = pairs_to_roots(&mut at_vertex);
    // Shells: half-pieces first (so a class's root is its smallest
    // half-piece when it has one), then the block's t-nodes.
    let half = |r: SRef| match r {
        SRef::Side(p, side) => Some(2 * poly_piece[p as usize] + side as u32),
        SRef::T(t) => Some(2 * pieces as u32 + t),
        SRef::Half(_) => None,
    };
    let mut shells = UnionFind::new(2 * pieces + out.tnodes as usize);
    for &(a, b) in &out.unions {
        let (Some(x), Some(y)) = (half(a), half(b)) else { unreachable!("halves are paired first") };
        shells.union(x, y);
    }
    for x in 0..2 * pieces as u32 {
        let r = shells.find(x);
        if r != x {
            s.shell_pairs.push((x, r));
        }
    }
    let mut extra: FxHashMap<u32, u32> = FxHashMap::default();
    // A class of t-nodes meeting no polygon side in the block is kept as an
    // extra node: two MI halves of one material (no face, the shell passes
    // through) or a half left open at the block boundary whose tet has no
    // other network face.
    let mut node_of = |t: u32| {
        let r = shells.find(2 * pieces as u32 + t);
        if r < 2 * pieces as u32 {
            ShellNode::Half(r)
        } else {
            let n = extra.len() as u32;
            ShellNode::Extra(*extra.entry(r).or_insert(n))
        }
    };
    for (key, t) in &out.open_t {
        s.open_t.push((key.clone(), node_of(*t)));
    }
    s.open_half_node = open.iter().map(|h| node_of(h.t)).collect();
    s.extras = extra.len() as u32;
    for &(e, r1, r2) in &out.wedges {
        if let (SRef::Side(p, a), SRef::Side(q, b)) = (r1, r2) {
            s.wedges.push((e, 2 * p + a as u32, 2 * q + b as u32));
        }
    }
    s.poly_piece = poly_piece;
    s
}

/// Every polygon side as `(a, b, polygon)` with `a < b`, sorted: a
/// counting sort by `a` (linear in the sides), then each short bucket by
/// `(b, polygon)`; the same order as sorting the whole list.
fn sorted_sides<'a>(nv: usize, np: usize, poly: &impl Fn(usize) -> &'a [u32]) -> Vec<(u32, u32, u32)> {
    let side = |vs: &[u32], j: usize| {
        let (a, b) = (vs[j], vs[(j + 1) % vs.len()]);
        (a.min(b), a.max(b))
    };
    let mut start = vec![0u32; nv + 1];
    for p in 0..np {
        let vs = poly(p);
        for j in 0..vs.len() {
            start[side(vs, j).0 as usize + 1] += 1;
        }
    }
    for v in 0..nv {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut sides = vec![(0u32, 0u32, 0u32); start[nv] as usize];
    for p in 0..np {
        let vs = poly(p);
        for j in 0..vs.len() {
            let (a, b) = side(vs, j);
            sides[fill[a as usize] as usize] = (a, b, p as u32);
            fill[a as usize] += 1;
        }
    }
    for v in 0..nv {
        let bucket = &mut sides[start[v] as usize..start[v + 1] as usize];
        if bucket.len() > 1 {
            bucket.sort_unstable();
        }
    }
    sides
}

/// `(x, root)` for every element that is not its set's root.
fn pairs_to_roots(uf: &mut UnionFind) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    for x in 0..uf.len() as u32 {
        let r = uf.find(x);
        if r != x {
            out.push((x, r));
        }
    }
    out
}
