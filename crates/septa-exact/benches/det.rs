//! Micro-benchmark: ns per call of `det_sign::<N>` / `det_sign_diff::<N>`
//! against the naive floating-point sign measured in the same run, on
//! random and on near-degenerate matrices, with the filter hit rate.
//!
//! Run: `cargo bench -p septa-exact` (plain `std::time`, no harness);
//! `cargo bench -p septa-exact -- "near N=3"` runs the matching lines only.
#![allow(clippy::needless_range_loop)] // matrix code reads best with indices

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use septa_exact::{det_sign, det_sign_diff, det_sign_diff_f64_naive, det_sign_f64_naive, stats, Sign};
use std::hint::black_box;
use std::time::Instant;

const POOL: usize = 4096;

/// An MI input: the matrices `a` and `b` of `det(a - b)`.
type Pair<const N: usize> = ([[f64; N]; N], [[f64; N]; N]);

fn unit(r: &mut ChaCha8Rng) -> f64 {
    r.gen_range(-1.0..1.0)
}

fn random<const N: usize>(r: &mut ChaCha8Rng) -> [[f64; N]; N] {
    std::array::from_fn(|_| std::array::from_fn(|_| unit(r)))
}

/// Last row a rounded combination of the others plus a relative 2^-40 nudge.
fn near<const N: usize>(r: &mut ChaCha8Rng) -> [[f64; N]; N] {
    let mut m = random::<N>(r);
    if N > 1 {
        let c: [f64; N] = std::array::from_fn(|_| unit(r));
        for j in 0..N {
            let mut s = unit(r) * 2f64.powi(-40);
            for i in 0..N - 1 {
                s += c[i] * m[i][j];
            }
            m[N - 1][j] = s;
        }
    }
    m
}

/// Like `near` but nudged by 2^-70 only: below the filter's resolution,
/// so the expansion tier decides most of these.
fn tiny<const N: usize>(r: &mut ChaCha8Rng) -> [[f64; N]; N] {
    let mut m = random::<N>(r);
    if N > 1 {
        let c: [f64; N] = std::array::from_fn(|_| unit(r));
        for j in 0..N {
            let mut s = unit(r) * 2f64.powi(-70);
            for i in 0..N - 1 {
                s += c[i] * m[i][j];
            }
            m[N - 1][j] = s;
        }
    }
    m
}

/// Exactly singular small-integer matrices (two equal rows, rows scaled
/// by different powers of two): the exact tiers must decide these.
fn singular<const N: usize>(r: &mut ChaCha8Rng) -> [[f64; N]; N] {
    let mut m: [[f64; N]; N] = std::array::from_fn(|_| std::array::from_fn(|_| r.gen_range(-9i32..=9) as f64));
    if N > 1 {
        m[N - 1] = m[0].map(|x| x * 0.5);
    }
    m
}

/// Mean ns per call of `f` over the pool, best of several rounds.
fn time<T>(pool: &[T], mut f: impl FnMut(&T) -> Sign) -> f64 {
    let reps = 200;
    let mut best = f64::INFINITY;
    for _ in 0..5 {
        let t = Instant::now();
        let mut acc = 0i64;
        for _ in 0..reps {
            for x in pool {
                acc += f(black_box(x)) as i64;
            }
        }
        black_box(acc);
        best = best.min(t.elapsed().as_nanos() as f64 / (reps * pool.len()) as f64);
    }
    best
}

fn bench<const N: usize>(label: &str, gen: fn(&mut ChaCha8Rng) -> [[f64; N]; N]) {
    // Optional filter: `cargo bench -p septa-exact -- near` or `-- "tiny N=4"`.
    let name = format!("{label} N={N}");
    if let Some(f) = std::env::args().skip(1).find(|a| !a.starts_with('-')) {
        if !name.contains(&f) {
            return;
        }
    }
    let mut r = ChaCha8Rng::seed_from_u64(N as u64);
    let ia: Vec<[[f64; N]; N]> = (0..POOL).map(|_| gen(&mut r)).collect();
    // MI: b random, a = b + x with x from the generator (differences round).
    let mi: Vec<Pair<N>> = (0..POOL)
        .map(|_| {
            let x = gen(&mut r);
            let b = random::<N>(&mut r);
            (std::array::from_fn(|i| std::array::from_fn(|j| b[i][j] + x[i][j])), b)
        })
        .collect();

    stats::reset();
    ia.iter().for_each(|m| {
        det_sign(m);
    });
    let s_ia = stats::snapshot();
    stats::reset();
    mi.iter().for_each(|(a, b)| {
        det_sign_diff(a, b);
    });
    let s_mi = stats::snapshot();

    let t_ia = time(&ia, det_sign);
    let t_ia0 = time(&ia, det_sign_f64_naive);
    let t_mi = time(&mi, |(a, b)| det_sign_diff(a, b));
    let t_mi0 = time(&mi, |(a, b)| det_sign_diff_f64_naive(a, b));
    println!(
        "{label:<6} N={N}  IA {t_ia:6.2} ns vs naive {t_ia0:6.2} ns (x{:5.2}) filter {:7.3}% [exact {} bignum {}]   \
         MI {t_mi:6.2} ns vs naive {t_mi0:6.2} ns (x{:5.2}) filter {:7.3}% [exact {} bignum {}]",
        t_ia / t_ia0,
        100.0 * s_ia.filter_rate(),
        s_ia.expansion,
        s_ia.bignum,
        t_mi / t_mi0,
        100.0 * s_mi.filter_rate(),
        s_mi.expansion,
        s_mi.bignum,
    );
}

fn main() {
    println!("septa-exact det_sign micro-benchmark ({POOL} matrices per case, best of 5 rounds)");
    bench::<1>("random", random::<1>);
    bench::<2>("random", random::<2>);
    bench::<3>("random", random::<3>);
    bench::<4>("random", random::<4>);
    bench::<2>("near", near::<2>);
    bench::<3>("near", near::<3>);
    bench::<4>("near", near::<4>);
    bench::<2>("tiny", tiny::<2>);
    bench::<3>("tiny", tiny::<3>);
    bench::<4>("tiny", tiny::<4>);
    bench::<2>("sing", singular::<2>);
    bench::<3>("sing", singular::<3>);
    bench::<4>("sing", singular::<4>);
}
