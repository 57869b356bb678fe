//! The robustness test of Du et al. Sec. 8.1 (Table 1): near-degenerate
//! inputs inside one tetrahedron, each built twice in two function orders.
//!
//! Inputs are linear functions over the tet `(0,0,0), (1,0,0), (0,1,0),
//! (0,0,1)` whose zero sets (IA, 4 functions) or pairwise-difference zero
//! sets (MI, 5 functions) almost meet in a common point, segment, triangle
//! or quadrilateral. "Almost" is the rounding of evaluating exact
//! constructions in `f64`, plus a random relative perturbation between
//! `1e-18` and `1e-13`. A case succeeds when both orders build and give the
//! same [`CanonicalForm`]; a **Type I** failure builds twice but differently
//! (or breaks an invariant), a **Type II** failure cannot build.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::{CanonicalForm, Complex, Mode, Options};

/// The kind of near-degeneracy (Fig. 10).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Degeneracy {
    /// All planes nearly through one point.
    Point,
    /// All planes nearly through one line.
    Segment,
    /// All planes nearly equal to one plane cutting the tet in a triangle.
    Tri,
    /// All planes nearly equal to one plane cutting the tet in a quadrilateral.
    Quad,
}

impl Degeneracy {
    /// Parses `point|segment|tri|quad`.
    pub fn parse(s: &str) -> Option<Degeneracy> {
        Some(match s {
            "point" => Degeneracy::Point,
            "segment" => Degeneracy::Segment,
            "tri" => Degeneracy::Tri,
            "quad" => Degeneracy::Quad,
            _ => return None,
        })
    }
}

/// Outcome counts of a stress run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StressReport {
    /// Cases run.
    pub cases: usize,
    /// Both orders built the same structure.
    pub success: usize,
    /// Built twice, structures differ (or an invariant broke).
    pub type1: usize,
    /// Construction could not proceed in at least one order.
    pub type2: usize,
}

const TET: [[f64; 3]; 4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn unit(rng: &mut ChaCha8Rng) -> [f64; 3] {
    loop {
        let v = [0; 3].map(|_| rng.gen_range(-1.0..1.0));
        let n = dot(v, v).sqrt();
        if n > 0.1 && n <= 1.0 {
            return v.map(|x| x / n);
        }
    }
}

fn inside_point(rng: &mut ChaCha8Rng) -> [f64; 3] {
    let mut b = [0; 4].map(|_| rng.gen_range(0.05..1.0));
    let s: f64 = b.iter().sum();
    b.iter_mut().for_each(|x| *x /= s);
    [0, 1, 2].map(|k| (0..4).map(|i| b[i] * TET[i][k]).sum())
}

fn perturb(rng: &mut ChaCha8Rng, x: f64) -> f64 {
    let rel = 10f64.powf(rng.gen_range(-18.0..-13.0));
    x * (1.0 + rng.gen_range(-rel..rel))
}

/// Values at the 4 tet corners of `x -> n.x + c`, perturbed.
fn sample(rng: &mut ChaCha8Rng, n: [f64; 3], c: f64) -> [f64; 4] {
    [0, 1, 2, 3].map(|i| perturb(rng, dot(n, TET[i]) + c))
}

/// One near-degenerate input: 4 functions for IA, 5 for MI.
pub fn generate(mode: Mode, kind: Degeneracy, rng: &mut ChaCha8Rng) -> Vec<[f64; 4]> {
    let k = if mode == Mode::Ia { 4 } else { 5 };
    let p = inside_point(rng);
    // Planes through p (point), through a line through p (segment), or
    // equal to one plane through p cutting off 1 or 2 corners (tri, quad).
    let u = unit(rng);
    let common = match kind {
        Degeneracy::Tri | Degeneracy::Quad => {
            let n = unit(rng);
            let mut h: Vec<f64> = TET.iter().map(|&q| dot(n, q)).collect();
            h.sort_by(f64::total_cmp);
            let cut = if kind == Degeneracy::Tri { 0 } else { 1 };
            let t = rng.gen_range(0.2..0.8);
            Some((n, h[cut] * (1.0 - t) + h[cut + 1] * t))
        }
        _ => None,
    };
    let normal = |rng: &mut ChaCha8Rng| -> [f64; 3] {
        match kind {
            Degeneracy::Point => unit(rng),
            Degeneracy::Segment => {
                let v = unit(rng);
                let d = dot(v, u);
                [v[0] - d * u[0], v[1] - d * u[1], v[2] - d * u[2]]
            }
            _ => {
                let (n, _) = common.unwrap();
                let s = rng.gen_range(0.2..2.0) * if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
                n.map(|x| x * s)
            }
        }
    };
    match mode {
        Mode::Ia => (0..k)
            .map(|_| {
                let n = normal(rng);
                let c = match common {
                    Some((m, h)) => -h * dot(n, m), // n = s m, so n.x + c = s (m.x - h)
                    None => -dot(n, p),
                };
                sample(rng, n, c)
            })
            .collect(),
        Mode::Mi => {
            // f_i(x) = base + a_i.(x - p): every difference vanishes at p;
            // with a_i.u shared, along the line p + t u; with a_i parallel
            // to one normal, on one plane.
            let base = rng.gen_range(-1.0..1.0);
            let shared = rng.gen_range(-1.0..1.0);
            (0..k)
                .map(|_| {
                    let mut a = normal(rng);
                    if kind == Degeneracy::Segment {
                        a = [0, 1, 2].map(|i| a[i] + shared * u[i]);
                    }
                    let anchor = match common {
                        Some((m, h)) => {
                            // a point of the common plane: p moved along m
                            let d = dot(m, p) - h;
                            [0, 1, 2].map(|i| p[i] - d * m[i])
                        }
                        None => p,
                    };
                    sample(rng, a, base - dot(a, anchor))
                })
                .collect()
        }
    }
}

/// Builds one input in two orders (given, and reversed) and compares.
pub fn run_case(mode: Mode, values: &[[f64; 4]], options: &Options, c: &mut Complex) -> Result<bool, ()> {
    let k = values.len();
    let mut forms = Vec::with_capacity(2);
    for reversed in [false, true] {
        let order: Vec<usize> = if reversed { (0..k).rev().collect() } else { (0..k).collect() };
        let permuted: Vec<[f64; 4]> = order.iter().map(|&i| values[i]).collect();
        c.build(mode, &permuted, options).map_err(|_| ())?;
        if c.check_invariants().is_err() {
            return Ok(false);
        }
        let ids: Vec<u32> = order.iter().map(|&i| i as u32).collect();
        forms.push(CanonicalForm::new(c, &ids));
    }
    Ok(forms[0] == forms[1])
}

/// Runs `cases` inputs of one kind from `seed`.
pub fn stress(mode: Mode, kind: Degeneracy, cases: usize, seed: u64, options: &Options) -> StressReport {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut c = Complex::new();
    let mut r = StressReport { cases, ..Default::default() };
    for _ in 0..cases {
        let values = generate(mode, kind, &mut rng);
        match run_case(mode, &values, options, &mut c) {
            Ok(true) => r.success += 1,
            Ok(false) => r.type1 += 1,
            Err(()) => r.type2 += 1,
        }
    }
    r
}
