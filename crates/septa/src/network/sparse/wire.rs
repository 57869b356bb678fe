//! A block result as bytes (docs/distributed.md): what a worker
//! on another machine sends back for one block of a sparse job.
//!
//! Hand-written little-endian, versioned, with a checksum, so that the
//! layout is fixed by this file alone (no derive on the block's types) and
//! a truncated, corrupt or foreign payload is refused with a typed error
//! naming the byte offset and the field, never a panic. Decoding also
//! checks every index the merge will follow (vertex, polygon, region,
//! half-polygon, t-node), so even well-formed but inconsistent bytes cannot
//! make the merge index out of bounds.
//!
//! Layout (all integers little-endian; `len` is a u64 count):
//! `b"SEPTABLK"`, version u16, total length u64 (so a cut-off payload is
//! reported as truncated), then the job key (mode u8, split u8,
//! functions u32, resolution 3 x u64, bounds 6 x f64 bits, block u64), the
//! block (index u64, clean u8, sampled vertices u64), the `BlockOut`
//! fields in declaration order, and an FNV-1a 64 checksum of everything
//! before it. Floats travel as their bits, so a decoded block is
//! bit-identical to the encoded one.

use smallvec::SmallVec;

use super::run::{BlockResult, JobKey};
use crate::complex::Mode;
use crate::network::block::{BlockOut, FaceKey, HalfPoly, Label, SRef};
use crate::network::VKey;

const MAGIC: &[u8; 8] = b"SEPTABLK";
/// Version of the layout; bump it on any change.
pub const VERSION: u16 = 1;

/// Why bytes are not a block result.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum WireError {
    /// Not a Septa block result at all.
    #[error("not a septa block result (bad magic bytes)")]
    Magic,
    /// Written by another layout version.
    #[error("block result layout version {found}, this septa reads version {VERSION}")]
    Version {
        /// Version in the bytes.
        found: u16,
    },
    /// The bytes end before the field.
    #[error("block result truncated at byte {offset} (reading {field}, {len} bytes in all)")]
    Truncated {
        /// Where the field starts.
        offset: usize,
        /// The field being read.
        field: &'static str,
        /// Total length.
        len: usize,
    },
    /// The checksum does not match (bytes changed in transit or on disk).
    #[error("block result corrupt: checksum mismatch")]
    Checksum,
    /// A field holds an impossible value.
    #[error("block result invalid at byte {offset}: {field}: {message}")]
    Invalid {
        /// Where the field starts.
        offset: usize,
        /// The field.
        field: &'static str,
        /// What is wrong.
        message: String,
    },
}

fn fnv1a(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= b as u64;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

struct W(Vec<u8>);

impl W {
    fn u8(&mut self, x: u8) {
        self.0.push(x);
    }
    fn u16(&mut self, x: u16) {
        self.0.extend_from_slice(&x.to_le_bytes());
    }
    fn u32(&mut self, x: u32) {
        self.0.extend_from_slice(&x.to_le_bytes());
    }
    fn u64(&mut self, x: u64) {
        self.0.extend_from_slice(&x.to_le_bytes());
    }
    fn len(&mut self, n: usize) {
        self.u64(n as u64);
    }
    fn f64(&mut self, x: f64) {
        self.u64(x.to_bits());
    }
    fn face(&mut self, f: &FaceKey) {
        f.iter().for_each(|&x| self.u32(x));
    }
    fn vkey(&mut self, k: &VKey) {
        k.grid.iter().for_each(|&x| self.u32(x));
        k.funcs.iter().for_each(|&x| self.u16(x));
    }
    fn label(&mut self, l: &Label) {
        self.len(l.len());
        l.iter().for_each(|&x| self.u64(x));
    }
    fn sref(&mut self, r: &SRef) {
        match *r {
            SRef::Side(p, s) => {
                self.u8(0);
                self.u32(p);
                self.u8(s);
            }
            SRef::Half(h) => {
                self.u8(1);
                self.u32(h);
            }
            SRef::T(t) => {
                self.u8(2);
                self.u32(t);
            }
        }
    }
}

struct R<'a> {
    b: &'a [u8],
    at: usize,
}

impl<'a> R<'a> {
    fn take(&mut self, n: usize, field: &'static str) -> Result<&'a [u8], WireError> {
        if self.b.len() - self.at < n {
            return Err(WireError::Truncated { offset: self.at, field, len: self.b.len() });
        }
        self.at += n;
        Ok(&self.b[self.at - n..self.at])
    }
    fn u8(&mut self, field: &'static str) -> Result<u8, WireError> {
        Ok(self.take(1, field)?[0])
    }
    fn u16(&mut self, field: &'static str) -> Result<u16, WireError> {
        Ok(u16::from_le_bytes(self.take(2, field)?.try_into().unwrap()))
    }
    fn u32(&mut self, field: &'static str) -> Result<u32, WireError> {
        Ok(u32::from_le_bytes(self.take(4, field)?.try_into().unwrap()))
    }
    fn u64(&mut self, field: &'static str) -> Result<u64, WireError> {
        Ok(u64::from_le_bytes(self.take(8, field)?.try_into().unwrap()))
    }
    fn usize(&mut self, field: &'static str) -> Result<usize, WireError> {
        let at = self.at;
        let x = self.u64(field)?;
        usize::try_from(x).map_err(|_| self.invalid(at, field, format!("{x} does not fit this machine")))
    }
    fn f64(&mut self, field: &'static str) -> Result<f64, WireError> {
        Ok(f64::from_bits(self.u64(field)?))
    }
    fn invalid(&self, offset: usize, field: &'static str, message: String) -> WireError {
        WireError::Invalid { offset, field, message }
    }
    /// A count of items at least `item` bytes each: refused if the rest of
    /// the bytes cannot hold them (no huge allocation from a corrupt count).
    fn len(&mut self, item: usize, field: &'static str) -> Result<usize, WireError> {
        let at = self.at;
        let n = self.u64(field)?;
        let rest = (self.b.len() - self.at) as u64;
        if n.checked_mul(item as u64).is_none_or(|need| need > rest) {
            return Err(WireError::Truncated { offset: at, field, len: self.b.len() });
        }
        Ok(n as usize)
    }
    fn vec<T>(
        &mut self,
        item: usize,
        field: &'static str,
        mut f: impl FnMut(&mut Self) -> Result<T, WireError>,
    ) -> Result<Vec<T>, WireError> {
        let n = self.len(item, field)?;
        (0..n).map(|_| f(self)).collect()
    }
    fn face(&mut self, field: &'static str) -> Result<FaceKey, WireError> {
        Ok([self.u32(field)?, self.u32(field)?, self.u32(field)?])
    }
    fn vkey(&mut self, field: &'static str) -> Result<VKey, WireError> {
        let mut k = VKey { grid: [0; 4], funcs: [0; 4] };
        for g in &mut k.grid {
            *g = self.u32(field)?;
        }
        for f in &mut k.funcs {
            *f = self.u16(field)?;
        }
        Ok(k)
    }
    /// A region label with exactly `words` words (what the merge indexes).
    fn label(&mut self, words: usize, field: &'static str) -> Result<Label, WireError> {
        let at = self.at;
        let n = self.len(8, field)?;
        if n != words {
            return Err(self.invalid(at, field, format!("label of {n} words, expected {words}")));
        }
        let mut l: Label = SmallVec::with_capacity(n);
        for _ in 0..n {
            l.push(self.u64(field)?);
        }
        Ok(l)
    }
    fn sref(&mut self, field: &'static str) -> Result<SRef, WireError> {
        let at = self.at;
        match self.u8(field)? {
            0 => {
                let p = self.u32(field)?;
                match self.u8(field)? {
                    s @ (0 | 1) => Ok(SRef::Side(p, s)),
                    s => Err(self.invalid(at, field, format!("side {s} is not 0 or 1"))),
                }
            }
            1 => Ok(SRef::Half(self.u32(field)?)),
            2 => Ok(SRef::T(self.u32(field)?)),
            t => Err(self.invalid(at, field, format!("unknown side reference tag {t}"))),
        }
    }
}

impl BlockResult {
    /// The block result as bytes (see the module doc for the layout).
    pub fn to_bytes(&self) -> Vec<u8> {
        let j = &self.job;
        let BlockOut {
            keys,
            shared,
            points,
            poly_start,
            poly_verts,
            poly_label,
            poly_cells,
            halves,
            comp_label,
            comp_volume,
            contacts,
            unions,
            wedges,
            tnodes,
            open_t,
            active_tets,
            tets,
        } = &self.out;
        let mut w = W(Vec::with_capacity(128 + keys.len() * 48 + poly_verts.len() * 4));
        w.0.extend_from_slice(MAGIC);
        w.u16(VERSION);
        w.u64(0); // total length, patched below
        w.u8(match j.mode {
            Mode::Ia => 0,
            Mode::Mi => 1,
        });
        w.u8(j.split);
        w.u32(j.functions as u32);
        j.res.iter().for_each(|&r| w.len(r));
        j.bounds.iter().flatten().for_each(|&x| w.f64(x));
        w.len(j.block);
        w.len(self.index);
        w.u8(self.clean as u8);
        w.len(self.sampled_vertices);
        w.len(keys.len());
        keys.iter().for_each(|k| w.vkey(k));
        w.len(shared.len());
        shared.iter().for_each(|&s| w.u8(s as u8));
        w.len(points.len());
        points.iter().flatten().for_each(|&x| w.f64(x));
        w.len(poly_start.len());
        poly_start.iter().for_each(|&x| w.u32(x));
        w.len(poly_verts.len());
        poly_verts.iter().for_each(|&x| w.u32(x));
        w.len(poly_label.len());
        poly_label.iter().flatten().for_each(|&x| w.u16(x));
        w.len(poly_cells.len());
        poly_cells.iter().flatten().for_each(|&x| w.u32(x));
        w.len(halves.len());
        for h in halves {
            w.face(&h.face);
            w.len(h.verts.len());
            h.verts.iter().for_each(|&v| w.u32(v));
            w.u32(h.cell);
            w.u16(h.zero);
        }
        w.len(comp_label.len());
        comp_label.iter().for_each(|l| w.label(l));
        w.len(comp_volume.len());
        comp_volume.iter().for_each(|&x| w.f64(x));
        w.len(contacts.len());
        for (f, l, c) in contacts {
            w.face(f);
            w.label(l);
            w.u32(*c);
        }
        w.len(unions.len());
        for (a, b) in unions {
            w.sref(a);
            w.sref(b);
        }
        w.len(wedges.len());
        for (e, a, b) in wedges {
            w.u32(e[0]);
            w.u32(e[1]);
            w.sref(a);
            w.sref(b);
        }
        w.u32(*tnodes);
        w.len(open_t.len());
        for ((f, l, a, b), t) in open_t {
            w.face(f);
            w.label(l);
            w.vkey(a);
            w.vkey(b);
            w.u32(*t);
        }
        w.len(*active_tets);
        w.len(*tets);
        let total = (w.0.len() + 8) as u64;
        w.0[10..18].copy_from_slice(&total.to_le_bytes());
        let sum = fnv1a(&w.0);
        w.u64(sum);
        w.0
    }

    /// Reads a block result written by [`BlockResult::to_bytes`]; a clear
    /// [`WireError`] on anything else (never a panic).
    pub fn from_bytes(bytes: &[u8]) -> Result<BlockResult, WireError> {
        let mut r = R { b: bytes, at: 0 };
        if r.take(8, "magic").map_err(|_| WireError::Magic)? != MAGIC {
            return Err(WireError::Magic);
        }
        let found = r.u16("version")?;
        if found != VERSION {
            return Err(WireError::Version { found });
        }
        let total = r.u64("length")?;
        if (bytes.len() as u64) < total || bytes.len() < r.at + 8 {
            return Err(WireError::Truncated { offset: bytes.len(), field: "the block (length)", len: bytes.len() });
        }
        if bytes.len() as u64 > total {
            return Err(WireError::Invalid {
                offset: total as usize,
                field: "end",
                message: format!("{} bytes after the block", bytes.len() as u64 - total),
            });
        }
        let (body, sum) = bytes.split_at(bytes.len() - 8);
        if fnv1a(body) != u64::from_le_bytes(sum.try_into().unwrap()) {
            return Err(WireError::Checksum);
        }
        let mut r = R { b: body, at: r.at };
        let at = r.at;
        let mode = match r.u8("mode")? {
            0 => Mode::Ia,
            1 => Mode::Mi,
            m => return Err(r.invalid(at, "mode", format!("{m} is neither IA (0) nor MI (1)"))),
        };
        let split = r.u8("split")?;
        let functions = r.u32("functions")? as usize;
        let res = [r.usize("resolution")?, r.usize("resolution")?, r.usize("resolution")?];
        let mut bounds = [[0.0; 3]; 2];
        for c in bounds.iter_mut().flatten() {
            *c = r.f64("bounds")?;
        }
        let block = r.usize("block")?;
        let job = JobKey { mode, functions, res, bounds, split, block };
        let index = r.usize("index")?;
        let clean = r.u8("clean")? != 0;
        let sampled_vertices = r.usize("sampled vertices")?;
        let words = match mode {
            Mode::Ia => functions.div_ceil(64).max(1),
            Mode::Mi => 1,
        };

        let keys = r.vec(24, "keys", |r| r.vkey("keys"))?;
        let nv = keys.len();
        let at = r.at;
        let shared = r.vec(1, "shared", |r| r.u8("shared").map(|s| s != 0))?;
        let points = r.vec(24, "points", |r| Ok([r.f64("points")?, r.f64("points")?, r.f64("points")?]))?;
        if shared.len() != nv || points.len() != nv {
            return Err(r.invalid(
                at,
                "shared/points",
                format!("{} and {} entries for {nv} keys", shared.len(), points.len()),
            ));
        }
        let at = r.at;
        let poly_start = r.vec(4, "poly_start", |r| r.u32("poly_start"))?;
        let poly_verts = r.vec(4, "poly_verts", |r| r.u32("poly_verts"))?;
        let np = poly_start.len().saturating_sub(1);
        let monotone = poly_start.windows(2).all(|w| w[0] <= w[1]);
        if poly_start.first() != Some(&0) || !monotone || poly_start.last().copied() != Some(poly_verts.len() as u32) {
            return Err(r.invalid(at, "poly_start", "not offsets from 0 to the number of polygon vertices".into()));
        }
        if let Some(v) = poly_verts.iter().find(|&&v| v as usize >= nv) {
            return Err(r.invalid(at, "poly_verts", format!("vertex {v} of {nv}")));
        }
        let at = r.at;
        let poly_label = r.vec(4, "poly_label", |r| Ok([r.u16("poly_label")?, r.u16("poly_label")?]))?;
        let poly_cells = r.vec(8, "poly_cells", |r| Ok([r.u32("poly_cells")?, r.u32("poly_cells")?]))?;
        if poly_label.len() != np || poly_cells.len() != np {
            return Err(r.invalid(at, "poly_label/poly_cells", format!("lengths differ from {np} polygons")));
        }
        let at_halves = r.at;
        let halves = r.vec(32, "halves", |r| {
            let face = r.face("halves.face")?;
            let n = r.len(4, "halves.verts")?;
            let mut verts = SmallVec::with_capacity(n);
            for _ in 0..n {
                verts.push(r.u32("halves.verts")?);
            }
            Ok(HalfPoly { face, verts, cell: r.u32("halves.cell")?, zero: r.u16("halves.zero")? })
        })?;
        let at_comp = r.at;
        let comp_label = r.vec(8, "comp_label", |r| r.label(words, "comp_label"))?;
        let comp_volume = r.vec(8, "comp_volume", |r| r.f64("comp_volume"))?;
        let nc = comp_label.len();
        if comp_volume.len() != nc {
            return Err(r.invalid(at_comp, "comp_volume", format!("{} volumes for {nc} regions", comp_volume.len())));
        }
        if mode == Mode::Mi && comp_label.iter().any(|l| l[0] >= functions as u64) {
            return Err(r.invalid(at_comp, "comp_label", "a material is not a function".into()));
        }
        if poly_cells.iter().flatten().any(|&c| c as usize >= nc) {
            return Err(r.invalid(at, "poly_cells", format!("a region beyond the {nc} regions")));
        }
        for h in &halves {
            if h.verts.iter().any(|&v| v as usize >= nv) || h.cell as usize >= nc || h.zero as usize >= functions {
                return Err(r.invalid(at_halves, "halves", "a vertex, region or function out of range".into()));
            }
        }
        let at = r.at;
        let contacts =
            r.vec(20, "contacts", |r| Ok((r.face("contacts")?, r.label(words, "contacts")?, r.u32("contacts")?)))?;
        if contacts.iter().any(|c| c.2 as usize >= nc) {
            return Err(r.invalid(at, "contacts", format!("a region beyond the {nc} regions")));
        }
        let at_unions = r.at;
        let unions = r.vec(10, "unions", |r| Ok((r.sref("unions")?, r.sref("unions")?)))?;
        let at_wedges = r.at;
        let wedges =
            r.vec(18, "wedges", |r| Ok(([r.u32("wedges")?, r.u32("wedges")?], r.sref("wedges")?, r.sref("wedges")?)))?;
        let tnodes = r.u32("tnodes")?;
        let at = r.at;
        let open_t = r.vec(80, "open_t", |r| {
            let key = (r.face("open_t")?, r.label(words, "open_t")?, r.vkey("open_t")?, r.vkey("open_t")?);
            Ok((key, r.u32("open_t")?))
        })?;
        if open_t.iter().any(|o| o.1 >= tnodes) {
            return Err(r.invalid(at, "open_t", format!("a t-node beyond the {tnodes} t-nodes")));
        }
        let sref_ok = |s: &SRef| match *s {
            SRef::Side(p, _) => (p as usize) < np,
            SRef::Half(h) => (h as usize) < halves.len(),
            SRef::T(t) => t < tnodes,
        };
        if !unions.iter().all(|(a, b)| sref_ok(a) && sref_ok(b)) {
            return Err(r.invalid(at_unions, "unions", "a side reference out of range".into()));
        }
        if !wedges.iter().all(|(e, a, b)| (e[0] as usize) < nv && (e[1] as usize) < nv && sref_ok(a) && sref_ok(b)) {
            return Err(r.invalid(at_wedges, "wedges", "a vertex or side reference out of range".into()));
        }
        let active_tets = r.usize("active_tets")?;
        let tets = r.usize("tets")?;
        if r.at != body.len() {
            return Err(r.invalid(r.at, "end", format!("{} bytes after the block", body.len() - r.at)));
        }
        let out = BlockOut {
            keys,
            shared,
            points,
            poly_start,
            poly_verts,
            poly_label,
            poly_cells,
            halves,
            comp_label,
            comp_volume,
            contacts,
            unions,
            wedges,
            tnodes,
            open_t,
            active_tets,
            tets,
        };
        Ok(BlockResult { job, index, out, clean, sampled_vertices })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::{BoxGrid, Split};
    use crate::network::{finish_sparse, plan_sparse, run_block, NetworkOptions};
    use crate::scene::Primitive;

    fn job() -> (BoxGrid, Vec<Primitive>, NetworkOptions) {
        let g = BoxGrid::new([12; 3], [[-1.0; 3], [1.0; 3]], Split::Five).unwrap();
        let f = vec![
            Primitive::sphere([0.013, -0.007, 0.004], 0.61),
            Primitive::sphere([0.31, 0.27, -0.22], 0.43),
            Primitive::plane([0.01, 0.02, 0.03], [0.3, 0.5, 0.8]),
        ];
        let mut o = NetworkOptions::new(Mode::Ia);
        o.block = 4;
        (g, f, o)
    }

    #[test]
    fn round_trip_is_bit_identical() {
        let (g, f, o) = job();
        let plan = plan_sparse(&g, &f, &o).unwrap();
        assert!(!plan.kept.is_empty());
        let mut nonempty = 0;
        for &i in &plan.kept {
            let a = run_block(&g, &f, &o, i).unwrap();
            let bytes = a.to_bytes();
            let b = BlockResult::from_bytes(&bytes).unwrap();
            // Re-encoding the decoded block gives the same bytes: every field survived.
            assert_eq!(b.to_bytes(), bytes, "block {i}");
            assert_eq!((b.index, b.clean, b.sampled_vertices), (a.index, a.clean, a.sampled_vertices));
            assert!(b.job.same(&a.job));
            assert_eq!(format!("{:?}", a.out), format!("{:?}", b.out));
            nonempty += !a.out.poly_label.is_empty() as usize;
        }
        assert!(nonempty > 0);
    }

    #[test]
    fn truncated_and_corrupt_bytes_are_errors() {
        let (g, f, o) = job();
        let plan = plan_sparse(&g, &f, &o).unwrap();
        let i = *plan.kept.iter().max_by_key(|&&i| run_block(&g, &f, &o, i).unwrap().active_tets()).unwrap();
        let bytes = run_block(&g, &f, &o, i).unwrap().to_bytes();
        // Every prefix is refused.
        for n in (0..bytes.len()).step_by(7).chain([bytes.len() - 1]) {
            let e = BlockResult::from_bytes(&bytes[..n]).unwrap_err();
            assert!(matches!(e, WireError::Magic | WireError::Truncated { .. } | WireError::Checksum), "{n}: {e}");
        }
        // Any flipped byte is refused.
        for at in (0..bytes.len()).step_by(13) {
            let mut b = bytes.clone();
            b[at] ^= 0x5a;
            assert!(BlockResult::from_bytes(&b).is_err(), "flip at {at}");
        }
        let mut b = bytes.clone();
        b[8] = 9;
        assert_eq!(BlockResult::from_bytes(&b).unwrap_err(), WireError::Version { found: 9 });
        assert_eq!(BlockResult::from_bytes(b"hello").unwrap_err(), WireError::Magic);
        // A well-formed block whose indices are wrong (checksum recomputed) is refused too.
        let mut r = BlockResult::from_bytes(&bytes).unwrap();
        r.out.poly_verts[0] = r.out.keys.len() as u32;
        let e = BlockResult::from_bytes(&r.to_bytes()).unwrap_err();
        assert!(matches!(e, WireError::Invalid { field: "poly_verts", .. }), "{e}");
    }

    #[test]
    fn finish_refuses_missing_repeated_and_foreign_blocks_and_ignores_order() {
        let (g, f, o) = job();
        let plan = plan_sparse(&g, &f, &o).unwrap();
        let run_all = || plan.kept.iter().map(|&i| run_block(&g, &f, &o, i).unwrap()).collect::<Vec<_>>();
        let (local, _) = crate::network::compute_sparse(&g, &f, &o).unwrap();
        // Reversed completion order: same network.
        let mut rev = run_all();
        rev.reverse();
        let (net, stats) = finish_sparse(&g, &f, &o, &plan, rev).unwrap();
        assert_eq!((net.keys, net.face_verts, net.shells), (local.keys, local.face_verts, local.shells));
        assert_eq!(stats.sampled, plan.kept.len());
        let mut missing = run_all();
        missing.pop();
        let last = *plan.kept.last().unwrap();
        assert!(matches!(
            finish_sparse(&g, &f, &o, &plan, missing),
            Err(crate::network::NetworkError::BlockCount { ref missing, .. }) if missing == &[last]
        ));
        let mut twice = run_all();
        twice[0] = run_block(&g, &f, &o, plan.kept[1]).unwrap();
        assert!(matches!(
            finish_sparse(&g, &f, &o, &plan, twice),
            Err(crate::network::NetworkError::BlockCount { missing: ref m, .. }) if m == &[plan.kept[0]]
        ));
        let mut other = o.clone();
        other.mode = Mode::Mi;
        let mut foreign = run_all();
        foreign[0] = run_block(&g, &f, &other, plan.kept[0]).unwrap();
        assert!(matches!(
            finish_sparse(&g, &f, &o, &plan, foreign),
            Err(crate::network::NetworkError::ForeignBlock { index, .. }) if index == plan.kept[0]
        ));
        let e = run_block(&g, &f, &o, plan.blocks).unwrap_err();
        assert_eq!(e, crate::network::NetworkError::NoSuchBlock { index: plan.blocks, blocks: plan.blocks });
    }
}
