//! Isotropic remeshing of every patch to a target edge length `L`, with the
//! network's chains and corners as constraints shared by all the patches
//! around them (Botsch & Kobbelt 2004, "A remeshing approach to
//! multiresolution modeling"; CGAL's isotropic remeshing with protected
//! constraints is the anchor): repeated rounds of
//!
//! 1. splitting edges longer than `4/3 L` (`split.rs`),
//! 2. collapsing edges shorter than `4/5 L` where that keeps the topology
//!    (`collapse.rs`),
//! 3. flipping edges inside a patch towards valence 6 and Delaunay
//!    (`flip.rs`),
//! 4. tangential smoothing, each vertex put back on the surface
//!    (`smooth.rs`).
//!
//! The constraints (`constraints.rs`) are the exact network's: a chain is
//! resampled once, in the one triangle soup of all patches, so every patch
//! around it uses the same vertices; corners never move. Vertices stay on
//! the original patch (closest point on its triangles, `original.rs`) or
//! constraint curve. The result has the same patches (each with its Euler
//! characteristic and boundary loops), chains, corners and cells; its
//! written doubles are then certified by the exact check (`certify.rs`),
//! and its quality reported (`quality.rs`). Should violations remain after
//! the repairs, the remeshing is refused (the unremeshed result kept,
//! `Remeshing::refused` says how many): never worse than without it.

mod collapse;
mod constraints;
mod flip;
mod original;
mod quality;
mod sizing;
mod smooth;
mod soup;
mod split;
mod surface;
mod written;
mod zeros;

pub use quality::Quality;
pub use written::{remesh_written, Rewritten, Written};

use constraints::{build, rebuild_chains, Source};
use original::Original;
use soup::{Kind, Soup, V};
use surface::Surface;

use super::certify::{certify, Target};
use crate::network::embedding::Embedding;
use crate::network::{Network, Patch};
use crate::regions::RegionSurfaces;

/// What to remesh to.
#[derive(Clone, Debug)]
pub struct RemeshOptions {
    /// The target edge length `L`.
    pub length: f64,
    /// Rounds of split, collapse, flip and smoothing. Default value: 8.
    pub iterations: usize,
}

impl RemeshOptions {
    /// Remeshing to edge length `length`, 8 rounds.
    pub fn new(length: f64) -> RemeshOptions {
        RemeshOptions { length, iterations: 8 }
    }
}

/// What remeshing did and what came of it.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct Remeshing {
    /// The target edge length.
    pub length: f64,
    /// Rounds run.
    pub iterations: usize,
    /// The triangles before (the polygons fanned) and after.
    pub before: Quality,
    /// See `before`.
    pub after: Quality,
    /// Sampled Hausdorff distance `[remeshed -> unremeshed, unremeshed ->
    /// remeshed]` (corners, edge middles and centroids of each triangle to
    /// the other surface).
    pub hausdorff: [f64; 2],
    /// Edges split, collapsed, flipped; vertex moves of smoothing.
    pub splits: usize,
    /// See `splits`.
    pub collapses: usize,
    /// See `splits`.
    pub flips: usize,
    /// See `splits`.
    pub smoothed: usize,
    /// Wedges of the input under 20 degrees: a patch's angle at a vertex
    /// that never moves (two chains meeting at a small angle at a corner),
    /// which bounds the angle of the triangles there whatever the
    /// remeshing does (`quality::sharp_wedges`).
    pub sharp_wedges: usize,
    /// Triangles of the result at such a wedge (of its patch, at its vertex).
    pub at_sharp_wedges: usize,
    /// The smallest angle of the other triangles, in degrees: what the
    /// remeshing reached where the input does not bound it.
    pub min_angle_away: f64,
    /// Vertices that never move (corners, chain ends, where patches meet at
    /// a point) and constraint traces between them.
    pub fixed: usize,
    /// See `fixed`.
    pub traces: usize,
    /// Every patch has its triangles' Euler characteristic and boundary
    /// loops of before.
    pub patches_kept: bool,
    /// Violations of the exact check left after the remeshed triangles'
    /// repairs: when not 0 the remeshing is refused and the result is the
    /// unremeshed one (`after` is then `before`'s polygons).
    pub refused: usize,
    /// Seconds.
    pub seconds: f64,
}

/// The remeshed soup's live triangles, patches and chains, and the report
/// (without the certification).
struct Remeshed {
    soup: Soup,
    tris: Vec<[u32; 3]>,
    tri_patch: Vec<u32>,
    chains: Vec<Vec<u32>>,
    report: Remeshing,
}

fn area(x: &[V], tris: &[[u32; 3]]) -> f64 {
    tris.iter().map(|t| 0.5 * soup::norm(Soup::normal_of(x, t))).sum()
}

/// The largest number of triangles a remeshing may make.
const MAX_TRIANGLES: f64 = 2e7;

/// The formulas a network came from: its patches' labels and the functions.
struct Formulas<'a> {
    functions: &'a [crate::scene::Primitive],
    mi: bool,
    labels: Vec<[u16; 2]>,
}

fn remesh_source(src: &Source, opts: &RemeshOptions, patches: usize, f: Option<Formulas>) -> Result<Remeshed, String> {
    let t0 = std::time::Instant::now();
    let l = opts.length;
    if !(l.is_finite() && l > 0.0) {
        return Err(format!("--remesh: the target edge length must be a positive number, not {l}"));
    }
    let built = build(src);
    let estimate = area(src.points, &built.tris) / (3f64.sqrt() / 4.0 * l * l);
    if estimate > MAX_TRIANGLES {
        return Err(format!(
            "--remesh {l}: the target edge length is too small for these patches (about {estimate:.0} triangles; at most {MAX_TRIANGLES:.0})"
        ));
    }
    let mean_edge = {
        let (mut s, mut n) = (0.0, 0usize);
        for t in &built.tris {
            for k in 0..3 {
                s += soup::dist(src.points[t[k] as usize], src.points[t[(k + 1) % 3] as usize]);
                n += 1;
            }
        }
        if n > 0 {
            s / n as f64
        } else {
            l
        }
    };
    let size = mean_edge.max(l);
    let orig = Original::new(src.points, &built.tris, &built.tri_patch, &built.segs, &built.seg_trace, size);
    let zeros = f.and_then(|f| {
        let eq = |p: u32| -> Option<zeros::Eq> {
            let [a, b] = *f.labels.get(p as usize)?;
            let (a, b) = (a as usize, b as usize);
            if a >= f.functions.len() || b >= f.functions.len() {
                return None;
            }
            Some(if f.mi { (a, Some(b)) } else { (a, None) })
        };
        let patch: Option<Vec<zeros::Eq>> = (0..patches as u32).map(eq).collect();
        let trace = built
            .trace_class
            .iter()
            .map(|(ps, sides)| {
                let mut eqs: Vec<zeros::Eq> = Vec::new();
                for &p in ps {
                    if let Some(e) = eq(p) {
                        if !eqs.contains(&e) {
                            eqs.push(e);
                        }
                    }
                }
                (eqs, std::array::from_fn(|k| sides >> (2 * k) & 3 != 0))
            })
            .collect();
        Some(zeros::Zeros { functions: f.functions, patch: patch?, trace, l })
    });
    let surf = Surface { orig, zeros };
    let mut report = Remeshing {
        length: l,
        iterations: opts.iterations,
        before: quality::quality(src.points, &built.tris),
        traces: built.traces,
        ..Default::default()
    };
    let counts_before = quality::patch_counts(&built.tris, &built.tri_patch, patches);
    let mut s = built.soup;
    report.fixed = s.kind.iter().zip(&s.vt).filter(|(k, t)| **k == Kind::Fixed && !t.is_empty()).count();
    let fixed: Vec<bool> = s.kind.iter().map(|k| *k == Kind::Fixed).collect();
    let sharp = quality::sharp_wedges(src.points, &built.tris, &built.tri_patch, &fixed);
    report.sharp_wedges = sharp.len();
    let target = sizing::Sizing::new(&s, l);
    for _ in 0..opts.iterations {
        report.splits += split::split_long(&mut s, &surf, &target);
        report.collapses += collapse::collapse_short(&mut s, &surf, &target);
        report.flips += flip::flip_all(&mut s, false);
        report.smoothed += smooth::smooth_all(&mut s, &surf);
    }
    report.flips += flip::flip_all(&mut s, true);
    let chains = rebuild_chains(&s, &built.chains);
    let live: Vec<usize> = (0..s.tris.len()).filter(|&t| s.alive[t]).collect();
    let tris: Vec<[u32; 3]> = live.iter().map(|&t| s.tris[t]).collect();
    let tri_patch: Vec<u32> = live.iter().map(|&t| s.patch[t]).collect();
    report.patches_kept = quality::patch_counts(&tris, &tri_patch, patches)
        .iter()
        .zip(&counts_before)
        .all(|(a, b)| a[1] == b[1] && a[2] == b[2]);
    if std::env::var_os("SEPTA_REMESH_DEBUG").is_some() {
        debug(&s, &tris, &tri_patch, &built.tris, &built.tri_patch, patches);
    }
    report.hausdorff = quality::hausdorff(src.points, &built.tris, &s.x, &tris, size);
    // fixed vertices keep their ids in the soup
    (report.min_angle_away, report.at_sharp_wedges) = quality::away_from_sharp(&s.x, &tris, &tri_patch, &sharp);
    report.seconds = t0.elapsed().as_secs_f64();
    Ok(Remeshed { soup: s, tris, tri_patch, chains, report })
}

/// The live vertices of `s` numbered densely: old id -> new id.
fn compact(s: &Soup) -> Vec<u32> {
    let mut map = vec![u32::MAX; s.x.len()];
    let mut n = 0;
    for v in 0..s.x.len() {
        if !s.vt[v].is_empty() {
            map[v] = n;
            n += 1;
        }
    }
    map
}

/// Remeshes a grid network in place (module doc): its polygons become the
/// remeshed triangles, its chains their new paths, its corners the same
/// points; vertices take the grid key of the vertex they came from. The
/// patches, chains, corners, shells and cells are the same. Then the
/// written doubles are certified (`bounds`: the grid's box closing the
/// cells); the certificate is in `net.embedding`.
pub fn remesh_network(
    net: &mut Network,
    opts: &RemeshOptions,
    bounds: Option<[[f64; 3]; 2]>,
) -> Result<Remeshing, String> {
    remesh_network_with(net, opts, bounds, None)
}

/// [`remesh_network`] with the new vertices on the true zero sets of
/// `functions` (the formulas the network was sampled from; `zeros.rs`).
pub fn remesh_network_on(
    net: &mut Network,
    opts: &RemeshOptions,
    bounds: Option<[[f64; 3]; 2]>,
    functions: &[crate::scene::Primitive],
) -> Result<Remeshing, String> {
    let f = Formulas {
        functions,
        mi: net.mode == crate::complex::Mode::Mi,
        labels: net.patches.iter().map(|p| p.label).collect(),
    };
    remesh_network_with(net, opts, bounds, Some(f))
}

fn remesh_network_with(
    net: &mut Network,
    opts: &RemeshOptions,
    bounds: Option<[[f64; 3]; 2]>,
    f: Option<Formulas>,
) -> Result<Remeshing, String> {
    let src = Source {
        points: &net.points,
        start: &net.face_start,
        verts: &net.face_verts,
        patch: &net.face_patch,
        chains: &net.chains,
        corners: &net.corners,
        bounds,
    };
    let r = remesh_source(&src, opts, net.patches.len(), f)?;
    let kept = net.clone();
    let map = compact(&r.soup);
    let n = map.iter().filter(|&&m| m != u32::MAX).count();
    let mut points = vec![[0.0; 3]; n];
    let mut keys = Vec::with_capacity(n);
    for v in 0..map.len() {
        if map[v] != u32::MAX {
            points[map[v] as usize] = r.soup.x[v];
            keys.push(net.keys[r.soup.origin[v] as usize]);
        }
    }
    // per patch, the label and cells of its polygons
    let mut patch_cells = vec![[u32::MAX; 2]; net.patches.len()];
    for f in 0..net.num_faces() {
        patch_cells[net.face_patch[f] as usize] = net.face_cells[f];
    }
    let m = |v: u32| map[v as usize];
    net.face_start = (0..=r.tris.len() as u32).map(|i| 3 * i).collect();
    net.face_verts = r.tris.iter().flat_map(|t| t.map(m)).collect();
    net.face_patch = r.tri_patch.clone();
    net.face_label = r.tri_patch.iter().map(|&p| net.patches[p as usize].label).collect();
    net.face_cells = r.tri_patch.iter().map(|&p| patch_cells[p as usize]).collect();
    let mut faces = vec![0usize; net.patches.len()];
    for &p in &r.tri_patch {
        faces[p as usize] += 1;
    }
    net.patches = net.patches.iter().zip(faces).map(|(p, f)| Patch { label: p.label, faces: f }).collect();
    net.chains = r.chains.iter().map(|c| c.iter().map(|&v| m(v)).collect()).collect();
    net.corners = net.corners.iter().map(|&v| m(v)).collect();
    let mut edges: Vec<[u32; 2]> = Vec::with_capacity(r.tris.len() * 3 / 2);
    for t in net.face_verts.chunks(3) {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            edges.push([a.min(b), a.max(b)]);
        }
    }
    edges.sort_unstable();
    edges.dedup();
    net.edges = edges;
    net.points = points;
    net.keys = keys;
    let mut t = Target {
        points: &mut net.points,
        start: &net.face_start,
        verts: &mut net.face_verts,
        cells: Some(&net.face_cells),
        bounds,
        fixed: None,
    };
    let e = certify(&mut t);
    let mut report = r.report;
    if e.after.violations() > 0 {
        // never worse: the unremeshed network, certified before, is kept
        report.refused = e.after.violations();
        *net = kept;
        report.after = report.before.clone();
        return Ok(report);
    }
    report.after = quality::quality(&net.points, &tris_of(&net.face_verts));
    net.seconds.push(("remesh", report.seconds));
    net.embedding = Some(merge_embedding(net.embedding.take(), e));
    Ok(report)
}

fn tris_of(verts: &[u32]) -> Vec<[u32; 3]> {
    verts.chunks(3).map(|t| [t[0], t[1], t[2]]).collect()
}

/// The certificate of the remeshed doubles, with the earlier repairs'
/// counts and projection kept.
fn merge_embedding(old: Option<Embedding>, new: Embedding) -> Embedding {
    let mut e = new;
    if let Some(o) = old {
        e.snapped += o.snapped;
        e.rotated += o.rotated;
        e.nudged += o.nudged;
        e.projection = o.projection;
    }
    e
}

/// Remeshes region surfaces in place ([`remesh_network`] for their kept
/// polygons): surfaces are the patches, curves the chains. Original
/// vertices that stay (fixed ones) keep their ids; every other vertex is
/// new, appended to the network's points (its polygons, which the
/// regions' volumes are measured on, are left as they were).
pub fn remesh_regions(
    r: &mut RegionSurfaces,
    opts: &RemeshOptions,
    bounds: Option<[[f64; 3]; 2]>,
) -> Result<Remeshing, String> {
    let chains: Vec<Vec<u32>> = r.curves.iter().map(|c| c.vertices.clone()).collect();
    let corners: Vec<u32> =
        r.curves.iter().filter(|c| !c.closed).flat_map(|c| [c.vertices[0], *c.vertices.last().unwrap()]).collect();
    let n0 = r.network.points.len();
    let src = Source {
        points: &r.network.points,
        start: &r.loop_start,
        verts: &r.loops,
        patch: &r.face_surface,
        chains: &chains,
        corners: &corners,
        bounds,
    };
    let out = remesh_source(&src, opts, r.surfaces.len(), None)?;
    let kept = r.clone();
    let s = &out.soup;
    let mut map = vec![u32::MAX; s.x.len()];
    for v in 0..s.x.len() {
        if s.vt[v].is_empty() {
            continue;
        }
        if v < n0 && s.kind[v] == Kind::Fixed && s.x[v] == r.network.points[v] {
            map[v] = v as u32;
        } else {
            map[v] = r.network.points.len() as u32;
            r.network.points.push(s.x[v]);
            let key = r.network.keys[s.origin[v] as usize];
            r.network.keys.push(key);
        }
    }
    // per surface, a kept polygon of it (its network polygon gives the
    // regions on either side, as the writers read them)
    let mut first = vec![u32::MAX; r.surfaces.len()];
    for (i, &g) in r.face_surface.iter().enumerate() {
        if first[g as usize] == u32::MAX {
            first[g as usize] = r.faces[i];
        }
    }
    let m = |v: u32| map[v as usize];
    r.faces = out.tri_patch.iter().map(|&g| first[g as usize]).collect();
    r.loop_start = (0..=out.tris.len() as u32).map(|i| 3 * i).collect();
    r.loops = out.tris.iter().flat_map(|t| t.map(m)).collect();
    r.face_surface = out.tri_patch.clone();
    for (c, path) in r.curves.iter_mut().zip(&out.chains) {
        c.vertices = path.iter().map(|&v| m(v)).collect();
    }
    let counts = quality::patch_counts(&tris_of(&r.loops), &r.face_surface, r.surfaces.len());
    for (s, c) in r.surfaces.iter_mut().zip(&counts) {
        s.faces = c[0] as usize;
    }
    r.normals.clear();
    let cells = super::region_cells(r);
    let mut t = Target {
        points: &mut r.network.points,
        start: &r.loop_start,
        verts: &mut r.loops,
        cells: Some(&cells),
        bounds,
        fixed: None,
    };
    let e = certify(&mut t);
    let mut report = out.report;
    if e.after.violations() > 0 {
        // as in remesh_network: the unremeshed surfaces are kept
        report.refused = e.after.violations();
        *r = kept;
        report.after = report.before.clone();
        return Ok(report);
    }
    report.after = quality::quality(&r.network.points, &tris_of(&r.loops));
    r.seconds.push(("remesh", report.seconds));
    r.embedding = Some(merge_embedding(r.embedding.take(), e));
    r.measure_surfaces();
    Ok(report)
}

fn debug(s: &Soup, tris: &[[u32; 3]], tri_patch: &[u32], t0: &[[u32; 3]], p0: &[u32], patches: usize) {
    let a = quality::patch_counts(t0, p0, patches);
    let b = quality::patch_counts(tris, tri_patch, patches);
    for p in 0..patches {
        if a[p][1] != b[p][1] || a[p][2] != b[p][2] {
            eprintln!("patch {p}: before {:?} after {:?}", a[p], b[p]);
        }
    }
    for (t, tri) in tris.iter().enumerate() {
        let m = soup::min_angle(tri.map(|v| s.x[v as usize]));
        if m < 20.0 {
            let kinds: Vec<String> =
                tri.iter().map(|&v| format!("{:?}@{:?}", s.kind[v as usize], s.x[v as usize])).collect();
            eprintln!("tri {t} patch {} angle {m:.2}: {}", tri_patch[t], kinds.join(" "));
        }
    }
}
