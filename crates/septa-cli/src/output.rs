//! The output options every computing command shares: where (`-o`), what
//! (`--format`), how many threads, and how much to print (`--json`, `-q`).
use std::path::PathBuf;

use septa::io::Format;

/// `-o/--output`, `--format`, `--threads`, `--json`, `-q/--quiet`.
#[derive(clap::Args, Clone, Debug)]
pub struct Output {
    /// Output folder (created if needed); files are named network.<format>.
    #[arg(short, long, default_value = "septa-out")]
    pub output: PathBuf,
    /// Formats to write, comma-separated: json (the whole result as text;
    /// the viewer reads it), npz (the whole result as numpy arrays, fastest
    /// to load), ply (triangles with per-face patch/labels/cells), plain.ply
    /// (triangles only, for meshio), obj, vtu (polygons with patch, labels,
    /// cells; triangles, quads, then larger polygons by size, `face` naming
    /// each row's face), vtm (ParaView multiblock: patches, chains, corners,
    /// cells), stl (regions/NAME.stl: each closed region, label or cell as
    /// a closed, outward solid; solid.obj, solid.ply the same as OBJ, PLY),
    /// or all.
    #[arg(long, default_value = "json,npz,ply,obj,vtu", value_parser = parse_formats)]
    pub format: Formats,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = crate::args::threads)]
    pub threads: Option<usize>,
    /// Print one JSON object (counts, timings) on standard output.
    #[arg(long)]
    pub json: bool,
    /// Print nothing but errors (and the `--json` object if asked for).
    #[arg(short, long)]
    pub quiet: bool,
    /// Write the doubles as computed, without the exact check of the written
    /// triangles and its repairs (by default no two vertices share a point,
    /// no triangle is degenerate and no two triangles cross, proven by exact
    /// signs; `embedding` in network.json and --json says what was changed).
    #[arg(long)]
    pub no_certify: bool,
    /// Remesh every patch to triangles of edge length about L (isotropic:
    /// split, collapse, flip, smooth), with the chains and corners as
    /// constraints shared by the patches around them and vertices kept on
    /// the unremeshed patches: the same patches, chains, corners and cells,
    /// certified by the exact check after (`remesh` in --json: angles,
    /// radius ratios, Hausdorff distance to the unremeshed result).
    #[arg(long, value_name = "L", conflicts_with = "no_certify", value_parser = crate::args::positive)]
    pub remesh: Option<f64>,
}

/// The parsed `--format` list.
#[derive(Clone, Debug)]
pub struct Formats(pub Vec<Format>);

fn parse_formats(s: &str) -> Result<Formats, String> {
    Format::parse_list(s).map(Formats)
}

impl Output {
    /// Runs `work` on a pool of `--threads` threads (all cores by default).
    pub fn install<T: Send>(&self, work: impl FnOnce() -> T + Send) -> Result<T, Box<dyn std::error::Error>> {
        let mut pool = rayon::ThreadPoolBuilder::new();
        if let Some(t) = self.threads {
            pool = pool.num_threads(t.max(1));
        }
        Ok(pool.build()?.install(work))
    }

    /// Prints what remeshing did (human-readable mode only).
    pub fn tell_remesh(&self, r: Option<&septa::mesh::Remeshing>) {
        if let (true, Some(r)) = (self.talk(), r) {
            if r.refused > 0 {
                println!(
                    "remesh to L = {}: refused, {} violations of the exact check left after repairs; the unremeshed \
                     result is written",
                    r.length, r.refused
                );
                return;
            }
            let (b, a) = (&r.before, &r.after);
            println!(
                "remesh to L = {}: {} -> {} triangles, smallest angle {:.2} -> {:.2} degrees (mean smallest {:.2} -> \
                 {:.2}), {} -> {} under 20 degrees; Hausdorff distance {:.3e} (to the unremeshed) / {:.3e} (from it); \
                 patches kept: {}",
                r.length,
                b.triangles,
                a.triangles,
                b.min_angle,
                a.min_angle,
                b.mean_min_angle,
                a.mean_min_angle,
                b.below_20_degrees,
                a.below_20_degrees,
                r.hausdorff[0],
                r.hausdorff[1],
                r.patches_kept
            );
            if r.at_sharp_wedges > 0 {
                println!(
                    "  {} triangles sit in {} wedges of the input under 20 degrees (chains meeting at a small angle: \
                     their angle there is bounded by the input's); smallest angle of the others {:.2} degrees",
                    r.at_sharp_wedges, r.sharp_wedges, r.min_angle_away
                );
            }
        }
    }

    /// Prints what certification did (human-readable mode only).
    pub fn tell_embedding(&self, e: Option<&septa::mesh::Embedding>) {
        if let (true, Some(e)) = (self.talk(), e) {
            let (b, a) = (&e.before, &e.after);
            println!(
                "embedding: {} violations as computed ({} coincident points, {} degenerate triangles, {} crossing \
                 pairs), {} written; {} vertices put on the grid, {} polygons re-fanned, {} vertices nudged; {} of {} \
                 closed cells proven positive",
                b.violations(),
                b.coincident_points,
                b.degenerate_triangles,
                b.intersecting_pairs,
                a.violations(),
                e.snapped,
                e.rotated,
                e.nudged,
                a.cells_positive,
                a.cells_checked
            );
        }
    }

    /// Prints the per-region solid files written (`--format stl`,
    /// `solid.obj`, `solid.ply`), human-readable mode only.
    pub fn tell_solids(&self) {
        if !self.talk() {
            return;
        }
        let dir = self.output.join(septa::io::SOLIDS_DIR);
        for f in self.format.0.iter().filter_map(|f| f.solid()) {
            let mut names: Vec<String> = std::fs::read_dir(&dir)
                .into_iter()
                .flatten()
                .flatten()
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .filter(|n| !n.starts_with('.') && n.ends_with(&format!(".{}", f.ext())))
                .collect();
            names.sort();
            let shown = if names.len() > 12 { format!("{}, ...", names[..12].join(", ")) } else { names.join(", ") };
            println!(
                "solids: {} {} file(s) in {} ({shown}); regions that reach the box have no closed surface and no file",
                names.len(),
                f.ext(),
                dir.display()
            );
        }
    }

    /// Whether to print human-readable lines.
    pub fn talk(&self) -> bool {
        !self.json && !self.quiet
    }
}
