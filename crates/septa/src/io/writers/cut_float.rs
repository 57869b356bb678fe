//! Text of doubles for `cells.obj`, byte for byte what `format!("{x:?}")`
//! writes, from the shortest round-trip digits of `zmij` (Schubfach).
//!
//! Both give the shortest decimal digit string that reads back as `x`
//! (the closest such to `x`), so only the layout differs: Rust's `Debug`
//! writes `1e-4 <= |x| < 1e16` as a decimal with at least one fraction
//! digit (`0.25`, `3.0`, `1000000000000000.0`) and everything else as
//! `d.ddde-7` / `1e16`. zmij's own text is kept where it is a decimal in
//! that range too (the same layout), else the layout is re-made from its
//! digits; the
//! tests compare with `{:?}` on random bit patterns over every exponent,
//! values near the decimal/exponential switch and the coordinates of
//! every cut case (`cells.obj` byte-identical).

use std::fmt::Write as _;

/// Digits as text (always ASCII).
fn ascii(b: &[u8]) -> &str {
    std::str::from_utf8(b).unwrap_or_default()
}

/// Whether the exact decimal expansion of `x` has at most 18 significant
/// digits. Only such a double can lie exactly half way between two
/// shortest candidates (a tie needs the digit after the last one to be a
/// final 5, and the candidates of 16 or 17 digits that can share a rounding
/// interval), and the two algorithms break ties differently
/// (`2086845729129147.25`: `{:?}` writes `.3`, zmij `.2`). Such doubles
/// (input coordinates like 0.5, large integers, tiny dyadics) take `{:?}`.
fn short_decimal(x: f64) -> bool {
    let bits = x.to_bits();
    let exp = ((bits >> 52) & 0x7ff) as i32;
    let frac = bits & ((1u64 << 52) - 1);
    let (mut m, mut e) = if exp == 0 { (frac, -1074) } else { (frac | (1u64 << 52), exp - 1075) };
    let tz = m.trailing_zeros() as i32;
    m >>= tz;
    e += tz;
    const LIMIT: u128 = 1_000_000_000_000_000_000; // 10^18
    if e >= 0 {
        // an integer m 2^e
        e < 64 && ((m as u128) << e) < LIMIT
    } else {
        // m 2^e = m 5^-e / 10^-e: the digits of m 5^-e
        let k = -e;
        k <= 27 && (m as u128) * 5u128.pow(k as u32) < LIMIT
    }
}

/// Reusable buffers of [`push_f64`].
#[derive(Default)]
pub(crate) struct FloatText {
    z: zmij::Buffer,
}

impl FloatText {
    /// Appends `x` to `s` exactly as `write!(s, "{x:?}")` would.
    pub(crate) fn push_f64(&mut self, s: &mut String, x: f64) {
        if !x.is_finite() || x == 0.0 || short_decimal(x) {
            let _ = write!(s, "{x:?}");
            return;
        }
        let text = self.z.format_finite(x);
        // zmij lays out the same digits as a decimal (`12.34`, `0.001234`,
        // `12340000000.0`, `5.0`) when their exponent is in -5..=15, and
        // `{:?}` does so, identically, when 1e-4 <= |x| < 1e16: where both
        // chose the decimal the texts are equal and need no re-layout (an
        // exponent, `e-324` at the longest, would be among the last 5 bytes)
        let exponent = text.as_bytes().iter().rev().take(5).any(|&b| b == b'e');
        if (1e-4..1e16).contains(&x.abs()) && !exponent {
            s.push_str(text);
            return;
        }
        let t = text.as_bytes();
        // the shortest digits d1 d2 .. dn and k with |x| ~ 0.d1..dn * 10^k
        let mut digits = [0u8; 32];
        let (mut n, mut k, mut seen_point, mut i) = (0usize, 0i32, false, 0usize);
        if t.first() == Some(&b'-') {
            i = 1;
        }
        while i < t.len() {
            match t[i] {
                b'.' => seen_point = true,
                d @ b'0'..=b'9' => {
                    if n == 0 && d == b'0' {
                        // a leading zero: before the point it carries no
                        // weight, after it the value moves one place down
                        if seen_point {
                            k -= 1;
                        }
                    } else {
                        digits[n] = d;
                        n += 1;
                        if !seen_point {
                            k += 1;
                        }
                    }
                }
                _ => break, // 'e' or 'E'
            }
            i += 1;
        }
        if i < t.len() {
            let e = std::str::from_utf8(&t[i + 1..]).ok().and_then(|e| e.trim_start_matches('+').parse::<i32>().ok());
            match e {
                Some(e) => k += e,
                None => {
                    let _ = write!(s, "{x:?}");
                    return;
                }
            }
        }
        while n > 1 && digits[n - 1] == b'0' {
            n -= 1;
        }
        let d = &digits[..n];
        if x < 0.0 {
            s.push('-');
        }
        let abs = x.abs();
        if (1e-4..1e16).contains(&abs) {
            if k <= 0 {
                s.push_str("0.");
                (0..-k).for_each(|_| s.push('0'));
                s.push_str(ascii(d));
            } else if (k as usize) < n {
                s.push_str(ascii(&d[..k as usize]));
                s.push('.');
                s.push_str(ascii(&d[k as usize..]));
            } else {
                s.push_str(ascii(d));
                (0..k as usize - n).for_each(|_| s.push('0'));
                s.push_str(".0");
            }
        } else {
            s.push(d[0] as char);
            if n > 1 {
                s.push('.');
                s.push_str(ascii(&d[1..]));
            }
            s.push('e');
            s.push_str(itoa::Buffer::new().format(k - 1));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::FloatText;
    use rand::{Rng, SeedableRng};

    fn check(f: &mut FloatText, x: f64) {
        let mut s = String::new();
        f.push_f64(&mut s, x);
        assert_eq!(s, format!("{x:?}"), "bits {:#x}", x.to_bits());
    }

    #[test]
    fn same_text_as_debug() {
        let mut f = FloatText::default();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        // every exponent, random mantissas, both signs (NaN / inf included)
        for _ in 0..400_000 {
            check(&mut f, f64::from_bits(rng.gen::<u64>()));
        }
        // coordinate-like values, short decimals, integers
        for _ in 0..200_000 {
            let x: f64 = rng.gen_range(-2.0..2.0);
            check(&mut f, x);
            check(&mut f, (x * 1e4).round() / 1e4);
            check(&mut f, (x * 1e6).round());
        }
        // around the switch between decimal and exponential text, powers
        // of ten and their neighbours, zeros, subnormals, extremes
        for e in -330..=310 {
            let p: f64 = format!("1e{e}").parse().unwrap();
            for x in [p, -p, f64::from_bits(p.to_bits().wrapping_add(1)), f64::from_bits(p.to_bits().wrapping_sub(1))] {
                check(&mut f, x);
            }
        }
        // ties between two shortest candidates (broken differently)
        for x in [f64::from_bits(0x431da7e6898b0aed), 3.0 * 2f64.powi(-24), 2086845729129147.5, 1e17 + 16.0] {
            check(&mut f, x);
        }
        for _ in 0..200_000 {
            // dyadics with short expansions around the tie-prone range
            let m = rng.gen_range(1u64..1 << 20) as f64;
            check(&mut f, m * 2f64.powi(rng.gen_range(-40..60)));
        }
        for x in [0.0, -0.0, f64::MIN_POSITIVE, f64::MAX, f64::MIN, 5e-324, 1e-4, 9.999999999999999e15, 0.1 + 0.2] {
            check(&mut f, x);
        }
    }
}
