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
//! ## Why expansions as well as fixed-width integers
//!
//! Fixed-width integers must hold every entry of a row scaled to a common
//! unit, so their width grows with the *exponent range* within a row: a
//! 4x4 determinant whose rows mix `2^-180` and `2^180` would need products
//! of ~1650 bits. The integer tier (`integer_det.rs`) therefore only takes
//! rows spanning at most 62 bits, where it is fastest. Expansions store only
//! the significant bits actually present (a handful of doubles whatever the
//! exponents), need no scaling, and run on the floating-point unit, so they
//! cover the wide rows. They are exact only while no intermediate underflows
//! or overflows, which the caller guarantees with an exponent window on the
//! inputs (see `window` in `filter.rs`); outside it the bignum tier
//! ([`crate::Exact`]) takes over.
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

/// A run of components inside an [`Arena`]: `buf[start .. start + len]`.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Ex {
    start: usize,
    len: usize,
}

impl Ex {
    fn end(self) -> usize {
        self.start + self.len
    }
}

/// A stack-allocated bump arena of `CAP` doubles holding expansions with
/// their *actual* lengths (zero elimination keeps them short), so one small
/// buffer replaces worst-case-sized arrays per intermediate. Every operation
/// checks capacity first and returns `None` if the arena would overflow;
/// callers then fall back to the bignum tier, so a too-small arena costs
/// speed, never correctness.
pub(crate) struct Arena<const CAP: usize> {
    buf: [f64; CAP],
    top: usize,
}

impl<const CAP: usize> Arena<CAP> {
    /// An empty arena.
    #[inline]
    pub(crate) fn new() -> Self {
        Arena { buf: [0.0; CAP], top: 0 }
    }

    /// The components of `e`, smallest first.
    #[cfg(test)]
    pub(crate) fn slice(&self, e: Ex) -> &[f64] {
        &self.buf[e.start..e.end()]
    }

    /// Exact sign of `e`: that of its largest component.
    #[inline]
    pub(crate) fn sign(&self, e: Ex) -> crate::Sign {
        match e.len {
            0 => crate::Sign::Zero,
            n => crate::Sign::of_f64(self.buf[e.start + n - 1]),
        }
    }

    #[inline]
    fn room(&self, n: usize) -> Option<()> {
        (self.top + n <= CAP).then_some(())
    }

    /// Appends one input value.
    #[inline]
    pub(crate) fn push(&mut self, x: f64) -> Option<Ex> {
        self.room(1)?;
        let start = self.top;
        if x != 0.0 {
            self.buf[start] = x;
            self.top += 1;
        }
        Some(Ex { start, len: self.top - start })
    }

    /// Appends the exact difference `a - b` of two inputs.
    #[inline]
    pub(crate) fn push_diff(&mut self, a: f64, b: f64) -> Option<Ex> {
        self.room(2)?;
        let (x, y) = two_sum(a, -b);
        let start = self.top;
        for c in [y, x] {
            if c != 0.0 {
                self.buf[self.top] = c;
                self.top += 1;
            }
        }
        Some(Ex { start, len: self.top - start })
    }

    /// Appends `e + s f`.
    #[inline]
    pub(crate) fn sum(&mut self, e: Ex, f: Ex, s: f64) -> Option<Ex> {
        self.room(e.len + f.len)?;
        let start = self.top;
        let (lo, hi) = self.buf.split_at_mut(start);
        let len = sum(&lo[e.start..e.end()], &lo[f.start..f.end()], s, hi);
        self.top += len;
        Some(Ex { start, len })
    }

    /// Replaces the two runs `acc`, `t` (adjacent, at the top of the arena,
    /// `acc` first) by `acc + s t`, stored where `acc` began.
    #[inline]
    pub(crate) fn fold(&mut self, acc: Ex, t: Ex, s: f64) -> Option<Ex> {
        debug_assert!(acc.end() == t.start && t.end() == self.top);
        let r = self.sum(acc, t, s)?;
        self.buf.copy_within(r.start..r.end(), acc.start);
        self.top = acc.start + r.len;
        Some(Ex { start: acc.start, len: r.len })
    }

    /// Moves the top run `t` down to where `over` begins (discarding
    /// `over` and anything between).
    #[inline]
    pub(crate) fn lower(&mut self, t: Ex, over: Ex) -> Ex {
        let to = over.start;
        debug_assert!(t.end() == self.top && to <= t.start);
        self.buf.copy_within(t.start..t.end(), to);
        self.top = to + t.len;
        Ex { start: to, len: t.len }
    }

    /// Appends `e * f`: one scaled copy of `e` per component of `f`, folded
    /// into a running sum that stays at the top of the arena.
    pub(crate) fn product(&mut self, e: Ex, f: Ex) -> Option<Ex> {
        // Make `f` the shorter factor: fewer scaled copies to merge.
        let (e, f) = if f.len > e.len { (f, e) } else { (e, f) };
        let start = self.top;
        if f.len == 0 {
            return Some(Ex { start, len: 0 });
        }
        self.room(2 * e.len)?;
        if e.len == 1 {
            // The common case of two single components: one Two-Product.
            let (x, y) = two_product(self.buf[e.start], self.buf[f.start]);
            for c in [y, x] {
                if c != 0.0 {
                    self.buf[self.top] = c;
                    self.top += 1;
                }
            }
            return Some(Ex { start, len: self.top - start });
        }
        let (lo, hi) = self.buf.split_at_mut(start);
        self.top += scale(&lo[e.start..e.end()], lo[f.start], hi);
        let mut acc = Ex { start, len: self.top - start };
        for k in 1..f.len {
            let b = self.buf[f.start + k];
            self.room(2 * e.len)?;
            let t = self.top;
            let (lo, hi) = self.buf.split_at_mut(t);
            let len = scale(&lo[e.start..e.end()], b, hi);
            self.top += len;
            acc = self.fold(acc, Ex { start: t, len }, 1.0)?;
        }
        Some(acc)
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
        let mut ar = Arena::<16>::new();
        let a = ar.push_diff(1.0, 1e-30).unwrap();
        let d = ar.sum(a, a, -1.0).unwrap();
        assert_eq!(ar.slice(d).len(), 0);
        assert_eq!(ar.sign(d), crate::Sign::Zero);
    }

    #[test]
    fn product_keeps_tiny_tail_sign() {
        // (1 + 2^-60) * (1 - 2^-60) - 1 = -2^-120 < 0.
        let mut ar = Arena::<32>::new();
        let a = ar.push_diff(1.0, -(2f64.powi(-60))).unwrap();
        let b = ar.push_diff(1.0, 2f64.powi(-60)).unwrap();
        let one = ar.push(1.0).unwrap();
        let p = ar.product(a, b).unwrap();
        let d = ar.sum(p, one, -1.0).unwrap();
        assert_eq!(ar.slice(d), &[-(2f64.powi(-120))]);
    }

    #[test]
    fn full_arena_reports_overflow() {
        let mut ar = Arena::<4>::new();
        let a = ar.push_diff(1.0, 1e-30).unwrap();
        let b = ar.push_diff(3.0, 1e-31).unwrap();
        assert!(ar.product(a, b).is_none());
    }
}
