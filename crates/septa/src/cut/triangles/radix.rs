//! Stable radix sorts of (key, value) entries for the exact checks'
//! candidate-pair grid: a least significant digit pass per up to 16 bits of
//! the keys that vary, instead of comparison sorts of hundreds of thousands
//! of entries.

/// An unsigned key in the order of [`f64::total_cmp`]: the sign bit set
/// for non-negative values, every bit flipped for negative ones.
#[inline]
pub(crate) fn total_order_key(v: f64) -> u64 {
    let b = v.to_bits();
    if b >> 63 == 1 {
        !b
    } else {
        b | 1 << 63
    }
}

/// [`radix_sort_stable`] on the bits where the keys differ.
pub(crate) fn radix_sort_keys(v: &mut Vec<(u64, u32)>) {
    let Some(&(first, _)) = v.first() else { return };
    let spread = v.iter().fold(0u64, |m, e| m | (e.0 ^ first));
    radix_sort_stable(v, 64 - spread.leading_zeros());
}

/// Stable sort of `v` by its keys, which agree above their low `bits` bits
/// (below `2^bits`, or all sharing the higher bits): a least
/// significant digit radix sort, one histogram pass for all digits and one
/// scatter per digit (digits of at most 16 bits; a digit every key shares
/// is skipped). Stable, so entries with one key keep their order.
pub(crate) fn radix_sort_stable(v: &mut Vec<(u64, u32)>, bits: u32) {
    radix_sort_by(v, bits, |e| e.0)
}

/// Sorts plain `u64` keys: [`radix_sort_by`] on the bits where they differ
/// for long lists, a comparison sort for short ones (same result: equal
/// keys are indistinguishable).
pub(crate) fn sort_u64(v: &mut Vec<u64>) {
    if v.len() < 512 {
        v.sort_unstable();
        return;
    }
    let first = v[0];
    let spread = v.iter().fold(0u64, |m, &e| m | (e ^ first));
    radix_sort_by(v, 64 - spread.leading_zeros(), |&e| e);
}

/// [`radix_sort_stable`] of any entries by `key(entry)`.
pub(crate) fn radix_sort_by<T: Copy>(v: &mut Vec<T>, bits: u32, key: impl Fn(&T) -> u64) {
    if v.len() < 2 || bits == 0 {
        return;
    }
    // digits of up to 16 bits, fewer for short inputs (the counts of a
    // digit are cleared and summed once per pass)
    let cap = (usize::BITS - v.len().leading_zeros()).saturating_sub(2).clamp(8, 16);
    let passes = bits.div_ceil(cap) as usize;
    let d = bits.div_ceil(passes as u32);
    let width = 1usize << d;
    let mask = (width - 1) as u64;
    let mut counts = vec![0u32; width * passes];
    for e in v.iter() {
        for p in 0..passes {
            counts[p * width + ((key(e) >> (p as u32 * d)) & mask) as usize] += 1;
        }
    }
    let mut tmp = v.clone();
    let (mut src, mut dst) = (v, &mut tmp);
    let mut swapped = false;
    for p in 0..passes {
        let c = &mut counts[p * width..(p + 1) * width];
        if c.iter().any(|&k| k as usize == src.len()) {
            continue; // every key has this digit: the order stays
        }
        let mut sum = 0u32;
        for k in c.iter_mut() {
            let here = *k;
            *k = sum;
            sum += here;
        }
        let shift = p as u32 * d;
        for e in src.iter() {
            let b = ((key(e) >> shift) & mask) as usize;
            dst[c[b] as usize] = *e;
            c[b] += 1;
        }
        std::mem::swap(&mut src, &mut dst);
        swapped = !swapped;
    }
    if swapped {
        // the sorted entries are in `tmp`
        std::mem::swap(src, dst);
    }
}

#[cfg(test)]
#[path = "radix_tests.rs"]
mod tests;
