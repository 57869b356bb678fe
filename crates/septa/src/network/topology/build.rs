//! Topology of the merged network (Du et al. Sec. 7): edges, patches,
//! chains, corners, components, shells, and cells by cell grouping.

use smallvec::SmallVec;

use super::merge::Merged;
use crate::buckets::for_each_bucket;
use crate::complex::NONE;
use crate::grid::Grid;
use crate::network::block::Ctx;
use crate::network::{CellInfo, CellMethod, Patch};
use crate::uf::UnionFind;

/// The topology stage's results.
pub(crate) struct Topology {
    pub edges: Vec<[u32; 2]>,
    pub face_patch: Vec<u32>,
    pub patches: Vec<Patch>,
    pub chains: Vec<Vec<u32>>,
    pub corners: Vec<u32>,
    pub components: usize,
    pub shells: Vec<Vec<u32>>,
    pub cells: Vec<CellInfo>,
    pub face_cells: Vec<[u32; 2]>,
    pub cells_method: CellMethod,
    pub chain_patches: Vec<Vec<u32>>,
}

pub(crate) fn topology(m: &mut Merged, ray: Option<&Ctx>) -> Topology {
    let nf = m.face_label.len();
    let nv = m.points.len();
    // Edges: (a << 32 | b, face) sorted; a run of equal keys is one edge.
    // A counting sort by the smaller vertex `a`, then each short bucket
    // sorted: linear time instead of a global sort of every polygon side.
    // A polygon's sides as (smaller, larger) end, the closing side first
    // (the order within a bucket does not matter: buckets are sorted whole).
    fn for_each_side(vs: &[u32], mut side: impl FnMut(u32, u32)) {
        let Some(&last) = vs.last() else { return };
        let mut prev = last;
        for &v in vs {
            side(prev.min(v), prev.max(v));
            prev = v;
        }
    }
    let mut start = vec![0u32; nv + 1];
    for f in 0..nf {
        let vs = &m.face_verts[m.face_start[f] as usize..m.face_start[f + 1] as usize];
        for_each_side(vs, |a, _| start[a as usize + 1] += 1);
    }
    for v in 0..nv {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    // (other end b, face) per polygon side, bucketed by the smaller end `a`
    // (implied by the bucket: 8 bytes per side instead of 16), packed as
    // `b << 32 | face`: the numeric order is the pairs' lexicographic one,
    // and the buckets' small sorts compare one word instead of two.
    let mut ef: Vec<u64> = vec![0; m.face_verts.len()];
    let other = |x: u64| (x >> 32) as u32;
    let face = |x: u64| x as u32;
    for f in 0..nf {
        let vs = &m.face_verts[m.face_start[f] as usize..m.face_start[f + 1] as usize];
        for_each_side(vs, |a, b| {
            ef[fill[a as usize] as usize] = u64::from(b) << 32 | f as u64;
            fill[a as usize] += 1;
        });
    }
    drop(fill);
    // Sort the buckets and count the edges first: the edge list is sized
    // exactly (growing by doubling left up to half of it empty at the
    // run's peak of memory).
    let ne = for_each_bucket(&mut ef, &start, |_, bucket| {
        bucket.sort_unstable();
        bucket.iter().enumerate().filter(|&(i, &x)| i == 0 || other(bucket[i - 1]) != other(x)).count()
    });
    let mut edges = Vec::with_capacity(ne);
    let mut patch_uf = UnionFind::new(nf);
    let mut vert_uf = UnionFind::new(nv);
    let mut chain_edges = Vec::new();
    let mut sheet_uf = UnionFind::new(nf);
    let mut cracked = false;
    let box_grid = match ray.map(|c| c.grid) {
        Some(Grid::Box(g)) => Some(g),
        _ => None,
    };
    // Faces around each chain edge (3 or more), for the cyclic order.
    let mut chain_faces: rustc_hash::FxHashMap<[u32; 2], Vec<u32>> = Default::default();
    for a in 0..nv {
        let bucket = &ef[start[a] as usize..start[a + 1] as usize];
        let a = a as u32;
        let mut i = 0;
        while i < bucket.len() {
            let mut j = i;
            while j < bucket.len() && other(bucket[j]) == other(bucket[i]) {
                j += 1;
            }
            let b = other(bucket[i]);
            edges.push([a, b]);
            vert_uf.union(a, b);
            for k in i + 1..j {
                sheet_uf.union(face(bucket[i]), face(bucket[k]));
            }
            match j - i {
                2 => patch_uf.union(face(bucket[i]), face(bucket[i + 1])),
                1 => {
                    if let Some(g) = box_grid {
                        cracked |= !super::contact::edge_on_grid_boundary(g, &m.keys[a as usize], &m.keys[b as usize]);
                    }
                }
                _ => {
                    chain_edges.push([a, b]);
                    chain_faces.insert([a, b], bucket[i..j].iter().map(|&x| face(x)).collect());
                }
            }
            i = j;
        }
    }
    drop(start);
    drop(ef);
    let (face_patch, np) = patch_uf.into_components();
    // A patch's label is its smallest face label: the faces of a patch share
    // one label except where MI ties on the grid's boundary leave no face
    // between two interfaces (then every path must name it the same way).
    let mut patches: Vec<Patch> = (0..np).map(|_| Patch { label: [u16::MAX; 2], faces: 0 }).collect();
    for f in 0..nf {
        let p = &mut patches[face_patch[f] as usize];
        p.label = p.label.min(m.face_label[f]);
        p.faces += 1;
    }
    let (chains, corners) = chains(nv, &chain_edges);
    let (vertex_comp, components) = vert_uf.into_components();
    // Shells: components of face sides joined around edges (block unions),
    // and every side of a half-patch together.
    let mut shell_uf = UnionFind::new(m.shell_nodes);
    for &(a, b) in &m.shell_pairs {
        shell_uf.union(a, b);
    }
    let mut first_side = vec![NONE; 2 * np];
    for f in 0..nf {
        for s in 0..2 {
            let hp = 2 * face_patch[f] as usize + s;
            let node = 2 * f as u32 + s as u32;
            if first_side[hp] == NONE {
                first_side[hp] = node;
            } else {
                shell_uf.union(first_side[hp], node);
            }
        }
    }
    // Number shells by their smallest half-patch.
    let mut shell_of_root = rustc_hash::FxHashMap::default();
    let mut shells: Vec<Vec<u32>> = Vec::new();
    let mut shell_of_hp = vec![NONE; 2 * np];
    for hp in 0..2 * np {
        if first_side[hp] == NONE {
            continue;
        }
        let r = shell_uf.find(first_side[hp]);
        let s = *shell_of_root.entry(r).or_insert_with(|| {
            shells.push(Vec::new());
            shells.len() as u32 - 1
        });
        shells[s as usize].push(hp as u32);
        shell_of_hp[hp] = s;
    }
    drop(shell_uf);
    // Cells: by ray shooting where it applies, else by region groups.
    // Sheets of one component touching only at points (tangent spheres)
    // have their shells linked at those points first.
    let (face_sheet, sheets) = sheet_uf.into_components();
    // Behind a crack (an edge of one face off the grid boundary) the sheets
    // may only seem to touch at points: cells are grouped there.
    let contacts = if sheets == components { Vec::new() } else { contact_points(m, &face_sheet) };
    let rays = ray.filter(|_| sheets == components || !cracked).and_then(|ctx| {
        let inp = super::ray_index::RayInput {
            keys: &m.keys,
            face_start: &m.face_start,
            face_verts: &m.face_verts,
            face_patch: &face_patch,
            face_label: &m.face_label,
            shell_of_hp: &shell_of_hp,
            vertex_comp: &vertex_comp,
            num_comps: components,
        };
        let starts = inp.starts()?;
        let mut index = super::ray_index::MergedIndex::new(&inp);
        let mut links = Vec::new();
        for &v in &contacts {
            links.extend(super::contact::contact_links(ctx, &mut index, &m.keys[v as usize])?);
        }
        super::raytrace::ray_cells(ctx, &mut index, &starts, shells.len(), &links)
    });
    if let Some((shell_cell, ncells)) = rays {
        let mut t = ray_topology(
            m,
            edges,
            face_patch,
            patches,
            chains,
            corners,
            components,
            shells,
            shell_of_hp,
            shell_cell,
            ncells,
        );
        t.chain_patches = cyclic_patches(m, &t.chains, &t.face_patch, &t.face_cells, &chain_faces);
        return t;
    }
    if m.regions_dropped {
        // The caller falls back to its grouping path (see `Merged::drop_region_groups`).
        return Topology {
            edges,
            face_patch,
            patches,
            chains,
            corners,
            components,
            shells,
            cells: Vec::new(),
            face_cells: Vec::new(),
            cells_method: CellMethod::Grouping,
            chain_patches: Vec::new(),
        };
    }
    let (region_cell, ncells) = m.region_uf.components();
    let mut cells: Vec<CellInfo> =
        (0..ncells).map(|_| CellInfo { shells: Vec::new(), label: Default::default(), volume: 0.0 }).collect();
    for (r, &c) in region_cell.iter().enumerate() {
        let cell = &mut cells[c as usize];
        if cell.label.is_empty() {
            cell.label = m.region_label.get(r as u32).into();
        }
        cell.volume += m.region_volume.get(r).copied().unwrap_or(0.0);
    }
    let face_cells: Vec<[u32; 2]> =
        m.face_nodes.iter().map(|n| n.map(|x| if x == NONE { NONE } else { region_cell[x as usize] })).collect();
    let mut shell_cell = vec![NONE; shells.len()];
    for f in 0..nf {
        for s in 0..2 {
            let c = face_cells[f][s];
            let sh = shell_of_hp[2 * face_patch[f] as usize + s];
            if c != NONE && shell_cell[sh as usize] == NONE {
                shell_cell[sh as usize] = c;
            }
        }
    }
    for (s, &c) in shell_cell.iter().enumerate() {
        if c != NONE {
            cells[c as usize].shells.push(s as u32);
        }
    }
    let chain_patches = cyclic_patches(m, &chains, &face_patch, &face_cells, &chain_faces);
    Topology {
        edges,
        face_patch,
        patches,
        chains,
        corners,
        components,
        shells,
        cells,
        face_cells,
        cells_method: CellMethod::Grouping,
        chain_patches,
    }
}

/// Assembles cells from the ray-shooting partition of shells (the cell
/// containing no shell, if any, is the outer one with no network).
#[allow(clippy::too_many_arguments)]
fn ray_topology(
    m: &Merged,
    edges: Vec<[u32; 2]>,
    face_patch: Vec<u32>,
    patches: Vec<Patch>,
    chains: Vec<Vec<u32>>,
    corners: Vec<u32>,
    components: usize,
    shells: Vec<Vec<u32>>,
    shell_of_hp: Vec<u32>,
    shell_cell: Vec<u32>,
    ncells: usize,
) -> Topology {
    let mut cells: Vec<CellInfo> =
        (0..ncells).map(|_| CellInfo { shells: Vec::new(), label: Default::default(), volume: 0.0 }).collect();
    for (s, &c) in shell_cell.iter().enumerate() {
        cells[c as usize].shells.push(s as u32);
    }
    let nf = m.face_label.len();
    let mut face_cells = vec![[NONE; 2]; nf];
    for f in 0..nf {
        for s in 0..2 {
            let sh = shell_of_hp[2 * face_patch[f] as usize + s];
            let c = shell_cell[sh as usize];
            face_cells[f][s] = c;
            let node = m.face_nodes[f][s];
            if cells[c as usize].label.is_empty() && node != NONE {
                cells[c as usize].label = m.region_label.get(node).into();
            }
        }
    }
    Topology {
        edges,
        face_patch,
        patches,
        chains,
        corners,
        components,
        shells,
        cells,
        face_cells,
        cells_method: CellMethod::Raytrace,
        chain_patches: Vec::new(),
    }
}

/// Orders chain edges into curves between corners (vertices where the
/// number of chain edges is not 2: junctions of 3+ chains, and chain ends
/// on the grid boundary); closed loops without corners are chains too.
pub(crate) fn chains(nv: usize, chain_edges: &[[u32; 2]]) -> (Vec<Vec<u32>>, Vec<u32>) {
    let mut deg = vec![0u32; nv];
    for &[a, b] in chain_edges {
        deg[a as usize] += 1;
        deg[b as usize] += 1;
    }
    // CSR adjacency.
    let mut start = vec![0u32; nv + 1];
    for v in 0..nv {
        start[v + 1] = start[v] + deg[v];
    }
    let mut fill = start.clone();
    let mut adj = vec![(0u32, 0u32); 2 * chain_edges.len()];
    for (e, &[a, b]) in chain_edges.iter().enumerate() {
        adj[fill[a as usize] as usize] = (b, e as u32);
        fill[a as usize] += 1;
        adj[fill[b as usize] as usize] = (a, e as u32);
        fill[b as usize] += 1;
    }
    let corners: Vec<u32> = (0..nv as u32).filter(|&v| deg[v as usize] != 0 && deg[v as usize] != 2).collect();
    let mut used = vec![false; chain_edges.len()];
    let mut out = Vec::new();
    let walk = |from: u32, e0: u32, used: &mut Vec<bool>| -> Vec<u32> {
        let mut path = vec![from];
        let (mut cur, mut e) = (from, e0);
        loop {
            used[e as usize] = true;
            let [a, b] = chain_edges[e as usize];
            let next = if a == cur { b } else { a };
            path.push(next);
            cur = next;
            if deg[cur as usize] != 2 {
                break;
            }
            let r = start[cur as usize] as usize..start[cur as usize + 1] as usize;
            match adj[r].iter().find(|&&(_, x)| !used[x as usize]) {
                Some(&(_, x)) => e = x,
                None => break,
            }
        }
        path
    };
    for &c in &corners {
        for k in start[c as usize]..start[c as usize + 1] {
            let (_, e) = adj[k as usize];
            if !used[e as usize] {
                out.push(walk(c, e, &mut used));
            }
        }
    }
    for e in 0..chain_edges.len() {
        if !used[e] {
            let from = chain_edges[e][0];
            out.push(walk(from, e as u32, &mut used));
        }
    }
    (out, corners)
}

/// The patches around each chain in cyclic order (the order is the same
/// along the whole chain: a chain is where the same sheets meet).
///
/// First from the wedges of the per-tet complexes (Sec. 7), at the first
/// chain edge that lies inside a tet: there one complex sees the whole star
/// of the edge. A chain lying entirely on tet faces or tet edges (functions
/// vanishing on grid faces, planes through grid nodes) has no such edge; its
/// star is split among several tets. Then the cells decide: the faces around
/// an edge in cyclic order bound one wedge between each consecutive pair,
/// and when every cell met at the edge fills exactly one wedge (two face
/// sides facing it), the pairs of face sides by cell *are* the wedges. A
/// chain where neither applies (a cell filling two wedges at every edge,
/// which needs a function touching zero along the chain without changing
/// sign) keeps an empty list.
fn cyclic_patches(
    m: &Merged,
    chains: &[Vec<u32>],
    face_patch: &[u32],
    face_cells: &[[u32; 2]],
    chain_faces: &rustc_hash::FxHashMap<[u32; 2], Vec<u32>>,
) -> Vec<Vec<u32>> {
    // The wedges are sorted by edge (`canon::canonicalize_merged`), so an
    // edge's wedges are one run, found by binary search: only the chains'
    // first edges are looked up, far fewer than the wedges.
    debug_assert!(m.wedges.windows(2).all(|w| w[0] <= w[1]), "wedges sorted by edge");
    let wedges_at = |e: [u32; 2]| -> SmallVec<[(u32, u32); 8]> {
        let lo = m.wedges.partition_point(|w| w.0 < e);
        m.wedges[lo..].iter().take_while(|w| w.0 == e).map(|w| (w.1, w.2)).collect()
    };
    let edge = |c: &[u32], k: usize| [c[k].min(c[k + 1]), c[k].max(c[k + 1])];
    chains
        .iter()
        .map(|c| {
            let n = c.len().saturating_sub(1);
            (0..n)
                .find_map(|k| {
                    let pairs = wedges_at(edge(c, k));
                    if pairs.is_empty() {
                        return None;
                    }
                    wedge_cycle(&pairs, &|x| face_patch[x as usize / 2])
                })
                .or_else(|| {
                    (0..n).find_map(|k| {
                        let faces = chain_faces.get(&edge(c, k))?;
                        cell_cycle(faces, face_cells, face_patch)
                    })
                })
                .unwrap_or_default()
        })
        .collect()
}

/// The cycle of faces around an edge from one complex's wedges (pairs of
/// face sides `2 f + s` facing the same cell), or `None` if it does not close.
pub(crate) fn wedge_cycle(pairs: &[(u32, u32)], patch_of: &dyn Fn(u32) -> u32) -> Option<Vec<u32>> {
    let start = pairs[0].0;
    let mut cur = start;
    let mut out = Vec::new();
    for _ in 0..=pairs.len() {
        // The next face around, facing the same cell as `cur`.
        let next = pairs.iter().find_map(|&(x, y)| {
            if x == cur {
                Some(y)
            } else if y == cur {
                Some(x)
            } else {
                None
            }
        })?;
        out.push(patch_of(next));
        cur = next ^ 1; // cross the face
        if cur == start || next == start {
            break;
        }
    }
    (cur == start).then_some(out)
}

/// The cycle of faces around an edge with faces `faces`, pairing face sides
/// by the cell they face; `None` unless every cell there is faced by
/// exactly two sides (then each pair is one wedge) and the walk closes
/// through every face.
pub(crate) fn cell_cycle(faces: &[u32], face_cells: &[[u32; 2]], face_patch: &[u32]) -> Option<Vec<u32>> {
    let sides: Vec<(u32, u32)> =
        faces.iter().flat_map(|&f| [0, 1].map(|s| (face_cells[f as usize][s], 2 * f + s as u32))).collect();
    if sides.iter().any(|x| x.0 == NONE) {
        return None;
    }
    let partner = |x: u32| -> Option<u32> {
        let cell = face_cells[x as usize / 2][x as usize % 2];
        let mut same = sides.iter().filter(|s| s.0 == cell && s.1 != x);
        let p = same.next()?.1;
        same.next().is_none().then_some(p)
    };
    let start = 2 * faces.iter().min()?;
    let mut cur = start;
    let mut out = Vec::new();
    for _ in 0..faces.len() {
        let next = partner(cur)?;
        out.push(face_patch[next as usize / 2]);
        cur = next ^ 1;
        if cur == start {
            break;
        }
    }
    (cur == start && out.len() == faces.len()).then_some(out)
}

/// Vertices where faces of two or more sheets (faces joined across edges,
/// `face_sheet`) meet: the points where sheets touch.
fn contact_points(m: &Merged, face_sheet: &[u32]) -> Vec<u32> {
    let nv = m.keys.len();
    let mut sheet_at = vec![NONE; nv];
    let mut contact = vec![false; nv];
    for (f, &sh) in face_sheet.iter().enumerate() {
        for &v in &m.face_verts[m.face_start[f] as usize..m.face_start[f + 1] as usize] {
            let at = &mut sheet_at[v as usize];
            if *at == NONE {
                *at = sh;
            } else if *at != sh {
                contact[v as usize] = true;
            }
        }
    }
    (0..nv as u32).filter(|&v| contact[v as usize]).collect()
}
