//! A progress callback shared by the long computations (network blocks,
//! region labels, cut stages).

/// A progress callback `(done, total)`: blocks finished for a network
/// ([`crate::network::NetworkOptions::progress`]), stages finished for a
/// cut ([`crate::cut::CutOptions::progress`]). Called from worker threads.
#[derive(Clone)]
pub struct Progress(pub std::sync::Arc<dyn Fn(usize, usize) + Send + Sync>);

impl std::fmt::Debug for Progress {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Progress(..)")
    }
}

impl Progress {
    /// Counts one finished block out of `total` and reports it.
    pub(crate) fn tick(&self, done: &std::sync::atomic::AtomicUsize, total: usize) {
        let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        (self.0)(n, total);
    }
}
