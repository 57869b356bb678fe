//! Tests of `radix`: the radix sort against the library's stable sort, and
//! the keys of doubles against `f64::total_cmp`.

use super::*;

use crate::cut::test_rng::lcg;

#[test]
fn radix_sort_is_a_stable_sort() {
    let mut r = lcg(7);
    for bits in [1u32, 5, 12, 13, 24, 25, 37, 53] {
        for len in [0usize, 1, 2, 17, 1000, 5000] {
            // few distinct keys (many ties) and keys with shared digits
            let v: Vec<(u64, u32)> = (0..len)
                .map(|i| {
                    let k = match i % 3 {
                        0 => r() % 7,
                        1 => r() & ((1 << bits) - 1) & !0xfff,
                        _ => r(),
                    };
                    (k & ((1u64 << bits) - 1), i as u32)
                })
                .collect();
            let mut want = v.clone();
            want.sort_by_key(|e| e.0);
            let mut got = v.clone();
            radix_sort_stable(&mut got, bits);
            assert_eq!(got, want, "bits {bits} len {len}");
        }
    }
    // one key everywhere: every digit skipped
    let mut v: Vec<(u64, u32)> = (0..100).map(|i| (12345, i)).collect();
    let want = v.clone();
    radix_sort_stable(&mut v, 20);
    assert_eq!(v, want);
}

#[test]
fn total_order_keys_sort_like_total_cmp() {
    let mut r = lcg(3);
    let mut v: Vec<f64> = (0..3000)
        .map(|i| match i % 4 {
            0 => f64::from_bits(r() << 11 | r() & 0x7ff),
            1 => (r() as f64 / (1u64 << 53) as f64 - 0.5) * 1e3,
            2 => (r() % 17) as f64 - 8.0,
            _ => 1.0 + (r() % 5) as f64 * f64::EPSILON,
        })
        .filter(|x| !x.is_nan())
        .collect();
    v.extend([0.0, -0.0, f64::INFINITY, f64::NEG_INFINITY, f64::MIN_POSITIVE, -f64::MIN_POSITIVE, 5e-324, -5e-324]);
    let mut want = v.clone();
    want.sort_by(f64::total_cmp);
    let mut keyed: Vec<(u64, u32)> = v.iter().enumerate().map(|(i, &x)| (total_order_key(x), i as u32)).collect();
    radix_sort_stable(&mut keyed, 64);
    let got: Vec<u64> = keyed.iter().map(|e| v[e.1 as usize].to_bits()).collect();
    assert_eq!(got, want.iter().map(|x| x.to_bits()).collect::<Vec<_>>());
    // keys sharing their high bits: sorting the low bits is enough
    let mut near: Vec<(u64, u32)> = (0..500).map(|i| (total_order_key(1.0 + (r() % 1000) as f64 * 1e-9), i)).collect();
    let spread = near.iter().fold(0u64, |m, e| m | (e.0 ^ near[0].0));
    let mut want = near.clone();
    want.sort_by_key(|e| e.0);
    radix_sort_stable(&mut near, 64 - spread.leading_zeros());
    assert_eq!(near, want);
}

#[test]
fn sort_u64_sorts_short_and_long_lists() {
    let mut r = lcg(5);
    for len in [0usize, 1, 3, 511, 512, 513, 4000] {
        for shape in 0..3 {
            // edge keys (two vertex ids), few distinct keys, any bits
            let v: Vec<u64> = (0..len)
                .map(|_| match shape {
                    0 => ((r() % 5000) << 32) | (r() % 5000),
                    1 => r() % 9,
                    _ => r() << 11 | r() & 0x7ff,
                })
                .collect();
            let mut want = v.clone();
            want.sort_unstable();
            let mut got = v;
            sort_u64(&mut got);
            assert_eq!(got, want, "len {len} shape {shape}");
        }
    }
}
