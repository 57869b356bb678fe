//! Floating-point expansion arithmetic (Shewchuk 1997, "Adaptive Precision
//! Floating-Point Arithmetic and Fast Robust Geometric Predicates", Sec. 2),
//! on fixed-size stack arrays: the middle, allocation-free exact tier.
//!
//! An *expansion* is a sum of doubles `c[0] + c[1] + ... + c[n-1]`, stored
//! in increasing order of magnitude, pairwise nonoverlapping, with zeros
//! eliminated. Its value is exact; its sign is the sign of its largest
//! component `c[n-1]` (the rest sum to less than that component in
//! magnitude), and the empty expansion is zero.
//!
//! ## Why expansions and not fixed-width integers
//!
//! Fixed-width integers would have to hold every input scaled to a common
//! unit, so their width grows with the *exponent range* of the data: a
//! 4x4 determinant whose entries span `2^-180 .. 2^180` would need products
//! of ~1650 bits. Expansions only store the significant bits that are
//! actually present (a handful of doubles for typical data, whatever the
//! exponents), need no scaling step, and reuse the hardware's floating-point
//! unit. They are exact only while no intermediate underflows or overflows,
//! which the caller guarantees with an exponent window on the inputs (see
//! `window` in `filter.rs`); outside it the bignum tier ([`crate::Exact`])
//! takes over.
//!
//! ## Exactness argument under the window
//!
//! If every nonzero input has magnitude in `[2^-L, 2^H]`, every input is an
//! integer multiple of `2^(-L-52)`. Sums of multiples of a power of two `U`
//! stay multiples of `U`, and a product of a multiple of `U1` by a multiple
//! of `U2` is a multiple of `U1*U2`, both after rounding as long as the unit
//! is `>= 2^-1022` (a double no smaller than `2^52*U` has `ulp >= U`; a
//! smaller value is representable exactly). The windows are chosen so that
//! the unit of an `N`-fold product, `2^(-N(L+52))`, is `>= 2^-960`, hence no
//! nonzero intermediate is subnormal, and so that every magnitude stays
//! below `2^995`, where Veltkamp's split cannot overflow. Under these
//! conditions `two_sum` and `two_product` are error-free.

/// `x + y == a + b` exactly, `x = fl(a + b)` (Knuth's Two-Sum, no ordering needed).
#[inline(always)]
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let x = a + b;
    let b_virtual = x - a;
    let a_virtual = x - b_virtual;
    let b_round = b - b_virtual;
    let a_round = a - a_virtual;
    (x, a_round + b_round)
}

/// `x + y == a * b` exactly, `x = fl(a * b)` (no underflow/overflow assumed).
#[inline(always)]
pub(crate) fn two_product(a: f64, b: f64) -> (f64, f64) {
    let x = a * b;
    #[cfg(target_feature = "fma")]
    {
        // With a hardware FMA the tail is one fused operation.
        (x, a.mul_add(b, -x))
    }
    #[cfg(not(target_feature = "fma"))]
    {
        // Dekker's product on Veltkamp halves: each half has at most 26
        // significant bits, so the four partial products are exact.
        let (ahi, alo) = split(a);
        let (bhi, blo) = split(b);
        let err1 = x - ahi * bhi;
        let err2 = err1 - alo * bhi;
        let err3 = err2 - ahi * blo;
        (x, alo * blo - err3)
    }
}

/// Veltkamp split of `a` into `hi + lo`, each with at most 26 significant bits.
#[cfg(not(target_feature = "fma"))]
#[inline(always)]
fn split(a: f64) -> (f64, f64) {
    const SPLITTER: f64 = 134_217_729.0; // 2^27 + 1
    let c = SPLITTER * a;
    let a_big = c - a;
    let hi = c - a_big;
    (hi, a - hi)
}

/// Sum of two expansions into `h` (Shewchuk's Fast-Expansion-Sum with zero
/// elimination, Theorem 13): merge the components by magnitude and sweep a
/// running sum through them with `two_sum`, emitting the nonzero tails.
/// `f` is added with sign `sf` (`1.0` or `-1.0`, an exact scaling).
/// Returns the length written; `h.len() >= e.len() + f.len()`.
pub(crate) fn sum(e: &[f64], f: &[f64], sf: f64, h: &mut [f64]) -> usize {
    let (m, n) = (e.len(), f.len());
    if m == 0 {
        for (hi, &fi) in h.iter_mut().zip(f) {
            *hi = sf * fi;
        }
        return n;
    }
    if n == 0 {
        h[..m].copy_from_slice(e);
        return m;
    }
    let (mut i, mut j) = (0, 0);
    // Next component in increasing magnitude order.
    let next = |i: &mut usize, j: &mut usize| -> f64 {
        if *j >= n || (*i < m && e[*i].abs() <= f[*j].abs()) {
            *i += 1;
            e[*i - 1]
        } else {
            *j += 1;
            sf * f[*j - 1]
        }
    };
    let mut q = next(&mut i, &mut j);
    let mut len = 0;
    while i < m || j < n {
        let g = next(&mut i, &mut j);
        let (s, tail) = two_sum(q, g);
        if tail != 0.0 {
            h[len] = tail;
            len += 1;
        }
        q = s;
    }
    if q != 0.0 {
        h[len] = q;
        len += 1;
    }
    len
}

/// `e * b` into `h` (Shewchuk's Scale-Expansion with zero elimination,
/// Theorem 19). Returns the length written; `h.len() >= 2 * e.len()`.
pub(crate) fn scale(e: &[f64], b: f64, h: &mut [f64]) -> usize {
    if e.is_empty() || b == 0.0 {
        return 0;
    }
    let mut len = 0;
    let (mut q, tail) = two_product(e[0], b);
    if tail != 0.0 {
        h[len] = tail;
        len += 1;
    }
    for &ei in &e[1..] {
        let (p1, p0) = two_product(ei, b);
        let (s, tail) = two_sum(q, p0);
        if tail != 0.0 {
            h[len] = tail;
            len += 1;
        }
        // Shewchuk uses Fast-Two-Sum here (|p1| >= |s|); Two-Sum returns
        // the identical pair without relying on the ordering.
        let (s2, tail) = two_sum(p1, s);
        if tail != 0.0 {
            h[len] = tail;
            len += 1;
        }
        q = s2;
    }
    if q != 0.0 {
        h[len] = q;
        len += 1;
    }
    len
}

/// An expansion with capacity `C` on the stack.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Expansion<const C: usize> {
    len: usize,
    c: [f64; C],
}

impl<const C: usize> Expansion<C> {
    /// The empty expansion (zero).
    #[inline]
    pub(crate) fn zero() -> Self {
        Expansion { len: 0, c: [0.0; C] }
    }

    /// One input value (needs `C >= 1`).
    #[inline]
    pub(crate) fn from_f64(x: f64) -> Self {
        let mut r = Self::zero();
        if x != 0.0 {
            r.c[0] = x;
            r.len = 1;
        }
        r
    }

    /// The exact difference `a - b` of two inputs (needs `C >= 2`).
    #[inline]
    pub(crate) fn from_diff(a: f64, b: f64) -> Self {
        let (x, y) = two_sum(a, -b);
        let mut r = Self::zero();
        if y != 0.0 {
            r.c[r.len] = y;
            r.len += 1;
        }
        if x != 0.0 {
            r.c[r.len] = x;
            r.len += 1;
        }
        r
    }

    /// The components, smallest first.
    #[inline]
    pub(crate) fn as_slice(&self) -> &[f64] {
        &self.c[..self.len]
    }

    /// Exact sign: that of the largest component.
    #[inline]
    pub(crate) fn sign(&self) -> crate::Sign {
        match self.len {
            0 => crate::Sign::Zero,
            n => crate::Sign::of_f64(self.c[n - 1]),
        }
    }

    /// `a + s * b` for `s` in `{1, -1}`.
    #[inline]
    pub(crate) fn sum_of<const A: usize, const B: usize>(a: &Expansion<A>, b: &Expansion<B>, s: f64) -> Self {
        let mut r = Self::zero();
        r.len = sum(a.as_slice(), b.as_slice(), s, &mut r.c);
        r
    }

    /// `a * b`: one scaled copy of `a` per component of `b`, summed.
    pub(crate) fn product_of<const A: usize, const B: usize>(a: &Expansion<A>, b: &Expansion<B>) -> Self {
        let mut bufs = [[0.0f64; C]; 2];
        let mut lens = [0usize; 2];
        let mut cur = 0;
        let mut scaled = [0.0f64; C];
        for &bj in b.as_slice() {
            let k = scale(a.as_slice(), bj, &mut scaled);
            let (lo, hi) = bufs.split_at_mut(1);
            let (src, dst) = if cur == 0 { (&lo[0], &mut hi[0]) } else { (&hi[0], &mut lo[0]) };
            lens[1 - cur] = sum(&src[..lens[cur]], &scaled[..k], 1.0, dst);
            cur = 1 - cur;
        }
        Expansion { len: lens[cur], c: bufs[cur] }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_product_is_exact_on_awkward_operands() {
        let a = 1.0 + f64::EPSILON;
        let (x, y) = two_product(a, a);
        // (1 + e)^2 = 1 + 2e + e^2: the tail is exactly e^2.
        assert_eq!(x, 1.0 + 2.0 * f64::EPSILON);
        assert_eq!(y, f64::EPSILON * f64::EPSILON);
    }

    #[test]
    fn sum_cancels_to_empty() {
        let a: Expansion<4> = Expansion::from_diff(1.0, 1e-30);
        let d: Expansion<8> = Expansion::sum_of(&a, &a, -1.0);
        assert_eq!(d.as_slice().len(), 0);
        assert_eq!(d.sign(), crate::Sign::Zero);
    }

    #[test]
    fn product_keeps_tiny_tail_sign() {
        // (1 + 2^-60) * (1 - 2^-60) - 1 = -2^-120 < 0.
        let a: Expansion<2> = Expansion::from_diff(1.0, -(2f64.powi(-60)));
        let b: Expansion<2> = Expansion::from_diff(1.0, 2f64.powi(-60));
        let p: Expansion<8> = Expansion::product_of(&a, &b);
        let one: Expansion<1> = Expansion::from_f64(1.0);
        let d: Expansion<9> = Expansion::sum_of(&p, &one, -1.0);
        assert_eq!(d.as_slice(), &[-(2f64.powi(-120))]);
    }
}
