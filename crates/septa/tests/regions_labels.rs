//! Label volumes: the fast path (curve triples picked per edge, no list of
//! every label triple) writes the same files, byte for byte, as the path
//! that lists every triple as a curve of interest (issue 17).

use std::path::PathBuf;

use septa::io::regions_out;
use septa::regions::{label_surfaces, label_surfaces_listing_triples, RegionSurfaces};

/// A small deterministic generator (no dependency): xorshift64*.
struct Rng(u64);

impl Rng {
    fn next(&mut self, n: u64) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 33) % n
    }
}

/// The written files, without stage timings (the only run-dependent part).
fn files(r: &RegionSurfaces, name: &str) -> Vec<(String, Vec<u8>)> {
    let mut r = r.clone();
    r.seconds.clear();
    r.network.seconds.clear();
    let dir: PathBuf = std::env::temp_dir().join(format!("septa-regions-labels-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    regions_out::write(&r, &dir).unwrap();
    let mut out: Vec<(String, Vec<u8>)> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (e.file_name().to_string_lossy().into_owned(), std::fs::read(e.path()).unwrap())
        })
        .collect();
    out.sort();
    std::fs::remove_dir_all(&dir).unwrap();
    out
}

/// Both paths on one volume; returns the number of curves.
fn same(name: &str, labels: &[i64], shape: [usize; 3], sigma: f64) -> usize {
    let fast = label_surfaces(labels, shape, sigma).unwrap();
    let listed = label_surfaces_listing_triples(labels, shape, sigma).unwrap();
    let (a, b) = (files(&fast, &format!("{name}-fast")), files(&listed, &format!("{name}-listed")));
    assert_eq!(a.iter().map(|f| &f.0).collect::<Vec<_>>(), b.iter().map(|f| &f.0).collect::<Vec<_>>(), "{name}");
    assert!(!a.is_empty(), "{name}: nothing written");
    for ((file, x), (_, y)) in a.iter().zip(&b) {
        assert!(x == y, "{name}: {file} differs between the fast and the listing path");
    }
    fast.curves.len()
}

#[test]
fn fast_label_path_writes_the_same_bytes_as_listing_every_triple() {
    let mut curves = 0;
    // Random labels: many labels, many triples and quadruples per tet.
    for (seed, n, k) in [(1u64, 6usize, 7u64), (2, 5, 20), (3, 4, 3)] {
        let mut rng = Rng(0x9E37_79B9_7F4A_7C15 ^ seed);
        let labels: Vec<i64> = (0..n * n * n).map(|_| rng.next(k) as i64 * 3 - 10).collect();
        curves += same(&format!("random{seed}"), &labels, [n, n, n], 0.0);
    }
    // Tiny volumes: one cube; two labels only (no triple); anisotropic.
    same("cube", &[0, 1, 2, 3, 1, 2, 3, 0], [2, 2, 2], 0.0);
    same("two", &[5, 5, 7, 7, 5, 7, 7, 5], [2, 2, 2], 0.0);
    let aniso: Vec<i64> = (0..2 * 3 * 5).map(|v| ((v * 7) % 4) as i64).collect();
    curves += same("aniso", &aniso, [2, 3, 5], 0.0);
    // Blocks of labels meeting along straight lines (ties of whole faces
    // of the indicators), and the same smoothed.
    let n = 8;
    let blocks: Vec<i64> = (0..n * n * n).map(|v| ((v / (n * n)) * 2 / n + 2 * ((v / n % n) * 2 / n)) as i64).collect();
    curves += same("blocks", &blocks, [n, n, n], 0.0);
    curves += same("blocks-smoothed", &blocks, [n, n, n], 0.7);
    assert!(curves > 0, "the volumes must have curves for the comparison to mean anything");
}
