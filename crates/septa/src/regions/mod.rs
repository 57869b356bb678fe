//! Non-manifold implicit shapes (Bloomenthal 1995, chapter 4): only the
//! surfaces and curves of interest of a region rule, computed exactly on
//! top of the implicit arrangement or material interface.
//!
//! A [`RegionRule`] maps every cell of the network to a region. Polygons
//! between cells of one region are dropped; those between a region pair of
//! interest are kept, oriented counter-clockwise seen from the lesser
//! region (Bloomenthal 4.5.2.4), and grouped into **surfaces**: connected
//! pieces with one region pair. **Curves** are the network edges around
//! which the three regions of a triple of interest meet, joined into
//! polylines.
//!
//! Unlike Bloomenthal's sampled polygonizer there is no limit of one
//! vertex per face or tet and no truncated loop: the combinatorics are
//! those of the exact network; only coordinates and normals are floating
//! point.
//!
//! ```
//! use septa::regions::region_surfaces;
//! use septa::scene::Scene;
//! let scene = Scene::load("builtin:sphere-with-hole").unwrap();
//! let shape = region_surfaces(&scene, &Default::default()).unwrap();
//! // One disk: Euler characteristic 1 and one boundary loop.
//! assert_eq!(shape.surfaces.len(), 1);
//! assert_eq!((shape.surfaces[0].euler, shape.surfaces[0].boundary_loops), (1, 1));
//! ```

mod clean;
mod curves;
mod features;
mod labels;
mod measures;
mod surfaces;

use std::time::Instant;

use crate::complex::Mode;
use crate::grid::Grid;
use crate::network::{compute, Network, NetworkError, NetworkOptions};
use crate::network::{compute_sparse, SparseStats};
use crate::scene::{sample_grid, Interest, Primitive, RegionId, RegionRule, Scene};
use crate::Progress;

pub use clean::{clean, CleanStats};
pub use curves::{Curve, CurveKind};
#[doc(hidden)]
pub use labels::label_surfaces_listing_triples;
pub use labels::{label_surfaces, label_surfaces_with_progress};
pub use surfaces::Surface;

/// Options of [`region_surfaces`].
#[derive(Clone, Debug)]
pub struct RegionOptions {
    /// Compute per-vertex normals (one vertex copy per region pair) from
    /// the analytic gradients. Default value: `false`.
    pub normals: bool,
    /// Sparse evaluation (docs/sparse.md): sample only blocks that the functions'
    /// bounds do not prove empty; the output is identical, because the
    /// bounds enclose the rounded samples (docs/sparse.md). Default value:
    /// `true`; `false` samples every grid vertex.
    pub sparse: bool,
    /// Clean up small and thin triangles (Bloomenthal 4.5.3.1, [`clean`]):
    /// edges shorter than this factor times the grid's smallest cube edge
    /// are collapsed where that keeps the combinatorics. Default value:
    /// `None` (the exact polygons as they are).
    pub clean: Option<f64>,
    /// Called as blocks of the network finish ([`NetworkOptions::progress`]).
    /// Default value: `None`.
    pub progress: Option<Progress>,
}

impl Default for RegionOptions {
    fn default() -> RegionOptions {
        RegionOptions { normals: false, sparse: true, clean: None, progress: None }
    }
}

/// The surfaces and curves of interest of a region rule.
#[derive(Clone, Debug)]
pub struct RegionSurfaces {
    /// The underlying exact network (all polygons, cells, labels).
    pub network: Network,
    /// Region of every network cell.
    pub cell_region: Vec<RegionId>,
    /// Kept polygons as network polygon ids.
    pub faces: Vec<u32>,
    /// Kept polygons' vertex loops, counter-clockwise seen from the lesser
    /// region of their pair; polygon `i` is `loops[loop_start[i]..loop_start[i+1]]`.
    pub loop_start: Vec<u32>,
    /// See `loop_start`.
    pub loops: Vec<u32>,
    /// Surface of each kept polygon.
    pub face_surface: Vec<u32>,
    /// Surfaces of interest.
    pub surfaces: Vec<Surface>,
    /// Curves of interest.
    pub curves: Vec<Curve>,
    /// With normals: one vertex copy per (vertex, region pair): its network
    /// vertex, region pair and unit normal pointing into the lesser region.
    pub normals: Vec<(u32, [RegionId; 2], [f64; 3])>,
    /// Seconds per stage.
    pub seconds: Vec<(&'static str, f64)>,
    /// Block counts of sparse evaluation (`None` on the dense path).
    pub sparse: Option<SparseStats>,
    /// What the clean-up did (`None`: not asked for).
    pub clean: Option<CleanStats>,
    /// What the certification of the kept polygons' written doubles found
    /// and changed (`septa::mesh::certify_regions`; `None`: not certified).
    pub embedding: Option<crate::network::embedding::Embedding>,
    /// The scene's function and region names (or a label table's).
    pub names: crate::io::Names,
    /// The box the network was computed in (`None`: unknown), for the
    /// volumes of regions that reach its boundary.
    pub domain: Option<crate::measure::BoxDomain>,
    /// Per region (ascending) its volume, per surface its area, per curve
    /// its length ([`RegionSurfaces::measure`]; empty until measured).
    pub measures: crate::measure::Measures,
}

impl RegionSurfaces {
    /// Volume enclosed by the kept polygons around region `r` (divergence
    /// theorem over the oriented polygons; floating point). Meaningful when
    /// the region's whole boundary is of interest and inside the grid.
    pub fn enclosed_volume(&self, r: RegionId) -> f64 {
        let net = &self.network;
        let mut vol = 0.0;
        for (i, &f) in self.faces.iter().enumerate() {
            let [cp, cn] = net.face_cells[f as usize];
            let (a, b) = (self.cell_region[cp as usize], self.cell_region[cn as usize]);
            // Normals point into the lesser region: outward for the greater.
            let sign = if r == a.max(b) {
                1.0
            } else if r == a.min(b) {
                -1.0
            } else {
                continue;
            };
            let p = &self.loops[self.loop_start[i] as usize..self.loop_start[i + 1] as usize];
            let q = |v: u32| net.points[v as usize];
            for k in 1..p.len() - 1 {
                let (x, y, z) = (q(p[0]), q(p[k]), q(p[k + 1]));
                let cross = [y[1] * z[2] - y[2] * z[1], y[2] * z[0] - y[0] * z[2], y[0] * z[1] - y[1] * z[0]];
                vol += sign * (x[0] * cross[0] + x[1] * cross[1] + x[2] * cross[2]) / 6.0;
            }
        }
        vol
    }
}

/// Why region surfaces could not be computed.
#[derive(Debug, thiserror::Error)]
pub enum RegionError {
    /// The grid of the scene is invalid.
    #[error("grid: {0}")]
    Grid(#[from] crate::grid::GridError),
    /// The dense path would need more memory than the machine has.
    #[error("grid: {0}")]
    Memory(#[from] crate::grid::memory::MemoryError),
    /// A label volume's shape is too small or does not match its labels.
    #[error(
        "grid: a label volume needs at least 2 voxels per axis and shape {shape:?} must match its {labels} labels"
    )]
    LabelShape {
        /// The shape given.
        shape: [usize; 3],
        /// Number of labels given.
        labels: usize,
    },
    /// The smoothing width is negative or not finite.
    #[error("grid: smoothing sigma must be a finite number >= 0, not {0}")]
    Sigma(f64),
    /// The network failed.
    #[error(transparent)]
    Network(#[from] NetworkError),
}

/// Samples the scene's functions on its grid, computes the exact network
/// and extracts the surfaces and curves of interest.
pub fn region_surfaces(scene: &Scene, options: &RegionOptions) -> Result<RegionSurfaces, RegionError> {
    let t0 = Instant::now();
    let bgrid = scene.grid.box_grid()?;
    let mode = scene.mode;
    let mut network_options = NetworkOptions::new(mode);
    network_options.progress = options.progress.clone();
    if options.sparse {
        let (net, stats) = compute_sparse(&bgrid, &scene.functions, &network_options)?;
        let mut out = finish(from_network(net, &scene.regions, &scene.interest), scene, options);
        out.sparse = Some(stats);
        return Ok(out);
    }
    crate::grid::memory::check_dense(
        bgrid.num_vertices(),
        scene.functions.len(),
        "drop --dense (sparse evaluation samples only the blocks near the surfaces) or use a coarser grid",
    )?;
    let grid = Grid::Box(bgrid);
    let points = grid.vertices();
    let values = sample_grid(&scene.functions, &points);
    let t1 = Instant::now();
    let net = compute(&grid, &values, scene.functions.len(), &network_options)?;
    let mut out = finish(from_network(net, &scene.regions, &scene.interest), scene, options);
    out.seconds.insert(0, ("sample", (t1 - t0).as_secs_f64()));
    Ok(out)
}

/// [`region_surfaces`] on a given tet grid (an adaptive grid,
/// `crate::adaptive`): the scene's functions sampled at its vertices.
pub fn region_surfaces_on(scene: &Scene, grid: &Grid, options: &RegionOptions) -> Result<RegionSurfaces, RegionError> {
    let t0 = Instant::now();
    let mut network_options = NetworkOptions::new(scene.mode);
    network_options.progress = options.progress.clone();
    let values = sample_grid(&scene.functions, &grid.vertices());
    let t1 = Instant::now();
    let net = compute(grid, &values, scene.functions.len(), &network_options)?;
    let mut out = finish(from_network(net, &scene.regions, &scene.interest), scene, options);
    out.seconds.insert(0, ("sample", (t1 - t0).as_secs_f64()));
    Ok(out)
}

/// Region of a network cell.
fn cell_region(net: &Network, rule: &RegionRule, c: usize) -> RegionId {
    let label = &net.cells[c].label;
    match net.mode {
        Mode::Ia => {
            let positive: Vec<bool> = (0..net.functions).map(|f| crate::network::sign_bit(label, f)).collect();
            rule.region_ia(&positive)
        }
        Mode::Mi => rule.region_mi(label.first().copied().unwrap_or(0) as usize),
    }
}

/// The surfaces and curves of interest of an existing network.
pub fn from_network(network: Network, rule: &RegionRule, interest: &Interest) -> RegionSurfaces {
    from_network_with(network, rule, interest, &|net, region| curves::extract(net, region, interest))
}

/// [`from_network`] with the curves made by `curves` from the network and
/// the cells' regions (label volumes pick triples without listing them).
pub(crate) fn from_network_with(
    network: Network,
    rule: &RegionRule,
    interest: &Interest,
    curves: &dyn Fn(&Network, &[RegionId]) -> Vec<Curve>,
) -> RegionSurfaces {
    let t0 = Instant::now();
    let cell_region: Vec<RegionId> = (0..network.cells.len()).map(|c| cell_region(&network, rule, c)).collect();
    let s = surfaces::extract(&network, &cell_region, interest);
    let mut curves = curves(&network, &cell_region);
    if interest.features {
        curves.extend(features::extract(&network, &cell_region, &s.faces, &s.loop_start, &s.loops));
    }
    let t1 = Instant::now();
    let mut seconds = network.seconds.clone();
    seconds.push(("regions", (t1 - t0).as_secs_f64()));
    RegionSurfaces {
        network,
        cell_region,
        faces: s.faces,
        loop_start: s.loop_start,
        loops: s.loops,
        face_surface: s.face_surface,
        surfaces: s.surfaces,
        curves,
        normals: Vec::new(),
        seconds,
        sparse: None,
        clean: None,
        embedding: None,
        names: Default::default(),
        domain: None,
        measures: Default::default(),
    }
}

/// The optional steps after extraction: clean-up, then normals (of the
/// cleaned triangles).
fn finish(mut out: RegionSurfaces, scene: &Scene, options: &RegionOptions) -> RegionSurfaces {
    out.names = scene.result_names();
    out.domain = scene.grid.box_grid().ok().map(|g| crate::measure::BoxDomain::of_box(&g));
    if let Some(factor) = options.clean {
        let g = &scene.grid;
        let h =
            (0..3).map(|a| (g.bounds[1][a] - g.bounds[0][a]) / g.resolution[a] as f64).fold(f64::INFINITY, f64::min);
        let t = Instant::now();
        let (cleaned, stats) = clean(&out, factor * h);
        out = cleaned;
        out.clean = Some(stats);
        out.seconds.push(("clean", t.elapsed().as_secs_f64()));
    }
    if options.normals {
        add_normals(&mut out, &scene.functions);
    }
    out.measure();
    out
}

/// Fills [`RegionSurfaces::normals`] from the gradients of the network's
/// `functions` (for region surfaces made by [`from_network`], e.g. from
/// block results merged elsewhere).
pub fn add_normals(r: &mut RegionSurfaces, functions: &[Primitive]) {
    r.normals = normals(r, functions);
}

/// Per (vertex, region pair) normals from the gradient of the function (IA)
/// or function difference (MI) each kept polygon lies on, summed over the
/// polygons of that pair at the vertex (Bloomenthal 4.5.3.2).
fn normals(r: &RegionSurfaces, functions: &[Primitive]) -> Vec<(u32, [RegionId; 2], [f64; 3])> {
    use std::collections::BTreeMap;
    let net = &r.network;
    let mut acc: BTreeMap<(u32, [RegionId; 2]), [f64; 3]> = BTreeMap::new();
    for (i, &f) in r.faces.iter().enumerate() {
        let f = f as usize;
        let [cp, cn] = net.face_cells[f];
        let (rp, rn) = (r.cell_region[cp as usize], r.cell_region[cn as usize]);
        let pair = [rp.min(rn), rp.max(rn)];
        let [a, b] = net.face_label[f];
        for &v in &r.loops[r.loop_start[i] as usize..r.loop_start[i + 1] as usize] {
            let p = net.points[v as usize];
            // Gradient of the plane's function, pointing to its positive side.
            let ga = functions[a as usize].gradient(p);
            let g = match net.mode {
                Mode::Ia => ga,
                Mode::Mi => {
                    let gb = functions[b as usize].gradient(p);
                    [ga[0] - gb[0], ga[1] - gb[1], ga[2] - gb[2]]
                }
            };
            // The lesser region must be in front of the normal.
            let s = if rp < rn { 1.0 } else { -1.0 };
            let e = acc.entry((v, pair)).or_insert([0.0; 3]);
            for k in 0..3 {
                e[k] += s * g[k];
            }
        }
    }
    acc.into_iter()
        .map(|((v, pair), n)| {
            let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            (v, pair, if l > 0.0 { n.map(|x| x / l) } else { n })
        })
        .collect()
}
