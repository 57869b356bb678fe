//! Generation of the look-up tables by running the incremental construction
//! (Du et al. Sec. 6: "created automatically by running the incremental
//! construction algorithm for every combination of vertex signs and every
//! combination of edge predicates").
//!
//! For every main index the corner signs are realised by sampled values
//! (infeasible MI orderings, e.g. `f0 > f1 > f2 > f0`, are skipped); each
//! sample is built incrementally and filed under its branch. Two samples
//! with the same branch must give the identical complex, which this
//! generator asserts: it is the proof that signs alone decide the result.

use std::collections::HashMap;
use std::fmt::Write;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::lookup::{branch_vertex, main_index};
use super::predicate::Predicates;
use super::types::{Complex, Mode, NONE};
use super::Options;

const TET_EDGES: [[usize; 2]; 6] = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]];

/// Sample values realising the corner signs of `index`, or `None` if infeasible.
fn realise(mode: Mode, k: usize, index: usize, rng: &mut ChaCha8Rng) -> Option<Vec<[f64; 4]>> {
    let mut v = vec![[0.0; 4]; k];
    match mode {
        Mode::Ia => {
            for (f, row) in v.iter_mut().enumerate() {
                for (c, x) in row.iter_mut().enumerate() {
                    let positive = index >> (f * 4 + c) & 1 == 1;
                    let m: f64 = rng.gen_range(0.01..1.0);
                    *x = if positive { m } else { -m };
                }
            }
        }
        Mode::Mi => {
            let pairs: Vec<(usize, usize)> = (0..k).flat_map(|a| (a + 1..k).map(move |b| (a, b))).collect();
            for c in 0..4 {
                // Rank functions by how many others they beat; a consistent
                // strict order has ranks 0..k exactly.
                let mut wins = vec![0usize; k];
                for (j, &(a, b)) in pairs.iter().enumerate() {
                    let a_wins = index >> (c * pairs.len() + j) & 1 == 1;
                    wins[if a_wins { a } else { b }] += 1;
                }
                let mut sorted = wins.clone();
                sorted.sort_unstable();
                if sorted != (0..k).collect::<Vec<_>>() {
                    return None;
                }
                let mut levels: Vec<f64> = (0..k).map(|_| rng.gen_range(-1.0..1.0)).collect();
                levels.sort_by(f64::total_cmp);
                for f in 0..k {
                    v[f][c] = levels[wins[f]];
                }
            }
        }
    }
    Some(v)
}

/// Tet edges whose crossing order is not decided by the corner signs.
fn ambiguous_edges(mode: Mode, k: usize, values: &[[f64; 4]]) -> Vec<usize> {
    let changes = |g: &dyn Fn(usize) -> f64, [a, b]: [usize; 2]| (g(a) > 0.0) != (g(b) > 0.0);
    (0..6)
        .filter(|&e| match (mode, k) {
            (Mode::Ia, 2) => changes(&|c| values[0][c], TET_EDGES[e]) && changes(&|c| values[1][c], TET_EDGES[e]),
            (Mode::Mi, 3) => {
                changes(&|c| values[0][c] - values[1][c], TET_EDGES[e])
                    && changes(&|c| values[0][c] - values[2][c], TET_EDGES[e])
                    && changes(&|c| values[1][c] - values[2][c], TET_EDGES[e])
            }
            _ => false,
        })
        .collect()
}

struct Generated {
    main: Vec<u32>,
    data: Vec<u32>,
}

fn generate_table(mode: Mode, k: usize, samples: usize, seed: u64) -> Generated {
    let bits = match mode {
        Mode::Ia => 4 * k,
        Mode::Mi => 4 * k * (k - 1) / 2,
    };
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut main = vec![NONE; 1 << bits];
    let mut data: Vec<u32> = Vec::new();
    let mut templates: HashMap<Vec<u32>, u32> = HashMap::new();
    let mut c = Complex::new();
    let opts = Options { float: false, lookup: false };
    for index in 0..1usize << bits {
        let Some(first) = realise(mode, k, index, &mut rng) else { continue };
        let edges = ambiguous_edges(mode, k, &first);
        let mut branches: Vec<Option<Vec<u32>>> = vec![None; 1 << edges.len()];
        for _ in 0..samples {
            let values = realise(mode, k, index, &mut rng).unwrap();
            debug_assert_eq!(main_index(mode, &values), Some(index));
            let preds = Predicates { values: &values, mode, float: false };
            let mut branch = 0;
            let mut zero = false;
            for (i, &e) in edges.iter().enumerate() {
                let (v, f) = branch_vertex(mode, k, e);
                let s = preds.vertex_sign(&v, preds.orient(&v), f);
                zero |= s == 0;
                branch |= ((s > 0) as usize) << i;
            }
            if zero {
                continue;
            }
            c.build(mode, &values, &opts).expect("exact construction never fails");
            let mut enc = Vec::new();
            c.encode(&mut enc);
            match &branches[branch] {
                Some(prev) => {
                    assert_eq!(prev, &enc, "{mode:?} k={k} index {index} branch {branch} is not decided by signs")
                }
                None => branches[branch] = Some(enc),
            }
        }
        main[index] = data.len() as u32;
        data.push(edges.len() as u32);
        data.extend(edges.iter().map(|&e| e as u32));
        let slots = data.len();
        data.extend(std::iter::repeat(NONE).take(branches.len()));
        for (b, enc) in branches.into_iter().enumerate() {
            if let Some(enc) = enc {
                let next = data.len() as u32;
                let offset = *templates.entry(enc.clone()).or_insert_with(|| {
                    data.extend(&enc);
                    next
                });
                data[slots + b] = offset;
            }
        }
    }
    Generated { main, data }
}

fn write_array(out: &mut String, name: &str, v: &[u32]) {
    writeln!(out, "static {name}: [u32; {}] = [", v.len()).unwrap();
    for chunk in v.chunks(16) {
        let line: Vec<String> = chunk.iter().map(|x| if *x == NONE { "N".into() } else { x.to_string() }).collect();
        writeln!(out, "    {},", line.join(", ")).unwrap();
    }
    writeln!(out, "];").unwrap();
}

/// The Rust source of `lookup_table.rs`.
#[doc(hidden)]
pub fn generate_source() -> String {
    let mut out = String::new();
    out.push_str(
        "//! @generated by `septa::complex::lookup_gen::generate_source`; do not edit.\n\
         //! Regenerate: `SEPTA_BLESS=1 cargo test -p septa --release --test complex lookup_tables::`.\n\n\
         use super::lookup::Table;\n\nconst N: u32 = u32::MAX;\n\n",
    );
    for (name, mode, k, samples, seed) in [
        ("IA1", Mode::Ia, 1, 4, 1),
        ("IA2", Mode::Ia, 2, 300, 2),
        ("MI2", Mode::Mi, 2, 4, 3),
        ("MI3", Mode::Mi, 3, 300, 4),
    ] {
        let g = generate_table(mode, k, samples, seed);
        writeln!(out, "pub(crate) static {name}: Table = Table {{ main: &{name}_MAIN, data: &{name}_DATA }};").unwrap();
        write_array(&mut out, &format!("{name}_MAIN"), &g.main);
        write_array(&mut out, &format!("{name}_DATA"), &g.data);
        out.push('\n');
    }
    out
}
