//! Each closed cell of a result as a solid of its own (`--format stl`,
//! `solids.obj`, `solids.ply`; Python `Network.save_regions`): a region, a
//! label, a material or arrangement cell whose polygons close around it,
//! as a closed, outward-oriented triangle surface holding only its own
//! vertices (`measure::cell_solid`), one file per cell in `regions/`, named
//! by the region's name when it has a plain, unique one
//! (`regions/part.stl`), else `region_<id>` (regions and labels: the region
//! or label id) or `cell_<c>` (`ia`, `mi`: the cell's index).
//!
//! A cell that reaches the domain's box has no closed surface (the network
//! holds no polygons on the box's faces) and gets no file.
//! STL holds float32 coordinates: its surface is the float32 one (vertices
//! rounded, merged where they round to one point), so that a reader merging
//! corners finds it watertight; OBJ and PLY hold the doubles.

use std::io::Write;

use crate::io::files::outdir::OutputDir;
use crate::io::writers::result::{ResultView, SolidFormat};
use crate::measure::{cell_solid, Solid, SolidError};

/// The folder of an output set the solids go into (`files/outdir.rs`
/// cleans it of stale temporaries by this name).
pub const SOLIDS_DIR: &str = "regions";

/// One cell's solid file, or why it has none.
#[derive(Clone, Debug)]
pub struct SolidFile {
    /// The cell (index into the result's cells).
    pub cell: usize,
    /// The file's stem (module doc).
    pub stem: String,
    /// The solid, or why the cell has none.
    pub solid: Result<Solid, SolidError>,
}

/// Whether `n` is a plain file stem (no path, no leading dot, no spaces).
fn plain(n: &str) -> bool {
    let mut chars = n.chars();
    chars.next().is_some_and(|c| c.is_ascii_alphanumeric())
        && n.len() <= 100
        && n.chars().all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '.' | '-'))
}

/// The file stem of each cell of `r` (module doc).
pub fn solid_stems(r: &ResultView) -> Vec<String> {
    let count = |n: &str| r.names.regions.values().filter(|m| *m == n).count();
    (0..r.cell_labels.len())
        .map(|c| {
            if r.mode != "regions" {
                return format!("cell_{c}");
            }
            let id = r.cell_labels[c].first().copied().unwrap_or(c as i64);
            match r.names.region(id) {
                Some(n) if plain(n) && count(n) == 1 => n.to_string(),
                _ => format!("region_{id}"),
            }
        })
        .collect()
}

/// Every cell's solid (float32 for STL; module doc).
pub fn solids(r: &ResultView, format: SolidFormat) -> Vec<SolidFile> {
    let stems = solid_stems(r);
    let float32 = format == SolidFormat::Stl;
    stems
        .into_iter()
        .enumerate()
        .map(|(c, stem)| {
            let volume = r.measures.cell_volume.get(c).copied().filter(|v| v.is_finite());
            let solid = cell_solid(&r.points, &r.face_start, &r.face_verts, &r.cells, c as i32, float32, volume);
            SolidFile { cell: c, stem, solid }
        })
        .collect()
}

/// A binary STL of `s` (float32; each triangle's unit normal from its
/// float32 corners). The header names the solid without starting with
/// `solid`, which readers take for an ASCII STL.
pub fn stl_bytes(s: &Solid, name: &str) -> Vec<u8> {
    let mut out = Vec::with_capacity(84 + 50 * s.triangles.len());
    let mut head = format!("septa solid {name}").into_bytes();
    head.resize(80, b' ');
    out.extend_from_slice(&head);
    out.extend_from_slice(&(s.triangles.len() as u32).to_le_bytes());
    for t in &s.triangles {
        let [a, b, c] = t.map(|v| s.points[v as usize]);
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let w = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let n = if len > 0.0 { n.map(|x| x / len) } else { [0.0; 3] };
        for x in n.iter().chain(a.iter()).chain(b.iter()).chain(c.iter()) {
            out.extend_from_slice(&(*x as f32).to_le_bytes());
        }
        out.extend_from_slice(&0u16.to_le_bytes());
    }
    out
}

/// An OBJ of `s`: one object `name`, `v` lines (doubles, shortest
/// round-trip form), `f` lines (1-based).
pub fn obj_text(s: &Solid, name: &str) -> String {
    use std::fmt::Write as _;
    let mut out = format!("# septa solid: closed, outward, volume {}\no {name}\n", s.volume);
    for p in &s.points {
        writeln!(out, "v {} {} {}", p[0], p[1], p[2]).unwrap();
    }
    for t in &s.triangles {
        writeln!(out, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1).unwrap();
    }
    out
}

/// A binary little-endian PLY of `s` (double vertices, triangles).
pub fn ply_bytes(s: &Solid, name: &str) -> Vec<u8> {
    let mut out = format!(
        "ply\nformat binary_little_endian 1.0\ncomment septa solid {name}\nelement vertex {}\n\
         property double x\nproperty double y\nproperty double z\nelement face {}\n\
         property list uchar int vertex_indices\nend_header\n",
        s.points.len(),
        s.triangles.len()
    )
    .into_bytes();
    for p in &s.points {
        for x in p {
            out.extend_from_slice(&x.to_le_bytes());
        }
    }
    for t in &s.triangles {
        out.push(3);
        for v in t {
            out.extend_from_slice(&(*v as i32).to_le_bytes());
        }
    }
    out
}

/// The bytes of one solid file.
pub fn solid_bytes(s: &Solid, name: &str, format: SolidFormat) -> Vec<u8> {
    match format {
        SolidFormat::Stl => stl_bytes(s, name),
        SolidFormat::Obj => obj_text(s, name).into_bytes(),
        SolidFormat::Ply => ply_bytes(s, name),
    }
}

/// Writes `regions/<stem>.<ext>` of every closed cell of `r` into the
/// output set `out`; returns every cell's entry (those without a solid say
/// why).
pub fn write_solids_into(r: &ResultView, out: &mut OutputDir, format: SolidFormat) -> std::io::Result<Vec<SolidFile>> {
    let all = solids(r, format);
    for f in &all {
        if let Ok(s) = &f.solid {
            out.write(&format!("{SOLIDS_DIR}/{}.{}", f.stem, format.ext()), &solid_bytes(s, &f.stem, format))?;
        }
    }
    Ok(all)
}

/// Writes `dir/<stem>.<ext>` of every closed cell of `r` (Python's
/// `save_regions`), each file atomically; returns every cell's entry.
pub fn write_solids(r: &ResultView, dir: &std::path::Path, format: SolidFormat) -> std::io::Result<Vec<SolidFile>> {
    std::fs::create_dir_all(dir)?;
    let all = solids(r, format);
    for f in &all {
        if let Ok(s) = &f.solid {
            let path = dir.join(format!("{}.{}", f.stem, format.ext()));
            crate::io::files::safe_write::check_output_file(&path)?;
            let bytes = solid_bytes(s, &f.stem, format);
            crate::io::files::atomic::write_atomic_with(&path, |w| w.write_all(&bytes))?;
        }
    }
    Ok(all)
}
