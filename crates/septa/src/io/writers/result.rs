//! The one result model every writer reads (PLY, OBJ, VTU, VTM, NPZ), for
//! grid networks (IA/MI, Du et al. Sec. 3), region surfaces (Bloomenthal
//! 1995) and label volumes alike, so that every command and the Python
//! package write the same files with the same names.
//!
//! **Vocabulary** (the same in every format):
//! - `patch` per polygon: its patch (a region surface for `regions`/`labels`);
//! - `labels` per polygon, 2 components: IA `[f, f]` (the function whose
//!   zero set holds the polygon), MI `[a, b]` (the materials on its positive
//!   and negative side), regions `[lesser, greater]` region of its pair
//!   (the polygon is oriented from the lesser region, so as in VTK's
//!   `BoundaryLabels` of `vtkSurfaceNets3D` the lesser label comes first);
//! - `cells` per polygon, 2 components: the cell on its positive and on its
//!   negative side (`-1`: outside the grid);
//! - chains as polylines (line cells) with the patches around them, corners
//!   as vertex cells.
//!
//! Formats that hold one number per property (PLY) split a 2-component
//! array into `labels_0`, `labels_1` (ParaView's names for components).

use std::borrow::Cow;

use crate::complex::Mode;
use crate::complex::NONE;
use crate::io::readers::names::Names;
use crate::measure::Measures;
use crate::network::Network;
use crate::regions::RegionSurfaces;

/// What a grid network's writers add to it beyond the [`Network`]: the
/// names of its functions (and materials) and its measures (either may be
/// empty: then nothing is written for them).
#[derive(Clone, Debug, Default)]
pub struct Annotations {
    /// Function and region (material) names.
    pub names: Names,
    /// Cell volumes, patch areas, chain lengths.
    pub measures: Measures,
}

/// A result as the writers see it: polygons with per-polygon `patch`,
/// `labels` and `cells`, chains, corners, shells and cells. Borrowed from a
/// [`Network`] where the layout already matches, owned otherwise.
#[derive(Clone, Debug)]
pub struct ResultView<'a> {
    /// `"ia"`, `"mi"` or `"regions"`.
    pub mode: &'static str,
    /// Number of functions (0 for regions).
    pub functions: usize,
    /// Vertex positions.
    pub points: Cow<'a, [[f64; 3]]>,
    /// Polygon `f` is `face_verts[face_start[f]..face_start[f + 1]]`,
    /// counter-clockwise seen from its positive side.
    pub face_start: Cow<'a, [u32]>,
    /// See `face_start`.
    pub face_verts: Cow<'a, [u32]>,
    /// Per polygon: its patch.
    pub patch: Cow<'a, [u32]>,
    /// Per polygon: its two labels (module doc).
    pub labels: Vec<[i32; 2]>,
    /// Per polygon: the cells on its positive and negative side (-1: none).
    pub cells: Vec<[i32; 2]>,
    /// Per patch: its two labels.
    pub patch_labels: Vec<[i32; 2]>,
    /// Chains as vertex paths (a closed chain repeats its first vertex).
    pub chains: Cow<'a, [Vec<u32>]>,
    /// Per chain, the patches around it in cyclic order (may be empty).
    pub chain_patches: Cow<'a, [Vec<u32>]>,
    /// Corner vertices.
    pub corners: Cow<'a, [u32]>,
    /// Shells as half-patches (`2p` positive side of patch `p`, `2p + 1` negative).
    pub shells: Cow<'a, [Vec<u32>]>,
    /// Per cell: its shells.
    pub cell_shells: Vec<Vec<u32>>,
    /// Per cell: its label; IA one 0/1 per function (1: `f > 0`), MI
    /// `[material]`, regions `[region]`.
    pub cell_labels: Vec<Vec<i64>>,
    /// Names of functions and regions (may be empty).
    pub names: Cow<'a, Names>,
    /// Per cell its volume, per patch its area, per chain its length (empty
    /// when not known: then no writer writes them).
    pub measures: Cow<'a, Measures>,
}

fn id(x: u32) -> i32 {
    if x == NONE {
        -1
    } else {
        x as i32
    }
}

impl Annotations {
    /// A job's network's names (a scene's functions and regions) and
    /// measures (cell volumes need the box of a box grid; on a tet mesh only
    /// the cells the network closes get one).
    pub fn of_job(job: &crate::job::Job, net: &Network) -> Annotations {
        let domain = match &job.grid {
            crate::grid::Grid::Box(g) => Some(crate::measure::BoxDomain::of_box(g)),
            _ => None,
        };
        Annotations {
            names: job.scene.as_ref().map(|s| s.result_names()).unwrap_or_default(),
            measures: crate::measure::network_measures(net, domain.as_ref()),
        }
    }
}

impl<'a> ResultView<'a> {
    /// Number of polygons.
    pub fn num_faces(&self) -> usize {
        self.patch.len()
    }

    /// Vertices of polygon `f`.
    pub fn face(&self, f: usize) -> &[u32] {
        &self.face_verts[self.face_start[f] as usize..self.face_start[f + 1] as usize]
    }

    /// Area of polygon `f`.
    pub fn face_area(&self, f: usize) -> f64 {
        crate::measure::polygon_area(&self.points, self.face(f))
    }

    /// Number of triangles of the polygons' fans (each polygon is convex:
    /// a plane section of a convex cell of a tet, Du et al. Sec. 4).
    pub fn num_triangles(&self) -> usize {
        (0..self.num_faces()).map(|f| self.face(f).len().saturating_sub(2)).sum()
    }

    /// The view of a grid network (borrows its arrays).
    pub fn of_network(net: &'a Network) -> ResultView<'a> {
        let labels = net.face_label.iter().map(|l| [l[0] as i32, l[1] as i32]).collect();
        let cells = net.face_cells.iter().map(|c| [id(c[0]), id(c[1])]).collect();
        let cell_labels = net
            .cells
            .iter()
            .map(|c| match net.mode {
                Mode::Ia => (0..net.functions).map(|f| c.positive(f) as i64).collect(),
                Mode::Mi => vec![c.label.first().copied().unwrap_or(0) as i64],
            })
            .collect();
        ResultView {
            mode: match net.mode {
                Mode::Ia => "ia",
                Mode::Mi => "mi",
            },
            functions: net.functions,
            points: Cow::Borrowed(&net.points),
            face_start: Cow::Borrowed(&net.face_start),
            face_verts: Cow::Borrowed(&net.face_verts),
            patch: Cow::Borrowed(&net.face_patch),
            labels,
            cells,
            patch_labels: net.patches.iter().map(|p| [p.label[0] as i32, p.label[1] as i32]).collect(),
            chains: Cow::Borrowed(&net.chains),
            chain_patches: Cow::Borrowed(&net.chain_patches),
            corners: Cow::Borrowed(&net.corners),
            shells: Cow::Borrowed(&net.shells),
            cell_shells: net.cells.iter().map(|c| c.shells.clone()).collect(),
            cell_labels,
            names: Cow::Owned(Names::default()),
            measures: Cow::Owned(Measures::default()),
        }
    }

    /// The view of a grid network with its names and measures.
    pub fn of_annotated(net: &'a Network, notes: &'a Annotations) -> ResultView<'a> {
        ResultView {
            names: Cow::Borrowed(&notes.names),
            measures: Cow::Borrowed(&notes.measures),
            ..Self::of_network(net)
        }
    }

    /// The view of region surfaces: the kept polygons, oriented from the
    /// lesser region of their pair; patches are the surfaces of interest,
    /// chains the curves, corners the open curves' ends; cells are the
    /// regions (ascending, as `network.json`'s `cells`), each labelled by
    /// its region, so `cells` per polygon are indices into that list.
    pub fn of_regions(r: &'a RegionSurfaces) -> ResultView<'a> {
        let net = &r.network;
        let regions = r.region_ids();
        let index = |g: i64| regions.binary_search(&g).map_or(-1, |i| i as i32);
        let mut labels = Vec::with_capacity(r.faces.len());
        let mut cells = Vec::with_capacity(r.faces.len());
        for &f in &r.faces {
            let [cp, cn] = net.face_cells[f as usize];
            let region = |c: u32| if c == NONE { -1 } else { r.cell_region[c as usize] };
            let (a, b) = (region(cp), region(cn));
            // The loop is counter-clockwise seen from the lesser region: its
            // positive side (first) is the lesser region.
            let (lo, hi) = (a.min(b), a.max(b));
            labels.push([lo as i32, hi as i32]);
            cells.push([index(lo), index(hi)]);
        }
        let mut corners: Vec<u32> =
            r.curves.iter().filter(|c| !c.closed).flat_map(|c| [c.vertices[0], *c.vertices.last().unwrap()]).collect();
        corners.sort_unstable();
        corners.dedup();
        ResultView {
            mode: "regions",
            functions: net.functions,
            points: Cow::Borrowed(&net.points),
            face_start: Cow::Borrowed(&r.loop_start),
            face_verts: Cow::Borrowed(&r.loops),
            patch: Cow::Borrowed(&r.face_surface),
            labels,
            cells,
            patch_labels: r.surfaces.iter().map(|s| [s.regions[0] as i32, s.regions[1] as i32]).collect(),
            chains: Cow::Owned(r.curves.iter().map(|c| c.vertices.clone()).collect()),
            chain_patches: Cow::Owned(Vec::new()),
            corners: Cow::Owned(corners),
            shells: Cow::Owned(Vec::new()),
            cell_shells: vec![Vec::new(); regions.len()],
            cell_labels: regions.iter().map(|&g| vec![g]).collect(),
            names: Cow::Borrowed(&r.names),
            measures: Cow::Borrowed(&r.measures),
        }
    }

    /// Checks that every index is in range (for views built from user
    /// arrays, e.g. Python's `Network.save`): names the array and element.
    pub fn validate(&self) -> Result<(), String> {
        let nf = self.num_faces();
        if self.face_start.len() != nf + 1 {
            return Err(format!("offsets: expected {} entries (faces + 1), got {}", nf + 1, self.face_start.len()));
        }
        if self.face_start[0] != 0 || *self.face_start.last().unwrap() as usize != self.face_verts.len() {
            return Err("offsets: must start at 0 and end at the length of indices".into());
        }
        for f in 0..nf {
            if self.face_start[f + 1] < self.face_start[f] + 3 {
                return Err(format!("face {f}: fewer than 3 vertices (or offsets not increasing)"));
            }
        }
        if self.labels.len() != nf || self.cells.len() != nf {
            return Err(format!("labels/cells: expected {nf} rows (one per face)"));
        }
        let np = self.points.len() as u32;
        if let Some(i) = self.face_verts.iter().position(|&v| v >= np) {
            return Err(format!("indices[{i}]: vertex {} does not exist ({np} points)", self.face_verts[i]));
        }
        for (c, chain) in self.chains.iter().enumerate() {
            if chain.iter().any(|&v| v >= np) {
                return Err(format!("chain {c}: refers to a vertex that does not exist ({np} points)"));
            }
        }
        if let Some(i) = self.corners.iter().position(|&v| v >= np) {
            return Err(format!("corners[{i}]: vertex {} does not exist ({np} points)", self.corners[i]));
        }
        let m = &self.measures;
        for (name, len, want) in [
            ("cell_volume", m.cell_volume.len(), self.cell_labels.len()),
            ("patch_area", m.patch_area.len(), self.patch_labels.len()),
            ("chain_length", m.chain_length.len(), self.chains.len()),
        ] {
            if len != 0 && len != want {
                return Err(format!("{name}: expected {want} entries (or none), got {len}"));
            }
        }
        Ok(())
    }
}

/// The file format of one cell's solid (`solids_out.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SolidFormat {
    /// Binary STL (float32).
    Stl,
    /// Wavefront OBJ (doubles).
    Obj,
    /// Binary little-endian PLY (doubles).
    Ply,
}

impl SolidFormat {
    /// The file extension.
    pub fn ext(self) -> &'static str {
        match self {
            SolidFormat::Stl => "stl",
            SolidFormat::Obj => "obj",
            SolidFormat::Ply => "ply",
        }
    }
}

/// A result file format (`--format`, Python `Network.save` by extension).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// `network.json`: the whole result as text (the viewer's input).
    Json,
    /// `network.npz`: the whole result as numpy arrays (`result_npz.rs`).
    Npz,
    /// `network.ply`: triangle fans with per-face arrays (`result_mesh.rs`).
    Ply,
    /// `network.plain.ply`: triangle fans without per-face arrays (meshio 5.3 reads it).
    PlyPlain,
    /// `network.obj`: a group per patch, chains as `l`, corners as `p`.
    Obj,
    /// `network.vtu`: the polygons with `patch`, `labels`, `cells`.
    Vtu,
    /// `network.vtm` and `network/`: patches, chains, corners, cells (`result_vtk.rs`).
    Vtm,
    /// `regions/<name>.stl`: each closed cell (region, label) as a binary
    /// STL of its closed, outward surface (`solids_out.rs`).
    Stl,
    /// `regions/<name>.obj`: the same solids as OBJ (doubles).
    SolidObj,
    /// `regions/<name>.ply`: the same solids as binary PLY (doubles).
    SolidPly,
}

impl Format {
    /// Every format, in the order they are written.
    pub const ALL: &'static [Format] = &[
        Format::Npz,
        Format::Ply,
        Format::PlyPlain,
        Format::Obj,
        Format::Vtu,
        Format::Vtm,
        Format::Stl,
        Format::SolidObj,
        Format::SolidPly,
        Format::Json,
    ];
    /// What a job writes without `--format`: json, npz, ply, obj, vtu.
    pub const DEFAULT: &'static [Format] = &[Format::Npz, Format::Ply, Format::Obj, Format::Vtu, Format::Json];

    /// The name used by `--format` (also the file's extension but for `plain.ply`).
    pub fn name(self) -> &'static str {
        match self {
            Format::Json => "json",
            Format::Npz => "npz",
            Format::Ply => "ply",
            Format::PlyPlain => "plain.ply",
            Format::Obj => "obj",
            Format::Vtu => "vtu",
            Format::Vtm => "vtm",
            Format::Stl => "stl",
            Format::SolidObj => "solid.obj",
            Format::SolidPly => "solid.ply",
        }
    }

    /// The solid file format of a per-cell format (`stl`, `solid.obj`, `solid.ply`).
    pub fn solid(self) -> Option<SolidFormat> {
        match self {
            Format::Stl => Some(SolidFormat::Stl),
            Format::SolidObj => Some(SolidFormat::Obj),
            Format::SolidPly => Some(SolidFormat::Ply),
            _ => None,
        }
    }

    /// Parses a comma-separated list (`json,npz,vtm`, or `all`).
    pub fn parse_list(s: &str) -> Result<Vec<Format>, String> {
        let mut out = Vec::new();
        for part in s.split(',').map(str::trim).filter(|p| !p.is_empty()) {
            if part == "all" {
                out.extend_from_slice(Format::ALL);
                continue;
            }
            let f = Format::ALL
                .iter()
                .copied()
                .find(|f| f.name() == part || (part == "ply-plain" && *f == Format::PlyPlain))
                .ok_or_else(|| {
                    let names: Vec<&str> = Format::ALL.iter().map(|f| f.name()).collect();
                    format!("unknown format {part:?} (use {} or all)", names.join(", "))
                })?;
            out.push(f);
        }
        if out.is_empty() {
            return Err("no format given".into());
        }
        out.sort_by_key(|f| Format::ALL.iter().position(|g| g == f));
        out.dedup();
        Ok(out)
    }

    /// The format of a file name (`x.plain.ply` before `x.ply`).
    pub fn of_path(path: &std::path::Path) -> Option<Format> {
        let name = path.file_name()?.to_string_lossy().to_lowercase();
        if name.ends_with(".plain.ply") {
            return Some(Format::PlyPlain);
        }
        let ext = name.rsplit_once('.')?.1.to_string();
        Format::ALL.iter().copied().filter(|f| f.solid().is_none() || *f == Format::Stl).find(|f| f.name() == ext)
    }
}
