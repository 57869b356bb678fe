//! `.npy` label volumes of integers or booleans read straight from the file
//! into the labels: the header is parsed (and checked) by npyz, then the data
//! is decoded a 64 KiB chunk at a time. Reading the whole file into memory
//! first and converting it element by element through npyz's generic reader
//! took about a tenth of `septa labels` on a 128^3 volume (a second copy of
//! the volume to fault in, and a call per voxel).
//!
//! Anything else (floats, strings, structures, other axis counts, data
//! shorter than the shape, unsigned values above `i64::MAX`, booleans not 0
//! or 1) is left to the general reader, so its errors stay as they were.

use std::io::{BufReader, Read};
use std::path::Path;

use npyz::{DType, Endianness, NpyHeader, Order, TypeChar};

/// How one element is stored: its size in bytes, its kind and byte order.
#[derive(Clone, Copy)]
struct Element {
    size: usize,
    kind: Kind,
    big: bool,
}

#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Signed,
    Unsigned,
    Bool,
}

impl Element {
    fn of(header: &NpyHeader) -> Option<Element> {
        let DType::Plain(ts) = header.dtype() else { return None };
        let size = usize::try_from(ts.size_field()).ok()?;
        let kind = match (ts.type_char(), size) {
            (TypeChar::Int, 1 | 2 | 4 | 8) => Kind::Signed,
            (TypeChar::Uint, 1 | 2 | 4 | 8) => Kind::Unsigned,
            (TypeChar::Bool, 1) => Kind::Bool,
            _ => return None,
        };
        Some(Element { size, kind, big: ts.endianness() == Endianness::Big })
    }

    /// Appends the labels of whole elements `bytes`; `None` at a value the
    /// general reader refuses (an unsigned 64-bit value above `i64::MAX`, a
    /// boolean byte other than 0 or 1). One conversion per element type, in
    /// an `extend` of known length (no capacity test per element); the
    /// refused values are looked for afterwards.
    fn decode_into(self, bytes: &[u8], out: &mut Vec<i64>) -> Option<()> {
        use Kind::*;
        let from = out.len();
        match (self.size, self.kind, self.big) {
            (1, Signed, _) => each(bytes, out, |b: [u8; 1]| i8::from_le_bytes(b) as i64),
            (1, Unsigned | Bool, _) => each(bytes, out, |b: [u8; 1]| b[0] as i64),
            (2, Signed, false) => each(bytes, out, |b| i16::from_le_bytes(b) as i64),
            (2, Signed, true) => each(bytes, out, |b| i16::from_be_bytes(b) as i64),
            (2, Unsigned, false) => each(bytes, out, |b| u16::from_le_bytes(b) as i64),
            (2, Unsigned, true) => each(bytes, out, |b| u16::from_be_bytes(b) as i64),
            (4, Signed, false) => each(bytes, out, |b| i32::from_le_bytes(b) as i64),
            (4, Signed, true) => each(bytes, out, |b| i32::from_be_bytes(b) as i64),
            (4, Unsigned, false) => each(bytes, out, |b| u32::from_le_bytes(b) as i64),
            (4, Unsigned, true) => each(bytes, out, |b| u32::from_be_bytes(b) as i64),
            // Unsigned 64-bit values read as their bits: above i64::MAX is negative.
            (8, Signed | Unsigned, false) => each(bytes, out, i64::from_le_bytes),
            (8, Signed | Unsigned, true) => each(bytes, out, i64::from_be_bytes),
            _ => return None,
        }
        let refused = match (self.size, self.kind) {
            (8, Unsigned) => out[from..].iter().any(|&x| x < 0),
            (_, Bool) => out[from..].iter().any(|&x| x > 1),
            _ => false,
        };
        (!refused).then_some(())
    }
}

fn each<const N: usize>(bytes: &[u8], out: &mut Vec<i64>, label: impl Fn([u8; N]) -> i64) {
    out.extend(bytes.chunks_exact(N).map(|b| label(b.try_into().expect("N bytes"))));
}

/// The volume's shape, its labels in the file's order and whether that
/// order is Fortran's, or `None` when the general reader must decide
/// (see the module doc). I/O errors also give `None`: the general reader
/// reports them with its own words.
pub(crate) fn read(path: &Path) -> Option<([usize; 3], Vec<i64>, bool)> {
    let file = crate::io::files::input::open_regular(path).ok()?;
    let available = file.metadata().ok()?.len();
    let mut r = BufReader::with_capacity(1 << 16, file);
    let header = NpyHeader::from_reader(&mut r).ok()?;
    let el = Element::of(&header)?;
    let dims = header.shape();
    if dims.len() != 3 {
        return None;
    }
    let axis = |a: usize| usize::try_from(dims[a]).ok();
    let shape = [axis(0)?, axis(1)?, axis(2)?];
    let count = shape.iter().try_fold(1usize, |a, &d| a.checked_mul(d))?;
    let need = count.checked_mul(el.size)?;
    if (need as u64) > available {
        return None; // truncated: the general reader says so
    }
    // The data goes from the file straight into `chunk`: through the
    // `BufReader` every byte would be copied twice (a chunk's read after the
    // header straddles the reader's buffer, which then refills itself).
    let rest = r.buffer().to_vec();
    let mut r = rest.as_slice().chain(r.into_inner());
    let mut labels = Vec::with_capacity(count);
    let mut chunk = vec![0u8; (1 << 16) / el.size * el.size];
    let mut left = need;
    while left > 0 {
        let take = left.min(chunk.len());
        let part = &mut chunk[..take];
        r.read_exact(part).ok()?;
        el.decode_into(part, &mut labels)?;
        left -= part.len();
    }
    Some((shape, labels, header.order() == Order::Fortran))
}
