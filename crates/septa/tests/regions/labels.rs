//! Label volumes: the fast path (curve triples picked per edge, no list of
//! every label triple) writes the same files, byte for byte, as the path
//! that lists every triple as a curve of interest.

use crate::common;

use std::path::PathBuf;

use septa::complex::Mode;
use septa::grid::{BoxGrid, Grid, Split};
use septa::network::{compute, NetworkOptions};

use septa::io::write_regions;
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
    write_regions(&r, &dir).unwrap();
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
    // Larger than a block (16 cubes): blocks of one label are skipped by
    // the fast path's bounds; two balls and a slab cross block borders.
    let shape = [36, 20, 18];
    let big: Vec<i64> = (0..shape.iter().product::<usize>())
        .map(|v| {
            let (i, j, k) =
                ((v / (shape[1] * shape[2])) as f64, (v / shape[2] % shape[1]) as f64, (v % shape[2]) as f64);
            let ball = |c: [f64; 3], r: f64| (i - c[0]).powi(2) + (j - c[1]).powi(2) + (k - c[2]).powi(2) < r * r;
            if ball([14.0, 9.0, 8.0], 6.5) {
                4
            } else if ball([19.0, 11.0, 9.0], 5.0) {
                9
            } else if i > 30.0 {
                2
            } else {
                0
            }
        })
        .collect();
    curves += same("big", &big, shape, 0.0);
    assert!(curves > 0, "the volumes must have curves for the comparison to mean anything");
}

/// Label indicators are the case where materials absent from a tet tie at
/// 0 and no single material dominates them: the network leaves them out of
/// a tet's active functions when the average of the corner winners is
/// proven above them (complex/dominated.rs), so 2- and 3-label tets reach
/// the templates and tables. The network must equal, byte for byte, the
/// one with every such function active and the incremental construction.
#[test]
fn dropping_absent_labels_changes_no_byte_of_the_network() {
    let n = 7;
    let mut rng = Rng(0xD1B5_4A32_D192_ED03);
    // Few labels per neighbourhood (blocks with random borders), many
    // labels mixed everywhere, and blocks ahead of a tied smooth field.
    let blocks: Vec<i64> = (0..n * n * n)
        .map(|v| {
            let (i, j, k) = (v / (n * n), v / n % n, v % n);
            ((i + rng.next(2) as usize) / 3 + 3 * ((j + k + rng.next(2) as usize) / 4)) as i64
        })
        .collect();
    let mixed: Vec<i64> = (0..n * n * n).map(|_| rng.next(9) as i64).collect();
    let mut cases = Vec::new();
    for (name, labels) in [("blocks", blocks), ("mixed", mixed)] {
        let mut ids = labels.clone();
        ids.sort_unstable();
        ids.dedup();
        let k = ids.len();
        let mut values = vec![0.0; labels.len() * k];
        for (v, l) in labels.iter().enumerate() {
            values[v * k + ids.binary_search(l).unwrap()] = 1.0;
        }
        cases.push((name, k, values));
    }
    // A function below the maximum at every grid vertex that still wins
    // inside tets: with x = i/5, x and 1 - x are >= 0.6 at every grid
    // vertex but cross at 0.5 < 0.55 between i = 2 and 3. The winners'
    // average (0.5) is below it there, so it must stay active.
    let tent: Vec<f64> = (0..n * n * n)
        .flat_map(|v| {
            let x = (v / (n * n)) as f64 / 5.0;
            [x, 1.0 - x, 0.55]
        })
        .collect();
    cases.push(("tent", 3, tent));
    for (name, k, values) in cases {
        let m = (n - 1) as f64;
        let grid = Grid::Box(BoxGrid::new([n - 1; 3], [[0.0; 3], [m; 3]], Split::Five).unwrap());
        let mut texts = Vec::new();
        for (lookup, average) in [(true, true), (true, false), (false, false)] {
            let mut o = NetworkOptions::new(Mode::Mi);
            o.lookup = lookup;
            o.mi_average_domination = average;
            let net = compute(&grid, &values, k, &o).unwrap();
            assert!(!net.face_label.is_empty(), "{name}: empty network");
            texts.push(common::network_json(&net, &format!("labels-{name}-{lookup}-{average}")));
        }
        assert!(texts[0] == texts[1], "{name}: dropping dominated labels changed the network");
        assert!(texts[0] == texts[2], "{name}: the fast paths differ from the incremental network");
    }
}
