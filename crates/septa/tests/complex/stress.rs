//! The paper's Table 1 robustness test, at a size fit for every CI run
//! (`septa stress --count 10000` runs the full size).

use septa::complex::stress::{stress, Degeneracy};
use septa::complex::{Mode, Options};

const KINDS: [Degeneracy; 4] = [Degeneracy::Point, Degeneracy::Segment, Degeneracy::Tri, Degeneracy::Quad];

#[test]
fn exact_predicates_never_fail() {
    for mode in [Mode::Ia, Mode::Mi] {
        for kind in KINDS {
            for seed in [0, 7] {
                let r = stress(mode, kind, 500, seed, &Options::default());
                assert_eq!(r.success, r.cases, "{mode:?} {kind:?} seed {seed}: {r:?}");
            }
        }
    }
}

#[test]
fn the_generator_really_is_near_degenerate() {
    // The naive floating-point predicate must fail on these inputs, or the
    // test above would prove nothing.
    for mode in [Mode::Ia, Mode::Mi] {
        let failures: usize =
            KINDS.iter().map(|&k| stress(mode, k, 500, 1, &Options::with_float(true))).map(|r| r.type1 + r.type2).sum();
        assert!(failures > 100, "{mode:?}: only {failures} float failures in 2000 cases");
    }
}
