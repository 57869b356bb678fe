//! The expansion tier's arena-overflow path.

use super::*;

#[test]
fn tiny_arena_reports_overflow_and_large_arena_decides() {
    // Entries with long exact differences: each a - b needs two components.
    let t = 2f64.powi(-60);
    let a = [
        [1.0 + 4.0 * f64::EPSILON, 2.0, 3.0, 5.0],
        [7.0, 11.0, 13.0, 17.0],
        [19.0, 23.0, 29.0, 31.0],
        [37.0, 41.0, 43.0, 47.0],
    ];
    let b = [[t, -t, t, -t], [-t, t, -t, t], [t, t, -t, -t], [-t, -t, t, t]];
    assert_eq!(mi_in::<8, 4>(&a, &b), None);
    let big = mi_in::<CAP_BIG, 4>(&a, &b).expect("fits");
    assert_eq!(Some(big), det_sign_mi(&a, &b));
    assert_eq!(big, crate::bignum::det_sign_diff(&a, &b));
}
