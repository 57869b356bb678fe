//! Work on the buckets of a counting sort in parallel. The network's
//! canonical order, its edge list and the surfaces' edge entries all bucket
//! their items by a vertex id and then sort each short bucket; the buckets
//! are independent, so contiguous runs of them go to different threads. Each bucket is handled by the same code
//! whatever the thread count, so the result does not depend on it.

use rayon::prelude::*;

/// Runs of buckets per thread: enough pieces to balance uneven buckets.
const PIECES_PER_THREAD: usize = 16;

/// Calls `f(b, bucket)` for every bucket `b` of `data`, where bucket `b` is
/// `data[start[b]..start[b + 1]]` (`start` non-decreasing, `start[0] == 0`,
/// last entry `data.len()`), in parallel on the current rayon pool, and
/// returns the sum of what `f` returns.
pub(crate) fn for_each_bucket<T: Send>(
    data: &mut [T],
    start: &[u32],
    f: impl Fn(usize, &mut [T]) -> usize + Sync,
) -> usize {
    let nb = start.len().saturating_sub(1);
    let pieces = (rayon::current_num_threads() * PIECES_PER_THREAD).clamp(1, nb.max(1));
    // Split `data` at bucket boundaries into `pieces` runs of buckets.
    let mut runs: Vec<(usize, usize, &mut [T])> = Vec::with_capacity(pieces);
    let mut rest = data;
    let mut b0 = 0;
    for p in 1..=pieces {
        let b1 = nb * p / pieces;
        let len = (start[b1] - start[b0]) as usize;
        let (head, tail) = rest.split_at_mut(len);
        runs.push((b0, b1, head));
        rest = tail;
        b0 = b1;
    }
    runs.into_par_iter()
        .map(|(b0, b1, run)| {
            let base = start[b0] as usize;
            (b0..b1).map(|b| f(b, &mut run[start[b] as usize - base..start[b + 1] as usize - base])).sum::<usize>()
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::for_each_bucket;

    #[test]
    fn every_bucket_once_on_any_pool() {
        // Buckets of lengths 0..7 repeated, some empty, sorted in place.
        let lens: Vec<u32> = (0..200).map(|b| (b * 7 + 3) % 8).collect();
        let mut start = vec![0u32];
        for l in &lens {
            start.push(start.last().unwrap() + l);
        }
        let n = *start.last().unwrap() as usize;
        let data: Vec<u32> = (0..n as u32).rev().collect();
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let mut d = data.clone();
            let total = pool.install(|| {
                for_each_bucket(&mut d, &start, |b, s| {
                    assert_eq!(s.len(), lens[b] as usize);
                    s.sort_unstable();
                    s.len()
                })
            });
            assert_eq!(total, n);
            for b in 0..lens.len() {
                let s = &d[start[b] as usize..start[b + 1] as usize];
                assert!(s.windows(2).all(|w| w[0] < w[1]));
            }
        }
        // No buckets at all.
        assert_eq!(for_each_bucket::<u32>(&mut [], &[0], |_, _| 1), 0);
    }
}
