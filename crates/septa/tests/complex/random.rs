//! Random and degenerate per-tet complexes: invariants, and independence of
//! the function order (compared by canonical form).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use septa::complex::{CanonicalForm, Complex, Mode, Options};

fn build(mode: Mode, values: &[[f64; 4]]) -> Complex {
    let mut c = Complex::new();
    c.build(mode, values, &Options::default()).unwrap_or_else(|e| panic!("{e} on {values:?}"));
    if let Err(e) = c.check_invariants() {
        panic!("{e} on {mode:?} {values:?}");
    }
    c
}

fn canonical(mode: Mode, values: &[[f64; 4]], order: &[usize]) -> CanonicalForm {
    let permuted: Vec<[f64; 4]> = order.iter().map(|&i| values[i]).collect();
    let ids: Vec<u32> = order.iter().map(|&i| i as u32).collect();
    CanonicalForm::new(&build(mode, &permuted), &ids)
}

fn check_orders(mode: Mode, values: &[[f64; 4]], rng: &mut ChaCha8Rng) -> CanonicalForm {
    let k = values.len();
    let id: Vec<usize> = (0..k).collect();
    let a = canonical(mode, values, &id);
    for _ in 0..3 {
        let mut order = id.clone();
        for i in (1..k).rev() {
            order.swap(i, rng.gen_range(0..=i));
        }
        let b = canonical(mode, values, &order);
        assert_eq!(a, b, "{mode:?} order {order:?} on {values:?}");
    }
    a
}

/// With exact degeneracies a point may be encoded by different planes in
/// different orders, but the structure (its counts) must not change.
fn counts_independent_of_order(mode: Mode, values: &[[f64; 4]], rng: &mut ChaCha8Rng) {
    let k = values.len();
    let id: Vec<usize> = (0..k).collect();
    let a = canonical(mode, values, &id).counts();
    let mut order = id.clone();
    for i in (1..k).rev() {
        order.swap(i, rng.gen_range(0..=i));
    }
    assert_eq!(a, canonical(mode, values, &order).counts(), "{mode:?} {values:?} order {order:?}");
}

fn random_values(rng: &mut ChaCha8Rng, k: usize) -> Vec<[f64; 4]> {
    (0..k).map(|_| [0; 4].map(|_| rng.gen_range(-1.0..1.0))).collect()
}

#[test]
fn one_function_splits_the_tet_in_two() {
    let c = build(Mode::Ia, &[[-1.0, 1.0, 1.0, 1.0]]);
    assert_eq!(c.cells().len(), 2);
    assert_eq!(c.network_faces().count(), 1);
    assert_eq!(c.vertices().len(), 7);
    let c = build(Mode::Ia, &[[-1.0, -1.0, 1.0, 1.0]]);
    assert_eq!((c.vertices().len(), c.network_faces().count()), (8, 1));
}

#[test]
fn ia_random_is_order_independent() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    for k in 1..=6 {
        for _ in 0..200 {
            check_orders(Mode::Ia, &random_values(&mut rng, k), &mut rng);
        }
    }
}

#[test]
fn mi_random_is_order_independent() {
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    for k in 1..=7 {
        for _ in 0..200 {
            check_orders(Mode::Mi, &random_values(&mut rng, k), &mut rng);
        }
    }
}

#[test]
fn ia_zero_values_at_corners() {
    // Exact degeneracies: functions vanishing at tet vertices and along tet edges.
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for _ in 0..2000 {
        let k = rng.gen_range(1..=4);
        let vals: Vec<[f64; 4]> =
            (0..k).map(|_| [0; 4].map(|_| [-1.0, 0.0, 1.0, 2.0, -0.5][rng.gen_range(0..5)])).collect();
        counts_independent_of_order(Mode::Ia, &vals, &mut rng);
    }
}

#[test]
fn mi_ties_at_corners() {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    for _ in 0..2000 {
        let k = rng.gen_range(1..=5);
        let vals: Vec<[f64; 4]> = (0..k).map(|_| [0; 4].map(|_| [0.0, 1.0, 2.0, 0.5][rng.gen_range(0..4)])).collect();
        counts_independent_of_order(Mode::Mi, &vals, &mut rng);
    }
}

#[test]
fn duplicate_function_is_harmless() {
    let f = [-1.0, 0.5, 2.0, -0.25];
    let c = build(Mode::Ia, &[f, f]);
    assert_eq!(c.cells().len(), 2);
    let c = build(Mode::Mi, &[f, [0.3, 0.1, -0.2, 0.0], f]);
    c.check_invariants().unwrap();
}

#[test]
fn non_finite_values_are_rejected_with_their_position() {
    use septa::complex::BuildError;
    let mut c = Complex::new();
    for mode in [Mode::Ia, Mode::Mi] {
        let err = c.build(mode, &[[0.5, -1.0, 1.0, 2.0], [1.0, 1.0, f64::NAN, 0.0]], &Options::default()).unwrap_err();
        assert!(matches!(err, BuildError::NonFinite { function: 1, vertex: 2, .. }), "{err:?}");
        let err = c.build(mode, &[[f64::NEG_INFINITY, 0.0, 0.0, 0.0]], &Options::default()).unwrap_err();
        assert!(matches!(err, BuildError::NonFinite { function: 0, vertex: 0, .. }), "{err}");
    }
    assert_eq!(c.build(Mode::Mi, &[], &Options::default()), Err(BuildError::NoFunctions));
    // IA with no function is the bare tet.
    c.build(Mode::Ia, &[], &Options::default()).unwrap();
    assert_eq!(c.cells().len(), 1);
}

#[test]
fn extreme_magnitudes_and_subnormals() {
    let tiny = f64::from_bits(3);
    let cases: Vec<Vec<[f64; 4]>> = vec![
        vec![[1e-300, -1e300, 1e-300, -1e-300], [-1e300, 1e-300, tiny, -tiny]],
        vec![
            [tiny, -tiny, 2.0 * tiny, -3.0 * tiny],
            [-tiny, tiny, -2.0 * tiny, 3.0 * tiny],
            [1e300, -1e-300, 0.0, 1.0],
        ],
    ];
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for vals in &cases {
        for mode in [Mode::Ia, Mode::Mi] {
            counts_independent_of_order(mode, vals, &mut rng);
        }
    }
}
