//! The cut's thirteen stages in order (the tour is in `cut/mod.rs`): each
//! stage's result is handed to the next here, timed (`CutStats::seconds`)
//! and reported to [`CutOptions::progress`]; what is done with is freed as it
//! goes.

use crate::cut::arrangement::clip::{self, EdgeLine};
use crate::cut::arrangement::nodes::{FxMap, Nodes};
use crate::cut::arrangement::plane_graph::{self, Boundary, GEdge};
use crate::cut::arrangement::{holes, lines};
use crate::cut::base::geom::{Ctx, Def, LineDir};
use crate::cut::cells::cells::{self, FaceLoop};
use crate::cut::cells::{voids, volume};
use crate::cut::certify::repair;
use crate::cut::embed::{embed, round};
use crate::cut::input::{input, scale, shells};
use crate::cut::output::output;
use crate::cut::triangles::triangulate;
use crate::cut::{CutCellMesh, CutCounts, CutError, CutFace, CutStats, Support};
use rayon::prelude::*;
use septa_exact::Sign;
use std::time::Instant;

/// Options of [`cut_mesh`].
#[derive(Clone, Debug, Default)]
pub struct CutOptions {
    /// Worker threads (0: all available). The result does not depend on it.
    pub threads: usize,
    /// Skip the exact self-intersection test of the input (for inputs known
    /// to be clean; the reference implementation assumes it).
    pub skip_self_intersection_check: bool,
    /// Skip the exact check and repair of the written embedding
    /// (`repair.rs`; default: run it, [`CutStats::embedding`] holds the report).
    pub skip_certify: bool,
    /// Called with `(stages done, STAGES)` as each stage of the cut ends
    /// ([`CutStats::seconds`] names them). Default value: none.
    pub progress: Option<crate::Progress>,
}

/// Number of stages [`CutOptions::progress`] counts.
pub const STAGES: usize = 13;

/// Cuts the domain bounded by `triangles` (closed, outward) by `planes`
/// (`a x + b y + c z + d = 0`).
pub fn cut_mesh(
    vertices: &[[f64; 3]],
    triangles: &[[u32; 3]],
    planes: &[[f64; 4]],
    opts: &CutOptions,
) -> Result<CutCellMesh, CutError> {
    // up front: the memory the plane tables need, and a scale the doubles
    // can cut at (scale.rs)
    scale::check_memory(planes.len(), vertices.len(), triangles.len())?;
    let s = scale::Scaled::new(vertices, planes)?;
    let run = || cut_impl(&s.vertices, triangles, &s.planes, opts);
    let pool = (opts.threads != 0).then(|| rayon::ThreadPoolBuilder::new().num_threads(opts.threads).build());
    let mut out = match pool {
        Some(Ok(pool)) => pool.install(run),
        _ => run(),
    }?;
    s.restore(&mut out, planes);
    Ok(out)
}

/// The filters' copies of the triangle normals and of the plane-pair line
/// directions in `R` (`Ctx::tn_iv`, `Ctx::pp_iv` and their [`Bounded`]
/// twins), computed once: entries `p < q` of the pairs (`line_dir` reads no
/// others; lines are keyed so), zero elsewhere.
///
/// [`Bounded`]: septa_exact::Bounded
fn filter_copies<R: septa_exact::Ring>(c: &Ctx) -> (Vec<[R; 3]>, Vec<[R; 3]>) {
    let np = c.planes.len() as u32;
    let tn = (0..c.tris.len() as u32).map(|t| c.tn_compute::<R>(t)).collect();
    let pp = (0..np * np)
        .map(|i| {
            let (p, q) = (i / np, i % np);
            if p < q {
                c.pp_compute::<R>(p, q)
            } else {
                std::array::from_fn(|_| R::of(0.0))
            }
        })
        .collect();
    (tn, pp)
}

fn cut_impl(
    vertices: &[[f64; 3]],
    triangles: &[[u32; 3]],
    planes: &[[f64; 4]],
    opts: &CutOptions,
) -> Result<CutCellMesh, CutError> {
    let fb0 = septa_exact::fallback_count();
    let mut stats = CutStats::default();
    let mut clock = Instant::now();
    let debug = std::env::var_os("SEPTA_DEBUG").is_some();
    let mut lap = |name: &str, stats: &mut CutStats| {
        if debug {
            let rss = std::fs::read_to_string("/proc/self/statm").unwrap_or_default();
            eprintln!("stage {name}: {:.3}s statm {rss}", clock.elapsed().as_secs_f64());
        }
        stats.seconds.push((name.to_string(), clock.elapsed().as_secs_f64()));
        if let Some(p) = &opts.progress {
            (p.0)(stats.seconds.len(), STAGES);
        }
        clock = Instant::now();
    };
    let ((edges, tri_edges, edge_tris), nm) = input::check_mesh_nm(vertices, triangles)?;
    lap("check_mesh", &mut stats);
    if !opts.skip_self_intersection_check {
        input::check_self_intersections(vertices, triangles)?;
    }
    // After the self-intersection test: shells are then disjoint, which
    // the winding-number argument needs (timed with it).
    shells::check_shells(vertices, triangles, &edge_tris, &tri_edges, &nm)?;
    lap("self_intersection", &mut stats);
    let keep = input::check_planes(planes, &mut stats.dropped_planes)?;
    let planes: Vec<[f64; 4]> = keep.iter().map(|&i| planes[i]).collect();
    let nv = vertices.len();
    let np = planes.len();
    let mut pv = vec![0i8; np * nv];
    if nv > 0 {
        pv.par_chunks_mut(nv).zip(planes.par_iter()).for_each(|(row, pl)| {
            for (r, x) in row.iter_mut().zip(vertices) {
                *r = septa_exact::plane_point_sign(pl, x).as_i8();
            }
        });
    }
    let c = Ctx {
        verts: vertices,
        tris: triangles,
        planes: &planes,
        edges,
        tri_edges,
        edge_tris,
        wedges: nm.wedges,
        pv,
        tn_iv: Vec::new(),
        pp_iv: Vec::new(),
        tn_b: Vec::new(),
        pp_b: Vec::new(),
    };
    let (tn_iv, pp_iv) = filter_copies::<septa_exact::Interval>(&c);
    let (tn_b, pp_b) = filter_copies::<septa_exact::Bounded>(&c);
    let c = Ctx { tn_iv, pp_iv, tn_b, pp_b, ..c };
    let mut crosses = vec![false; np * np];
    for p in 0..np {
        for q in p + 1..np {
            crosses[p * np + q] = c.planes_cross(p as u32, q as u32);
        }
    }
    lap("input", &mut stats);
    let mut nodes = Nodes::default();
    let mut line_pts = lines::LinePoints::default();
    let chains = lines::mesh_edges(&c, &mut nodes, &mut line_pts, &crosses);
    lap("mesh_edges", &mut stats);
    let clipped = clip::clip_all(&c);
    for (d, z) in &clipped.interior {
        let n = nodes.get(*d);
        lines::register(&mut line_pts, &crosses, np, n, z);
    }
    // every piece's corners as nodes, in one list (numbered here, in this
    // order: the node ids do not depend on what follows)
    let mut piece_start: Vec<u32> = Vec::with_capacity(clipped.num_pieces() + 1);
    piece_start.push(0);
    let mut piece_nodes: Vec<u32> = Vec::new();
    for p in clipped.pieces() {
        piece_nodes.extend(p.nodes.iter().map(|&d| nodes.get(d)));
        piece_start.push(piece_nodes.len() as u32);
    }
    lap("triangles", &mut stats);
    let plines = lines::plane_lines(&c, &mut nodes, &mut line_pts, &crosses);
    lap("plane_lines", &mut stats);
    // compact ids of distinct points
    let mut canon = vec![u32::MAX; nodes.len()];
    let mut rep: Vec<Def> = Vec::new();
    for i in 0..nodes.len() as u32 {
        let r = nodes.find(i);
        if canon[r as usize] == u32::MAX {
            canon[r as usize] = rep.len() as u32;
            rep.push(nodes.defs[r as usize]);
        }
        canon[i as usize] = canon[r as usize];
    }
    let cid = |n: u32| canon[n as usize];
    // boundary edge maps and per-plane edge lists
    let mut bnd = Boundary { gamma: FxMap::default(), mesh: FxMap::default() };
    let mut pedges: Vec<Vec<GEdge>> = vec![Vec::new(); np];
    for (e, chain) in chains.iter().enumerate() {
        let [u, v] = c.edges[e];
        let inside: Vec<u32> = (0..np as u32).filter(|&p| c.pv_sign(p, u) == 0 && c.pv_sign(p, v) == 0).collect();
        // only the planes' graphs look pieces of mesh edges up, and a piece
        // on a plane's graph lies on that plane with its whole mesh edge
        if inside.is_empty() {
            continue;
        }
        for w in chain.windows(2) {
            let (a, b) = (cid(w[0]), cid(w[1]));
            bnd.mesh.insert((a.min(b), a.max(b)), e as u32);
            for &p in &inside {
                pedges[p as usize].push(GEdge { a, b, dir: LineDir::Mesh(e as u32), fwd: true });
            }
        }
    }
    // the pieces' edges inside their triangles, on the planes: the
    // boundary map and the planes' graphs (the pieces' loops are made
    // below, once the planes' loops are counted)
    for (k, piece) in clipped.pieces().enumerate() {
        let pn = &piece_nodes[piece_start[k] as usize..piece_start[k + 1] as usize];
        let (t, n) = (piece.tri, pn.len());
        for i in 0..n {
            if let EdgeLine::Plane(p, fwd) = piece.lines[i] {
                let (a, b) = (cid(pn[i]), cid(pn[(i + 1) % n]));
                let dir = LineDir::TriPlane(t, p);
                debug_assert_eq!(fwd, c.order(rep[a as usize], rep[b as usize], dir) == Sign::Positive);
                bnd.gamma.insert((a.min(b), a.max(b)), t);
                pedges[p as usize].push(GEdge { a, b, dir, fwd });
            }
        }
    }
    for ((p, q), pts) in &plines {
        // before the first and after the last point on the mesh the line is
        // outside the domain (a point's representative triple is (P,P,P)
        // only when no mesh triple names it)
        let on_mesh = |n: &u32| !matches!(rep[cid(*n) as usize], Def::PPP(..));
        let (Some(i0), Some(i1)) = (pts.iter().position(on_mesh), pts.iter().rposition(on_mesh)) else {
            continue;
        };
        for w in pts[i0..=i1].windows(2) {
            let (a, b) = (cid(w[0]), cid(w[1]));
            let ge = GEdge { a, b, dir: LineDir::PlanePlane(*p, *q), fwd: true };
            pedges[*p as usize].push(ge);
            pedges[*q as usize].push(ge);
        }
    }
    lap("edges", &mut stats);
    let mut nholes = 0usize;
    let mut nface = clipped.num_pieces() as u32;
    let per_plane: Vec<(Vec<plane_graph::PlaneLoop>, u64, usize, usize)> = (0..np)
        .into_par_iter()
        .map(|p| {
            let mut u = 0u64;
            let mut loops = plane_graph::plane_faces(&c, p as u32, &pedges[p], &bnd, &mut u);
            let (h, t) = holes::assign_holes(&c, p as u32, &rep, &mut loops);
            (loops, u, h, t)
        })
        .collect();
    // the pieces' loops, then the planes' (room for all at once: grown by
    // doubling, or by the planes' loops after the pieces', the pieces'
    // loops, most of them, were copied into fresh pages)
    let mut faces: Vec<FaceLoop> =
        Vec::with_capacity(nface as usize + per_plane.iter().map(|p| p.0.len()).sum::<usize>());
    for (k, piece) in clipped.pieces().enumerate() {
        let pn = &piece_nodes[piece_start[k] as usize..piece_start[k + 1] as usize];
        let (t, n) = (piece.tri, pn.len());
        let mut fl =
            FaceLoop { support: Support::Tri(t), verts: Default::default(), dirs: Default::default(), face: k as u32 };
        for i in 0..n {
            fl.verts.push(cid(pn[i]));
            fl.dirs.push(match piece.lines[i] {
                EdgeLine::Mesh(e) => (LineDir::Mesh(e), c.runs_forward(t, e)),
                EdgeLine::Plane(p, fwd) => (LineDir::TriPlane(t, p), fwd),
            });
        }
        faces.push(fl);
    }
    // the pieces are loops now; their pages go to what follows
    drop((clipped, piece_nodes, piece_start));
    for (loops, u, h, t) in per_plane {
        let _ = u; // loops of unbounded, outside regions
        nholes += h;
        stats.hole_containment_tests += t;
        let mut id = vec![u32::MAX; loops.len()];
        for (k, l) in loops.iter().enumerate() {
            if l.outer as usize == k {
                id[k] = nface;
                nface += 1;
            }
        }
        // each face's outer loop before its holes (CutFace::loops: the
        // outer boundary first); a hole may precede its face in the
        // plane's list, and its loop was then written, bridged and
        // triangulated as the outer boundary (a hole beside a notch)
        let (outer, holes): (Vec<_>, Vec<_>) = loops.into_iter().enumerate().partition(|(k, l)| l.outer as usize == *k);
        for (_, l) in outer.into_iter().chain(holes) {
            let face = id[l.outer as usize];
            faces.push(FaceLoop {
                support: Support::Plane(l.plane),
                verts: smallvec::SmallVec::from_vec(l.verts),
                dirs: smallvec::SmallVec::from_vec(l.dirs),
                face,
            });
        }
    }
    stats.holes = nholes;
    lap("plane_faces", &mut stats);
    let cells = cells::assemble(&c, &faces);
    stats.ordered_edges = cells.ordered_edges;
    lap("cells", &mut stats);
    // output: used vertices, coordinates, volumes
    let mut used = vec![u32::MAX; rep.len()];
    let mut out = CutCellMesh::default();
    for f in &faces {
        for &v in &f.verts {
            if used[v as usize] == u32::MAX {
                used[v as usize] = out.vertex_defs.len() as u32;
                out.vertex_defs.push(rep[v as usize]);
            }
        }
    }
    let (rounded, boxes): (Vec<[f64; 3]>, Vec<_>) = out.vertex_defs.par_iter().map(|&d| round::round(&c, d)).unzip();
    out.vertices = rounded;
    let nf = nface as usize;
    out.faces = vec![CutFace { support: Support::Plane(0), loops: Vec::new(), cells: [u32::MAX; 2] }; nf];
    for f in faces.iter() {
        let i = f.face as usize;
        let cf = &mut out.faces[i];
        cf.support = f.support;
        cf.cells = [cells.cell_of[2 * i + 1], cells.cell_of[2 * i]];
        cf.loops.push(f.verts.iter().map(|&v| used[v as usize]).collect());
    }
    out.num_cells = cells.count;
    out.cell_volumes = vec![0.0; cells.count];
    let cut_edges = cells.edges + nholes;
    // What is done with is freed as it goes: the heap only grows, so the
    // certificate's arrays reuse these pages instead of faulting in new
    // ones (a page fault is about 1.4 us here, ~10% of a run; armadillo
    // R20's loops alone were 38 MB).
    drop((faces, cells, bnd, pedges));
    let (attached, unresolved) = voids::attach_voids(&c, &mut out, &boxes);
    stats.voids_attached = attached;
    stats.voids_unresolved = unresolved;
    lap("faces", &mut stats);
    // floating-point embedding (Sec. 6.1): line orders and vertex-face
    // sidedness over the final cells (voids attached)
    let to_out = |n: &u32| used[cid(*n) as usize];
    let mut lines: Vec<embed::Line> = Vec::with_capacity(chains.len() + plines.len());
    for (e, chain) in chains.iter().enumerate() {
        let verts: Vec<u32> = chain.iter().map(to_out).filter(|&v| v != u32::MAX).collect();
        lines.push(embed::Line { dir: LineDir::Mesh(e as u32), verts });
    }
    for ((p, q), pts) in &plines {
        let verts: Vec<u32> = pts.iter().map(to_out).filter(|&v| v != u32::MAX).collect();
        lines.push(embed::Line { dir: LineDir::PlanePlane(*p, *q), verts });
    }
    drop((chains, plines, canon, rep, used, nodes, line_pts));
    let es = embed::embed(&c, &mut out, &boxes, &lines);
    drop(lines);
    stats.moved_vertices = es.line_moved;
    stats.sidedness_moved = es.sidedness_moved;
    stats.sidedness_violations_rounded = es.sidedness_violations_rounded;
    stats.sidedness_violations = es.sidedness_violations;
    stats.line_order_violations = es.line_order_violations;
    // the moves above may leave an axis plane by an ulp: back onto it
    for (x, &d) in out.vertices.iter_mut().zip(&out.vertex_defs) {
        round::snap_axis_planes(&c, d, x);
    }
    lap("embed", &mut stats);
    // volumes by the divergence theorem: loops count + for cells[0] and -
    // for cells[1] (volume.rs relies on this orientation)
    for f in &out.faces {
        for l in &f.loops {
            let vol = output::loop_volume(&out.vertices, l);
            if f.cells[0] != u32::MAX {
                out.cell_volumes[f.cells[0] as usize] += vol;
            }
            if f.cells[1] != u32::MAX {
                out.cell_volumes[f.cells[1] as usize] -= vol;
            }
        }
    }
    out.cell_volume_signs = volume::cell_volume_signs(&c, &out, &boxes);
    drop((boxes, c));
    // planarity on the written doubles, exactly: a face whose rounded
    // vertices leave its plane is written as triangles
    out.face_split = out
        .faces
        .par_iter()
        .map(|f| f.loops.len() > 1 || crate::cut::polygon_planar(&out.vertices, &f.loops[0]) != Some(true))
        .collect();
    stats.faces_split_holes = out.faces.iter().filter(|f| f.loops.len() > 1).count();
    stats.faces_split_nonplanar = out.face_split.iter().filter(|&&s| s).count() - stats.faces_split_holes;
    out.mesh_volume = output::mesh_volume(vertices, triangles);
    out.planes = planes.clone();
    out.tri_normals = triangles
        .iter()
        .map(|t| {
            let [a, b, cc] = t.map(|i| vertices[i as usize]);
            let (u, v) = ([b[0] - a[0], b[1] - a[1], b[2] - a[2]], [cc[0] - a[0], cc[1] - a[1], cc[2] - a[2]]);
            [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        })
        .collect();
    out.mesh_euler = nm.domain_euler2;
    out.counts = CutCounts { cut_vertices: out.vertex_defs.len(), cut_edges, cut_faces: nf, cut_cells: out.num_cells };
    lap("output", &mut stats);
    out.face_triangles = out
        .faces
        .par_iter()
        .zip(&out.face_split)
        .map(
            |(f, &s)| {
                if s {
                    triangulate::triangulate(&out.vertices, &f.loops, out.support_normal(f))
                } else {
                    Vec::new()
                }
            },
        )
        .collect();
    if !opts.skip_certify {
        // the input check passed: its triangles need no second test among themselves
        let clean = (!opts.skip_self_intersection_check).then_some((vertices, triangles));
        stats.embedding = Some(repair::repair(&mut out, clean));
    }
    lap("certify", &mut stats);
    stats.exact_fallbacks = septa_exact::fallback_count() - fb0;
    out.stats = stats;
    Ok(out)
}
