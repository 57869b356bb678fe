//! Tests of `tri_pair`: the filters against exact signs, exact zeros, and
//! coplanar triangle pairs.

mod filters {
    use super::super::*;
    #[allow(unused_imports)]
    use crate::cut::triangles::orient::orient_exact;

    #[test]
    fn static_filter_agrees_with_exact_orientation() {
        let x = [[0.1, 0.2, 0.3], [1.7, -0.4, 0.2], [0.3, 2.1, -0.6], [0.5, 0.5, 1.9], [0.9, 0.7, 0.05]];
        for a in 0..5u32 {
            for b in 0..5u32 {
                for c in 0..5u32 {
                    for d in 0..5u32 {
                        assert_eq!(orient(&x, a, b, c, d), orient_exact(&x, a, b, c, d));
                    }
                }
            }
        }
    }

    #[test]
    fn prepared_plane_filter_never_contradicts_exact_orientation() {
        // random triangles and query points on, one ulp off, and far from
        // their planes; the filter may give up but never be wrong
        let mut rnd = crate::cut::test_rng::xorshift_unit(0x9e3779b97f4a7c15u64);
        let (mut decided, mut undecided) = (0, 0);
        for i in 0..4000 {
            let mut x: Vec<[f64; 3]> = (0..3).map(|_| [rnd(), rnd(), rnd()]).collect();
            let (l, m) = (rnd().abs(), rnd().abs());
            // a point of the plane (rounded), then nudged by `i % 3` ulps
            let q: [f64; 3] = std::array::from_fn(|k| {
                let v = x[0][k] + l * (x[1][k] - x[0][k]) + m * (x[2][k] - x[0][k]);
                let bits = v.to_bits() as i64 + (i % 3) as i64 - 1;
                if i % 5 == 0 {
                    v + rnd()
                } else {
                    f64::from_bits(bits as u64)
                }
            });
            x.push(q);
            let p = TriPlane::new(&x, &[0, 1, 2]);
            match p.side(&x[3]) {
                Some(sg) => {
                    decided += 1;
                    assert_eq!(sg, orient_exact(&x, 0, 1, 2, 3), "case {i}");
                }
                None => undecided += 1,
            }
        }
        // both branches exercised
        assert!(decided > 100 && undecided > 100, "{decided} {undecided}");
    }

    #[test]
    fn filters_at_extreme_magnitudes_give_up_or_are_exact() {
        // differences that overflow to infinity (coordinates near f64::MAX
        // of both signs), products that overflow, permanents that underflow,
        // and exactly coplanar points at every scale: `proven_sign` relies on
        // |det| <= perm in floating point instead of testing for non-finite
        // values, so neither filter may claim a sign the exact one denies
        let mut rnd = crate::cut::test_rng::xorshift_unit(0x2545f4914f6cdd1du64);
        let (mut decided, mut undecided) = (0, 0);
        for i in 0..3000 {
            let scale =
                [2f64.powi(-1070), 2f64.powi(-600), 1.0, 2f64.powi(400), 2f64.powi(511), 2f64.powi(1000), f64::MAX]
                    [i % 7];
            let mut x: Vec<[f64; 3]> = (0..4).map(|_| [rnd() * scale, rnd() * scale, rnd() * scale]).collect();
            if i % 4 == 0 {
                // exactly coplanar: all on the plane z = c
                let c = x[0][2];
                x.iter_mut().for_each(|p| p[2] = c);
            }
            if i % 9 == 0 {
                x[3] = [f64::MAX, -f64::MAX, f64::MAX];
            }
            let exact = orient_exact(&x, 0, 1, 2, 3);
            for got in [TriPlane::new(&x, &[0, 1, 2]).side(&x[3]), orient_filtered(&x, 0, 1, 2, 3)] {
                match got {
                    Some(sg) => {
                        decided += 1;
                        assert_eq!(sg, exact, "case {i}: {x:?}");
                    }
                    None => undecided += 1,
                }
            }
        }
        assert!(decided > 500 && undecided > 500, "{decided} {undecided}");
    }

    #[test]
    fn axis_plane_points_are_exactly_coplanar() {
        let x = [[0.1, 0.3, 0.7], [0.9, -2.5, 0.7], [1e-30, 4.0, 0.7], [3.3, 1.0 / 3.0, 0.7]];
        assert_eq!(orient(&x, 0, 1, 2, 3), Sign::Zero);
        assert_eq!(orient_exact(&x, 0, 1, 2, 3), Sign::Zero);
        // 2D: on an axis-parallel line, or a repeated projected point
        let y = [[0.1, 0.3, 0.7], [0.1, -2.5, 9.0], [0.1, 4.0, 1e-300], [5.0, 0.3, 0.7]];
        for k in 0..3 {
            assert_eq!(orient2(&y, k, 0, 0, 3), Sign::Zero);
        }
        assert_eq!(orient2(&y, 1, 0, 1, 2), Sign::Zero);
        assert_eq!(orient2(&y, 2, 0, 1, 2), Sign::Zero);
        // a projection where they are not collinear still gets its sign
        assert_ne!(orient2(&y, 2, 0, 1, 3), Sign::Zero);
        assert_ne!(orient2(&y, 0, 0, 1, 2), Sign::Zero);
    }
}

mod overlap {
    use super::super::*;
    #[allow(unused_imports)]
    use crate::cut::triangles::orient::orient_exact;

    #[test]
    fn remembered_orientations_match_direct_ones() {
        // nearly coplanar points (a plane through rounded points, corners one
        // ulp off) so that the static filter gives up and the memo is used;
        // every ordering of every 4 of them, twice, including repeated ids
        let mut x: Vec<[f64; 3]> = Vec::new();
        for i in 0..6 {
            let (u, v) = (0.1 + 0.37 * i as f64, 0.3 - 0.21 * i as f64);
            let z: f64 = 0.3 * u + 0.7 * v + 0.1;
            let z = f64::from_bits((z.to_bits() as i64 + (i % 3) as i64 - 1) as u64);
            x.push([u, v, z]);
        }
        // with the planes of two of their triangles prepared (and without)
        let t = [[0, 1, 2], [5, 3, 4]];
        let p = t.map(|t| TriPlane::new(&x, &t));
        let mut o = PairOrients::new(&x, [(&t[0], Some(&p[0])), (&t[1], Some(&p[1]))]);
        let (mut slow, mut nonzero) = (0, 0);
        for _ in 0..2 {
            for a in 0..6u32 {
                for b in 0..6u32 {
                    for c in 0..6u32 {
                        for d in 0..6u32 {
                            let s = orient(&x, a, b, c, d);
                            assert_eq!(o.orient(a, b, c, d), s, "{a} {b} {c} {d}");
                            slow += orient_filtered(&x, a, b, c, d).is_none() as usize;
                            nonzero += (s != Sign::Zero) as usize;
                        }
                    }
                }
            }
            o = PairOrients::new(&x, [(&t[0], None), (&t[1], None)]);
        }
        assert!(slow > 100 && nonzero > 0, "{slow} {nonzero}");
    }

    #[test]
    fn coplanar_triangles_sharing_a_vertex() {
        // t1 = (0, 1, 2) in z = 0; t2 = (0, 3, 4) in z = 0
        let x = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [1.0, 0.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0]];
        // edge 0-3 runs along edge 0-1: overlapping
        assert!(pair_intersects(&x, &[0, 1, 2], &[0, 4, 3]));
        // (0, 5, ..) pokes into t1's angle
        assert!(pair_intersects(&x, &[0, 1, 2], &[0, 4, 5]));
        // mirrored below the x axis: touch only at the shared vertex
        let y = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [1.0, -0.5, 0.0], [1.0, -1.0, 0.0]];
        assert!(!pair_intersects(&y, &[0, 1, 2], &[0, 4, 3]));
    }
}

mod general_position {
    use super::super::*;
    use crate::cut::check::polygon::collinear;
    #[allow(unused_imports)]
    use crate::cut::triangles::orient::orient_exact;

    /// The pair test with only the edge tests (no general-position
    /// shortcut): the reference the shortcut must agree with.
    fn by_edges(x: &[[f64; 3]], t1: &[u32; 3], t2: &[u32; 3]) -> bool {
        let (p1, p2) = (TriPlane::new(x, t1), TriPlane::new(x, t2));
        edge_tests(&mut PairOrients::new(x, [(t1, Some(&p1)), (t2, Some(&p2))]), t1, t2)
    }

    /// Every pair of non-degenerate triangles over the points `x`, drawn by
    /// `pick`; returns, per number of shared corners, how many pairs the
    /// shortcut decided as meeting and as apart.
    fn agree(x: &[[f64; 3]], tris: &[[u32; 3]]) -> [[usize; 2]; 3] {
        let mut decided = [[0; 2]; 3];
        for (i, t1) in tris.iter().enumerate() {
            for t2 in &tris[i + 1..] {
                let want = by_edges(x, t1, t2);
                assert_eq!(pair_intersects(x, t1, t2), want, "{t1:?} {t2:?} {x:?}");
                let (p1, p2) = (TriPlane::new(x, t1), TriPlane::new(x, t2));
                let mut o = PairOrients::new(x, [(t1, Some(&p1)), (t2, Some(&p2))]);
                if let Some(meet) = general_position(&mut o, t1, t2) {
                    assert_eq!(meet, want, "{t1:?} {t2:?} {x:?}");
                    let ns = t1.iter().filter(|v| t2.contains(v)).count();
                    decided[ns][meet as usize] += 1;
                }
            }
        }
        decided
    }

    fn triangles(x: &[[f64; 3]], n: usize, mut r: impl FnMut() -> u64) -> Vec<[u32; 3]> {
        let mut t = Vec::new();
        while t.len() < n {
            let c = [0, 1, 2].map(|_| (r() % x.len() as u64) as u32);
            if c[0] != c[1] && c[1] != c[2] && c[0] != c[2] && !collinear(x, c[0], c[1], c[2]) {
                t.push(c);
            }
        }
        t
    }

    fn lcg(seed: u64) -> impl FnMut() -> u64 {
        let mut s = seed;
        move || {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            s >> 33
        }
    }

    #[test]
    fn agrees_with_edge_tests_on_small_integer_points() {
        // a small pool of points with coordinates in -2..=2: shared corners,
        // corners on the other plane, coplanar and touching pairs abound
        let mut total = [[0; 2]; 3];
        for seed in 0..40 {
            let mut r = lcg(seed);
            let x: Vec<[f64; 3]> = (0..10).map(|_| [0, 1, 2].map(|_| (r() % 5) as f64 - 2.0)).collect();
            let t = triangles(&x, 40, &mut r);
            let d = agree(&x, &t);
            for ns in 0..3 {
                for m in 0..2 {
                    total[ns][m] += d[ns][m];
                }
            }
        }
        // every case of the shortcut exercised, meeting and apart
        // (two shared corners off each other's plane never meet)
        for (ns, m) in [(0, 0), (0, 1), (1, 0), (1, 1), (2, 0)] {
            assert!(total[ns][m] > 20, "{total:?}");
        }
    }

    #[test]
    fn grid_triangles_separated_in_projection() {
        // the faces of a cut by axis-aligned planes: squares of a grid in
        // the plane x = 0, each split by a diagonal (alternating), whose
        // neighbours' corners lie on one another's edge lines; no two
        // triangles meet beyond shared corners and edges, and the
        // projections prove it for nearly every pair
        let m = 5;
        let x: Vec<[f64; 3]> =
            (0..(m + 1) * (m + 1)).map(|v| [0.0, (v % (m + 1)) as f64 / 9.0, (v / (m + 1)) as f64 / 9.0]).collect();
        let id = |i: usize, j: usize| (j * (m + 1) + i) as u32;
        let mut t = Vec::new();
        for j in 0..m {
            for i in 0..m {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                if (i + j) % 2 == 0 {
                    t.extend([[a, b, c], [a, c, d]]);
                } else {
                    t.extend([[a, b, d], [b, c, d]]);
                }
            }
        }
        let (mut pairs, mut by_projection) = (0, 0);
        for (u, t1) in t.iter().enumerate() {
            for t2 in &t[u + 1..] {
                assert!(!pair_intersects(&x, t1, t2), "{t1:?} {t2:?}");
                assert!(!by_edges(&x, t1, t2), "{t1:?} {t2:?}");
                if t1.iter().filter(|v| t2.contains(v)).count() < 2 {
                    pairs += 1;
                    by_projection += projections_separated(&x, t1, &TriPlane::new(&x, t1).n, t2) as usize;
                }
            }
        }
        assert_eq!(by_projection, pairs);
    }

    #[test]
    fn lone_contacts_agree_with_edge_tests() {
        // pairs without shared corners where one corner of a triangle lies
        // exactly on the other's plane, its other corners on one side: the
        // corner-in-triangle rule against the edge tests, meeting and apart
        let (mut meet, mut apart) = (0, 0);
        for seed in 0..40 {
            let mut r = lcg(500 + seed);
            let x: Vec<[f64; 3]> = (0..12).map(|_| [0, 1, 2].map(|_| (r() % 5) as f64 - 2.0)).collect();
            let t = triangles(&x, 40, &mut r);
            for t1 in &t {
                for t2 in &t {
                    if t1.iter().any(|v| t2.contains(v)) {
                        continue;
                    }
                    let s2 = t2.map(|w| orient(&x, t1[0], t1[1], t1[2], w));
                    let Some(k) = lone_contact(&s2) else { continue };
                    let got = in_tri2(&x, proj_axis(&x, t1), t2[k], t1);
                    assert_eq!(got, by_edges(&x, t1, t2), "{t1:?} {t2:?} {x:?}");
                    if got {
                        meet += 1;
                    } else {
                        apart += 1;
                    }
                }
            }
        }
        assert!(meet > 20 && apart > 20, "{meet} {apart}");
    }

    #[test]
    fn agrees_with_edge_tests_on_nearly_coplanar_points() {
        // points of one plane rounded to doubles and moved by a few ulps:
        // the static filters give up and every sign is exact
        let mut total = 0;
        for seed in 0..20 {
            let mut r = lcg(100 + seed);
            let mut f = || (r() % 1_000_000) as f64 / 1e6;
            let x: Vec<[f64; 3]> = (0..9)
                .map(|i| {
                    let (u, v) = (f(), f());
                    let z: f64 = 0.3 * u - 0.7 * v + 0.1;
                    [u, v, f64::from_bits((z.to_bits() as i64 + (i % 5) - 2) as u64)]
                })
                .collect();
            let mut r = lcg(seed);
            let t = triangles(&x, 30, &mut r);
            total += agree(&x, &t).iter().flatten().sum::<usize>();
        }
        assert!(total > 100, "{total}");
    }
}
