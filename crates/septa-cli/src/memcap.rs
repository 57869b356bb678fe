//! `SEPTA_MEMORY_LIMIT` as a cap, not only a budget for the estimates made
//! before large allocations (`septa::grid::memory`): an estimate is a lower
//! bound, so a run could pass it and still grow past the limit (a run with
//! `SEPTA_MEMORY_LIMIT=2G` peaked at 2.6 GB).
//!
//! The cap is the kernel's: `RLIMIT_DATA` (the heap and every private
//! writable mapping, so resident memory cannot exceed it) is set to the
//! limit, and an allocation the kernel refuses comes back empty. The
//! allocator below turns an empty allocation into a message naming the
//! limit and exit code 2, instead of the standard library's abort (exit
//! 134, "memory allocation failed"). It adds one comparison per allocation
//! and no shared counter. The same message, without a limit, reports a
//! machine out of memory.

use std::alloc::{GlobalAlloc, Layout, System};

/// The global allocator of the `septa` command: the system's, with the
/// clean stop above.
pub struct Capped;

// SAFETY: every call is forwarded to `System` unchanged; only a null result
// is handled (by ending the process).
unsafe impl GlobalAlloc for Capped {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        // SAFETY: the caller's contract, forwarded.
        checked(unsafe { System.alloc(l) }, l.size())
    }
    unsafe fn alloc_zeroed(&self, l: Layout) -> *mut u8 {
        // SAFETY: as above.
        checked(unsafe { System.alloc_zeroed(l) }, l.size())
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        // SAFETY: as above.
        unsafe { System.dealloc(p, l) }
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, new: usize) -> *mut u8 {
        // SAFETY: as above.
        checked(unsafe { System.realloc(p, l, new) }, new)
    }
}

/// The limit in bytes, when `SEPTA_MEMORY_LIMIT` set one (0: none).
static LIMIT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

#[inline]
fn checked(p: *mut u8, size: usize) -> *mut u8 {
    if p.is_null() && size > 0 {
        out_of_memory(size);
    }
    p
}

/// A fixed buffer written without allocating (the allocator just failed).
struct Buf {
    bytes: [u8; 512],
    len: usize,
}

impl std::fmt::Write for Buf {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        let n = s.len().min(self.bytes.len() - self.len);
        self.bytes[self.len..self.len + n].copy_from_slice(&s.as_bytes()[..n]);
        self.len += n;
        Ok(())
    }
}

#[cold]
fn out_of_memory(size: usize) -> ! {
    use std::fmt::Write as _;
    let mut b = Buf { bytes: [0; 512], len: 0 };
    let limit = LIMIT.load(std::sync::atomic::Ordering::Relaxed);
    let _ = if limit > 0 {
        write!(
            b,
            "error: the memory limit SEPTA_MEMORY_LIMIT ({limit} bytes) is reached (allocating {size} more bytes); the run stopped before finishing: give a larger limit or a smaller job (coarser grid, fewer planes)\n"
        )
    } else {
        write!(b, "error: out of memory (allocating {size} bytes); the run stopped before finishing: give a smaller job (coarser grid, fewer planes)\n")
    };
    // SAFETY: writing an initialised buffer to stderr, then ending the
    // process without running anything that could allocate.
    unsafe {
        libc::write(2, b.bytes.as_ptr().cast(), b.len);
        libc::_exit(2)
    }
}

/// Sets `RLIMIT_DATA` to `SEPTA_MEMORY_LIMIT` when it is set (called first
/// thing in `main`, before any thread starts).
pub fn apply() {
    let Some(limit) = std::env::var("SEPTA_MEMORY_LIMIT").ok().and_then(|s| septa::grid::memory::parse_size(&s)) else {
        return;
    };
    LIMIT.store(limit, std::sync::atomic::Ordering::Relaxed);
    #[cfg(target_os = "linux")]
    {
        let mut lim = libc::rlimit { rlim_cur: 0, rlim_max: 0 };
        // SAFETY: plain system calls on a valid struct; a soft limit at or
        // below the hard one needs no privilege.
        unsafe {
            if libc::getrlimit(libc::RLIMIT_DATA, &mut lim) == 0 {
                lim.rlim_cur = (limit as libc::rlim_t).min(lim.rlim_max);
                libc::setrlimit(libc::RLIMIT_DATA, &lim);
            }
        }
    }
}
