//! PLY and OBJ of a [`ResultView`] (the vocabulary is in `result.rs`).
//!
//! PLY: binary little-endian, the polygons as fans of triangles, per
//! triangle `face` (its polygon), `patch`, `labels_0`, `labels_1`,
//! `cells_0`, `cells_1` and the patch colour. Triangles because mesh tools
//! (trimesh, Open3D, MeshLab) read face lists of one length best; the exact
//! polygons are in the VTU, OBJ and NPZ. meshio 5.3's binary PLY reader
//! reads face properties column by column (all `vertex_indices`, then all
//! of the next property), which no PLY file laid out row by row satisfies
//! once a face has a second property; [`PlyLayout::Plain`] writes faces
//! with `vertex_indices` only, which meshio reads.
//!
//! OBJ: a group `patch_<p>_labels_<a>_<b>` per patch with its polygons,
//! a group `chain_<c>` per chain (an `l` polyline), and the corners as one
//! `p` element in group `corners`.

use std::io::Write;
use std::path::Path;

use crate::io::files::atomic::write_atomic_with;
use crate::io::writers::result::ResultView;

/// Which face properties a PLY carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlyLayout {
    /// `vertex_indices`, `face`, `patch`, `labels_0`, `labels_1`,
    /// `cells_0`, `cells_1` and `red`, `green`, `blue`.
    Full,
    /// `vertex_indices` only (for meshio 5.3; module doc).
    Plain,
}

/// Writes a binary PLY of `r`'s polygons as triangle fans (module doc).
pub fn write_ply(r: &ResultView, path: &Path, layout: PlyLayout) -> std::io::Result<()> {
    let triangles = r.num_triangles();
    let props = match layout {
        PlyLayout::Full => {
            "property int face\nproperty int patch\nproperty int labels_0\nproperty int labels_1\n\
             property int cells_0\nproperty int cells_1\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
        }
        PlyLayout::Plain => "",
    };
    write_atomic_with(path, |w| {
        write!(
            w,
            "ply\nformat binary_little_endian 1.0\ncomment septa {} result: polygons as triangle fans\n\
             element vertex {}\nproperty double x\nproperty double y\nproperty double z\n\
             element face {triangles}\nproperty list uchar int vertex_indices\n{props}end_header\n",
            r.mode,
            r.points.len(),
        )?;
        let mut buf = Vec::with_capacity(1 << 16);
        for p in r.points.iter() {
            for x in p {
                buf.extend_from_slice(&x.to_le_bytes());
            }
            if buf.len() > 1 << 16 {
                w.write_all(&buf)?;
                buf.clear();
            }
        }
        // One triangle's record is assembled in place and appended at once
        // (an append per 4-byte field was most of this loop's cost).
        let full = layout == PlyLayout::Full;
        let mut rec = [0u8; 40];
        rec[0] = 3;
        // Colours per patch, computed once each (a few patches, many faces).
        let patches = r.patch.iter().map(|&p| p as usize + 1).max().unwrap_or(0);
        let colours: Vec<[u8; 3]> = if full { (0..patches as u32).map(patch_colour).collect() } else { Vec::new() };
        for f in 0..r.num_faces() {
            let vs = r.face(f);
            let p = r.patch[f];
            if full {
                let [l0, l1] = r.labels[f];
                let [c0, c1] = r.cells[f];
                for (i, x) in [f as i32, p as i32, l0, l1, c0, c1].into_iter().enumerate() {
                    rec[13 + 4 * i..17 + 4 * i].copy_from_slice(&x.to_le_bytes());
                }
                rec[37..40].copy_from_slice(&colours[p as usize]);
            }
            rec[1..5].copy_from_slice(&(vs[0] as i32).to_le_bytes());
            for j in 1..vs.len() - 1 {
                rec[5..9].copy_from_slice(&(vs[j] as i32).to_le_bytes());
                rec[9..13].copy_from_slice(&(vs[j + 1] as i32).to_le_bytes());
                // Fixed lengths, so the copies are inlined (not a memcpy call).
                if full {
                    buf.extend_from_slice(&rec);
                } else {
                    buf.extend_from_slice(&rec[..13]);
                }
            }
            if buf.len() > 1 << 16 {
                w.write_all(&buf)?;
                buf.clear();
            }
        }
        w.write_all(&buf)
    })
}

/// Writes an OBJ of `r` (module doc).
pub fn write_obj(r: &ResultView, path: &Path) -> std::io::Result<()> {
    write_atomic_with(path, |w| {
        writeln!(
            w,
            "# septa {} result: {} patches (groups patch_<p>_<names of its labels>, or patch_<p>_labels_<a>_<b>), {} chains (l), {} corners (p)",
            r.mode,
            r.patch_labels.len().max(r.patch.iter().map(|&p| p as usize + 1).max().unwrap_or(0)),
            r.chains.len(),
            r.corners.len()
        )?;
        let mut line = String::with_capacity(64);
        use std::fmt::Write as _;
        for p in r.points.iter() {
            line.clear();
            writeln!(line, "v {} {} {}", p[0], p[1], p[2]).unwrap();
            w.write_all(line.as_bytes())?;
        }
        let patches = r.patch.iter().map(|&p| p as usize + 1).max().unwrap_or(0).max(r.patch_labels.len());
        // Polygons grouped by patch without sorting: a counting pass.
        let mut start = vec![0usize; patches + 1];
        for &p in r.patch.iter() {
            start[p as usize + 1] += 1;
        }
        for i in 0..patches {
            start[i + 1] += start[i];
        }
        let mut order = vec![0u32; r.num_faces()];
        let mut next = start.clone();
        for (f, &p) in r.patch.iter().enumerate() {
            order[next[p as usize]] = f as u32;
            next[p as usize] += 1;
        }
        for p in 0..patches {
            let labels = r.patch_labels.get(p).copied().unwrap_or([-1, -1]);
            writeln!(w, "g {}", r.names.patch_name(r.mode, p, labels))?;
            for &f in &order[start[p]..start[p + 1]] {
                line.clear();
                line.push('f');
                for &v in r.face(f as usize) {
                    write!(line, " {}", v + 1).unwrap();
                }
                line.push('\n');
                w.write_all(line.as_bytes())?;
            }
        }
        for (c, chain) in r.chains.iter().enumerate() {
            writeln!(w, "g chain_{c}")?;
            line.clear();
            line.push('l');
            for &v in chain {
                write!(line, " {}", v + 1).unwrap();
            }
            line.push('\n');
            w.write_all(line.as_bytes())?;
        }
        if !r.corners.is_empty() {
            line.clear();
            line.push_str("g corners\np");
            for &v in r.corners.iter() {
                write!(line, " {}", v + 1).unwrap();
            }
            line.push('\n');
            w.write_all(line.as_bytes())?;
        }
        Ok(())
    })
}

/// A colour per patch (golden-ratio hue walk).
pub fn patch_colour(p: u32) -> [u8; 3] {
    let h = (p as f64 * 0.618_033_988_749_895).fract() * 6.0;
    let x = 1.0 - (h % 2.0 - 1.0).abs();
    let (r, g, b) = match h as u32 {
        0 => (1.0, x, 0.0),
        1 => (x, 1.0, 0.0),
        2 => (0.0, 1.0, x),
        3 => (0.0, x, 1.0),
        4 => (x, 0.0, 1.0),
        _ => (1.0, 0.0, x),
    };
    let s = |v: f64| (55.0 + 200.0 * v) as u8;
    [s(r), s(g), s(b)]
}
