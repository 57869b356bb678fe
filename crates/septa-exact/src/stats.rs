//! Per-thread counts of which tier decided each determinant sign.
//!
//! The counters are `thread_local` cells, so the hot path pays one
//! thread-local increment and no atomic operation. They count **the calling
//! thread only**: a benchmark that runs predicates on several threads must
//! snapshot on each thread (or run single-threaded) and add the results.

use std::cell::Cell;

thread_local! {
    static FILTER: Cell<u64> = const { Cell::new(0) };
    static EXPANSION: Cell<u64> = const { Cell::new(0) };
    static BIGNUM: Cell<u64> = const { Cell::new(0) };
}

/// How many determinant signs each tier decided on this thread.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Decided by the floating-point filter (including trivial N = 1 signs
    /// and exact zeros proven by a zero permanent).
    pub filter: u64,
    /// Decided by the allocation-free exact tier (`i128` for low-precision
    /// rows, else expansions).
    pub expansion: u64,
    /// Decided by the bignum tier (inputs outside the exponent window).
    pub bignum: u64,
}

impl Stats {
    /// All decisions.
    pub fn total(&self) -> u64 {
        self.filter + self.expansion + self.bignum
    }

    /// Fraction decided by the filter (1.0 when nothing was counted).
    pub fn filter_rate(&self) -> f64 {
        match self.total() {
            0 => 1.0,
            t => self.filter as f64 / t as f64,
        }
    }

    /// Counts since `earlier` (a previous snapshot of the same thread).
    pub fn since(&self, earlier: &Stats) -> Stats {
        Stats {
            filter: self.filter - earlier.filter,
            expansion: self.expansion - earlier.expansion,
            bignum: self.bignum - earlier.bignum,
        }
    }
}

/// The calling thread's counts so far.
pub fn snapshot() -> Stats {
    Stats { filter: FILTER.with(Cell::get), expansion: EXPANSION.with(Cell::get), bignum: BIGNUM.with(Cell::get) }
}

/// Sets the calling thread's counts to zero.
pub fn reset() {
    FILTER.with(|c| c.set(0));
    EXPANSION.with(|c| c.set(0));
    BIGNUM.with(|c| c.set(0));
}

#[inline(always)]
pub(crate) fn count_filter() {
    FILTER.with(|c| c.set(c.get() + 1));
}

#[inline(always)]
pub(crate) fn count_expansion() {
    EXPANSION.with(|c| c.set(c.get() + 1));
}

#[inline(always)]
pub(crate) fn count_bignum() {
    BIGNUM.with(|c| c.set(c.get() + 1));
}
