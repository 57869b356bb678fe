//! `read_label_volume` on `.npy` files: integer and boolean volumes are read
//! straight from the file (not through the general array reader); the
//! labels, and the errors for files the general reader refuses, must be the
//! same as that reader's in every dtype, byte order and axis order.
use std::path::PathBuf;

use proptest::prelude::*;
use septa::io::{parse_npy, read_label_volume, NpyArray};

use super::readers_fuzz::npy;

/// The dtypes read directly: (descr, item size).
const DTYPES: [(&str, usize); 15] = [
    ("|i1", 1),
    ("|u1", 1),
    ("|b1", 1),
    ("<i2", 2),
    (">i2", 2),
    ("<u2", 2),
    (">u2", 2),
    ("<i4", 4),
    (">i4", 4),
    ("<u4", 4),
    (">u4", 4),
    ("<i8", 8),
    (">i8", 8),
    ("<u8", 8),
    (">u8", 8),
];

fn temp_file(bytes: &[u8], tag: &str) -> PathBuf {
    let p = std::env::temp_dir().join(format!("septa-npy-volume-{}-{tag}.npy", std::process::id()));
    std::fs::write(&p, bytes).unwrap();
    p
}

/// What the general reader makes of the same bytes: C-order labels of a
/// 3-axis integer array, or its error.
fn general(bytes: &[u8]) -> Result<([usize; 3], Vec<i64>), String> {
    match parse_npy(bytes)? {
        NpyArray::I64(s, d) if s.len() == 3 => Ok(([s[0], s[1], s[2]], d)),
        other => Err(format!("not a 3-axis integer array: {:?}", other.shape())),
    }
}

/// Reads `bytes` as a file and checks it against [`general`]; returns
/// whether the volume was read.
fn same_as_general(bytes: &[u8], tag: &str) -> bool {
    let path = temp_file(bytes, tag);
    let got = read_label_volume(&path);
    std::fs::remove_file(&path).unwrap();
    match (general(bytes), got) {
        (Ok((shape, labels)), Ok(v)) => {
            assert_eq!((v.shape, &v.labels), (shape, &labels), "{tag}");
            true
        }
        (Err(e), Err(g)) => {
            // Refused by both, in the general reader's words.
            if !e.starts_with("not a 3-axis") {
                assert_eq!(g, format!("{}: {e}", path.display()), "{tag}");
            }
            false
        }
        (want, got) => panic!("{tag}: general reader {want:?}, read_label_volume {got:?}"),
    }
}

#[test]
fn every_integer_dtype_and_order_reads_as_the_general_reader() {
    let shape = [3, 2, 4];
    for (descr, size) in DTYPES {
        for fortran in [false, true] {
            // Distinct bytes per element, within 0/1 for booleans.
            let data: Vec<u8> = (0..24 * size)
                .map(|i| if descr == "|b1" { (i % 3 == 0) as u8 } else { (i * 37 % 251) as u8 })
                .collect();
            let data = if descr.ends_with("u8") {
                // Keep unsigned 64-bit values below 2^63 (above it is an error, tested below).
                data.chunks(8)
                    .flat_map(|c| {
                        let mut c = c.to_vec();
                        let top = if descr.starts_with('<') { 7 } else { 0 };
                        c[top] &= 0x7f;
                        c
                    })
                    .collect()
            } else {
                data
            };
            let tag = format!("{descr}-{fortran}");
            assert!(same_as_general(&npy(descr, fortran, &shape, &data), &tag), "{tag} not read");
        }
    }
}

#[test]
fn refused_files_keep_the_general_readers_errors() {
    // Truncated data, an unsigned value above i64::MAX, a boolean byte 2.
    assert!(!same_as_general(&npy("<i4", false, &[2, 2, 2], &[0; 31]), "truncated"));
    let mut big = vec![0u8; 64];
    big[7] = 0x80;
    assert!(!same_as_general(&npy("<u8", false, &[2, 2, 2], &big), "u8-high"));
    let mut b = vec![0u8; 8];
    b[5] = 2;
    let _ = same_as_general(&npy("|b1", false, &[2, 2, 2], &b), "bool-2");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, failure_persistence: None, ..ProptestConfig::default() })]

    /// Random dtypes, orders, shapes and bytes, the data sometimes one byte short or long.
    #[test]
    fn random_volumes_read_as_the_general_reader(
        dtype in 0..DTYPES.len(),
        fortran in any::<bool>(),
        shape in prop::array::uniform3(1usize..5),
        extra in -1i64..2,
        seed in any::<u64>(),
    ) {
        let (descr, size) = DTYPES[dtype];
        let n = (shape.iter().product::<usize>() * size) as i64 + extra;
        let mut x = seed;
        let data: Vec<u8> = (0..n.max(0)).map(|_| {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (x >> 56) as u8
        }).collect();
        same_as_general(&npy(descr, fortran, &shape, &data), "random");
    }
}
