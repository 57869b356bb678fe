//! Giving the heap's free memory back to the system between stages.
//!
//! The blocks' outputs are small arrays (below glibc's mmap threshold, which
//! the command line sets to 1 MiB) that live in the heap and are freed once
//! merged; the merged network and the topology that follows are large
//! arrays with pages of their own, so they never reuse that freed room, and
//! it would stay resident through the run's peak (the topology stage). On
//! IA 18 spheres at 64^3 it was 4 MB of a 65 MB peak (docs/history/performance-log.md,
//! "Tenth round on the grid").
//!
//! A program that keeps freed memory on purpose (`septa labels` trades
//! resident memory for fewer page faults) turns this off.

use std::sync::atomic::{AtomicBool, Ordering};

static RELEASE: AtomicBool = AtomicBool::new(true);

/// Whether the grid pipeline returns the heap's free pages to the system
/// after its blocks are merged (default: yes), for the rest of the process.
pub fn set_release_free_memory(on: bool) {
    RELEASE.store(on, Ordering::Relaxed);
}

/// Returns the heap's free pages to the system (glibc's `malloc_trim`, which
/// releases free pages anywhere in the heap, not only at its top), unless
/// turned off by [`set_release_free_memory`]. A no-op on other allocators
/// and platforms.
pub(crate) fn release_free_memory() {
    if !RELEASE.load(Ordering::Relaxed) {
        return;
    }
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: malloc_trim only returns free heap pages to the kernel; no
    // live allocation is touched.
    unsafe {
        libc::malloc_trim(0);
    }
}
