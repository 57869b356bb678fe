//! The committed look-up tables equal a fresh generation, and the table
//! path gives exactly the incremental path's complex, also when a table
//! only decodes the first functions (IA 3-4, MI 4-5) and the rest are
//! inserted incrementally.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use septa::complex::{Complex, Mode, Options};

const TABLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/src/complex/lookup_table.rs");

#[test]
fn committed_tables_are_current() {
    let fresh = septa::complex::lookup_gen::generate_source();
    if std::env::var_os("SEPTA_BLESS").is_some() {
        std::fs::write(TABLE, &fresh).unwrap();
    }
    let committed = std::fs::read_to_string(TABLE).unwrap();
    assert!(committed == fresh, "lookup_table.rs is stale; regenerate with SEPTA_BLESS=1");
}

fn same_complex(mode: Mode, values: &[[f64; 4]]) {
    let (mut a, mut b) = (Complex::new(), Complex::new());
    a.build(mode, values, &Options::with_lookup(true)).unwrap();
    b.build(mode, values, &Options::with_lookup(false)).unwrap();
    a.check_invariants().unwrap();
    assert_eq!(
        format!("{:?}", (a.vertices(), a.edges(), a.faces(), a.cells())),
        format!("{:?}", (b.vertices(), b.edges(), b.faces(), b.cells())),
        "{mode:?} {values:?}"
    );
}

#[test]
fn table_path_equals_incremental_path() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for (mode, k) in [
        (Mode::Ia, 1),
        (Mode::Ia, 2),
        (Mode::Mi, 2),
        (Mode::Mi, 3),
        (Mode::Ia, 3),
        (Mode::Ia, 4),
        (Mode::Mi, 4),
        (Mode::Mi, 5),
    ] {
        for _ in 0..20_000 {
            let v: Vec<[f64; 4]> = (0..k).map(|_| [0; 4].map(|_| rng.gen_range(-1.0..1.0))).collect();
            same_complex(mode, &v);
        }
        // Degenerate: small integers give zeros and ties, which must fall back.
        for _ in 0..5_000 {
            let v: Vec<[f64; 4]> = (0..k).map(|_| [0; 4].map(|_| rng.gen_range(-2..=2) as f64)).collect();
            same_complex(mode, &v);
        }
        // Near-degenerate: crossings almost at the same point of an edge.
        for _ in 0..5_000 {
            let base = [0; 4].map(|_| rng.gen_range(-1.0..1.0));
            let v: Vec<[f64; 4]> = (0..k)
                .map(|_| {
                    let s = rng.gen_range(0.5..2.0);
                    base.map(|x: f64| x * s + rng.gen_range(-1e-15..1e-15))
                })
                .collect();
            same_complex(mode, &v);
        }
    }
}
