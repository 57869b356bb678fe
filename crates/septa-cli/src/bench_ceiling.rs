//! The machine's parallel ceiling, measured in the same run as a benchmark:
//! how much more work `n` busy threads get done together than one alone.
//! On a shared machine (or cores that share caches and memory bandwidth)
//! this is well below `n`; a program's `n`-thread speed-up is bounded by it,
//! so `septa bench` prints the two side by side.
use std::time::Instant;

/// Throughput gain of `n` concurrent copies of `work` over one copy:
/// `n * t(one) / t(n together)`. `work` should be single-threaded,
/// CPU-bound and take at least tens of milliseconds.
pub fn ceiling(n: usize, work: &(dyn Fn() + Sync)) -> f64 {
    let n = n.max(1);
    work(); // warm caches and allocator
    let t = Instant::now();
    work();
    let one = t.elapsed().as_secs_f64();
    let t = Instant::now();
    std::thread::scope(|s| {
        for _ in 0..n {
            s.spawn(|| work());
        }
    });
    let together = t.elapsed().as_secs_f64();
    n as f64 * one / together
}
