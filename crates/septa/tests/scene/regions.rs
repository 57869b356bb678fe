//! Region rules as pure functions on labels: expression parsing and
//! precedence, first-match semantics, interest, orientation, and the
//! built-in Bloomenthal scenes against his `Region(p)` pseudo-code written
//! out independently here (chapter 4.8).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use septa::scene::{builtin, must_flip, Expr, Interest, RegionRule, Rule, Scene};

fn parse(s: &str) -> Result<Expr, String> {
    let names = ["a", "b", "c", "d"];
    Expr::parse(s, &|n: &str| names.iter().position(|x| *x == n))
}

/// Truth table of an expression over a, b, c, d.
fn table(e: &Expr) -> Vec<bool> {
    (0..16u32).map(|m| e.eval(&|i| m >> i & 1 == 1)).collect()
}

#[test]
fn expression_precedence_and_errors() {
    let same = |x: &str, y: &str| assert_eq!(table(&parse(x).unwrap()), table(&parse(y).unwrap()), "{x} vs {y}");
    same("a | b - c", "(a | b) - c");
    same("a - b - c", "(a - b) - c");
    same("a | b & c", "a | (b & c)");
    same("!a & b", "(!a) & b");
    same("!!a", "a");
    same("a - b", "a & !b");
    same("!(a | b)", "!a & !b");
    assert_ne!(table(&parse("a - (b - c)").unwrap()), table(&parse("a - b - c").unwrap()));
    assert!(parse("a & e").unwrap_err().contains("unknown function `e`"));
    assert!(parse("(a | b").unwrap_err().contains("missing `)`"));
    assert!(parse("a |").is_err());
    assert!(parse("").is_err());
    assert!(parse("a $ b").is_err());
    assert!(parse("a b").is_err());
    let mut f = Default::default();
    parse("a - (c | !a)").unwrap().functions(&mut f);
    assert_eq!(f.into_iter().collect::<Vec<_>>(), vec![0, 2]);
}

#[test]
fn first_match_wins_and_identity() {
    let r = RegionRule::Rules {
        rules: vec![Rule { when: Expr::Func(0), region: 5 }, Rule { when: Expr::Func(1), region: 7 }],
        otherwise: -1,
    };
    assert_eq!(r.region_ia(&[true, true]), 5);
    assert_eq!(r.region_ia(&[false, true]), 7);
    assert_eq!(r.region_ia(&[false, false]), -1);
    // MI: an atom is "this material".
    assert_eq!(r.region_mi(0), 5);
    assert_eq!(r.region_mi(1), 7);
    assert_eq!(r.region_mi(2), -1);
    assert_eq!(r.regions().into_iter().collect::<Vec<_>>(), vec![-1, 5, 7]);
    // Identity: sign bit masks and materials.
    let id = RegionRule::Identity;
    assert_eq!(id.region_ia(&[true, false, true]), 0b101);
    assert_eq!(id.region_mi(3), 3);
}

#[test]
fn interest_pairs_and_triples() {
    let i = Interest::new(Some(&[[3, 1], [2, 3]]), &[[3, 2, 1], [0, 2, 3]]);
    assert!(i.surface(1, 3) && i.surface(3, 1) && i.surface(3, 2));
    assert!(!i.surface(1, 2) && !i.surface(3, 3));
    assert_eq!(i.curve(&[2, 1, 3]), Some([1, 2, 3]));
    assert_eq!(i.curve(&[3, 0, 2, 2]), Some([0, 2, 3]));
    assert_eq!(i.curve(&[0, 1, 3]), None);
    assert_eq!(i.curve(&[1, 3]), None);
    let all = Interest::all();
    assert!(all.surface(4, 9) && !all.surface(4, 4));
    // Every triple by default: an edge's curve is its three least regions.
    assert_eq!(all.curve(&[0, 1, 2, 5]), Some([0, 1, 2]));
    assert_eq!(all.curve(&[0, 1]), None);
    assert!(all.features && i.features);
    let none = Interest::new(None, &[]);
    assert_eq!(none.curve(&[0, 1, 2]), None);
    // Counter-clockwise seen from the lesser region: normal into it.
    assert!(!must_flip(0, 2) && must_flip(2, 0));
}

/// Applies a scene's rule to the sign vector of its functions at `p`.
fn region_at(s: &Scene, p: [f64; 3]) -> i64 {
    let signs: Vec<bool> = s.functions.iter().map(|f| f.eval(p) > 0.0).collect();
    s.regions.region_ia(&signs)
}

fn sigmoid(d: f64) -> f64 {
    if d.abs() > 1.0 {
        0.0
    } else {
        1.0 - (4.0 * d.powi(6) - 17.0 * d.powi(4) + 22.0 * d * d) / 9.0
    }
}

/// Random points, denser near z = 0 where the interesting regions meet.
fn points(seed: u64) -> Vec<[f64; 3]> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..20000)
        .map(|i| {
            let zr = if i % 2 == 0 { 0.4 } else { 1.0 };
            [rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0), rng.gen_range(-zr..zr)]
        })
        .collect()
}

#[test]
fn saucer_square_is_bloomenthals_region_function() {
    // 4.8.1 pseudo-code: not InsideCube -> 0; Saucer(p) > |p_z| -> 1;
    // p_z > 0 -> 2; else 3, with Saucer(p) = .35 Sigmoid(1.4 sqrt(x^2+y^2)).
    let s = builtin::saucer_square();
    let mut counts = [0; 4];
    for p in points(1) {
        let inside_cube = p.iter().all(|x| x.abs() < 0.9);
        let saucer = 0.35 * sigmoid(1.4 * (p[0] * p[0] + p[1] * p[1]).sqrt());
        let want = if !inside_cube {
            0
        } else if saucer > p[2].abs() {
            1
        } else if p[2] > 0.0 {
            2
        } else {
            3
        };
        // Skip points within rounding of a boundary.
        if (saucer - p[2].abs()).abs() < 1e-12 {
            continue;
        }
        assert_eq!(region_at(&s, p), want, "at {p:?}");
        counts[want as usize] += 1;
    }
    assert!(counts.iter().all(|&c| c > 100), "{counts:?}");
}

#[test]
fn sphere_with_hole_is_bloomenthals_region_function() {
    let s = builtin::sphere_with_hole();
    let d = |p: [f64; 3], c: [f64; 3]| ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2) + (p[2] - c[2]).powi(2)).sqrt();
    let mut counts = [0; 3];
    for p in points(2) {
        let want = if d(p, [0.25, 0.15, 0.5]) < 0.3 {
            1
        } else if d(p, [0.0; 3]) < 0.6 {
            2
        } else {
            0
        };
        assert_eq!(region_at(&s, p), want, "at {p:?}");
        counts[want as usize] += 1;
    }
    assert!(counts.iter().all(|&c| c > 100), "{counts:?}");
    assert_eq!(s.interest.surfaces.as_ref().unwrap().len(), 1);
    assert!(s.interest.surface(0, 2) && !s.interest.surface(1, 2) && !s.interest.surface(0, 1));
}

#[test]
fn sphere_plane_hole_matches_the_books_interest() {
    // Figure 4.30: surfaces {(0,2),(0,3),(2,3)}, curves {(0,1,2),(0,1,3),
    // (1,2,3),(0,2,3),(2,3,4)}; every region occurs, and the hole touches
    // the three surfaces of interest (it sits on the intersection circle).
    let s = builtin::sphere_plane_hole();
    let mut seen = std::collections::BTreeSet::new();
    for p in points(3) {
        seen.insert(region_at(&s, p));
    }
    assert_eq!(seen.into_iter().collect::<Vec<_>>(), vec![0, 1, 2, 3, 4]);
    for t in [[0, 1, 2], [0, 1, 3], [1, 2, 3], [0, 2, 3], [2, 3, 4]] {
        assert_eq!(s.interest.curve(&t), Some(t));
    }
    assert_eq!(s.interest.curve(&[0, 1, 4]), None);
    let hole = s.function_index("hole").unwrap();
    let sphere = s.function_index("sphere").unwrap();
    let above = s.function_index("above").unwrap();
    // A point where all three surfaces meet lies inside the hole.
    let a = std::f64::consts::PI / 6.0;
    let q = [0.55 * a.cos(), 0.55 * a.sin(), 0.0];
    assert!(s.functions[hole].eval(q) > 0.0);
    assert!(s.functions[sphere].eval(q).abs() < 1e-15 && s.functions[above].eval(q) == 0.0);
}

#[test]
fn patch_blend_regions() {
    let s = builtin::patch_blend();
    let patch = builtin::blend_patch();
    let c = patch.point(0.5, 0.5);
    // Just above and below the blob centre: region 1; high above the
    // patch inside the domain: 2; far below: 3; outside the prism: 0.
    assert_eq!(region_at(&s, [c[0], c[1], c[2] + 0.05]), 1);
    assert_eq!(region_at(&s, [c[0], c[1], c[2] - 0.05]), 1);
    let e = patch.point(0.1, 0.9);
    assert_eq!(region_at(&s, [e[0], e[1], e[2] + 0.05]), 2);
    assert_eq!(region_at(&s, [e[0], e[1], e[2] - 0.05]), 3);
    assert_eq!(region_at(&s, [0.9, 0.0, 0.0]), 0);
    // The patch function vanishes on the patch.
    let above = s.function_index("above").unwrap();
    for (u, v) in [(0.2, 0.3), (0.7, 0.6), (0.5, 0.5)] {
        assert!(s.functions[above].eval(patch.point(u, v)).abs() < 1e-15);
    }
}

#[test]
fn csg_builtins_inside_outside() {
    let b = builtin::box_minus_cylinder();
    assert_eq!(region_at(&b, [0.4, 0.4, 0.0]), 1);
    assert_eq!(region_at(&b, [0.05, -0.03, 0.2]), 0); // in the hole
    assert_eq!(region_at(&b, [0.6, 0.0, 0.0]), 0);
    // Monte Carlo volume of the rule agrees with the analytic volume.
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let n = 200_000;
    let inside = (0..n).filter(|_| region_at(&b, [0, 1, 2].map(|_| rng.gen_range(-0.6..0.6))) == 1).count();
    let vol = inside as f64 / n as f64 * 1.2f64.powi(3);
    assert!((vol - builtin::box_minus_cylinder_volume()).abs() < 0.01, "{vol}");

    let c = builtin::cad_part();
    assert_eq!(region_at(&c, [0.3, 0.3, -0.2]), 1); // plate
    assert_eq!(region_at(&c, [0.0, 0.2, 0.3]), 1); // boss
    assert_eq!(region_at(&c, [0.0, 0.0, -0.2]), 0); // bore
    assert_eq!(region_at(&c, [-0.5, 0.0, -0.2]), 0); // hole1
    assert_eq!(region_at(&c, [0.5, 0.05, -0.2]), 0); // hole2
    assert_eq!(region_at(&c, [0.65, 0.4, -0.2]), 0); // cut corner
    assert_eq!(region_at(&c, [0.0, 0.0, 0.6]), 0); // above the boss
}

#[test]
fn mi_builtins() {
    let a = builtin::apollonius_18();
    assert_eq!(a.functions.len(), 18);
    assert_eq!(a.grid.resolution, [20; 3]);
    assert_eq!(a.regions.region_mi(17), 17);
    let v = builtin::voronoi_lines_5();
    assert_eq!(v.functions.len(), 5);
    // Each line's own points belong to its material (negated distance 0 is
    // the maximum).
    let pts = [[0.31, -0.12, 0.05], [-0.28, 0.35, -0.1], [0.05, 0.02, 0.4], [-0.4, -0.38, 0.22], [0.22, 0.41, -0.45]];
    for (i, p) in pts.iter().enumerate() {
        let vals: Vec<f64> = v.functions.iter().map(|f| f.eval(*p)).collect();
        let arg = (0..5).max_by(|&x, &y| vals[x].total_cmp(&vals[y])).unwrap();
        assert_eq!(arg, i);
    }
}
