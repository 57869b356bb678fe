//! `network.npz`: a [`ResultView`] as a numpy archive (uncompressed zip of
//! `.npy` arrays), readable with `numpy.load` alone and fast to load: no
//! text is parsed, each array is one contiguous block.
//!
//! Arrays (integers `<i8`, coordinates `<f8`; ragged lists as CSR pairs
//! `*_offsets` (n + 1) / `*_indices`):
//! - `points` (#V, 3); `offsets` (#F + 1), `indices`: the polygons;
//! - `patch` (#F), `labels` (#F, 2), `cells` (#F, 2): per polygon (vocabulary
//!   in `result.rs`);
//! - `patch_labels` (#P, 2);
//! - `chain_offsets`/`chain_indices` (vertex paths), `chain_patch_offsets`/
//!   `chain_patch_indices` (patches around each chain), `corners`;
//! - `shell_offsets`/`shell_indices` (half-patches), `cell_shell_offsets`/
//!   `cell_shell_indices`, `cell_labels` (#C, L);
//! - `cell_volume` (#C), `patch_area` (#P), `chain_length` (#chains),
//!   float64, when measured (`crate::measure`; NaN: a cell not closed);
//! - `meta`: a unicode scalar holding JSON `{"format": "septa-result",
//!   "version": 1, "mode", "functions", "names", "counts", "seconds"}`.

use std::io::{Seek, Write};
use std::path::Path;

use crate::io::files::atomic::write_atomic_with;
use crate::io::writers::result::ResultView;

/// Version of the archive layout (in `meta`).
pub const NPZ_VERSION: u32 = 1;

/// The `.npy` header (format 1.0, padded so the data is 64-byte aligned
/// relative to the member's start).
fn npy_header(descr: &str, shape: &[usize]) -> Vec<u8> {
    let shape = match shape.len() {
        0 => "()".to_string(),
        1 => format!("({},)", shape[0]),
        _ => format!("({})", shape.iter().map(|s| s.to_string()).collect::<Vec<_>>().join(", ")),
    };
    let mut dict = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    let total = 10 + dict.len() + 1;
    dict.push_str(&" ".repeat((64 - total % 64) % 64));
    dict.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(dict.len() as u16).to_le_bytes());
    out.extend_from_slice(dict.as_bytes());
    out
}

struct Npz<W: Write + Seek> {
    zip: zip::ZipWriter<W>,
}

impl<W: Write + Seek> Npz<W> {
    fn member(&mut self, name: &str, descr: &str, shape: &[usize], bytes: usize) -> std::io::Result<()> {
        let options = zip::write::SimpleFileOptions::default()
            .compression_method(zip::CompressionMethod::Stored)
            .large_file(bytes > (u32::MAX as usize) / 2);
        self.zip.start_file(format!("{name}.npy"), options).map_err(std::io::Error::other)?;
        self.zip.write_all(&npy_header(descr, shape))
    }

    fn i64s(&mut self, name: &str, shape: &[usize], xs: impl Iterator<Item = i64>) -> std::io::Result<()> {
        let n: usize = shape.iter().product();
        self.member(name, "<i8", shape, n * 8)?;
        let mut buf = Vec::with_capacity(1 << 16);
        let mut written = 0usize;
        for x in xs {
            buf.extend_from_slice(&x.to_le_bytes());
            written += 1;
            if buf.len() >= 1 << 16 {
                self.zip.write_all(&buf)?;
                buf.clear();
            }
        }
        debug_assert_eq!(written, n, "{name}: shape and data disagree");
        self.zip.write_all(&buf)
    }

    fn f64s(&mut self, name: &str, xs: &[f64]) -> std::io::Result<()> {
        self.member(name, "<f8", &[xs.len()], xs.len() * 8)?;
        let bytes: Vec<u8> = xs.iter().flat_map(|x| x.to_le_bytes()).collect();
        self.zip.write_all(&bytes)
    }

    /// A ragged list as `NAME_offsets` / `NAME_indices`.
    fn csr(&mut self, name: &str, lists: &[Vec<u32>]) -> std::io::Result<()> {
        let mut at = 0i64;
        let offsets = std::iter::once(0).chain(lists.iter().map(|l| {
            at += l.len() as i64;
            at
        }));
        self.i64s(&format!("{name}_offsets"), &[lists.len() + 1], offsets)?;
        let n: usize = lists.iter().map(|l| l.len()).sum();
        self.i64s(&format!("{name}_indices"), &[n], lists.iter().flatten().map(|&x| x as i64))
    }
}

/// Writes `r` as `path` (module doc); `meta` is extra JSON (counts,
/// seconds) merged into the `meta` member.
pub fn write_npz(r: &ResultView, path: &Path, meta: &serde_json::Value) -> std::io::Result<()> {
    write_atomic_with(path, |w| {
        let mut z = Npz { zip: zip::ZipWriter::new(w) };
        let (np, nf) = (r.points.len(), r.num_faces());
        z.member("points", "<f8", &[np, 3], np * 24)?;
        let mut buf = Vec::with_capacity(1 << 16);
        for p in r.points.iter() {
            for x in p {
                buf.extend_from_slice(&x.to_le_bytes());
            }
            if buf.len() >= 1 << 16 {
                z.zip.write_all(&buf)?;
                buf.clear();
            }
        }
        z.zip.write_all(&buf)?;
        z.i64s("offsets", &[nf + 1], r.face_start.iter().map(|&x| x as i64))?;
        z.i64s("indices", &[r.face_verts.len()], r.face_verts.iter().map(|&x| x as i64))?;
        z.i64s("patch", &[nf], r.patch.iter().map(|&x| x as i64))?;
        z.i64s("labels", &[nf, 2], r.labels.iter().flatten().map(|&x| x as i64))?;
        z.i64s("cells", &[nf, 2], r.cells.iter().flatten().map(|&x| x as i64))?;
        z.i64s("patch_labels", &[r.patch_labels.len(), 2], r.patch_labels.iter().flatten().map(|&x| x as i64))?;
        z.csr("chain", &r.chains)?;
        z.csr("chain_patch", &r.chain_patches)?;
        z.i64s("corners", &[r.corners.len()], r.corners.iter().map(|&x| x as i64))?;
        z.csr("shell", &r.shells)?;
        z.csr("cell_shell", &r.cell_shells)?;
        let width = r.cell_labels.iter().map(|l| l.len()).max().unwrap_or(0);
        z.i64s(
            "cell_labels",
            &[r.cell_labels.len(), width],
            r.cell_labels.iter().flat_map(|l| (0..width).map(move |i| l.get(i).copied().unwrap_or(-1))),
        )?;
        let ms = &r.measures;
        for (name, xs) in
            [("cell_volume", &ms.cell_volume), ("patch_area", &ms.patch_area), ("chain_length", &ms.chain_length)]
        {
            if !xs.is_empty() {
                z.f64s(name, xs)?;
            }
        }
        let mut m = serde_json::json!({
            "format": "septa-result", "version": NPZ_VERSION, "mode": r.mode, "functions": r.functions,
        });
        if !r.names.is_empty() {
            m["names"] = r.names.to_json();
        }
        if let (Some(m), Some(extra)) = (m.as_object_mut(), meta.as_object()) {
            for (k, v) in extra {
                m.insert(k.clone(), v.clone());
            }
        }
        let text = m.to_string();
        let chars: Vec<char> = text.chars().collect();
        z.member("meta", &format!("<U{}", chars.len().max(1)), &[], chars.len() * 4)?;
        let mut utf32: Vec<u8> = chars.iter().flat_map(|&c| (c as u32).to_le_bytes()).collect();
        if chars.is_empty() {
            utf32.extend_from_slice(&[0; 4]);
        }
        z.zip.write_all(&utf32)?;
        z.zip.finish().map_err(std::io::Error::other)?;
        Ok(())
    })
}
