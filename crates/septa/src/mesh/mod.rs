//! Meshes you can use: the written doubles of a result made an embedding of
//! its exact network, certified by exact signs.
//!
//! The combinatorics of a network are exact (Du et al. 2022); its vertices
//! are doubles rounded from the linear interpolants, and nothing made those
//! doubles an embedding: two vertices may round to one point, a triangle of
//! a polygon's fan may have collinear corners, two triangles may cross.
//! Cut-cells have a certificate (`cut/check/verify.rs`); this layer gives one to
//! grid networks, region surfaces and label volumes:
//!
//! - [`certify_network`], [`certify_regions`]: the exact check of the fans
//!   that the writers write (`check.rs`), repairs that keep every count of
//!   the network (`certify.rs`), and the check again, reported as an
//!   [`Embedding`] (in `network.json`, the `--json` summary and Python's
//!   `net.embedding`).
//!
//! Layer: above `network`, `regions`, `scene` and `cut` (whose exact
//! triangle-pair test and candidate grid it shares), below the writers'
//! callers (`septa-cli`, `septa-py`).

mod certify;
mod check;
mod local;
mod project;
mod remesh;
mod volume;

pub use project::Zeros;
pub use remesh::{
    remesh_network, remesh_network_on, remesh_regions, remesh_written, Quality, RemeshOptions, Remeshing, Rewritten,
    Written,
};

pub use crate::network::embedding::{snap_point, Embedding, EmbeddingCheck, Projection};

use crate::grid::BoxGrid;
use crate::network::{Network, VKey};
use crate::regions::RegionSurfaces;
use certify::{certify, Target};
use check::Polygons;

/// Puts every vertex where [`snap_point`] says (its coordinates shared with
/// its grid element set to the grid's doubles); returns how many changed.
pub fn snap_to_grid(points: &mut [[f64; 3]], keys: &[VKey], grid: &BoxGrid) -> usize {
    let mut changed = 0;
    for (p, key) in points.iter_mut().zip(keys) {
        let q = snap_point(*p, key, grid);
        if q != *p {
            *p = q;
            changed += 1;
        }
    }
    changed
}

/// Certifies a grid network's written doubles in place (module doc): with
/// `grid`, coordinates are first put on the grid's lines and planes where
/// the exact vertex is ([`snap_to_grid`]) and cells reaching the box are
/// closed by it. No count of the network changes; the report is also kept
/// in `net.embedding`.
pub fn certify_network(net: &mut Network, grid: Option<&BoxGrid>) -> Embedding {
    certify_network_with(net, grid, None)
}

/// [`certify_network`] after moving the vertices onto the true zero sets of
/// `functions` (the formulas the network was sampled from on `grid`;
/// `project.rs`): each vertex stays inside its grid element, a move that
/// would break the exact check is left undone and counted. The report's
/// `projection` has the largest `|f| / |grad f|` before and after.
pub fn certify_network_on(net: &mut Network, grid: &BoxGrid, functions: &[crate::scene::Primitive]) -> Embedding {
    let z = Zeros { functions, mi: net.mode == crate::complex::Mode::Mi };
    certify_network_with(net, Some(grid), Some(&z))
}

fn certify_network_with(net: &mut Network, grid: Option<&BoxGrid>, z: Option<&Zeros>) -> Embedding {
    let t0 = std::time::Instant::now();
    let snapped = grid.map_or(0, |g| snap_to_grid(&mut net.points, &net.keys, g));
    // the unprojected network, certified instead if the projected one fails
    let plain = z.map(|_| (net.points.clone(), net.face_verts.clone()));
    let proj = match (grid, z) {
        (Some(g), Some(z)) => {
            let p = Polygons { start: &net.face_start, verts: &net.face_verts, cells: Some(&net.face_cells) };
            Some(project::project(&mut net.points, &net.keys, &p, g, z))
        }
        _ => None,
    };
    let mut t = Target {
        points: &mut net.points,
        start: &net.face_start,
        verts: &mut net.face_verts,
        cells: Some(&net.face_cells),
        bounds: grid.map(|g| g.bounds),
        fixed: None,
    };
    let mut e = certify(&mut t);
    let mut proj = proj;
    if let (Some(p), Some((x, v))) = (proj.as_mut(), plain) {
        if e.after.violations() > 0 {
            // a projected vertex must never make the exact check fail: every
            // move undone (and counted kept), the unprojected network certified
            (net.points, net.face_verts) = (x, v);
            let mut t = Target {
                points: &mut net.points,
                start: &net.face_start,
                verts: &mut net.face_verts,
                cells: Some(&net.face_cells),
                bounds: grid.map(|g| g.bounds),
                fixed: None,
            };
            e = certify(&mut t);
            (p.kept, p.kept_by_check, p.moved) = (p.kept + p.moved, p.kept_by_check + p.moved, 0);
        }
    }
    e.snapped = snapped;
    e.projection = proj.map(|mut p| {
        let u = used(&net.face_verts, net.points.len());
        p.residual_after = project::largest_residual(z.unwrap(), &net.points, &net.keys, &u);
        p
    });
    e.seconds = t0.elapsed().as_secs_f64();
    net.seconds.push(("certify", e.seconds));
    net.embedding = Some(e.clone());
    e
}

fn used(verts: &[u32], n: usize) -> Vec<bool> {
    let mut u = vec![false; n];
    for &v in verts {
        u[v as usize] = true;
    }
    u
}

/// Certifies region surfaces (the kept polygons, as written) in place:
/// [`certify_network`] for [`RegionSurfaces`]; cells are the regions.
/// `grid`: the network's box grid, when the points are still the grid's
/// (not moved by an affine map); `bounds`: the box closing the regions (the
/// grid's, or its image under a diagonal map).
pub fn certify_regions(r: &mut RegionSurfaces, grid: Option<&BoxGrid>, bounds: Option<[[f64; 3]; 2]>) -> Embedding {
    certify_regions_with(r, grid, bounds, None)
}

/// [`certify_regions`] after moving the kept polygons' vertices onto the
/// true zero sets of the scene's `functions` ([`certify_network_on`]).
pub fn certify_regions_on(r: &mut RegionSurfaces, grid: &BoxGrid, functions: &[crate::scene::Primitive]) -> Embedding {
    let z = Zeros { functions, mi: r.network.mode == crate::complex::Mode::Mi };
    certify_regions_with(r, Some(grid), Some(grid.bounds), Some(&z))
}

fn certify_regions_with(
    r: &mut RegionSurfaces,
    grid: Option<&BoxGrid>,
    bounds: Option<[[f64; 3]; 2]>,
    z: Option<&Zeros>,
) -> Embedding {
    let t0 = std::time::Instant::now();
    let snapped = grid.map_or(0, |g| snap_to_grid(&mut r.network.points, &r.network.keys, g));
    let cells = region_cells(r);
    let plain = z.map(|_| (r.network.points.clone(), r.loops.clone()));
    let proj = match (grid, z) {
        (Some(g), Some(z)) => {
            let p = Polygons { start: &r.loop_start, verts: &r.loops, cells: Some(&cells) };
            Some(project::project(&mut r.network.points, &r.network.keys, &p, g, z))
        }
        _ => None,
    };
    let mut t = Target {
        points: &mut r.network.points,
        start: &r.loop_start,
        verts: &mut r.loops,
        cells: Some(&cells),
        bounds,
        fixed: None,
    };
    let mut e = certify(&mut t);
    let mut proj = proj;
    if let (Some(p), Some((x, v))) = (proj.as_mut(), plain) {
        if e.after.violations() > 0 {
            // as in certify_network_with: the unprojected surfaces certified
            (r.network.points, r.loops) = (x, v);
            let mut t = Target {
                points: &mut r.network.points,
                start: &r.loop_start,
                verts: &mut r.loops,
                cells: Some(&cells),
                bounds,
                fixed: None,
            };
            e = certify(&mut t);
            (p.kept, p.kept_by_check, p.moved) = (p.kept + p.moved, p.kept_by_check + p.moved, 0);
        }
    }
    e.snapped += snapped;
    e.projection = proj.map(|mut p| {
        let u = used(&r.loops, r.network.points.len());
        p.residual_after = project::largest_residual(z.unwrap(), &r.network.points, &r.network.keys, &u);
        p
    });
    e.seconds = t0.elapsed().as_secs_f64();
    r.seconds.push(("certify", e.seconds));
    r.embedding = Some(e.clone());
    // Volumes, areas and lengths of the doubles as written (repairs move points).
    r.measure();
    e
}

/// The box grid of a label volume of `shape` voxels in index space (what
/// `regions::label_surfaces` computes on: grid point `(i, j, k)` at voxel
/// `(i, j, k)`).
pub fn label_grid(shape: [usize; 3]) -> Option<BoxGrid> {
    let res = shape.map(|s| s.saturating_sub(1));
    let hi = res.map(|r| r as f64);
    BoxGrid::new(res, [[0.0; 3], hi], crate::grid::Split::Five).ok()
}

/// Places label surfaces computed on a volume of `shape` voxels by the
/// voxel-to-world `affine` (`io::place_surfaces`) and certifies them: the
/// coordinates are first put on the voxel grid's lines where the exact
/// vertices are (in index space, where the grid's doubles are whole
/// numbers), then placed, then checked and repaired; the box closing the
/// regions is the volume's image when `affine` has no rotation or shear.
/// With `certify` false, only the placement.
pub fn place_labels(
    r: &mut RegionSurfaces,
    shape: [usize; 3],
    affine: &[[f64; 4]; 3],
    certify: bool,
) -> Result<Option<Embedding>, String> {
    let grid = label_grid(shape);
    let snapped = match (&grid, certify) {
        (Some(g), true) => snap_to_grid(&mut r.network.points, &r.network.keys, g),
        _ => 0,
    };
    crate::io::place_surfaces(r, affine)?;
    if !certify {
        return Ok(None);
    }
    let bounds = label_bounds(shape, affine);
    let mut e = certify_regions(r, None, bounds);
    e.snapped = snapped;
    r.embedding = Some(e.clone());
    Ok(Some(e))
}

/// The box closing label surfaces of a volume of `shape` voxels placed by
/// `affine` (the volume's image; `None` when `affine` rotates or shears).
pub fn label_bounds(shape: [usize; 3], affine: &[[f64; 4]; 3]) -> Option<[[f64; 3]; 2]> {
    let diagonal = (0..3).all(|i| (0..3).all(|j| i == j || affine[i][j] == 0.0));
    label_grid(shape).filter(|_| diagonal).map(|g| {
        // the corners placed as `place_surfaces` places points
        let at = |k: usize, c: f64| affine[k][k] * c + affine[k][3];
        let (lo, hi) = (g.bounds[0], g.bounds[1]);
        let a: [f64; 3] = std::array::from_fn(|k| at(k, lo[k]).min(at(k, hi[k])));
        let b: [f64; 3] = std::array::from_fn(|k| at(k, lo[k]).max(at(k, hi[k])));
        [a, b]
    })
}

/// The exact check alone of a network's written doubles (nothing moves).
pub fn check_network(net: &Network, bounds: Option<[[f64; 3]; 2]>) -> EmbeddingCheck {
    let p = Polygons { start: &net.face_start, verts: &net.face_verts, cells: Some(&net.face_cells) };
    check::check(&net.points, &p, bounds).check
}

/// The exact check alone of region surfaces' kept polygons.
pub fn check_regions(r: &RegionSurfaces, bounds: Option<[[f64; 3]; 2]>) -> EmbeddingCheck {
    let cells = region_cells(r);
    let p = Polygons { start: &r.loop_start, verts: &r.loops, cells: Some(&cells) };
    check::check(&r.network.points, &p, bounds).check
}

/// Per kept polygon, its regions as cells `[lesser, greater]` (its loop is
/// counter-clockwise seen from the lesser region: its positive side),
/// numbered by rank among the regions present.
fn region_cells(r: &RegionSurfaces) -> Vec<[u32; 2]> {
    let mut regions: Vec<i64> = r.cell_region.clone();
    regions.sort_unstable();
    regions.dedup();
    let rank = |g: i64| regions.binary_search(&g).map_or(u32::MAX, |i| i as u32);
    r.faces
        .iter()
        .map(|&f| {
            let [cp, cn] = r.network.face_cells[f as usize];
            // as the writers read it (`io::ResultView::of_regions`): outside
            // the grid counts as region -1
            let region = |c: u32| if c == u32::MAX { (-1, u32::MAX) } else { (r.cell_region[c as usize], 0) };
            let (a, b) = (region(cp), region(cn));
            let (lo, hi) = if a.0 <= b.0 { (a, b) } else { (b, a) };
            let id = |(g, none): (i64, u32)| if none == u32::MAX { u32::MAX } else { rank(g) };
            [id(lo), id(hi)]
        })
        .collect()
}
