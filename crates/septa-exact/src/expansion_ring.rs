//! Exact *values* of small polynomials as floating-point expansions behind
//! the [`Ring`] interface (Shewchuk 1997, Sec. 2: Fast-Expansion-Sum,
//! Scale-Expansion and Compress), for formulas whose exact value is wanted
//! and not only a sign: the cut-vertices' homogeneous coordinates that
//! `septa cut` rounds when their interval enclosure is too wide.
//!
//! [`Exact`] gives the same values with big integers, but every operation
//! allocates; an [`Expansion`] lives on the stack (at most [`CAP`]
//! components, compressed after every operation) and runs on the
//! floating-point unit, several times cheaper for degree-5 formulas.
//!
//! Exact only inside an exponent window, as for the determinant tier
//! (`expansion.rs`, "Exactness argument under the window"): if every input
//! double is zero or has magnitude in `[2^-L, 2^H]` and every product has at
//! most `N` input factors, every intermediate is a multiple of
//! `2^(-N (L + 52))`, so `two_sum` and `two_product` are error-free as long
//! as that unit is at least `2^-960` and magnitudes stay below `2^995`. The
//! caller checks its inputs with [`expansion_window`] (`N <= 5`, `L = H = 100`:
//! unit `2^-760`, terms below `2^500` times the number of terms).
//!
//! A value whose compressed expansion would need more than [`CAP`]
//! components is marked *spilled*; [`Expansion::to_exact`] then answers
//! `None` and the caller evaluates with [`Exact`] instead. A spill costs
//! speed, never correctness.

use crate::exact::Exact;
use crate::expansion::{scale, sum, two_sum};
use crate::plane::Ring;

/// Components an [`Expansion`] holds (compressed: a value spanning `b`
/// significant bits needs about `b / 53` of them).
pub const CAP: usize = 12;

/// Largest input magnitude exponent of the window (see the module doc).
const WINDOW: i32 = 100;

/// Whether every double of `xs` is zero or has magnitude in
/// `[2^-100, 2^100]`: with such inputs, polynomials of at most 5 factors
/// per product evaluate exactly as [`Expansion`]s.
pub fn expansion_window(xs: impl IntoIterator<Item = f64>) -> bool {
    let (lo, hi) = (2f64.powi(-WINDOW), 2f64.powi(WINDOW));
    xs.into_iter().all(|x| x == 0.0 || (x.abs() >= lo && x.abs() <= hi))
}

/// An exact value `c[0] + ... + c[n-1]` (nonzero components, increasing
/// magnitude), or a spilled value (too long; see the module doc).
#[derive(Clone, Debug)]
pub struct Expansion {
    c: [f64; CAP],
    n: u8,
    spilled: bool,
}

impl Expansion {
    fn spilled() -> Expansion {
        Expansion { c: [0.0; CAP], n: 0, spilled: true }
    }

    /// The components, smallest first.
    #[inline]
    pub fn components(&self) -> &[f64] {
        &self.c[..self.n as usize]
    }

    /// Whether the value outgrew [`CAP`] components somewhere (then it is
    /// not available).
    #[inline]
    pub fn is_spilled(&self) -> bool {
        self.spilled
    }

    /// Compresses `buf` and keeps it if it fits.
    fn from_buf(buf: &mut [f64]) -> Expansion {
        let n = compress(buf);
        if n > CAP {
            return Expansion::spilled();
        }
        let mut c = [0.0; CAP];
        c[..n].copy_from_slice(&buf[..n]);
        Expansion { c, n: n as u8, spilled: false }
    }

    fn signed_sum(&self, o: &Expansion, s: f64) -> Expansion {
        if self.spilled || o.spilled {
            return Expansion::spilled();
        }
        let mut buf = [0.0; 2 * CAP];
        let n = sum(self.components(), o.components(), s, &mut buf);
        Expansion::from_buf(&mut buf[..n])
    }

    /// The value as `M 2^k` with `M` in two's complement on the first
    /// `n` of the returned limbs (`None` when spilled or too wide).
    fn integer(&self) -> Option<([u64; LIMBS], usize, i64)> {
        if self.spilled {
            return None;
        }
        // Each component is m 2^e with an integer |m| < 2^53; k is the
        // smallest e, so every component is an integer multiple of 2^k.
        let mut parts = [(0i64, 0i64); CAP];
        for (p, &x) in parts.iter_mut().zip(self.components()) {
            *p = dyadic(x);
        }
        let parts = &parts[..self.n as usize];
        let k = parts.iter().map(|p| p.1).min().unwrap_or(0);
        let top = parts.iter().map(|p| p.1).max().unwrap_or(0);
        // 53 bits of mantissa, a carry bit per component and a sign bit.
        let n = ((top - k) as usize + 53 + CAP + 1) / 64 + 1;
        if n > LIMBS {
            return None;
        }
        let mut limbs = [0u64; LIMBS];
        for &(m, e) in parts {
            add_shifted(&mut limbs[..n], m, (e - k) as usize);
        }
        Some((limbs, n, k))
    }

    /// The same value as an [`Exact`], or `None` when spilled or too wide.
    pub fn to_exact(&self) -> Option<Exact> {
        let (limbs, n, k) = self.integer()?;
        let bytes: Vec<u8> = limbs[..n].iter().flat_map(|l| l.to_le_bytes()).collect();
        Some(Exact::from_parts(num_bigint::BigInt::from_signed_bytes_le(&bytes), k))
    }

    /// [`Exact::to_f64_approx`] of the same value, without building the
    /// bignum: `M` rounded down (towards minus infinity, as a right shift
    /// of a negative big integer) to its top 60 bits, then to a double,
    /// times the power of two. `None` when spilled or too wide.
    pub fn to_f64_approx(&self) -> Option<f64> {
        let (mut limbs, n, k) = self.integer()?;
        let limbs = &mut limbs[..n];
        let negative = limbs[n - 1] >> 63 == 1;
        if negative {
            // |M| = !M + 1
            let mut carry = true;
            for l in limbs.iter_mut() {
                let (s, c) = (!*l).overflowing_add(carry as u64);
                *l = s;
                carry = c;
            }
        }
        let Some(hi) = limbs.iter().rposition(|&l| l != 0) else {
            return Some(0.0);
        };
        let bits = hi * 64 + (64 - limbs[hi].leading_zeros() as usize);
        let shift = bits.saturating_sub(60);
        // q = floor(|M| / 2^shift) (at most 60 bits), and whether bits
        // below the shift are set.
        let (w, b) = (shift / 64, shift % 64);
        let mut q = limbs[w] >> b;
        if b > 0 && w + 1 < n {
            q |= limbs[w + 1] << (64 - b);
        }
        let low = limbs[..w].iter().any(|&l| l != 0) || (b > 0 && limbs[w] & ((1u64 << b) - 1) != 0);
        let top = if negative { -(q as i64) - (low as i64) } else { q as i64 };
        Some(top as f64 * 2f64.powi((k + shift as i64).clamp(-2000, 2000) as i32))
    }
}

/// Limbs of the two's complement accumulator (2048 bits: the window's
/// values span at most about 1300).
const LIMBS: usize = 32;

/// `x = m 2^e` with `|m| < 2^53` an integer (`x` finite, nonzero).
fn dyadic(x: f64) -> (i64, i64) {
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i64;
    let fraction = (bits & ((1u64 << 52) - 1)) as i64;
    let (m, e) = if biased == 0 { (fraction, -1074) } else { (fraction | (1i64 << 52), biased - 1075) };
    (if bits >> 63 == 1 { -m } else { m }, e)
}

/// `limbs += m 2^off` in two's complement (modulo `2^(64 limbs.len())`).
fn add_shifted(limbs: &mut [u64], m: i64, off: usize) {
    let (w, b) = (off / 64, off % 64);
    let v = (m.unsigned_abs() as u128) << b;
    let parts = [v as u64, (v >> 64) as u64];
    if m >= 0 {
        let mut carry = false;
        for (i, l) in limbs.iter_mut().enumerate().skip(w) {
            let add = if i - w < 2 { parts[i - w] } else { 0 };
            if add == 0 && !carry && i - w >= 2 {
                break;
            }
            let (s1, c1) = l.overflowing_add(add);
            let (s2, c2) = s1.overflowing_add(carry as u64);
            *l = s2;
            carry = c1 || c2;
        }
    } else {
        let mut borrow = false;
        for (i, l) in limbs.iter_mut().enumerate().skip(w) {
            let sub = if i - w < 2 { parts[i - w] } else { 0 };
            if sub == 0 && !borrow && i - w >= 2 {
                break;
            }
            let (s1, b1) = l.overflowing_sub(sub);
            let (s2, b2) = s1.overflowing_sub(borrow as u64);
            *l = s2;
            borrow = b1 || b2;
        }
    }
}

/// Shewchuk's Compress (1997, Sec. 2.8): the same value in as few
/// components as a top-down and a bottom-up sweep of error-free sums give,
/// written at the start of `e`; returns that count. Zero components are
/// dropped. `two_sum` stands for Fast-Two-Sum (identical results where the
/// latter's ordering holds, and error-free without it), so the value stays
/// exact whatever the input order.
fn compress(e: &mut [f64]) -> usize {
    let m = e.len();
    if m == 0 {
        return 0;
    }
    // Top-down: carry the running sum down; each nonzero tail starts a new
    // group, whose head is stored at the top end (never below index i + 1).
    let mut bottom = m - 1;
    let mut q = e[m - 1];
    for i in (0..m - 1).rev() {
        let (s, t) = two_sum(q, e[i]);
        if t != 0.0 {
            e[bottom] = s;
            bottom -= 1;
            q = t;
        } else {
            q = s;
        }
    }
    e[bottom] = q;
    // Bottom-up: add the heads from the smallest, emitting nonzero tails.
    let mut top = 0;
    let mut q = e[bottom];
    for i in bottom + 1..m {
        let (s, t) = two_sum(e[i], q);
        if t != 0.0 {
            e[top] = t;
            top += 1;
        }
        q = s;
    }
    if q != 0.0 {
        e[top] = q;
        top += 1;
    }
    top
}

impl Ring for Expansion {
    #[inline]
    fn of(x: f64) -> Self {
        let mut c = [0.0; CAP];
        c[0] = x;
        Expansion { c, n: (x != 0.0) as u8, spilled: false }
    }

    fn add(&self, o: &Self) -> Self {
        self.signed_sum(o, 1.0)
    }

    fn sub(&self, o: &Self) -> Self {
        self.signed_sum(o, -1.0)
    }

    fn mul(&self, o: &Self) -> Self {
        if self.spilled || o.spilled {
            return Expansion::spilled();
        }
        let (e, f) = if self.n >= o.n { (self, o) } else { (o, self) };
        if f.n == 0 {
            return Expansion::of(0.0);
        }
        let mut t = [0.0; 2 * CAP];
        let tn = scale(e.components(), f.c[0], &mut t);
        if f.n == 1 {
            // Scale-Expansion's output is already an expansion; compress
            // only shortens it.
            return Expansion::from_buf(&mut t[..tn]);
        }
        // One scaled copy of the longer factor per component of the
        // shorter, summed into a running total compressed after each step.
        let mut acc = [0.0; 3 * CAP];
        acc[..tn].copy_from_slice(&t[..tn]);
        let mut n = compress(&mut acc[..tn]);
        let mut next = [0.0; 3 * CAP];
        for &b in &f.components()[1..] {
            if n > CAP {
                return Expansion::spilled();
            }
            let tn = scale(e.components(), b, &mut t);
            let sn = sum(&acc[..n], &t[..tn], 1.0, &mut next);
            n = compress(&mut next[..sn]);
            std::mem::swap(&mut acc, &mut next);
        }
        Expansion::from_buf(&mut acc[..n])
    }

    fn neg(&self) -> Self {
        let mut r = self.clone();
        for x in &mut r.c[..r.n as usize] {
            *x = -*x;
        }
        r
    }
}
